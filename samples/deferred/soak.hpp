#pragma once
// The flagship's soak run: many frames with the frame resized every `resize_every` frames
// (alternating two sizes) and the frame graph rebuilt every `rebuild_every` frames with the lit
// pass toggled (geometry + deferred <-> forward: passes, ports, plan and textures all change).
// After every frame it records what is alive on the device (rhi::ResourceStats) and the
// process's resident memory. The pattern repeats every soak_period() frames, so a run without
// leaks has, frame for frame, the same live objects as one period earlier; check_soak() checks
// exactly that once the first period (the warm-up: first compilations, first plans of each
// shape) is over. docs/soak.md has the measured curves.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"

namespace loom::deferred {

struct SoakSettings {
    uint64_t frames = 10000;
    /// Frames between resizes (the frame alternates between `size` and `alternate_size`); 0: never.
    uint32_t resize_every = 100;
    /// Frames between graph rebuilds (each toggles the lit pass); 0: never.
    uint32_t rebuild_every = 10;
    fg::Extent2D size{1280, 720};
    /// The other size; empty: three quarters of `size` (at least 1x1).
    std::optional<fg::Extent2D> alternate_size;
};

/// What was alive after one frame.
struct SoakSample {
    uint64_t frame = 0;  ///< 0-based
    fg::Extent2D size;
    bool forward = false;      ///< the lit pass of this frame's graph
    rhi::ResourceStats live;   ///< after the frame, once the device was idle
    uint64_t resident_bytes = 0;  ///< the process's resident set (0 where unknown)
    double frame_ms = 0.0;     ///< wall time of the frame (rebuild, plan, record, submit, wait)
};

/// Frames after which sizes and lit passes repeat: lcm(2 * resize_every, 2 * rebuild_every)
/// (a setting of 0 counts as 1).
uint64_t soak_period(const SoakSettings& settings);

/// Renders `settings.frames` frames with `pipeline` (whose settings give the first lit pass),
/// calling `on_frame` after each. Errors: those of rendering or rebuilding, named by frame.
Result<std::vector<SoakSample>> run_soak(rhi::Device& device, renderer::DeferredPipeline& pipeline, const SoakSettings& settings,
                                         const std::function<void(const SoakSample&)>& on_frame = {});

/// Whether the live objects stayed constant after the warm-up.
struct SoakVerdict {
    bool steady = false;
    uint64_t period = 0;
    uint64_t warm_up_frames = 0;  ///< the first period, neither compared nor compared with
    uint64_t compared = 0;        ///< frames compared with the frame one period earlier
    /// The first frame whose live objects differ from one period earlier, described; empty if none.
    std::string first_difference;
    /// Resident memory after the warm-up (the last warm-up frame), at the end and the highest
    /// after the warm-up.
    uint64_t resident_after_warm_up = 0;
    uint64_t resident_at_end = 0;
    uint64_t resident_peak = 0;
    /// One line, e.g. "steady: 300 frames compared with one period (200 frames) earlier, ...".
    [[nodiscard]] std::string describe() const;
};

/// Leaves out the first period (the warm-up) and compares every frame from the third period on
/// with the same frame one period earlier: all of ResourceStats must be equal. Runs shorter
/// than two periods and a frame are not steady, with the reason in first_difference.
SoakVerdict check_soak(const std::vector<SoakSample>& samples, uint64_t period);

/// The CSV of a soak run: a header line, then one line per sample.
std::string soak_csv_header();
std::string soak_csv_row(const SoakSample& sample);

/// The process's resident set size from /proc/self/statm; 0 where unavailable.
uint64_t resident_bytes();

}  // namespace loom::deferred
