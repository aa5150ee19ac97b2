#pragma once
// A soak run as a picture: one SVG with two charts over the frames, live GPU objects (textures,
// buffers, pipelines, samplers) and memory (GPU bytes the device holds, the process's resident
// set), with the warm-up shaded. Long runs are drawn with each pixel column's minimum and
// maximum, so a single-frame spike still shows.

#include <cstdint>
#include <string>
#include <vector>

#include "soak.hpp"

namespace loom::deferred {

/// The SVG document; `title` goes above the charts, `warm_up_frames` are shaded.
std::string soak_svg(const std::vector<SoakSample>& samples, const std::string& title, uint64_t warm_up_frames);

}  // namespace loom::deferred
