#include "gbuffer_graph.hpp"

namespace loom::test {

GBufferGraph::GBufferGraph(rhi::Device& device, uint32_t size, const scene::CameraMatrices& camera, std::string name)
    : device_(&device), executor_(device) {
    auto pass = std::make_unique<passes::GeometryPass>(passes::PassConfig{}, name);
    pass->set_camera(camera);
    pass_ = pass.get();
    // Errors here are programming errors of the test; frame() reports them.
    (void)graph_.add_pass(std::unique_ptr<fg::Pass>(std::move(pass)));
    for (const char* port : {"position", "normal", "albedo"}) (void)graph_.mark_output(fg::port(name, port));
    options_.frame = {size, size};
}

Status GBufferGraph::frame() { return executor_.run_frame(graph_, options_); }

Status GBufferGraph::record(rhi::CommandList& commands) { return executor_.execute(graph_, commands, options_); }

Result<rhi::Image> GBufferGraph::read(const std::string& port) {
    return device_->read_texture(executor_.texture(pass_->name(), port));
}

}  // namespace loom::test
