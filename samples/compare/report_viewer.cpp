#include "report_viewer.hpp"

namespace loom::compare::viewer {

const char* const kStyle = R"viewer(
.pictures figure a { cursor: zoom-in; }
body.viewing { overflow: hidden; }
#viewer { position: fixed; inset: 0; display: flex; flex-direction: column; background: #1b1d21; color: #e8e8e8; z-index: 10; }
#viewer[hidden], #viewer img[hidden] { display: none; }
#viewer-bar { display: flex; flex-wrap: wrap; align-items: center; gap: 6px 14px; padding: 6px 10px; background: #2a2d33; font-size: 0.9em; }
#viewer-bar button { font: inherit; color: inherit; background: #3a3e46; border: 1px solid #555; border-radius: 3px; padding: 1px 8px; cursor: pointer; }
#viewer-bar button.current { background: #4f7fdc; border-color: #8fb0f0; }
#viewer-bar button:disabled { opacity: 0.4; cursor: default; }
#viewer-title { font-weight: bold; }
#viewer-pixel { font-family: monospace; min-width: 9em; }
#viewer-help { color: #9aa0a8; }
#viewer-stage { position: relative; flex: 1; display: flex; overflow: auto; cursor: crosshair; }
#viewer-canvas { position: relative; flex: none; margin: auto; }
#viewer-canvas img { position: absolute; left: 0; top: 0; width: 100%; height: 100%; image-rendering: pixelated; }
)viewer";

const char* const kErrorCollector = R"viewer(<script>
window.loomErrors = [];
window.addEventListener("error", function (event) { window.loomErrors.push(String(event.message)); });
</script>
)viewer";

const char* const kBody = R"viewer(<div id="viewer" hidden>
<div id="viewer-bar">
  <span id="viewer-title"></span>
  <span id="viewer-images"></span>
  <span><button type="button" id="viewer-flip" title="flip between the backends (F or space)">flip</button>
  <label title="flip twice a second (B)"><input type="checkbox" id="viewer-blink"> blink</label></span>
  <span><button type="button" id="viewer-zoom-out" title="zoom out (-)">−</button> <span id="viewer-zoom"></span>
  <button type="button" id="viewer-zoom-in" title="zoom in (+)">+</button>
  <button type="button" id="viewer-fit" title="the whole picture (0)">fit</button></span>
  <span id="viewer-pixel"></span>
  <span id="viewer-help">← → case · wheel zooms · drag pans</span>
  <button type="button" id="viewer-close" title="back to the report (Esc)">close</button>
