// The retained object layer against the naive loop: one scene of 10,000 objects (300 meshes,
// 30 materials, random submission order; tests/passes/object_scene.hpp) drawn through the
// G-buffer pass on each backend, side by side in one run:
//
//   naive     the objects are MeshObjects registered with the pass; every frame the pass binds
//             and draws each one as submitted (its uniforms copied into per-frame memory, its
//             set bound, its buffers bound, one draw).
//   retained  the objects are shapes submitted to a RetainedScene once; every frame the pass
//             draws the scene's sorted render queue (one pipeline, material set and buffer
//             binding per state key, one indirect multi-draw per key).
//
// Each path is measured over frames in which 1% of the objects move (new model matrices) and
// over frames in which nothing changes. Per frame it reports what the backend counted (API calls,
// draws, pipeline/texture/buffer binds, bytes uploaded), the state changes (draws whose bound
// state differs from the draw before) against the minimum (the scene's distinct state keys),
// and CPU times on the recording thread: recording (the frame graph's execute: the pass's
// commands), submission (end_frame: GL runs the recorded GL calls, Vulkan submits), and the wait
// for the GPU (wait_idle) separately. Validation is off. The frame is small (64x64 by default) so
// that rasterising, which llvmpipe and lavapipe do on the same CPU, stays small.
//
//   loom_retained_bench [--backend gl|vulkan|all] [--objects N] [--meshes N] [--materials N]
//                       [--frames N] [--size N] [--move-percent P]
//
// Prints a Markdown table per backend (docs/BENCHMARKS.md shows one run).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gbuffer_graph.hpp"
#include "loom/passes/retained_mesh.hpp"
#include "loom/passes/retained_scene.hpp"
#include "loom/rhi/device.hpp"
#include "object_scene.hpp"

namespace {

using namespace loom;

struct Options {
    std::vector<rhi::Backend> backends;
    test::ObjectSceneSpec scene;
    uint32_t frames = 20;
    uint32_t size = 64;
    double move_percent = 1.0;
};

/// Seconds of CPU time this thread has used.
double thread_cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double wall_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// One frame's figures.
struct FrameFigures {
    rhi::FrameStats stats;
    double record_ms = 0.0;       ///< thread CPU time in execute()
    double submit_ms = 0.0;       ///< thread CPU time in end_frame()
    double wait_ms = 0.0;         ///< wall time in wait_idle()
    uint64_t state_changes = 0;
    uint64_t scene_upload_bytes = 0;
};

/// Medians (times) and the last frame's counts over a series of frames.
struct Series {
    std::string name;
    std::vector<FrameFigures> frames;

    [[nodiscard]] double median(double FrameFigures::*field) const {
        std::vector<double> values;
        for (const FrameFigures& f : frames) values.push_back(f.*field);
        std::sort(values.begin(), values.end());
        return values.empty() ? 0.0 : values[values.size() / 2];
    }
    [[nodiscard]] const FrameFigures& last() const { return frames.back(); }
};

void fail(const std::string& what, const Error& error) {
    std::fprintf(stderr, "loom_retained_bench: %s: %s\n", what.c_str(), error.to_string().c_str());
    std::exit(1);
}

/// Runs one frame of `graph`, timing recording, submission and the GPU wait.
FrameFigures timed_frame(rhi::Device& device, test::GBufferGraph& graph) {
    FrameFigures f;
    rhi::CommandList& commands = device.begin_frame();
    double t0 = thread_cpu_seconds();
    if (auto status = graph.record(commands); !status) fail("record", status.error());
    double t1 = thread_cpu_seconds();
    f.record_ms = (t1 - t0) * 1e3;
    if (auto status = device.end_frame(); !status) fail("end_frame", status.error());
    double t2 = thread_cpu_seconds();
    f.submit_ms = (t2 - t1) * 1e3;
    const double w0 = wall_seconds();
    if (auto status = device.wait_idle(); !status) fail("wait_idle", status.error());
    f.wait_ms = (wall_seconds() - w0) * 1e3;
    f.stats = device.last_frame_stats();
    return f;
}

/// Indices of the objects that move in frame `frame` (a different random 1% each frame).
std::vector<uint32_t> movers(uint32_t objects, double percent, uint32_t frame) {
    std::mt19937 random(1000 + frame);
    std::vector<uint32_t> all(objects);
    for (uint32_t i = 0; i < objects; ++i) all[i] = i;
    std::shuffle(all.begin(), all.end(), random);
    all.resize(static_cast<std::size_t>(static_cast<double>(objects) * percent / 100.0));
    return all;
}

/// The model matrix of object `i` in frame `frame`: its place, lifted by a little bounce (the
/// same rotation and scale, so its state key stays the same).
glm::mat4 moved(const test::SceneObject& object, uint32_t frame) {
    return glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.05f * static_cast<float>(frame % 7), 0.0f)) * object.model;
}

