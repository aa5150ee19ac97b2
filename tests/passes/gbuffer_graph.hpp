#pragma once
// A frame graph of one G-buffer pass (GeometryPass) with its three maps as outputs, for tests
// and benchmarks that draw objects and read the maps back.

#include <cstdint>
#include <memory>
#include <string>

#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/passes/geometry_pass.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"

namespace loom::test {

class GBufferGraph {
public:
    /// A graph of a GeometryPass named `name` seeing through `camera`, frames of size x size.
    GBufferGraph(rhi::Device& device, uint32_t size, const scene::CameraMatrices& camera, std::string name = "geometry");

    [[nodiscard]] passes::GeometryPass& pass() { return *pass_; }
    [[nodiscard]] fg::Executor& executor() { return executor_; }
    /// Runs one frame (begin_frame, the pass, end_frame).
    Status frame();
    /// Records the graph into a frame the caller began (Device::begin_frame) and will end.
    Status record(rhi::CommandList& commands);
    /// The latest frame's map of `port` ("position", "normal" or "albedo").
    Result<rhi::Image> read(const std::string& port);

private:
    rhi::Device* device_;
    fg::FrameGraph graph_;
    passes::GeometryPass* pass_ = nullptr;
    fg::Executor executor_;
    fg::PlanOptions options_;
};

}  // namespace loom::test
