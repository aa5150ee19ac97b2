#include "loom/passes/object.hpp"

namespace loom::passes {

ObjectKind::ObjectKind(std::string name, std::vector<ShaderPart> parts, std::vector<rhi::VertexBufferLayout> vertex_buffers)
    : name_(std::move(name)), parts_(std::move(parts)), vertex_buffers_(std::move(vertex_buffers)) {}

rhi::RasterState Object::raster() const {
    rhi::RasterState state;
    state.cull = rhi::CullMode::Back;
    state.front_face = rhi::FrontFace::CounterClockwise;
    return state;
}

}  // namespace loom::passes
