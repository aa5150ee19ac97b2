// The inspector's pages opened in headless Chromium: the page's script must finish without an
// error (the page writes data-status and data-errors on <body>) and show exactly the plan's
// passes and resources, its timings, memory figures and the selected pass's barriers.
#include <algorithm>
#include <iostream>
#include <stdexcept>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "inspect_page.hpp"
#include "inspect_test_support.hpp"
#include "loom_test/test_support.hpp"

namespace {

using namespace loom::inspect_test;
using nlohmann::json;

std::string graph(std::string_view name) { return quoted(std::filesystem::path(LOOM_PLAN_GRAPHS) / name); }

// The part of the DOM from the element `id` to the end of its list (the lists are <ol>s).
std::string_view list_of(std::string_view dom, std::string_view id) {
    std::string_view from = from_element(dom, id);
    return from.substr(0, from.find("</ol>"));
}

std::vector<std::string> names(const json& array, const char* key = nullptr) {
    std::vector<std::string> out;
    for (const json& item : array) out.push_back(key ? item.at(key).get<std::string>() : item.get<std::string>());
    return out;
}

// Opens the page and checks that its script ran to the end without an error.
std::string open_page(const std::string& chromium, const std::filesystem::path& page, std::string_view fragment) {
    const loom::test::PageDump dump = dump_dom(chromium, page, fragment, page.parent_path());
    EXPECT_EQ(dump.status, 0) << dump.log;
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-status"), "ok") << from_element(dump.dom, "errors").substr(0, 2000);
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-errors"), "0");
    return dump.dom;
}

TEST(InspectPage, Figure2ShowsEveryPassResourceTimingAndAllocator) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    const ToolRun plan_json = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --json");
    ASSERT_EQ(plan_json.status, 0) << plan_json.err;
    const json plan = json::parse(plan_json.out);
    // Timings as a sample records them; the deferred pass has no GPU time yet.
    write_file(dir / "timings.json", R"([{"pass": "shadow", "cpu_ms": 0.25, "gpu_ms": 1.5},
                                         {"pass": "geometry", "cpu_ms": 0.5, "gpu_ms": 2.0},
                                         {"pass": "deferred", "cpu_ms": 0.125, "gpu_ms": null},
                                         {"pass": "blur", "cpu_ms": 0.0625, "gpu_ms": 0.75},
                                         {"pass": "composite", "cpu_ms": 0.03125, "gpu_ms": 0.5}])");
    const ToolRun made = run(LOOM_INSPECT_TOOL, graph("figure2.json") + " --timings " + quoted(dir / "timings.json") +
                                                    " --out " + quoted(dir / "figure2.html"));
    ASSERT_EQ(made.status, 0) << made.err;

    const std::string dom = open_page(chromium, dir / "figure2.html", "");
    EXPECT_EQ(attribute_values(list_of(dom, "pass-list"), "data-pass"), names(plan.at("order")));
    EXPECT_EQ(attribute_values(list_of(dom, "resource-list"), "data-resource"), names(plan.at("resources"), "name"));
    const std::string_view timings = from_element(dom, "timing-table");
    EXPECT_EQ(attribute_values(timings.substr(0, timings.find("</table>")), "data-timing"),
              (std::vector<std::string>{"shadow", "geometry", "deferred", "blur", "composite"}));
    const std::string_view memory = from_element(dom, "memory-bars");
    const std::string_view bars = memory.substr(0, memory.find("</table>"));
    EXPECT_EQ(attribute_values(bars, "data-memory"),
              (std::vector<std::string>{"naive", "paper", "interval", "heap", "lower-bound"}));
    EXPECT_EQ(attribute_values(bars, "data-bytes")[0], std::to_string(plan.at("summary").at("naive_bytes").get<uint64_t>()));
    EXPECT_EQ(attribute_values(bars, "data-bytes")[2], std::to_string(plan.at("summary").at("bytes").get<uint64_t>()));
    EXPECT_EQ(attribute_values(from_element(dom, "overlap-check").substr(0, 200), "data-overlaps"), std::vector<std::string>{"0"});
}