/// State changes of the naive loop: every draw binds the object's own uniforms, so every draw
/// changes the bound state.
uint64_t naive_state_changes(const test::ObjectScene& scene) { return scene.objects.size(); }

struct BackendResult {
    rhi::Backend backend;
    std::string device_name;
    Series naive_moving, naive_static, retained_moving, retained_static;
    /// The same triangles in one draw of one merged mesh: what the device's vertex and raster
    /// work costs by itself (llvmpipe runs its vertex stage inside the GL calls).
    Series one_draw;
    FrameFigures retained_first;
    uint64_t distinct_keys = 0;
};

BackendResult run_backend(rhi::Backend backend, const Options& options, const test::ObjectScene& scene) {
    BackendResult result;
    result.backend = backend;
    rhi::DeviceDesc desc;
    desc.backend = backend;
    desc.debug = false;
    auto device = rhi::create_device(desc);
    if (!device) fail("create_device", device.error());
    result.device_name = (*device)->capabilities().device_name;
    result.distinct_keys = test::distinct_state_keys(scene);
    const uint32_t warmup = 3;

    {  // The naive loop.
        auto objects = test::make_naive_objects(**device, scene);
        if (!objects) fail("naive objects", objects.error());
        test::GBufferGraph graph(**device, options.size, scene.camera);
        for (const auto& object : objects->objects) {
            if (auto status = passes::register_object(graph.pass(), object); !status) fail("register_object", status.error());
        }
        for (uint32_t i = 0; i < warmup; ++i) timed_frame(**device, graph);
        result.naive_moving.name = "naive, 1% moving";
        for (uint32_t frame = 0; frame < options.frames; ++frame) {
            for (uint32_t i : movers(static_cast<uint32_t>(scene.objects.size()), options.move_percent, frame)) {
                objects->objects[i]->set_model(moved(scene.objects[i], frame + 1));
            }
            FrameFigures f = timed_frame(**device, graph);
            f.state_changes = naive_state_changes(scene);
            result.naive_moving.frames.push_back(f);
        }
        result.naive_static.name = "naive, static";
        for (uint32_t frame = 0; frame < options.frames; ++frame) {
            FrameFigures f = timed_frame(**device, graph);
            f.state_changes = naive_state_changes(scene);
            result.naive_static.frames.push_back(f);
        }
    }
    {  // The floor: every object's triangles, transformed on the CPU, in one mesh and one draw.
        std::vector<passes::MeshVertex> vertices;
        std::vector<uint32_t> indices;
        for (const test::SceneObject& object : scene.objects) {
            const test::SceneMesh& mesh = scene.meshes[object.mesh];
            const auto base = static_cast<uint32_t>(vertices.size());
            const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(object.model)));
            for (passes::MeshVertex v : mesh.vertices) {
                v.position = glm::vec3(object.model * glm::vec4(v.position, 1.0f));
                v.normal = normal_matrix * v.normal;
                vertices.push_back(v);
            }
            for (uint32_t index : mesh.indices) indices.push_back(base + index);
        }
        auto merged = passes::GpuMesh::create(**device, vertices, indices, "all objects");
        if (!merged) fail("merged mesh", merged.error());
        passes::MeshSurface material = test::plain_surface();
        material.material.double_sided = true;  // mirrored objects' triangles wind the other way
        auto object = std::make_shared<passes::MeshObject>("all objects", passes::pbr_mesh_kind(), *merged,
                                                           glm::mat4(1.0f), material);
        test::GBufferGraph graph(**device, options.size, scene.camera);
        if (auto status = passes::register_object(graph.pass(), object); !status) fail("register_object", status.error());
        for (uint32_t i = 0; i < warmup; ++i) timed_frame(**device, graph);
        result.one_draw.name = "one draw (floor)";
        for (uint32_t frame = 0; frame < options.frames; ++frame) {
            FrameFigures f = timed_frame(**device, graph);
            f.state_changes = 1;
            result.one_draw.frames.push_back(f);
        }
    }
    {  // The retained scene.
        auto objects = test::make_retained_objects(scene);
        if (!objects) fail("retained objects", objects.error());
        passes::RetainedScene retained;
        test::GBufferGraph graph(**device, options.size, scene.camera);
        if (auto status = retained.attach(graph.pass()); !status) fail("attach", status.error());
        for (const auto& shape : objects->shapes) {
            if (auto status = retained.submit(shape); !status) fail("submit", status.error());
        }
        auto measured = [&](Series& series) {
            retained.reset_stats();
            FrameFigures f = timed_frame(**device, graph);
            f.state_changes = retained.stats().state_changes;
            f.scene_upload_bytes = retained.stats().uploaded_bytes();
            series.frames.push_back(f);
        };
        Series first;
        measured(first);  // places every mesh, writes every set, builds the queue
        result.retained_first = first.last();
        for (uint32_t i = 0; i < warmup; ++i) timed_frame(**device, graph);
        result.retained_moving.name = "retained, 1% moving";
        for (uint32_t frame = 0; frame < options.frames; ++frame) {
            for (uint32_t i : movers(static_cast<uint32_t>(scene.objects.size()), options.move_percent, frame)) {
                objects->models[i]->set(moved(scene.objects[i], frame + 1));
            }
            measured(result.retained_moving);
        }
        result.retained_static.name = "retained, static";
        for (uint32_t frame = 0; frame < options.frames; ++frame) measured(result.retained_static);
    }
    return result;
}

