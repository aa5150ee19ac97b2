#include "draw_cost_common.hpp"

#include <atomic>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <new>

#include "loom/shader_compiler/shader_compiler.hpp"

#if defined(LOOM_HAVE_CALLGRIND)
#include <valgrind/callgrind.h>
#define LOOM_CALLGRIND_START() CALLGRIND_START_INSTRUMENTATION
#define LOOM_CALLGRIND_STOP() CALLGRIND_STOP_INSTRUMENTATION
#else
#define LOOM_CALLGRIND_START() ((void)0)
#define LOOM_CALLGRIND_STOP() ((void)0)
#endif

namespace {

// Counted only while measuring; the driver's own malloc calls are not operator new and are
// not counted (the table's "runtime" column shows what they cost).
std::atomic<bool> g_counting{false};
std::atomic<uint64_t> g_allocations{0};

void* allocate(std::size_t size) {
    if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}

}  // namespace

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace loom::draw_cost {

std::string_view path_name(Path path) {
    switch (path) {
        case Path::PushConstants: return "push_constants";
        case Path::TransientUniforms: return "transient_uniforms";
        case Path::BindGroup: return "bind_group";
        case Path::VertexBuffers: return "vertex_buffers";
        case Path::Pipeline: return "pipeline";
    }
    return "?";
}

std::optional<Path> parse_path(std::string_view name) {
    for (Path p : kPaths) {
        if (path_name(p) == name) return p;
    }
    return std::nullopt;
}

Result<Options> parse_options(int argc, char** argv, bool takes_backend) {
    Options options;
    auto number = [](std::string_view text, uint32_t& out) {
        const char* end = text.data() + text.size();
        auto [ptr, ec] = std::from_chars(text.data(), end, out);
        return ec == std::errc() && ptr == end;
    };
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        if (i + 1 >= argc) return Error{ErrorCode::InvalidArgument, std::string(arg) + " needs a value"};
        const std::string_view value = argv[++i];
        if (arg == "--path") {
            auto path = parse_path(value);
            if (!path) {
                return Error{ErrorCode::InvalidArgument, "--path: unknown path '" + std::string(value) +
                                                             "' (push_constants, transient_uniforms, bind_group, "
                                                             "vertex_buffers, pipeline)"};
            }
            options.path = *path;
        } else if (arg == "--draws") {
            if (!number(value, options.draws) || options.draws == 0) {
                return Error{ErrorCode::InvalidArgument, "--draws expects a positive number, got '" + std::string(value) + "'"};
            }
        } else if (arg == "--warmup") {
            if (!number(value, options.warmup_frames)) {
                return Error{ErrorCode::InvalidArgument, "--warmup expects a number, got '" + std::string(value) + "'"};
            }
        } else if (arg == "--backend" && takes_backend) {
            options.backend = std::string(value);
        } else if (arg == "--validation" && takes_backend) {
            if (value != "on" && value != "off") {
                return Error{ErrorCode::InvalidArgument, "--validation expects on or off, got '" + std::string(value) + "'"};
            }
            options.validation = value == "on";
        } else {
            return Error{ErrorCode::InvalidArgument, "unknown argument '" + std::string(arg) + "'"};
        }
    }
    return options;
}

namespace {

// One source for every path; the path picks what changes per draw. Positions are a small
// triangle per draw so that the rasteriser's work per draw is the same tiny amount everywhere.
constexpr const char* kVertexSource = R"(#version 450
#if defined(PUSH_CONSTANTS)
layout(push_constant) uniform DrawData { vec4 color; vec4 offset; } draw_data;
#elif defined(TRANSIENT_UNIFORMS)
layout(set = 0, binding = 0) uniform DrawData { vec4 color; vec4 offset; } draw_data;
#endif
#if defined(VERTEX_BUFFERS)
layout(location = 0) in vec2 position;
#endif
layout(location = 0) out vec4 v_color;
void main() {
#if defined(VERTEX_BUFFERS)
    vec2 p = position;
#else
    vec2 p = vec2(float(gl_VertexIndex & 1), float(gl_VertexIndex >> 1)) * 0.1 - 0.9;
#endif
#if defined(PUSH_CONSTANTS) || defined(TRANSIENT_UNIFORMS)
    p += draw_data.offset.xy;
    v_color = draw_data.color;
#else
    v_color = vec4(0.2, 0.6, 0.9, 1.0);
#endif
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

constexpr const char* kFragmentSource = R"(#version 450
#if defined(SAMPLED_TEXTURE)
layout(set = 0, binding = 0) uniform sampler2D image;
#endif
layout(location = 0) in vec4 v_color;
layout(location = 0) out vec4 color;
void main() {
#if defined(SAMPLED_TEXTURE)
    color = texture(image, vec2(0.5));
#elif defined(SECOND_COLOUR)
    color = vec4(1.0) - v_color;
#else
    color = v_color;
#endif
}
)";

Result<rhi::ShaderModule> compile(std::string name, rhi::ShaderStage stage, const char* code,
                                  std::vector<std::pair<std::string, std::string>> defines) {
    shader_compiler::ShaderCompiler compiler;
    return compiler.compile(shader_compiler::ShaderSource{std::move(name), stage, code, std::move(defines)});
}

}  // namespace

Result<rhi::ShaderModule> vertex_shader(Path path) {
    std::vector<std::pair<std::string, std::string>> defines;
    if (path == Path::PushConstants) defines.emplace_back("PUSH_CONSTANTS", "1");
    if (path == Path::TransientUniforms) defines.emplace_back("TRANSIENT_UNIFORMS", "1");
    if (path == Path::VertexBuffers) defines.emplace_back("VERTEX_BUFFERS", "1");
    return compile("draw_cost.vert", rhi::ShaderStage::Vertex, kVertexSource, std::move(defines));
}

Result<rhi::ShaderModule> fragment_shader(Path path, int variant) {
    std::vector<std::pair<std::string, std::string>> defines;
    if (path == Path::BindGroup) defines.emplace_back("SAMPLED_TEXTURE", "1");
    if (variant == 1) defines.emplace_back("SECOND_COLOUR", "1");
    return compile("draw_cost.frag", rhi::ShaderStage::Fragment, kFragmentSource, std::move(defines));
}

DrawConstants draw_constants(uint32_t draw) {
    const float f = static_cast<float>(draw % 97) / 97.0f;
    return DrawConstants{{f, 1.0f - f, 0.5f, 1.0f}, {f * 1.5f, static_cast<float>(draw % 13) * 0.1f, 0.0f, 0.0f}};
}

void begin_measurement() {
    g_allocations.store(0);
    g_counting.store(true);
    LOOM_CALLGRIND_START();
}

void end_measurement() {
    LOOM_CALLGRIND_STOP();
    g_counting.store(false);
}

uint64_t measured_allocations() { return g_allocations.load(); }

void report(std::string_view program, const Options& options) {
    std::printf("draw-cost: %.*s path=%.*s draws=%u allocations=%llu\n", static_cast<int>(program.size()), program.data(),
                static_cast<int>(path_name(options.path).size()), path_name(options.path).data(), options.draws,
                static_cast<unsigned long long>(measured_allocations()));
}

}  // namespace loom::draw_cost
