#pragma once
// What the three draw-cost programs (loom, raw GL, raw Vulkan) share: the command line, the
// draw loops' paths, the shaders they draw with, the callgrind markers around the measured
// frame and a count of the heap allocations made inside it. tests/bench/draw_cost/README.md
// says how draw_cost.py turns their callgrind profiles into docs/BENCHMARKS.md's table.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::draw_cost {

/// What changes between two draws of the measured frame.
enum class Path : uint8_t {
    PushConstants,      ///< 32 bytes of push constants per draw
    TransientUniforms,  ///< 32 bytes of per-draw uniform data (a transient range bound at set 0)
    BindGroup,          ///< one of two prebuilt bind groups (a sampled texture) per draw
    VertexBuffers,      ///< one of two vertex + index buffer pairs per draw (indexed draws)
    Pipeline,           ///< one of two pipelines per draw
};
inline constexpr Path kPaths[] = {Path::PushConstants, Path::TransientUniforms, Path::BindGroup, Path::VertexBuffers,
                                  Path::Pipeline};

std::string_view path_name(Path path);
std::optional<Path> parse_path(std::string_view name);

struct Options {
    Path path = Path::PushConstants;
    uint32_t draws = 1000;
    /// loom only: "gl" or "vulkan".
    std::string backend = "gl";
    /// loom only: frames recorded before the measured one (transient rings, descriptor pools
    /// and caches reach their steady state).
    uint32_t warmup_frames = 3;
    /// loom only: DeviceDesc::validation (--validation on|off).
    bool validation = true;
};

/// --path NAME --draws N [--backend gl|vulkan] [--warmup N] [--validation on|off]; an error
/// names the bad argument.
Result<Options> parse_options(int argc, char** argv, bool takes_backend);

/// The vertex and fragment shader of `path` (GLSL 450 compiled with loom's shader compiler, so
/// loom and the raw programs run the same SPIR-V and the same GL source). `variant` 1 is the
/// second pipeline of Path::Pipeline (another constant colour).
Result<rhi::ShaderModule> vertex_shader(Path path);
Result<rhi::ShaderModule> fragment_shader(Path path, int variant = 0);

/// The 32 bytes a draw sends on the push-constant and uniform paths (colour, offset of draw i).
struct DrawConstants {
    float color[4];
    float offset[4];
};
DrawConstants draw_constants(uint32_t draw);

/// The measured frame: callgrind collects between begin() and end() (the programs run under
/// `valgrind --tool=callgrind --collect-atstart=no`), and operator new calls are counted.
void begin_measurement();
void end_measurement();
/// Heap allocations (operator new) between the last begin_measurement() and end_measurement().
uint64_t measured_allocations();

/// Prints "draw-cost: <program> path=<path> draws=<n> allocations=<k>" for draw_cost.py.
void report(std::string_view program, const Options& options);

}  // namespace loom::draw_cost