TEST(InspectPage, AsyncHeapFrameShowsTheSelectedPassesPortsAndBarriers) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    const ToolRun planned = run(LOOM_PLAN_TOOL, graph("unreal_deferred_frame.json") + " --allocator heap --inspect " +
                                                    quoted(dir / "input.json"));
    ASSERT_EQ(planned.status, 0) << planned.err;
    const json input = json::parse(read_file(dir / "input.json"));
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "input.json") + " --out " + quoted(dir / "frame.html"));
    ASSERT_EQ(made.status, 0) << made.err;

    // The first pass with barriers before and after it, if any, else before it.
    const json& schedule = input.at("schedule");
    std::size_t chosen = schedule.size();
    for (std::size_t i = 0; i < schedule.size() && chosen == schedule.size(); ++i) {
        if (!schedule[i].at("before").empty()) chosen = i;
    }
    ASSERT_LT(chosen, schedule.size()) << "the frame has no pass with barriers";
    const json& entry = schedule[chosen];
    const json& pass = input.at("plan").at("passes")[chosen];
    const std::string name = pass.at("name");

    const std::string dom = open_page(chromium, dir / "frame.html", "#pass=" + name);
    const json& plan = input.at("plan");
    EXPECT_EQ(attribute_values(list_of(dom, "pass-list"), "data-pass"), names(plan.at("order")));
    EXPECT_EQ(attribute_values(list_of(dom, "resource-list"), "data-resource"), names(plan.at("resources"), "name"));
    // The heap placements never share bytes at the same time.
    EXPECT_EQ(attribute_values(from_element(dom, "overlap-check").substr(0, 200), "data-overlaps"), std::vector<std::string>{"0"});

    const std::string_view details = from_element(dom, "details-body");
    EXPECT_EQ(attribute_values(details.substr(0, details.find('>')), "data-selected"), std::vector<std::string>{"pass:" + name});
    const std::string_view ports = from_element(details, "detail-ports");
    EXPECT_EQ(attribute_values(ports.substr(0, ports.find("</table>")), "data-port"), names(pass.at("ports"), "name"));
    const auto barriers = attribute_values(details.substr(0, details.find("</aside>")), "data-barrier");
    const std::size_t before = entry.at("before").size() + entry.at("buffers_before").size();
    const std::size_t after = entry.at("after").size() + entry.at("buffers_after").size();
    EXPECT_EQ(std::count(barriers.begin(), barriers.end(), "before"), static_cast<long>(before));
    EXPECT_EQ(std::count(barriers.begin(), barriers.end(), "after"), static_cast<long>(after));
    // The first barrier as the schedule has it: its texture and state.
    const std::string first = entry.at("before")[0].at("slot").get<std::string>() + " → " + entry.at("before")[0].at("state").get<std::string>();
    EXPECT_NE(details.substr(0, details.find("</aside>")).find(first), std::string_view::npos) << first;
}

TEST(InspectPage, MemoryMapFlagsResourcesThatShareBytesAtOnce) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    const ToolRun planned = run(LOOM_PLAN_TOOL, graph("figure2.json") + " --allocator heap --json");
    ASSERT_EQ(planned.status, 0) << planned.err;
    json plan = json::parse(planned.out);
    // A broken placement: geometry.normal's texture moved onto geometry.position's bytes while
    // both are alive (the G-buffer is written by one pass and read by the next).
    const auto texture_of = [&](std::string_view name) -> json& {
        for (const json& r : plan.at("resources")) {
            if (r.at("name") == name) return plan.at("textures")[r.at("texture").get<std::size_t>()];
        }
        throw std::runtime_error("no resource " + std::string(name));
    };
    ASSERT_TRUE(texture_of("geometry.position").contains("offset"));
    texture_of("geometry.normal")["offset"] = texture_of("geometry.position").at("offset");
    write_file(dir / "broken.json", plan.dump());
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "broken.json") + " --out " + quoted(dir / "broken.html"));
    ASSERT_EQ(made.status, 0) << made.err;

    const std::string dom = open_page(chromium, dir / "broken.html", "");
    const std::string_view check = from_element(dom, "overlap-check");
    EXPECT_EQ(attribute_values(check.substr(0, 200), "data-overlaps"), std::vector<std::string>{"1"});
    EXPECT_NE(check.substr(0, check.find("</span>")).find("geometry.position and geometry.normal"), std::string_view::npos)
        << check.substr(0, 400);
}

