#pragma once
// The functions of the guides' snippets that docs/snippets/snippets_test.cpp runs (the rest of
// the snippet files is compiled only).

#include <cstdint>
#include <string>

#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"

namespace loom::docs {

/// getting_started.cpp: the first graph (gradient -> invert) at 256x64; the result read back.
Result<rhi::Image> render_first_graph(rhi::Device& device);

/// framegraph_guide.cpp: builds the example graphs of docs/framegraph.md and plans them.
Status plan_framegraph_examples();
/// framegraph_guide.cpp: the "Executing a plan" example (a blur pass) on `device`.
Result<rhi::Image> execute_framegraph_example(rhi::Device& device);

/// framegraph_buffers.cpp: plans the bloom pyramid, HZB chain and light list of
/// docs/framegraph.md built in C++ and checks each against its JSON twin in `graphs_dir`
/// (samples/plan/graphs) with every allocator, and the figures the guide quotes.
Status plan_buffer_examples(const std::string& graphs_dir);

/// backends_guide.cpp: what docs/backends.md shows about a device, as text.
Result<std::string> describe_device(rhi::Device& device);

/// embedding_gl.cpp: an engine frame on the current context (an RGBA8 target texture of
/// `width` x `height`, cleared by the engine): loom draws red into its top-left quadrant and
/// blits it into `window_framebuffer`; returns the target's texels.
Result<rhi::Image> gl_engine_frame(uint32_t engine_texture, uint32_t width, uint32_t height, uint32_t window_framebuffer);

}  // namespace loom::docs
