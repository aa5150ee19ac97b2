#pragma once
// What loom-compare found for one case (a scene through one pipeline on every backend), as
// plain data for the reports.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"

namespace loom::compare {

/// One backend's rendering of a case.
struct BackendRun {
    explicit BackendRun(rhi::Backend on = rhi::Backend::OpenGL) : backend(on) {}

    rhi::Backend backend;
    /// Why it did not render (empty when it did): the first error, one line.
    std::string error;
    /// Errors and API warnings logged while the case ran on this backend (GL debug output,
    /// Vulkan validation): any fails the case.
    std::vector<std::string> messages;
    std::optional<fg::Plan> plan;
    fg::ExecutionStats stats;
    /// Wall time of building the pipeline and rendering one frame (shader and pipeline
    /// compilation included), in milliseconds.
    double milliseconds = 0.0;
    /// The final picture, relative to the output directory (empty when not written).
    std::string image_file;
    /// The inspector page of the frame (its plan, barriers, timings and what the device created;
    /// docs/inspector.md), relative to the output directory (empty when not written).
    std::string inspector_file;

    [[nodiscard]] bool rendered() const { return error.empty() && plan.has_value(); }
};

/// How the backends' final pictures compare (rhi::compare_images).
struct ImageMetrics {
    double max_channel_diff = 0.0;
    uint64_t pixels_above_threshold = 0;
    uint64_t pixel_count = 0;
    double psnr = 0.0;  ///< +infinity for identical pictures
    std::string diff_file;  ///< the heat map, relative to the output directory
};

/// How far the forward pipeline's picture may differ from the deferred one's: the deferred
/// pass lights positions and normals read back from half-float G-buffer maps, the forward pass
/// the unrounded ones, so most pixels differ by a level at most; at shadow edges and on
/// specular highlights the rounding moves an edge by a pixel, which differs by more.
inline constexpr double kPipelineThreshold = 2.0;      ///< levels (RGBA8)
inline constexpr double kPipelineMaxDiffering = 0.005;  ///< of the pixels, above the threshold

struct CaseResult {
    std::string scene;     ///< the scene file's name (SceneFile::name)
    std::string file;      ///< its path
    std::string pipeline;  ///< "deferred", "forward", or "load" (loading only)
    std::string id;        ///< unique and file-system safe: where the case's pictures go
    /// The importer's error, when the file did not load (expected with --expect-errors).
    std::string load_error;
    /// What was drawn: draw items, materials, images, the camera.
    std::string scene_info;
    /// Importer warnings (not failures).
    std::vector<std::string> warnings;
    std::vector<BackendRun> runs;
    std::optional<ImageMetrics> image;
    /// The forward case only: its picture against the deferred case's on the first backend
    /// that rendered both (kPipelineThreshold, kPipelineMaxDiffering).
    std::optional<ImageMetrics> against_deferred;
    /// Why the case failed; empty when it passed.
    std::vector<std::string> failures;

    [[nodiscard]] bool passed() const { return failures.empty(); }
};

/// Counts over a run.
struct RunSummary {
    uint32_t cases = 0;
    uint32_t passed = 0;
    uint32_t failed = 0;
    double seconds = 0.0;
};

RunSummary summarize(const std::vector<CaseResult>& cases, double seconds);

/// Bytes of the plan's textures (what a backend without heaps creates for it).
uint64_t plan_texture_bytes(const fg::Plan& plan);

/// fg::plan_hash as 16 hex digits.
std::string plan_hash_text(const fg::Plan& plan);

}  // namespace loom::compare