// Names as a hand-edited plan may have them, with markup and characters beyond ASCII: the page
// is compressed and escaped on the way, and must show them exactly as written.
TEST(InspectPage, NamesWithMarkupAndNonAsciiCharactersShowAsWritten) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    // The Figure 2 graph with two passes renamed, everywhere their names and ports appear.
    const std::vector<std::pair<std::string, std::string>> renamed = {
        {"shadow", "shadow</script><script>alert(1)</script><!--"},
        {"geometry", "g\u00e9om\u00e9trie \u2192 G-Puffer \u51e0\u4f55 \U0001f3a8"}};
    const auto rename = [&](auto& self, json& value) -> void {
        if (value.is_structured()) {
            for (json& item : value) self(self, item);
        } else if (value.is_string()) {
            const std::string text = value;
            for (const auto& [from, to] : renamed) {
                if (text == from || text.starts_with(from + ".")) value = to + text.substr(from.size());
            }
        }
    };
    json graph_file = json::parse(read_file(std::filesystem::path(LOOM_PLAN_GRAPHS) / "figure2.json"));
    rename(rename, graph_file);
    write_file(dir / "names.json", graph_file.dump());
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "names.json") + " --out " + quoted(dir / "names.html"));
    ASSERT_EQ(made.status, 0) << made.err;

    const std::string dom = open_page(chromium, dir / "names.html", "");
    const std::vector<std::string> shown = attribute_values(list_of(dom, "pass-list"), "data-pass");
    ASSERT_EQ(shown.size(), 5u);
    EXPECT_EQ(shown[0], renamed[0].second);
    EXPECT_EQ(shown[1], renamed[1].second);
    EXPECT_EQ(shown[2], "deferred");
}

// The page's inflater (page/inflate.js) on its own, in the browser, against streams zlib wrote
// with each kind of block, and on streams it must refuse.
TEST(InspectPage, InflaterReadsEveryKindOfBlockZlibWritesAndRefusesBrokenStreams) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    std::string text;
    for (int i = 0; i < 4000; ++i) text += "{\"pass\":\"p" + std::to_string(i) + "\",\"reads\":" + std::to_string(i * 7 % 13) + "},";
    std::string noise;  // incompressible: zlib stores it
    uint32_t state = 12345;
    for (int i = 0; i < 30000; ++i) {
        state = state * 1664525u + 1013904223u;
        noise += static_cast<char>(state >> 24);
    }
    std::string every_byte;
    for (int i = 0; i < 256; ++i) every_byte += static_cast<char>(i);
    struct Vector {
        std::string name;
        std::string bytes;
        std::string stream;
    };
    using loom::inspect::deflate_raw;
    const std::vector<Vector> good = {
        {"empty", "", deflate_raw("")},
        {"stored", text, deflate_raw(text, 0)},
        {"fixed", text, deflate_raw(text, 6, Z_FIXED)},
        {"dynamic", text, deflate_raw(text, 9)},
        {"huffman-only", text, deflate_raw(text, 6, Z_HUFFMAN_ONLY)},
        {"run-length", std::string(100000, 'a'), deflate_raw(std::string(100000, 'a'), 6, Z_RLE)},
        {"incompressible", noise, deflate_raw(noise)},
        // Matches 30,000 bytes back: the longest distance codes, with 13 extra bits.
        {"far", noise + noise + every_byte, deflate_raw(noise + noise + every_byte, 9)},
    };
    nlohmann::json cases = nlohmann::json::array();
    for (const Vector& v : good) {
        cases.push_back({{"name", v.name}, {"stream", loom::inspect::base64(v.stream)}, {"bytes", loom::inspect::base64(v.bytes)},
                         {"size", v.bytes.size()}});
    }
    const std::string dynamic = deflate_raw(text, 9);
    const std::string_view reserved = "\x07", bad_stored_length = std::string_view("\x01\x05\x00\x00\x00", 5);
    const nlohmann::json broken = {
        {{"name", "truncated"}, {"stream", loom::inspect::base64(dynamic.substr(0, dynamic.size() - 2))}, {"size", text.size()}},
        {{"name", "longer than said"}, {"stream", loom::inspect::base64(dynamic)}, {"size", text.size() - 1}},
        {{"name", "shorter than said"}, {"stream", loom::inspect::base64(dynamic)}, {"size", text.size() + 1}},
        {{"name", "reserved block type"}, {"stream", loom::inspect::base64(reserved)}, {"size", 1}},
        {{"name", "bad stored length"}, {"stream", loom::inspect::base64(bad_stored_length)}, {"size", 5}},
    };
    const std::string inflate_js = read_file(std::filesystem::path(LOOM_INSPECT_PAGE_DIR) / "inflate.js");
    ASSERT_FALSE(inflate_js.empty());
    const std::string runner = R"(
window.loomErrors = [];
window.addEventListener("error", (event) => window.loomErrors.push(String(event.message)));
function bytes(text) { const b = atob(text); const out = new Uint8Array(b.length); for (let i = 0; i < b.length; ++i) out[i] = b.charCodeAt(i); return out; }
function result(name, text) { const li = document.createElement("li"); li.dataset.vector = name; li.dataset.result = text; document.getElementById("results").appendChild(li); }
)";
    const std::string checks = R"(