</div>
<div id="viewer-stage"><div id="viewer-canvas"></div></div>
</div>
<script>
"use strict";
(function () {
  // Whole steps above 1 keep every pixel a square of whole screen pixels.
  const ZOOMS = [0.125, 0.25, 0.5, 1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64];
  const viewer = document.getElementById("viewer");
  const stage = document.getElementById("viewer-stage");
  const canvas = document.getElementById("viewer-canvas");
  const buttons = document.getElementById("viewer-images");
  const flipButton = document.getElementById("viewer-flip");
  const blink = document.getElementById("viewer-blink");
  const zoomText = document.getElementById("viewer-zoom");
  const pixelText = document.getElementById("viewer-pixel");

  // Every case with pictures, in report order.
  const cases = Array.from(document.querySelectorAll(".pictures[data-case]")).map((div) => ({
    id: div.dataset.case,
    title: div.dataset.title,
    images: Array.from(div.querySelectorAll("figure[data-image]")).map((figure) => ({
      key: figure.dataset.image,
      label: figure.dataset.label,
      src: figure.querySelector("img").getAttribute("src"),
      backend: figure.hasAttribute("data-backend"),
    })),
  })).filter((c) => c.images.length > 0);
  // zoom: a step of ZOOMS, or "fit"; width and height: the pictures' pixels, once one loaded.
  const state = { index: -1, key: null, zoom: "fit", width: 0, height: 0, timer: 0 };

  function current() { return cases[state.index]; }

  function open(id, key, zoom) {
    const index = cases.findIndex((c) => c.id === id);
    if (index < 0) return;
    const c = cases[index];
    state.index = index;
    state.zoom = zoom;
    viewer.dataset.case = c.id;
    state.width = 0;
    state.height = 0;
    document.getElementById("viewer-title").textContent = c.title;
    buttons.textContent = "";
    canvas.textContent = "";
    c.images.forEach((image, n) => {
      const button = document.createElement("button");
      button.type = "button";
      button.dataset.image = image.key;
      button.title = image.label + " (" + (n + 1) + ")";
      button.textContent = (n + 1) + " " + image.label;
      button.addEventListener("click", () => show(image.key));
      buttons.appendChild(button);
      const img = document.createElement("img");
      img.dataset.image = image.key;
      img.alt = image.label;
      img.draggable = false;
      img.addEventListener("load", () => {
        if (state.width === 0) {
          state.width = img.naturalWidth;
          state.height = img.naturalHeight;
          applyZoom();
        }
      });
      img.src = image.src;
      canvas.appendChild(img);
    });
    flipButton.disabled = backends().length < 2;
    viewer.hidden = false;
    document.body.classList.add("viewing");
    show(c.images.some((image) => image.key === key) ? key : c.images[0].key);
    applyZoom();
  }

  function close() {
    if (viewer.hidden) return;
    setBlink(false);
    viewer.hidden = true;
    document.body.classList.remove("viewing");
    const id = current().id;
    history.replaceState(null, "", "#" + encodeURIComponent(id));
    const block = document.getElementById(id);
    if (block) block.scrollIntoView();
  }

  function show(key) {
    state.key = key;
    for (const img of canvas.children) img.hidden = img.dataset.image !== key;
    for (const button of buttons.children) button.classList.toggle("current", button.dataset.image === key);
    viewer.dataset.image = key;
    remember();
  }

  function backends() { return current().images.filter((image) => image.backend); }

  // The next backend's picture; from a difference picture, the first backend's.
  function flip() {
    const list = backends();
    if (list.length < 2) return;
    const at = list.findIndex((image) => image.key === state.key);
    show(list[(at + 1) % list.length].key);
  }

  function setBlink(on) {
    blink.checked = on;
    clearInterval(state.timer);
    state.timer = on ? setInterval(flip, 500) : 0;
  }

  // The step in use: "fit" is the largest step at which the whole picture shows.
  function scale() {
    if (state.zoom !== "fit") return state.zoom;
    let best = ZOOMS[0];
    for (const step of ZOOMS) {
      if (state.width * step <= stage.clientWidth && state.height * step <= stage.clientHeight) best = step;
    }
    return best;
  }

  function applyZoom() {
    viewer.dataset.zoom = String(state.zoom);
    remember();
    if (state.width === 0) return;
    const step = scale();
    canvas.style.width = state.width * step + "px";
    canvas.style.height = state.height * step + "px";
    zoomText.textContent = (step >= 1 ? step : "1/" + 1 / step) + "×" + (state.zoom === "fit" ? " (fit)" : "");
  }

  // One step in or out, keeping the picture's point under (x, y) (the stage's centre) in place.
  function zoomBy(steps, clientX, clientY) {
    if (state.width === 0) return;
    const from = scale();
    const to = ZOOMS[Math.max(0, Math.min(ZOOMS.length - 1, ZOOMS.indexOf(from) + steps))];
    if (to === from) return;
    const box = stage.getBoundingClientRect();
    const px = clientX === undefined ? box.width / 2 : clientX - box.left;
    const py = clientY === undefined ? box.height / 2 : clientY - box.top;
    const x = (stage.scrollLeft + px - canvas.offsetLeft) / from;
    const y = (stage.scrollTop + py - canvas.offsetTop) / from;
    state.zoom = to;
    applyZoom();
    stage.scrollLeft = x * to + canvas.offsetLeft - px;
    stage.scrollTop = y * to + canvas.offsetTop - py;
  }

  function remember() {
    if (viewer.hidden || state.index < 0) return;
    history.replaceState(null, "", "#view=" + encodeURIComponent(current().id) + "&image=" + encodeURIComponent(state.key) +
      "&zoom=" + state.zoom);
  }

  function fromAddress() {
    const params = new URLSearchParams(location.hash.slice(1));
    const id = params.get("view");
    if (id === null) {
      close();
      return;
    }
    const asked = Number(params.get("zoom"));
    // The nearest step to a zoom asked for; "fit" for none.
    const zoom = ZOOMS.includes(asked) ? asked : asked > 0 ? ZOOMS.reduce((a, b) => Math.abs(b - asked) < Math.abs(a - asked) ? b : a) : "fit";
    open(id, params.get("image"), zoom);
  }

  for (const figure of document.querySelectorAll(".pictures[data-case] figure[data-image]")) {
    figure.querySelector("a").addEventListener("click", (event) => {
      if (event.button !== 0 || event.ctrlKey || event.metaKey || event.shiftKey) return;  // a new tab: the file itself
      event.preventDefault();
      open(figure.closest(".pictures").dataset.case, figure.dataset.image, "fit");
    });
  }
  flipButton.addEventListener("click", flip);
  blink.addEventListener("change", () => setBlink(blink.checked));
  document.getElementById("viewer-zoom-in").addEventListener("click", () => zoomBy(1));
  document.getElementById("viewer-zoom-out").addEventListener("click", () => zoomBy(-1));
  document.getElementById("viewer-fit").addEventListener("click", () => { state.zoom = "fit"; applyZoom(); });
  document.getElementById("viewer-close").addEventListener("click", close);
  window.addEventListener("resize", () => { if (!viewer.hidden) applyZoom(); });
  window.addEventListener("hashchange", fromAddress);

  document.addEventListener("keydown", (event) => {
    if (viewer.hidden || event.ctrlKey || event.metaKey || event.altKey) return;
    const c = current();
    const key = event.key;
    if (key === "Escape") close();
    else if (key >= "1" && key <= "9" && Number(key) <= c.images.length) show(c.images[Number(key) - 1].key);
    else if (key === "f" || key === " ") flip();
    else if (key === "b") setBlink(!blink.checked);
    else if (key === "+" || key === "=") zoomBy(1);
    else if (key === "-") zoomBy(-1);
    else if (key === "0") { state.zoom = "fit"; applyZoom(); }
    else if (key === "ArrowLeft" || key === "ArrowRight") {
      const next = cases[(state.index + (key === "ArrowRight" ? 1 : cases.length - 1)) % cases.length];
      open(next.id, state.key, state.zoom);
    } else return;
    event.preventDefault();
  });

  // Wheel: zoom at the pointer; drag: pan; moving: the pixel under the pointer.
  stage.addEventListener("wheel", (event) => {
    event.preventDefault();
    zoomBy(event.deltaY < 0 ? 1 : -1, event.clientX, event.clientY);
  }, { passive: false });
  let drag = null;
  stage.addEventListener("pointerdown", (event) => {
    drag = { x: event.clientX, y: event.clientY, left: stage.scrollLeft, top: stage.scrollTop };
    stage.setPointerCapture(event.pointerId);
  });
  stage.addEventListener("pointerup", () => { drag = null; });
  stage.addEventListener("pointermove", (event) => {
    if (drag) {
      stage.scrollLeft = drag.left - (event.clientX - drag.x);
      stage.scrollTop = drag.top - (event.clientY - drag.y);
    }
    if (state.width === 0) return;
    const box = canvas.getBoundingClientRect();
    const step = scale();
    const x = Math.floor((event.clientX - box.left) / step);
    const y = Math.floor((event.clientY - box.top) / step);
    pixelText.textContent = x >= 0 && y >= 0 && x < state.width && y < state.height ? "pixel " + x + ", " + y : "";
  });

  fromAddress();
})();
</script>
<script>
// Last: how the page's scripts went, for the headless browser test.
document.body.dataset.errors = String(window.loomErrors.length);
document.body.dataset.status = window.loomErrors.length ? "error" : "ok";
</script>
)viewer";

}  // namespace loom::compare::viewer
