// The loom inspector page: reads the inspector input embedded in the page (#loom-input,
// compressed: inflate.js, the script before this one, inflates it) and draws the pass graph,
// lifetimes and memory map on canvases (a page of ten thousand passes must open in under two
// seconds, which per-element SVG would not), the memory figures and timings as tables, and
// the lists and details as plain elements. When done it writes on
// <body> data-status ("ok" or "error"), data-errors and data-load-ms, which the headless
// browser test reads from the dumped DOM.
"use strict";

(function () {
  const PASS_COLOURS = {
    graphics: "#4f7fdc",
    compute: "#2f9e6e",
    async_compute: "#e08a2c",
    copy: "#9a5fd0",
    culled: "#b4b9c3",
  };

  let model = null;
  const selection = { kind: null, name: null };
  let query = "";
  const views = {};

  // Lifetimes and the memory map share their columns: names at the left, pass names on top.
  const LABEL_W = 200;
  const HEADER_H = 22;
  let searchTimer = 0;

  // How long each step of opening the page took (data-phases on <body>), for finding where a
  // large plan's time goes.
  const phases = {};
  function timed(name, step) {
    const start = performance.now();
    const result = step();
    phases[name] = Math.round(performance.now() - start);
    return result;
  }

  function main() {
    phases.before_script = Math.round(performance.now());
    // The input's JSON text, compressed (raw DEFLATE) and in base64; data-bytes is its length.
    // The text is ASCII (the writer escapes every other character), which a one-byte decoder
    // turns into a string faster than UTF-8's, with the same result.
    const data = document.getElementById("loom-input");
    const compressed = timed("base64", () => fromBase64(data.textContent));
    data.textContent = "";
    const bytes = timed("inflate", () => loomInflate(compressed, Number(data.dataset.bytes)));
    const text = timed("text", () => new TextDecoder("latin1").decode(bytes));
    const input = timed("parse", () => JSON.parse(text));
    model = timed("model", () => buildModel(input));
    document.getElementById("title").textContent = document.title.replace(/^loom inspector: /, "");
    writeSubtitle();
    timed("lists", writeLists);
    timed("tables", () => { writeMemoryBars(); writeTimings(); });
    timed("graph", () => { views.graph = new CanvasView(document.getElementById("graph-view"), graphView()); });
    timed("lifetimes", () => { views.lifetimes = new CanvasView(document.getElementById("lifetime-view"), lifetimeView()); });
    timed("memory_map", () => { views.memory = new CanvasView(document.getElementById("memory-view"), memoryView()); });
    wireZoom(views.graph);
    writeOverlapCheck();
    writeLegend();
    // The lists measured their height before the views below them were laid out.
    model.passList.draw();
    model.resourceList.draw();
    window.addEventListener("resize", () => { model.passList.draw(); model.resourceList.draw(); });
    document.getElementById("search").addEventListener("input", onSearch);
    document.getElementById("details").addEventListener("click", onDetailsClick);
    window.addEventListener("hashchange", selectFromHash);
    selectFromHash();
  }

  function fromBase64(text) {
    const binary = atob(text);
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    return bytes;
  }

  function finish() {
    const errors = window.loomErrors;
    const list = document.getElementById("errors");
    for (const message of errors) {
      const item = document.createElement("li");
      item.textContent = message;
      list.appendChild(item);
    }
    document.body.dataset.errors = String(errors.length);
    document.body.dataset.phases = JSON.stringify(phases);
    // Since the navigation started: the page's parsing, the input's and every first drawing.
    document.body.dataset.loadMs = performance.now().toFixed(1);
    document.body.dataset.status = errors.length ? "error" : "ok";
  }

  // ---- the model: the plan with its links resolved to indices --------------------------------

  function buildModel(input) {
    const plan = input.plan;
    // The plan's own objects, with their position added (no copies: a large plan has tens of
    // thousands of them).
    const passes = plan.passes;
    passes.forEach((pass, index) => {
      pass.index = index;
      pass.culled = false;
    });
    const culled = plan.culled.map((name) => ({ name: name, index: -1, culled: true, ports: [] }));
    const passByName = new Map();
    const portOwner = new Map();
    for (const pass of passes) {
      passByName.set(pass.name, pass);
      for (const port of pass.ports) portOwner.set(pass.name + "." + port.name, pass.index);
    }
    for (const pass of culled) passByName.set(pass.name, pass);

    const resources = plan.resources;
    resources.forEach((resource, index) => { resource.index = index; });
    const resourceByName = new Map(resources.map((r) => [r.name, r]));
    const edges = [];
    for (const edge of plan.edges) {
      const from = portOwner.get(edge.from);
      const to = portOwner.get(edge.to);
      if (from !== undefined && to !== undefined) edges.push({ from: from, to: to, resource: edge.resource });
    }
    const timings = new Map();
    for (const timing of input.timings || []) timings.set(timing.pass, timing);
    const schedule = new Map();
    (input.schedule || []).forEach((entry, index) => schedule.set(index, entry));

    return {
      input: input,
      plan: plan,
      passes: passes,
      culled: culled,
      passByName: passByName,
      resources: resources,
      resourceByName: resourceByName,
      edges: edges,
      timings: timings,
      schedule: schedule,
      hasSchedule: Array.isArray(input.schedule),
      passMatch: null, // search: Set of pass names, or null when no search
      resourceMatch: null,
    };
  }

  function physicalOf(resource) {
    if (resource.type === "buffer") return model.plan.buffers[resource.buffer];
    return model.plan.textures[resource.texture];
  }

  // Physical objects get hues spread by the golden angle so that neighbours differ; buffers are
  // darker so that a texture and a buffer of one index do not look alike.
  function physicalColour(resource, alpha) {
    const isBuffer = resource.type === "buffer";
    const index = isBuffer ? resource.buffer : resource.texture;
    const hue = (index * 137.508 + (isBuffer ? 60 : 0)) % 360;
    return "hsla(" + hue.toFixed(1) + "," + (isBuffer ? "45%,40%" : "62%,52%") + "," + (alpha === undefined ? 1 : alpha) + ")";
  }

  function passColour(pass) {
    if (pass.culled) return PASS_COLOURS.culled;
    if (pass.queue === "async_compute") return PASS_COLOURS.async_compute;
    return PASS_COLOURS[pass.kind] || PASS_COLOURS.graphics;
  }

  // ---- text helpers ---------------------------------------------------------------------------

  function esc(text) {
    return String(text).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
  }

  function formatBytes(bytes) {
    const units = ["B", "KiB", "MiB", "GiB", "TiB"];
    let value = bytes;
    let unit = 0;
    while (value >= 1024 && unit + 1 < units.length) {
      value /= 1024;
      unit += 1;
    }
    return (unit === 0 ? String(value) : value.toFixed(1)) + " " + units[unit];
  }

  function plural(count, noun) {
    return count + " " + noun + (count === 1 ? "" : "s");
  }

  function formatMs(ms) {
    return ms === null || ms === undefined ? "–" : ms.toFixed(3);
  }

  function describeSpec(r) {
    if (r.type === "buffer") return formatBytes(r.size) + " buffer";
    let text = r.format + " " + r.width + "×" + r.height;
    if (r.mips > 1) text += ", " + r.mips + " mips";
    if (r.layers > 1) text += ", " + r.layers + (r.cube ? " layers (cube)" : " layers");
    if (r.samples > 1) text += ", " + r.samples + "× MSAA";
    return text;
  }

  function describeRange(range) {
    if (!range) return "";
    return "mips " + range.base_mip + "+" + range.mip_count + ", layers " + range.base_layer + "+" + range.layer_count;
  }

  // ---- header, lists, tables ------------------------------------------------------------------

  function writeSubtitle() {
    const plan = model.plan;
    const parts = [];
    if (model.input.source) parts.push(model.input.source);
    parts.push("allocator " + plan.allocator);
    parts.push(plan.frame.width + "×" + plan.frame.height);
    parts.push("order " + plan.pass_order + ", sharing " + plan.sharing);
    parts.push(model.passes.length + " passes" + (model.culled.length ? " (+" + model.culled.length + " culled)" : ""));
    parts.push(model.resources.length + " resources");
    parts.push("plan " + plan.hash);
    document.getElementById("subtitle").textContent = parts.join(" · ");
  }

  function passItem(pass) {
    const selected = selection.kind === "pass" && selection.name === pass.name ? " selected" : "";
    if (pass.culled) {
      return '<li class="culled' + selected + '" data-pass="' + esc(pass.name) + '" data-culled="true" title="culled: does not run">' +
        '<span class="swatch" style="background:' + passColour(pass) + '"></span>' + esc(pass.name) + "</li>";
    }
    return '<li class="' + selected + '" data-pass="' + esc(pass.name) + '" title="' + esc(pass.kind + " on " + pass.queue) +
      '"><span class="swatch" style="background:' + passColour(pass) + '"></span>' + pass.index + " " + esc(pass.name) + "</li>";
  }

  function resourceItem(r) {
    const selected = selection.kind === "resource" && selection.name === r.name ? " selected" : "";
    return '<li class="' + selected + '" data-resource="' + esc(r.name) + '" title="' + esc(describeSpec(r)) +
      '"><span class="swatch" style="background:' + physicalColour(r) + '"></span>' + esc(r.name) +
      ' <span class="count">' + esc(physicalOf(r).name) + "</span></li>";
  }

  function writeLists() {
    model.allPasses = model.passes.concat(model.culled);
    model.passList = new VirtualList(document.getElementById("pass-list"), passItem, (item) => select("pass", item.dataset.pass));
    model.passList.setItems(model.allPasses);
    model.resourceList = new VirtualList(document.getElementById("resource-list"), resourceItem, (item) => select("resource", item.dataset.resource));
    model.resourceList.setItems(model.resources);
    document.getElementById("pass-count").textContent = model.passes.length + (model.culled.length ? " + " + model.culled.length + " culled" : "");
    document.getElementById("resource-count").textContent = String(model.resources.length);
  }

  // A list that keeps only the rows in view as elements: ten thousand list items take seconds
  // to lay out, a window of them a millisecond. `render` makes one item's <li>; `pick` gets
  // the <li> clicked.
  function VirtualList(element, render, pick) {
    this.element = element;
    this.render = render;
    this.items = [];
    this.spacer = document.createElement("div");
    this.rows = document.createElement("ol");
    element.appendChild(this.spacer);
    element.appendChild(this.rows);
    let pending = false;
    element.addEventListener("scroll", () => {
      if (pending) return;
      pending = true;
      requestAnimationFrame(() => {
        pending = false;
        this.draw();
      });
    });
    element.addEventListener("click", (event) => {
      const item = event.target.closest("li");
      if (item) pick(item);
    });
  }

  VirtualList.prototype.ROW_H = 19;

  VirtualList.prototype.setItems = function (items) {
    this.items = items;
    this.spacer.style.height = items.length * this.ROW_H + "px";
    this.draw();
  };

  VirtualList.prototype.draw = function () {
    const first = Math.max(0, Math.floor(this.element.scrollTop / this.ROW_H));
    const count = Math.ceil(this.element.clientHeight / this.ROW_H) + 1;
    const visible = this.items.slice(first, first + count);
    this.rows.style.top = first * this.ROW_H + "px";
    this.rows.innerHTML = visible.map(this.render).join("");
  };

  // Scrolls so that `item` is in view.
  VirtualList.prototype.reveal = function (item) {
    const index = this.items.indexOf(item);
    if (index < 0) return;
    const top = index * this.ROW_H;
    if (top < this.element.scrollTop || top + this.ROW_H > this.element.scrollTop + this.element.clientHeight) {
      this.element.scrollTop = Math.max(0, top - this.element.clientHeight / 3);
    }
    this.draw();
  };

  function writeMemoryBars() {
    const plan = model.plan;
    const summary = plan.summary;
    const rows = [{ key: "naive", label: "naive", bytes: summary.naive_bytes, note: plural(summary.naive_textures, "texture") + " and " + plural(summary.naive_buffers || 0, "buffer") + ", one per resource" }];
    const allocators = model.input.allocators || [];
    if (allocators.length) {
      for (const row of allocators) {
        if (row.refused !== undefined) {
          rows.push({ key: row.allocator, label: row.allocator, bytes: null, note: "refuses: " + row.refused });
        } else {
          rows.push({ key: row.allocator, label: row.allocator, bytes: row.bytes, note: plural(row.textures, "texture") + ", " + plural(row.buffers, "buffer") });
        }
      }
    } else {
      rows.push({ key: plan.allocator, label: plan.allocator, bytes: summary.bytes, note: plural(summary.textures, "texture") + ", " + plural(summary.buffers, "buffer") });
    }
    rows.push({ key: "lower-bound", label: "lower bound", bytes: summary.lower_bound_bytes, note: "the peak of live bytes over the order" });
    const created = model.input.allocations;
    if (created) {
      const bytes = (created.heap_bytes || 0) + (created.texture_bytes || 0) + (created.buffer_bytes || 0);
      rows.push({ key: "device", label: "device", bytes: bytes,
        note: "created: " + plural(created.textures || 0, "texture") + " (" + (created.placed_textures || 0) + " placed), " +
          plural(created.buffers || 0, "buffer") + ", " + plural(created.heaps || 0, "heap") });
    }
    const most = Math.max(1, ...rows.map((row) => row.bytes || 0));
    const html = rows.map((row) => {
      const current = row.key === plan.allocator;
      const width = row.bytes === null ? 0 : (100 * row.bytes) / most;
      const colour = row.key === "naive" ? "#c2c8d3" : row.key === "lower-bound" ? "#7a8496" : row.key === "device" ? "#e08a2c" : "#4f7fdc";
      const share = row.bytes === null || !summary.naive_bytes ? "" : ((100 * row.bytes) / summary.naive_bytes).toFixed(1) + " %";
      return '<tr data-memory="' + esc(row.key) + '" data-bytes="' + (row.bytes === null ? "" : row.bytes) + '"' + (current ? ' class="current"' : "") + ">" +
        "<td>" + esc(row.label) + (current ? " (this plan)" : "") + "</td>" +
        '<td class="bar"><div class="bar-track"><div class="bar-fill" style="width:' + width.toFixed(2) + "%;background:" + colour + '"></div></div></td>' +
        "<td>" + (row.bytes === null ? "" : esc(formatBytes(row.bytes))) + "</td><td>" + esc(share) + "</td><td>" + esc(row.note) + "</td></tr>";
    });
    const columns = '<colgroup><col class="label"><col class="bar"><col class="bytes"><col class="share"><col></colgroup>';
    document.getElementById("memory-bars").innerHTML = columns + html.join("");
  }

  function writeTimings() {
    const summary = document.getElementById("timing-summary");
    const table = document.getElementById("timing-table");
    const timings = model.input.timings || [];
    document.getElementById("timing-section").dataset.timings = String(timings.length);
    if (!timings.length) {
      summary.textContent = "No timings in this input: a sample records them (loom-deferred --inspect FILE), " +
        "or give loom-inspect a timings file (--timings FILE).";
      return;
    }
    let most = 0;
    let cpuTotal = 0;
    let gpuTotal = 0;
    let gpuAll = true;
    for (const t of timings) {
      most = Math.max(most, t.cpu_ms, t.gpu_ms || 0);
      cpuTotal += t.cpu_ms;
      if (t.gpu_ms === null || t.gpu_ms === undefined) gpuAll = false;
      else gpuTotal += t.gpu_ms;
    }
    summary.textContent = "Per pass, latest frame: CPU (recording) " + cpuTotal.toFixed(3) + " ms, GPU " +
      (gpuAll ? gpuTotal.toFixed(3) + " ms" : "not measured for every pass (" + gpuTotal.toFixed(3) + " ms measured)") + ".";
    const bar = (ms, colour) => ms === null || ms === undefined ? "" :
      '<div class="bar-track"><div class="bar-fill" style="width:' + (most ? (100 * ms) / most : 0).toFixed(2) + "%;background:" + colour + '"></div></div>';
    const rows = ["<tr><th>pass</th><th>CPU ms</th><th></th><th>GPU ms</th><th></th></tr>"];
    for (const t of timings) {
      rows.push('<tr data-timing="' + esc(t.pass) + '"><td>' + esc(t.pass) + "</td><td>" + formatMs(t.cpu_ms) + '</td><td class="bar">' +
        bar(t.cpu_ms, "#4f7fdc") + "</td><td>" + formatMs(t.gpu_ms) + '</td><td class="bar">' + bar(t.gpu_ms, "#e08a2c") + "</td></tr>");
    }
    table.innerHTML = rows.join("");
  }

  function writeLegend() {
    const entries = [["graphics", "graphics pass"], ["compute", "compute pass"], ["async_compute", "async compute queue"],
      ["copy", "copy pass"], ["culled", "culled (does not run)"]];
    document.getElementById("graph-legend").innerHTML = entries.map(([key, label]) =>
      '<span><span class="swatch" style="background:' + PASS_COLOURS[key] + '"></span>' + label + "</span>").join("") +
      "<span>thick border: side effect</span>";
  }

  // ---- a canvas that draws only what is in view -----------------------------------------------

  // A transparent scroller over a canvas the size of the view: the scroller's content has the
  // full drawing's size (so the scroll bars are right), and every scroll redraws the visible
  // part. `spec` has width and height (in drawing units), draw(ctx, viewport) and click(x, y).
  function CanvasView(container, spec) {
    this.spec = spec;
    this.canvas = document.createElement("canvas");
    this.scroller = document.createElement("div");
    this.scroller.className = "scroller";
    this.sizer = document.createElement("div");
    this.scroller.appendChild(this.sizer);
    container.appendChild(this.canvas);
    container.appendChild(this.scroller);
    if (spec.height && spec.fitHeight) container.style.height = Math.min(spec.height + 20, spec.fitHeight) + "px";
    this.scale = 1;
    this.resize();
    let pending = false;
    const later = () => {
      if (pending) return;
      pending = true;
      requestAnimationFrame(() => {
        pending = false;
        this.render();
      });
    };
    this.later = later;
    this.scroller.addEventListener("scroll", later);
    window.addEventListener("resize", later);
    this.scroller.addEventListener("click", (event) => {
      const box = this.scroller.getBoundingClientRect();
      spec.click((event.clientX - box.left + this.scroller.scrollLeft) / this.scale,
        (event.clientY - box.top + this.scroller.scrollTop) / this.scale);
    });
    this.render();
  }

  CanvasView.prototype.render = function () {
    const width = this.scroller.clientWidth;
    const height = this.scroller.clientHeight;
    const ratio = window.devicePixelRatio || 1;
    if (this.canvas.width !== Math.round(width * ratio) || this.canvas.height !== Math.round(height * ratio)) {
      this.canvas.width = Math.round(width * ratio);
      this.canvas.height = Math.round(height * ratio);
      this.canvas.style.width = width + "px";
      this.canvas.style.height = height + "px";
    }
    const ctx = this.canvas.getContext("2d");
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
    ctx.clearRect(0, 0, width, height);
    // Drawing units: the scroll position and the view's size divided by the zoom.
    const x = this.scroller.scrollLeft / this.scale;
    const y = this.scroller.scrollTop / this.scale;
    ctx.scale(this.scale, this.scale);
    ctx.translate(-x, -y);
    this.spec.draw(ctx, { x: x, y: y, w: width / this.scale, h: height / this.scale });
  };

  CanvasView.prototype.resize = function () {
    this.sizer.style.width = Math.ceil(this.spec.width * this.scale) + "px";
    this.sizer.style.height = Math.ceil(this.spec.height * this.scale) + "px";
  };

  // Zooms to `scale`, keeping the drawing point at the view's centre where it was.
  CanvasView.prototype.zoom = function (scale) {
    const s = this.scroller;
    const cx = (s.scrollLeft + s.clientWidth / 2) / this.scale;
    const cy = (s.scrollTop + s.clientHeight / 2) / this.scale;
    this.scale = scale;
    this.resize();
    s.scrollLeft = Math.max(0, cx * scale - s.clientWidth / 2);
    s.scrollTop = Math.max(0, cy * scale - s.clientHeight / 2);
    this.render();
  };

  // The zoom at which the whole drawing fits the view, at most 1.
  CanvasView.prototype.fitScale = function () {
    return Math.min(1, this.scroller.clientWidth / this.spec.width, this.scroller.clientHeight / this.spec.height);
  };

  // Brings drawing point (x, y) into view, if it is not.
  CanvasView.prototype.reveal = function (x, y) {
    x *= this.scale;
    y *= this.scale;
    const s = this.scroller;
    if (x < s.scrollLeft || x > s.scrollLeft + s.clientWidth - 40) s.scrollLeft = Math.max(0, x - s.clientWidth / 3);
    if (y < s.scrollTop || y > s.scrollTop + s.clientHeight - 20) s.scrollTop = Math.max(0, y - s.clientHeight / 3);
  };

  // The graph's zoom buttons: out and in by halves (down to a box a few pixels wide), or the
  // whole graph in view.
  function wireZoom(view) {
    const smallest = 0.02;
    const set = (scale) => view.zoom(Math.max(smallest, Math.min(2, scale)));
    document.getElementById("zoom-out").addEventListener("click", () => set(view.scale / 2));
    document.getElementById("zoom-in").addEventListener("click", () => set(view.scale * 2));
    document.getElementById("zoom-fit").addEventListener("click", () => set(view.fitScale()));
  }

  function fitText(ctx, text, width) {
    if (ctx.measureText(text).width <= width) return text;
    let low = 0;
    let high = text.length;
    while (low < high) {
      const mid = (low + high + 1) >> 1;
      if (ctx.measureText(text.slice(0, mid) + "…").width <= width) low = mid;
      else high = mid - 1;
    }
    return low ? text.slice(0, low) + "…" : "";
  }

  function dimmed(kind, name) {
    const match = kind === "pass" ? model.passMatch : model.resourceMatch;
    return match !== null && !match.has(name);
  }

  // ---- the pass graph -------------------------------------------------------------------------

  function graphView() {
    const NODE_W = 150;
    const NODE_H = 30;
    const GAP_X = 46;
    const GAP_Y = 10;
    const PAD = 14;
    const passes = model.passes;
    // Column: the longest chain of producers before the pass. The order runs every pass after
    // its producers, so one sweep in order finds it.
    const preds = passes.map(() => []);
    for (const edge of model.edges) if (edge.from !== edge.to) preds[edge.to].push(edge.from);
    const column = new Int32Array(passes.length);
    for (const pass of passes) {
      let c = 0;
      for (const p of preds[pass.index]) if (p < pass.index) c = Math.max(c, column[p] + 1);
      column[pass.index] = c;
    }
    const columns = [];
    for (const pass of passes) {
      while (columns.length <= column[pass.index]) columns.push([]);
      columns[column[pass.index]].push(pass);
    }
    // Rows: each column sorted by the mean row of the passes feeding it (one sweep, left to
    // right), which keeps most edges short without a full crossing minimisation.
    const row = new Float64Array(passes.length);
    columns.forEach((list) => {
      const key = new Map();
      for (const pass of list) {
        const from = preds[pass.index];
        key.set(pass, from.length ? from.reduce((sum, p) => sum + row[p], 0) / from.length : pass.index);
      }
      if (list.some((pass) => preds[pass.index].length)) list.sort((a, b) => key.get(a) - key.get(b) || a.index - b.index);
      list.forEach((pass, r) => { row[pass.index] = r; });
    });
    if (model.culled.length) columns.push(model.culled.slice());
    const place = new Map();
    columns.forEach((list, c) => list.forEach((pass, r) => place.set(pass, { x: PAD + c * (NODE_W + GAP_X), y: PAD + r * (NODE_H + GAP_Y) })));
    const tallest = columns.reduce((most, list) => Math.max(most, list.length), 0);
    const width = PAD * 2 + columns.length * (NODE_W + GAP_X) - GAP_X;
    const height = PAD * 2 + tallest * (NODE_H + GAP_Y) - GAP_Y;
    // Edges by source column, so that drawing looks only at the columns in view and their
    // neighbours' edges.
    const edgesFrom = columns.map(() => []);
    for (const edge of model.edges) edgesFrom[column[edge.from]].push(edge);
    model.placeOfPass = (pass) => place.get(pass);

    function draw(ctx, view) {
      const first = Math.max(0, Math.floor((view.x - PAD) / (NODE_W + GAP_X)));
      const last = Math.min(columns.length - 1, Math.floor((view.x + view.w - PAD) / (NODE_W + GAP_X)));
      ctx.lineWidth = 1.5;
      for (let c = 0; c <= Math.min(last, edgesFrom.length - 1); ++c) {
        for (const edge of edgesFrom[c]) {
          // An edge whose target lies left of the view is not seen.
          if (column[edge.to] < first) continue;
          const from = place.get(passes[edge.from]);
          const to = place.get(passes[edge.to]);
          const selected = selection.kind === "pass" && (passes[edge.from].name === selection.name || passes[edge.to].name === selection.name);
          const resource = model.resources[edge.resource];
          const faint = dimmed("resource", resource.name) && dimmed("pass", passes[edge.from].name);
          ctx.strokeStyle = physicalColour(resource, faint ? 0.15 : selected ? 1 : 0.7);
          ctx.lineWidth = selected ? 3 : 1.5;
          const x0 = from.x + NODE_W;
          const y0 = from.y + NODE_H / 2;
          const x1 = to.x;
          const y1 = to.y + NODE_H / 2;
          const bend = Math.max(20, (x1 - x0) / 2);
          ctx.beginPath();
          ctx.moveTo(x0, y0);
          ctx.bezierCurveTo(x0 + bend, y0, x1 - bend, y1, x1, y1);
          ctx.stroke();
        }
      }
      ctx.font = "12px system-ui, sans-serif";
      ctx.textBaseline = "middle";
      for (let c = first; c <= last; ++c) {
        const list = columns[c];
        const r0 = Math.max(0, Math.floor((view.y - PAD) / (NODE_H + GAP_Y)));
        const r1 = Math.min(list.length - 1, Math.floor((view.y + view.h - PAD) / (NODE_H + GAP_Y)));
        for (let r = r0; r <= r1; ++r) drawNode(ctx, list[r]);
      }
    }

    function drawNode(ctx, pass) {
      const at = place.get(pass);
      const faint = dimmed("pass", pass.name);
      ctx.globalAlpha = pass.culled ? 0.55 : faint ? 0.3 : 1;
      ctx.fillStyle = passColour(pass);
      ctx.fillRect(at.x, at.y, NODE_W, NODE_H);
      const selected = selection.kind === "pass" && selection.name === pass.name;
      if (selected || pass.side_effect || pass.culled) {
        ctx.setLineDash(pass.culled ? [4, 3] : []);
        ctx.strokeStyle = selected ? "#111" : "#333";
        ctx.lineWidth = selected ? 3 : 2;
        ctx.strokeRect(at.x + 1, at.y + 1, NODE_W - 2, NODE_H - 2);
        ctx.setLineDash([]);
      }
      // Names only where they can be read; zoomed far out the boxes and edges are the picture.
      if (views.graph === undefined || views.graph.scale >= 0.4) {
        ctx.fillStyle = "#fff";
        ctx.fillText(fitText(ctx, pass.name, NODE_W - 12), at.x + 6, at.y + NODE_H / 2);
      }
      ctx.globalAlpha = 1;
    }

    function click(x, y) {
      const c = Math.floor((x - PAD) / (NODE_W + GAP_X));
      const r = Math.floor((y - PAD) / (NODE_H + GAP_Y));
      const pass = columns[c] && columns[c][r];
      if (!pass) return;
      const at = place.get(pass);
      if (x >= at.x && x <= at.x + NODE_W && y >= at.y && y <= at.y + NODE_H) select("pass", pass.name);
    }

    return { width: width, height: height, fitHeight: 420, draw: draw, click: click };
  }

  // ---- lifetimes and the memory map share their columns --------------------------------------

  function columnWidth() {
    const room = Math.max(300, document.getElementById("lifetime-view").clientWidth - LABEL_W - 24);
    return Math.max(3, Math.min(90, Math.floor(room / Math.max(1, model.passes.length))));
  }

  // The pass names (or positions, when columns are narrow) along the top, and the selected
  // pass's column; drawn last so they stay on top while scrolling.
  function drawHeader(ctx, view, colW) {
    ctx.fillStyle = "#fbfbfc";
    ctx.fillRect(view.x, view.y, view.w, HEADER_H);
    ctx.fillStyle = "#5b6478";
    ctx.font = "11px system-ui, sans-serif";
    ctx.textBaseline = "middle";
    const first = Math.max(0, Math.floor((view.x - LABEL_W) / colW));
    const last = Math.min(model.passes.length - 1, Math.ceil((view.x + view.w - LABEL_W) / colW));
    const every = colW >= 50 ? 1 : Math.ceil(50 / colW);
    for (let i = first - (first % every); i <= last; i += every) {
      if (i < 0) continue;
      const label = colW >= 50 ? fitText(ctx, model.passes[i].name, colW - 4) : String(i);
      ctx.fillText(label, LABEL_W + i * colW + 2, view.y + HEADER_H / 2);
    }
  }

  function drawSelectedColumn(ctx, view, colW) {
    if (selection.kind !== "pass") return;
    const pass = model.passByName.get(selection.name);
    if (!pass || pass.culled) return;
    ctx.fillStyle = "rgba(36, 87, 197, 0.12)";
    ctx.fillRect(LABEL_W + pass.index * colW, view.y, colW, view.h);
  }

  function lifetimeView() {
    const ROW_H = 16;
    const colW = columnWidth();
    const resources = model.resources;
    const width = LABEL_W + model.passes.length * colW + 10;
    const height = HEADER_H + resources.length * ROW_H + 6;
    model.lifetimeGeometry = { colW: colW, rowH: ROW_H };

    function draw(ctx, view) {
      drawSelectedColumn(ctx, view, colW);
      const r0 = Math.max(0, Math.floor((view.y - HEADER_H) / ROW_H));
      const r1 = Math.min(resources.length - 1, Math.floor((view.y + view.h - HEADER_H) / ROW_H));
      ctx.font = "11px system-ui, sans-serif";
      ctx.textBaseline = "middle";
      for (let i = r0; i <= r1; ++i) {
        const r = resources[i];
        const y = HEADER_H + i * ROW_H;
        const faint = dimmed("resource", r.name);
        const selected = selection.kind === "resource" && selection.name === r.name;
        if (selected) {
          ctx.fillStyle = "rgba(36, 87, 197, 0.12)";
          ctx.fillRect(view.x, y, view.w, ROW_H);
        }
        ctx.globalAlpha = faint ? 0.2 : 1;
        const occupancy = r.occupancy;
        ctx.fillStyle = physicalColour(r, 0.35);
        ctx.fillRect(LABEL_W + occupancy[0] * colW, y + 3, (occupancy[1] - occupancy[0] + 1) * colW, ROW_H - 6);
        const lifetime = r.lifetime;
        const x = LABEL_W + lifetime[0] * colW;
        const w = (lifetime[1] - lifetime[0] + 1) * colW;
        ctx.fillStyle = physicalColour(r);
        ctx.fillRect(x, y + 2, w, ROW_H - 4);
        if (r.graph_output) {
          // Read after the frame: an arrow past the last pass.
          ctx.beginPath();
          ctx.moveTo(x + w, y + 2);
          ctx.lineTo(x + w + 6, y + ROW_H / 2);
          ctx.lineTo(x + w, y + ROW_H - 2);
          ctx.fill();
        }
        if (w >= 34) {
          ctx.fillStyle = "#fff";
          ctx.fillText(fitText(ctx, physicalOf(r).name, w - 6), x + 3, y + ROW_H / 2);
        }
        ctx.globalAlpha = 1;
      }
      // Names in a column that stays at the left edge.
      ctx.fillStyle = "#fbfbfc";
      ctx.fillRect(view.x, view.y, LABEL_W - 4, view.h);
      ctx.fillStyle = "#1d2330";
      for (let i = r0; i <= r1; ++i) {
        ctx.globalAlpha = dimmed("resource", resources[i].name) ? 0.35 : 1;
        ctx.fillText(fitText(ctx, resources[i].name, LABEL_W - 10), view.x + 4, HEADER_H + i * ROW_H + ROW_H / 2);
      }
      ctx.globalAlpha = 1;
      drawHeader(ctx, view, colW);
    }

    function click(x, y) {
      const i = Math.floor((y - HEADER_H) / ROW_H);
      if (i >= 0 && i < resources.length) select("resource", resources[i].name);
    }

    return { width: width, height: height, fitHeight: 420, draw: draw, click: click };
  }

  // Bands: a heap, or one physical texture or buffer that the plan creates on its own. Each
  // band lists the rectangles of the resources living in it: positions in the order across,
  // bytes down.
  function memoryBands() {
    const plan = model.plan;
    const bands = plan.heaps.map((bytes, heap) => ({ label: "heap " + heap, bytes: bytes, rects: [] }));
    const add = (object, isBuffer) => {
      let band;
      let offset = 0;
      if (object.heap !== undefined) {
        band = bands[object.heap];
        offset = object.offset;
      } else {
        band = { label: object.name, bytes: object.bytes, rects: [] };
        bands.push(band);
      }
      for (const index of object.resources) {
        const r = model.resources[index];
        band.rects.push({ resource: r, physical: object, first: r.occupancy[0], last: r.occupancy[1], offset: offset, bytes: object.bytes, overlap: false });
      }
    };
    plan.textures.forEach((t) => add(t, false));
    plan.buffers.forEach((b) => add(b, true));
    return bands;
  }

  // Two resources overlap when they hold the same bytes of a band at the same position in the
  // order: an allocator bug, drawn in red. A sweep along the order: each rectangle is compared
  // only with those still alive where it starts (few, unless many resources live at once).
  function checkOverlaps(bands) {
    let overlaps = 0;
    const examples = [];
    for (const band of bands) {
      const rects = band.rects.slice().sort((a, b) => a.first - b.first);
      let alive = [];
      for (const rect of rects) {
        alive = alive.filter((other) => other.last >= rect.first);
        for (const other of alive) {
          if (rect.offset < other.offset + other.bytes && other.offset < rect.offset + rect.bytes) {
            rect.overlap = other.overlap = true;
            overlaps += 1;
            if (examples.length < 3) examples.push(other.resource.name + " and " + rect.resource.name);
          }
        }
        alive.push(rect);
      }
    }
    return { overlaps: overlaps, examples: examples };
  }

  function memoryView() {
    const colW = columnWidth();
    const bands = memoryBands();
    model.overlapCheck = checkOverlaps(bands);
    model.rectCount = bands.reduce((sum, band) => sum + band.rects.length, 0);
    const total = bands.reduce((sum, band) => sum + band.bytes, 0) || 1;
    // About 360 pixels for all the bytes, but at least 10 per band so that every band shows.
    const GAP = 4;
    let y = HEADER_H;
    for (const band of bands) {
      band.y = y;
      band.h = Math.max(10, Math.round((360 * band.bytes) / total));
      y += band.h + GAP;
    }
    const width = LABEL_W + model.passes.length * colW + 10;
    const height = y + 4;

    function draw(ctx, view) {
      drawSelectedColumn(ctx, view, colW);
      ctx.font = "11px system-ui, sans-serif";
      ctx.textBaseline = "middle";
      const visible = bands.filter((band) => band.y + band.h >= view.y && band.y <= view.y + view.h);
      for (const band of visible) {
        ctx.fillStyle = "#eef0f4";
        ctx.fillRect(LABEL_W, band.y, model.passes.length * colW, band.h);
        for (const rect of band.rects) {
          const x = LABEL_W + rect.first * colW;
          if (x > view.x + view.w || LABEL_W + (rect.last + 1) * colW < view.x) continue;
          const top = band.y + (band.h * rect.offset) / (band.bytes || 1);
          const h = Math.max(1, (band.h * rect.bytes) / (band.bytes || 1));
          const w = (rect.last - rect.first + 1) * colW;
          ctx.globalAlpha = dimmed("resource", rect.resource.name) ? 0.2 : 1;
          ctx.fillStyle = physicalColour(rect.resource, 0.85);
          ctx.fillRect(x + 0.5, top + 0.5, w - 1, h - 1);
          const selected = selection.kind === "resource" && selection.name === rect.resource.name;
          if (rect.overlap || selected) {
            ctx.strokeStyle = rect.overlap ? "#d0021b" : "#111";
            ctx.lineWidth = 2;
            ctx.strokeRect(x + 1, top + 1, w - 2, h - 2);
          }
          if (w >= 40 && h >= 12) {
            ctx.fillStyle = "#fff";
            ctx.fillText(fitText(ctx, rect.resource.name, w - 6), x + 3, top + Math.min(h, 16) / 2);
          }
        }
        ctx.globalAlpha = 1;
      }
      ctx.fillStyle = "#fbfbfc";
      ctx.fillRect(view.x, view.y, LABEL_W - 4, view.h);
      ctx.fillStyle = "#1d2330";
      for (const band of visible) {
        ctx.fillText(fitText(ctx, band.label + "  " + formatBytes(band.bytes), LABEL_W - 10), view.x + 4, band.y + Math.min(band.h, 16) / 2);
      }
      drawHeader(ctx, view, colW);
    }

    function click(x, y) {
      const position = Math.floor((x - LABEL_W) / colW);
      for (const band of bands) {
        if (y < band.y || y > band.y + band.h) continue;
        for (const rect of band.rects) {
          const top = band.y + (band.h * rect.offset) / (band.bytes || 1);
          const h = Math.max(1, (band.h * rect.bytes) / (band.bytes || 1));
          if (position >= rect.first && position <= rect.last && y >= top && y <= top + h) {
            select("resource", rect.resource.name);
            return;
          }
        }
      }
    }

    return { width: width, height: height, fitHeight: 460, draw: draw, click: click };
  }

  function writeOverlapCheck() {
    const check = model.overlapCheck;
    const out = document.getElementById("overlap-check");
    out.dataset.overlaps = String(check.overlaps);
    out.dataset.rectangles = String(model.rectCount);
    if (check.overlaps) {
      out.className = "bad";
      out.textContent = "Check: " + check.overlaps + (check.overlaps === 1 ? " pair of resources shares" : " pairs of resources share") +
        " bytes at the same time (" + check.examples.join("; ") + "), outlined in red.";
    } else {
      out.className = "good";
      out.textContent = "Check: no two of the " + model.rectCount + " rectangles share bytes at the same time.";
    }
  }

  // ---- search and selection -------------------------------------------------------------------

  function onSearch(event) {
    clearTimeout(searchTimer);
    searchTimer = setTimeout(() => applySearch(event.target.value), 120);
  }

  function applySearch(text) {
    query = text.trim().toLowerCase();
    if (!query) {
      model.passMatch = null;
      model.resourceMatch = null;
    } else {
      model.passMatch = new Set();
      model.resourceMatch = new Set();
      for (const pass of model.passes.concat(model.culled)) if (pass.name.toLowerCase().includes(query)) model.passMatch.add(pass.name);
      for (const r of model.resources) if (r.name.toLowerCase().includes(query) || physicalOf(r).name.toLowerCase() === query) model.resourceMatch.add(r.name);
    }
    model.passList.setItems(model.passMatch === null ? model.allPasses : model.allPasses.filter((pass) => model.passMatch.has(pass.name)));
    model.resourceList.setItems(model.resourceMatch === null ? model.resources : model.resources.filter((r) => model.resourceMatch.has(r.name)));
    document.getElementById("search-result").textContent = query ? model.passMatch.size + " passes, " + model.resourceMatch.size + " resources" : "";
    redraw();
  }

  function redraw() {
    for (const view of Object.values(views)) view.later();
  }

  function selectFromHash() {
    const match = /^#(pass|resource)=(.*)$/.exec(location.hash);
    if (match) select(match[1], decodeURIComponent(match[2]), true);
  }

  function select(kind, name, fromHash) {
    const known = kind === "pass" ? model.passByName.has(name) : model.resourceByName.has(name);
    if (!known) return;
    selection.kind = kind;
    selection.name = name;
    if (!fromHash) history.replaceState(null, "", "#" + kind + "=" + encodeURIComponent(name));
    if (kind === "pass") model.passList.reveal(model.passByName.get(name));
    else model.resourceList.reveal(model.resourceByName.get(name));
    model.passList.draw();
    model.resourceList.draw();
    const body = document.getElementById("details-body");
    body.innerHTML = kind === "pass" ? passDetails(model.passByName.get(name)) : resourceDetails(model.resourceByName.get(name));
    body.dataset.selected = kind + ":" + name;
    if (kind === "pass") {
      const at = model.placeOfPass(model.passByName.get(name));
      if (at) views.graph.reveal(at.x, at.y);
    } else {
      const r = model.resourceByName.get(name);
      views.lifetimes.reveal(LABEL_W + r.lifetime[0] * model.lifetimeGeometry.colW, HEADER_H + r.index * model.lifetimeGeometry.rowH);
    }
    for (const view of Object.values(views)) view.render();
  }

  function onDetailsClick(event) {
    const link = event.target.closest("[data-link-pass], [data-link-resource]");
    if (!link) return;
    if (link.dataset.linkPass !== undefined) select("pass", link.dataset.linkPass);
    else select("resource", link.dataset.linkResource);
  }

  function passLink(name) {
    return '<span class="link" data-link-pass="' + esc(name) + '">' + esc(name) + "</span>";
  }

  function resourceLink(name) {
    return '<span class="link" data-link-resource="' + esc(name) + '">' + esc(name) + "</span>";
  }

  function definitionList(rows) {
    return "<dl>" + rows.map(([term, value]) => "<dt>" + esc(term) + "</dt><dd>" + value + "</dd>").join("") + "</dl>";
  }

  function passDetails(pass) {
    if (pass.culled) {
      return "<h3>" + esc(pass.name) + "</h3><p class=\"note\">Culled: nothing it writes is read by a pass that runs or " +
        "is a graph output, and it has no side effect, so it does not run and gets no resources.</p>";
    }
    const rows = [["position", String(pass.index) + " of " + model.passes.length], ["kind", esc(pass.kind)], ["queue", esc(pass.queue)],
      ["declared", "#" + pass.declaration_index], ["side effect", pass.side_effect ? "yes" : "no"]];
    const timing = model.timings.get(pass.name);
    if (timing) rows.push(["time", "CPU " + formatMs(timing.cpu_ms) + " ms, GPU " + formatMs(timing.gpu_ms) + " ms"]);
    let html = "<h3>" + esc(pass.name) + "</h3>" + definitionList(rows);

    // Two rows per port: what it is connected to, then the joined spec of that resource.
    html += "<h4>Ports</h4><table id=\"detail-ports\">";
    for (const port of pass.ports) {
      let resource = '<span class="note">no resource</span>';
      let spec = "";
      if (port.resource !== null) {
        const r = model.resources[port.resource];
        resource = resourceLink(r.name) + " · " + esc(physicalOf(r).name);
        spec = esc(describeSpec(r));
        if (r.requested_format) spec += " · asked " + esc(r.requested_format) + (r.format_match ? " (" + esc(r.format_match) + ")" : "");
        if (port.usage) spec += " · used as " + esc(port.usage.join(", "));
      }
      html += '<tr data-port="' + esc(port.name) + '"><td><b>' + esc(port.name) + "</b> <span class=\"note\">" + esc(port.kind) +
        (port.optional ? ", optional" : "") + "</span></td><td>" + resource + "</td></tr>" +
        (spec ? '<tr class="spec"><td colspan="2">' + spec + "</td></tr>" : "");
    }
    html += "</table>";

    const entry = model.schedule.get(pass.index);
    if (!model.hasSchedule) {
      html += "<h4>Barriers</h4><p class=\"note\">Not in this input (a plain plan): loom-plan --inspect and the samples' --inspect write them.</p>";
    } else if (entry) {
      const barrier = (t, when) => '<li data-barrier="' + when + '">' + esc(t.slot) + " → " + esc(t.state) +
        (t.range ? " <span class=\"note\">(" + esc(describeRange(t.range)) + ")</span>" : "") + "</li>";
      const before = entry.before.map((t) => barrier(t, "before")).concat(entry.buffers_before.map((t) => barrier(t, "before")));
      const after = entry.after.map((t) => barrier(t, "after")).concat(entry.buffers_after.map((t) => barrier(t, "after")));
      html += "<h4>Barriers before</h4>" + (before.length ? "<ul>" + before.join("") + "</ul>" : "<p class=\"note\">none (attachments change state as the render pass begins)</p>");
      html += "<h4>Barriers after</h4>" + (after.length ? "<ul>" + after.join("") + "</ul>" : "<p class=\"note\">none</p>");
      html += "<h4>Load and store</h4><table><tr><th>port</th><th>texture</th><th>load</th><th>store</th></tr>";
      for (const port of entry.ports) {
        html += "<tr><td>" + esc(port.name) + "</td><td>" + esc(port.slot) + "</td><td>" + esc(port.load) + (port.first_write ? " (first write)" : "") +
          "</td><td>" + esc(port.store) + "</td></tr>";
      }
      html += "</table>";
      if (entry.copies.length) {
        html += "<h4>History copies after</h4><ul>" + entry.copies.map((c) => "<li>" + esc(c.source) + " → history " + c.history + "</li>").join("") + "</ul>";
      }
    }

    const syncs = model.plan.queue_syncs.filter((s) => s.signal_after === pass.index || s.wait_before === pass.index);
    const transfers = model.plan.ownership_transfers.filter((t) => t.release_after === pass.index || t.acquire_before === pass.index);
    if (syncs.length || transfers.length) {
      html += "<h4>Between queues</h4><ul>";
      for (const s of syncs) {
        html += "<li>" + (s.signal_after === pass.index ? "signals " + esc(s.to) + " after it" : "waits for " + esc(s.from) + " (signalled after " +
          (s.signal_pass ? esc(s.signal_pass) : "the frame's start") + ")") + "</li>";
      }
      for (const t of transfers) {
        html += "<li>" + resourceLink(t.resource_name) + (t.release_after === pass.index ? " released to " + esc(t.to) + " after it" : " acquired from " + esc(t.from) + " before it") + "</li>";
      }
      html += "</ul>";
    }
    return html;
  }

  function resourceDetails(r) {
    const physical = physicalOf(r);
    const rows = [["type", esc(r.type)], ["spec", esc(describeSpec(r))], ["bytes", esc(formatBytes(r.bytes))],
      ["physical", esc(physical.name) + " (" + esc(formatBytes(physical.bytes)) + (physical.heap !== undefined ? ", heap " + physical.heap + " at " + physical.offset : "") +
        ", shared by " + physical.resources.length + ")"],
      ["lifetime", "passes " + r.lifetime[0] + "–" + r.lifetime[1] + " (" + passLink(model.passes[r.lifetime[0]].name) + " to " + passLink(model.passes[r.lifetime[1]].name) + ")"]];
    if (r.occupancy[0] !== r.lifetime[0] || r.occupancy[1] !== r.lifetime[1]) rows.push(["held", "passes " + r.occupancy[0] + "–" + r.occupancy[1]]);
    if (r.requested_format) rows.push(["asked", esc(r.requested_format)]);
    if (r.format_match) rows.push(["format match", esc(r.format_match)]);
    if (r.usage) rows.push(["usage", esc(r.usage.join(", "))]);
    if (r.graph_output) rows.push(["graph output", "yes: lives until the frame ends"]);
    if (r.queue_shared) rows.push(["queues", "shared by both queue families"]);
    let html = "<h3>" + esc(r.name) + "</h3>" + definitionList(rows);
    html += "<h4>Ports on it</h4><ul>" + r.ports.map((name) => {
      const dot = name.lastIndexOf(".");
      return "<li>" + passLink(name.slice(0, dot)) + esc(name.slice(dot)) + "</li>";
    }).join("") + "</ul>";
    return html;
  }

  // Last, once every declaration above has run.
  try {
    main();
  } catch (error) {
    window.loomErrors.push(String((error && error.stack) || error));
  }
  finish();
})();