for (const c of GOOD) {
  try {
    const out = loomInflate(bytes(c.stream), c.size);
    const expected = bytes(c.bytes);
    let same = out.length === expected.length;
    for (let i = 0; same && i < out.length; ++i) same = out[i] === expected[i];
    result(c.name, same ? "ok" : "differs");
  } catch (error) { result(c.name, "threw: " + error.message); }
}
for (const c of BROKEN) {
  try { loomInflate(bytes(c.stream), c.size); result(c.name, "accepted"); } catch (error) { result(c.name, "refused"); }
}
document.body.dataset.errors = String(window.loomErrors.length);
)";
    write_file(dir / "inflate.html", "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><script>" + runner + "</script></head><body>"
                                     "<ul id=\"results\"></ul>\n<script>\n" + inflate_js + "\n</script>\n<script>\nconst GOOD = " +
                                     cases.dump() + ";\nconst BROKEN = " + broken.dump() + ";\n" + checks + "</script></body></html>\n");

    const loom::test::PageDump dump = dump_dom(chromium, dir / "inflate.html", "", dir);
    ASSERT_EQ(dump.status, 0) << dump.log;
    EXPECT_EQ(attribute_of(dump.dom, "body", "data-errors"), "0");
    std::string_view results = from_element(dump.dom, "results");
    results = results.substr(0, results.find("</ul>"));
    std::vector<std::string> expected_names, expected_results;
    for (const Vector& v : good) {
        expected_names.push_back(v.name);
        expected_results.push_back("ok");
    }
    for (const nlohmann::json& b : broken) {
        expected_names.push_back(b.at("name"));
        expected_results.push_back("refused");
    }
    EXPECT_EQ(attribute_values(results, "data-vector"), expected_names);
    EXPECT_EQ(attribute_values(results, "data-result"), expected_results);
}

// A chain of passes, every third one also reading the pass seven back, and one pass in a
// hundred whose output nobody reads (culled): ten thousand passes that run.
json big_graph(int passes) {
    json list = json::array();
    json connections = json::array();
    for (int i = 0; i < passes; ++i) {
        json pass = {{"name", "p" + std::to_string(i)},
                     {"outputs", {{{"name", "out"}, {"format", "RGBA8"}, {"size", {16, 16}}}}}};
        json inputs = json::array();
        if (i > 0) {
            inputs.push_back({{"name", "a"}});
            connections.push_back({"p" + std::to_string(i - 1) + ".out", "p" + std::to_string(i) + ".a"});
        }
        if (i >= 7 && i % 3 == 0) {
            inputs.push_back({{"name", "b"}});
            connections.push_back({"p" + std::to_string(i - 7) + ".out", "p" + std::to_string(i) + ".b"});
        }
        if (!inputs.empty()) pass["inputs"] = inputs;
        list.push_back(pass);
    }
    for (int i = 0; i < passes / 100; ++i) {
        list.push_back({{"name", "unused" + std::to_string(i)},
                        {"inputs", {{{"name", "in"}}}},
                        {"outputs", {{{"name", "out"}, {"format", "RGBA8"}, {"size", {16, 16}}}}}});
        connections.push_back({"p" + std::to_string(i * 50) + ".out", "unused" + std::to_string(i) + ".in"});
    }
    return {{"passes", list}, {"connections", connections}, {"outputs", {"p" + std::to_string(passes - 1) + ".out"}}};
}

// Every graph loom-plan ships opens: the script finishes without an error and the lists hold
// the plan's passes (culled ones last) and resources in order.
TEST(InspectPage, EverySampleGraphOpensWithItsPassesAndResources) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    std::vector<std::filesystem::path> graphs;
    for (const auto& entry : std::filesystem::directory_iterator(LOOM_PLAN_GRAPHS)) {
        if (entry.path().extension() == ".json") graphs.push_back(entry.path());
    }
    std::sort(graphs.begin(), graphs.end());
    ASSERT_GE(graphs.size(), 10u);
    for (const std::filesystem::path& file : graphs) {
        SCOPED_TRACE(file.filename().string());
        const ToolRun plan_json = run(LOOM_PLAN_TOOL, quoted(file) + " --json");
        ASSERT_EQ(plan_json.status, 0) << plan_json.err;
        const json plan = json::parse(plan_json.out);
        const std::filesystem::path page = dir / (file.stem().string() + ".html");
        const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(file) + " --out " + quoted(page));
        ASSERT_EQ(made.status, 0) << made.err;
        const std::string dom = open_page(chromium, page, "");
        // The passes that run, then the culled ones (shown faded).
        std::vector<std::string> passes = names(plan.at("order"));
        for (const std::string& culled : names(plan.at("culled"))) passes.push_back(culled);
        EXPECT_EQ(attribute_values(list_of(dom, "pass-list"), "data-pass"), passes);
        EXPECT_EQ(attribute_values(list_of(dom, "resource-list"), "data-resource"), names(plan.at("resources"), "name"));
        EXPECT_EQ(attribute_values(from_element(dom, "overlap-check").substr(0, 200), "data-overlaps"),
                  std::vector<std::string>{"0"});
    }
}

