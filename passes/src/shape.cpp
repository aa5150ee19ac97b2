#include "loom/passes/shape.hpp"

#include <atomic>

namespace loom::passes {
namespace {

std::atomic<uint64_t> next_material_id{1};

}  // namespace

GpuMaterial::GpuMaterial(std::string name, std::shared_ptr<UniformSet> uniforms, std::vector<MaterialTexture> textures,
                         rhi::CullMode cull)
    : name_(std::move(name)), id_(next_material_id++), uniforms_(std::move(uniforms)), textures_(std::move(textures)),
      cull_(cull) {}

Shape::Shape(std::string name, std::shared_ptr<const ObjectKind> kind, std::shared_ptr<const Geometry> geometry,
             std::shared_ptr<GpuMaterial> material, std::shared_ptr<Param<glm::mat4>> model)
    : name_(std::move(name)), kind_(std::move(kind)), geometry_(std::move(geometry)), material_(std::move(material)),
      model_(std::move(model)) {}

}  // namespace loom::passes
