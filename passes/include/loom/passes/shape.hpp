#pragma once
// What an application submits to a RetainedScene: shapes (geometry + material + a model
// transform, of an object kind) and the materials they share. Once submitted, a shape belongs to
// the scene until it is retracted; its parts are not replaced, but its parameters (the model
// transform, the material's values) change through their parameter nodes, and the scene
// uploads what changed.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "loom/passes/geometry_buffers.hpp"
#include "loom/passes/object.hpp"
#include "loom/passes/param.hpp"
#include "loom/passes/uniform_set.hpp"
#include "loom/rhi/descriptions.hpp"

namespace loom::passes {

/// A texture of a material, bound to the sampler variable `name` of the material's parts.
struct MaterialTexture {
    std::string name;
    rhi::TextureHandle texture;  ///< in ShaderRead state whenever it is drawn
    rhi::SamplerDesc sampler;
};

/// A material as the GPU draws it, shared by many shapes: the per-material uniform set (the
/// block its parts declare, "MaterialUniforms" for the retained mesh kinds), textures, and the
/// face culling it needs. Shapes with one material are drawn with one binding of it. (What a
/// material is made of, in glTF's terms, is scene::Material.)
class GpuMaterial {
public:
    /// `uniforms` is the per-material set (UpdateFrequency::PerMaterial); null for a material
    /// without one. `cull` is fixed for the material's lifetime (it is part of the pipeline).
    GpuMaterial(std::string name, std::shared_ptr<UniformSet> uniforms, std::vector<MaterialTexture> textures = {},
                rhi::CullMode cull = rhi::CullMode::Back);

    [[nodiscard]] const std::string& name() const { return name_; }
    /// Unique per material, increasing in creation order (render queues sort by it).
    [[nodiscard]] uint64_t id() const { return id_; }
    [[nodiscard]] const std::shared_ptr<UniformSet>& uniforms() const { return uniforms_; }
    [[nodiscard]] const std::vector<MaterialTexture>& textures() const { return textures_; }
    [[nodiscard]] rhi::CullMode cull() const { return cull_; }

private:
    std::string name_;
    uint64_t id_;
    std::shared_ptr<UniformSet> uniforms_;
    std::vector<MaterialTexture> textures_;
    rhi::CullMode cull_;
};

/// A thing to draw: a geometry of an object kind, a material and a model transform (a
/// parameter node: an InputParam to move it by hand, or a ComputedParam of a parent transform
/// and the time). Its per-object uniform set (ObjectRecord: the model matrix and the normal
/// matrix) is computed from `model` when the transform changes.
class Shape {
public:
    Shape(std::string name, std::shared_ptr<const ObjectKind> kind, std::shared_ptr<const Geometry> geometry,
          std::shared_ptr<GpuMaterial> material, std::shared_ptr<Param<glm::mat4>> model);

    [[nodiscard]] const std::string& name() const { return name_; }
    [[nodiscard]] const std::shared_ptr<const ObjectKind>& kind() const { return kind_; }
    [[nodiscard]] const std::shared_ptr<const Geometry>& geometry() const { return geometry_; }
    [[nodiscard]] const std::shared_ptr<GpuMaterial>& material() const { return material_; }
    [[nodiscard]] const std::shared_ptr<Param<glm::mat4>>& model() const { return model_; }

    /// Names of the passes that draw the shape; empty (the default): every pass attached to the
    /// scene. Set before submitting.
    std::vector<std::string> passes;

private:
    std::string name_;
    std::shared_ptr<const ObjectKind> kind_;
    std::shared_ptr<const Geometry> geometry_;
    std::shared_ptr<GpuMaterial> material_;
    std::shared_ptr<Param<glm::mat4>> model_;
};

}  // namespace loom::passes
