#pragma once
// The graph the embedding snippets run (embedding_graph.cpp).

#include <memory>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/device.hpp"

namespace loom::docs {

struct EmbeddingGraph {
    /// One pass, "ui", drawing red into the top-left quadrant of its optional inout "target".
    static Result<std::unique_ptr<EmbeddingGraph>> create(rhi::Device& device, rhi::Format target_format);
    fg::FrameGraph graph;
};

}  // namespace loom::docs
