#pragma once
// The loop of a windowed sample: poll events, record a frame into the back buffer, present.

#include <cstdint>
#include <functional>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::samples {

/// Records one frame into `backbuffer` (a colour target of `size`).
using FrameRecorder = std::function<void(rhi::CommandList& list, rhi::TextureHandle backbuffer, rhi::Extent3D size)>;

/// Runs frames until the window is closed (or `max_frames` frames, when not 0). Returns the
/// first frame error. The device must be windowed.
Status run_window_loop(rhi::Device& device, const FrameRecorder& record, uint64_t max_frames = 0);

}  // namespace loom::samples