// The frames the samples record with --inspect open with every pass, a timing row per pass and
// the device's allocations.
void check_sample_page(const std::string& chromium, const std::string& program, const std::string& arguments) {
    const auto dir = test_dir();
    const ToolRun rendered = run(program, "--backend gl --out " + quoted(dir / "out") + " --inspect " + quoted(dir / "in.json") + " " + arguments);
    ASSERT_EQ(rendered.status, 0) << rendered.err;
    const json input = json::parse(read_file(dir / "in.json"));
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "in.json") + " --out " + quoted(dir / "page.html"));
    ASSERT_EQ(made.status, 0) << made.err;
    const std::string dom = open_page(chromium, dir / "page.html", "");
    const std::vector<std::string> passes = names(input.at("plan").at("order"));
    EXPECT_EQ(attribute_values(list_of(dom, "pass-list"), "data-pass"), passes);
    const std::string_view timings = from_element(dom, "timing-table");
    EXPECT_EQ(attribute_values(timings.substr(0, timings.find("</table>")), "data-timing"), passes);
    EXPECT_EQ(attribute_values(from_element(dom, "overlap-check").substr(0, 200), "data-overlaps"),
              std::vector<std::string>{"0"});
}

TEST(InspectPage, TheDeferredSamplesFrameOpens) {
#ifdef LOOM_DEFERRED_EXE
    LOOM_REQUIRE_CHROMIUM(chromium);
    check_sample_page(chromium, LOOM_DEFERRED_EXE, "--size 64x48");
#else
    GTEST_SKIP() << "loom-deferred is not built (LOOM_WITH_GLTF=OFF)";
#endif
}

TEST(InspectPage, TheEngineSamplesFrameOpens) {
#ifdef LOOM_ENGINE_EXE
    LOOM_REQUIRE_CHROMIUM(chromium);
    check_sample_page(chromium, LOOM_ENGINE_EXE, "--size 128x96 --shadow-size 256 --lights 32");
#else
    GTEST_SKIP() << "loom-engine is not built (LOOM_WITH_GLTF=OFF)";
#endif
}

TEST(InspectPage, TenThousandPassesOpen) {
    LOOM_REQUIRE_CHROMIUM(chromium);
    const auto dir = test_dir();
    constexpr int kPasses = 10000;
    write_file(dir / "big.json", big_graph(kPasses).dump());
    // --no-compare: planning it three more times would only slow the test down.
    const ToolRun made = run(LOOM_INSPECT_TOOL, quoted(dir / "big.json") + " --no-compare --out " + quoted(dir / "big.html"));
    ASSERT_EQ(made.status, 0) << made.err;

    const std::string last = "p" + std::to_string(kPasses - 1);
    const std::string dom = open_page(chromium, dir / "big.html", "#pass=" + last);
    const std::string_view count = from_element(dom, "pass-count");
    EXPECT_TRUE(count.substr(count.find('>') + 1).starts_with(std::to_string(kPasses) + " + " + std::to_string(kPasses / 100) + " culled"))
        << count.substr(0, 80);
    // The list shows the rows in view: selecting the last pass scrolled it there.
    const auto shown = attribute_values(list_of(dom, "pass-list"), "data-pass");
    EXPECT_NE(std::find(shown.begin(), shown.end(), last), shown.end());
    EXPECT_LT(shown.size(), 1000u) << "the list draws only the rows in view";
    const std::string_view details = from_element(dom, "details-body");
    EXPECT_EQ(attribute_values(details.substr(0, details.find('>')), "data-selected"), std::vector<std::string>{"pass:" + last});

    // The time from navigation to the end of the page's script, as the page measured it:
    // reported, and bounded only loosely (CI machines are slow and shared).
    const auto load_ms = attribute_of(dom, "body", "data-load-ms");
    ASSERT_TRUE(load_ms.has_value());
    const double ms = std::stod(*load_ms);
    std::cout << "inspector page of " << kPasses << " passes opened in " << ms << " ms; steps (ms): "
              << attribute_of(dom, "body", "data-phases").value_or("?") << "\n";
    ::testing::Test::RecordProperty("load_ms", *load_ms);
    EXPECT_LT(ms, 20000.0);
}

}  // namespace