std::string fixed(double value, int digits = 2) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

std::string count(uint64_t value) {
    // Built forwards rather than by inserting commas (GCC 12 -O3 warns falsely about
    // std::string::insert: -Wrestrict, bug 105651).
    const std::string digits = std::to_string(value);
    std::string out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

void print(const BackendResult& r, const Options& options, const test::ObjectScene& scene) {
    const std::vector<const Series*> all = {&r.naive_moving, &r.retained_moving, &r.naive_static, &r.retained_static,
                                            &r.one_draw};
    std::printf("\n### %s (%s), %s objects, %zu meshes, %zu materials, %ux%u, %u frames each\n\n",
                std::string(rhi::backend_name(r.backend)).c_str(), r.device_name.c_str(),
                count(scene.objects.size()).c_str(), scene.meshes.size(), scene.materials.size(), options.size,
                options.size, options.frames);
    std::printf("| per frame |");
    for (const Series* s : all) std::printf(" %s |", s->name.c_str());
    std::printf("\n| --- |");
    for (std::size_t i = 0; i < all.size(); ++i) std::printf(" ---: |");
    std::printf("\n");
    auto row = [&](const char* label, const std::function<std::string(const Series&)>& value) {
        std::printf("| %s |", label);
        for (const Series* s : all) std::printf(" %s |", value(*s).c_str());
        std::printf("\n");
    };
    row("API calls", [](const Series& s) { return count(s.last().stats.api_calls); });
    row("draw calls", [](const Series& s) { return count(s.last().stats.draw_calls); });
    row("pipeline binds", [](const Series& s) { return count(s.last().stats.pipeline_binds); });
    row("texture binds", [](const Series& s) { return count(s.last().stats.texture_binds); });
    row("buffer binds", [](const Series& s) { return count(s.last().stats.buffer_binds); });
    const std::string changes = "state changes (minimum " + count(r.distinct_keys) + ")";
    row(changes.c_str(), [](const Series& s) { return count(s.last().state_changes); });
    row("bytes uploaded", [](const Series& s) { return count(s.last().stats.bytes_uploaded); });
    row("CPU: recording, ms", [](const Series& s) { return fixed(s.median(&FrameFigures::record_ms)); });
    row("CPU: submission, ms", [](const Series& s) { return fixed(s.median(&FrameFigures::submit_ms)); });
    row("CPU: recording + submission, ms", [](const Series& s) {
        std::vector<double> values;
        for (const FrameFigures& f : s.frames) values.push_back(f.record_ms + f.submit_ms);
        std::sort(values.begin(), values.end());
        return fixed(values[values.size() / 2]);
    });
    row("GPU wait (wall), ms", [](const Series& s) { return fixed(s.median(&FrameFigures::wait_ms)); });

    auto total = [](const Series& s) {
        std::vector<double> values;
        for (const FrameFigures& f : s.frames) values.push_back(f.record_ms + f.submit_ms);
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    const double floor = total(r.one_draw);
    std::printf("\nminimum state changes (distinct state keys): %s\n", count(r.distinct_keys).c_str());
    std::printf("CPU speed-up (recording + submission), 1%% moving: %sx, static: %sx\n",
                fixed(total(r.naive_moving) / total(r.retained_moving), 1).c_str(),
                fixed(total(r.naive_static) / total(r.retained_static), 1).c_str());
    // The floor is the device's own work on the recording thread (llvmpipe shades vertices and
    // sets up triangles inside the GL calls): what a path costs above it is the API overhead.
    auto above_floor = [&](const Series& s) { return std::max(total(s) - floor, 0.0); };
    auto overhead = [&](const Series& naive, const Series& retained) {
        const double n = above_floor(naive), rt = above_floor(retained);
        if (rt < 0.05) return fixed(n) + " ms against " + fixed(rt) + " ms (retained at the floor)";
        return fixed(n) + " ms against " + fixed(rt) + " ms: " + fixed(n / rt, 1) + "x";
    };
    std::printf("above the floor (%s ms: one draw of the same triangles, merged into one mesh), naive against "
                "retained, 1%% moving: %s; static: %s\n",
                fixed(floor).c_str(), overhead(r.naive_moving, r.retained_moving).c_str(),
                overhead(r.naive_static, r.retained_static).c_str());
    const FrameFigures& first = r.retained_first;
    std::printf("retained first frame (finalize: every mesh placed, every set written, queue built): %s bytes "
                "uploaded, recording %s ms, submission %s ms\n",
                count(first.stats.bytes_uploaded).c_str(), fixed(first.record_ms).c_str(), fixed(first.submit_ms).c_str());
}

Options parse(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "loom_retained_bench: %s needs a value\n", arg.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        auto number = [&]() { return static_cast<uint32_t>(std::strtoul(value().c_str(), nullptr, 10)); };
        if (arg == "--backend") {
            const std::string name = value();
            if (name == "all") {
                options.backends.assign(rhi::compiled_backends().begin(), rhi::compiled_backends().end());
            } else if (auto backend = rhi::parse_backend(name)) {
                options.backends.push_back(*backend);
            } else {
                std::fprintf(stderr, "loom_retained_bench: unknown backend '%s'\n", name.c_str());
                std::exit(2);
            }
        } else if (arg == "--objects") {
            options.scene.objects = number();
        } else if (arg == "--meshes") {
            options.scene.meshes = number();
        } else if (arg == "--materials") {
            options.scene.materials = number();
        } else if (arg == "--frames") {
            options.frames = std::max(1u, number());
        } else if (arg == "--size") {
            options.size = std::max(1u, number());
        } else if (arg == "--move-percent") {
            options.move_percent = std::strtod(value().c_str(), nullptr);
        } else {
            std::fprintf(stderr,
                         "usage: loom_retained_bench [--backend gl|vulkan|all] [--objects N] [--meshes N] "
                         "[--materials N] [--frames N] [--size N] [--move-percent P]\n");
            std::exit(arg == "--help" ? 0 : 2);
        }
    }
    if (options.backends.empty()) options.backends.assign(rhi::compiled_backends().begin(), rhi::compiled_backends().end());
    return options;
}

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse(argc, argv);
    const test::ObjectScene scene = test::make_object_scene(options.scene);
    std::printf("## Retained object layer vs the naive loop (loom_retained_bench)\n");
    for (rhi::Backend backend : options.backends) print(run_backend(backend, options, scene), options, scene);
    return 0;
}
