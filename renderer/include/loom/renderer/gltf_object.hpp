#pragma once
// glTF draw items as objects of the pass/object protocol: the object kind "gltf-mesh" and
// GltfObject, one primitive placed in the world with its material.
//
// "gltf-mesh" is made of two object parts (shaders/include/loom/parts/): "gltf-geometry" (the
// vertex layout of loom::scene::Vertex, the model and normal matrices, the tangent frame and
// second UV set for the material) and "gltf-material" (metallic-roughness with base colour,
// metallic-roughness, normal, occlusion and emissive textures, factors, UV sets, vertex colours,
// alpha MASK / BLEND, double-sided lighting). Its programs compose with the standard passes:
// the shadow map (vertex part only), the G-buffer, the forward pass, and the transparent pass
// of this library (which reads object_alpha()).

#include <cstdint>
#include <memory>
#include <string>

#include "loom/passes/object.hpp"
#include "loom/passes/view.hpp"
#include "loom/rhi/result.hpp"
#include "loom/scene/material.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/renderer/skin_palette.hpp"

namespace loom::renderer {

/// The kind "gltf-mesh" (one shared instance): parts "gltf-geometry" and "gltf-material", the
/// vertex buffer layout of loom::scene::Vertex.
const std::shared_ptr<const passes::ObjectKind>& gltf_mesh_kind();
/// The kind "gltf-skinned-mesh" of skinned draw items: parts "gltf-skinned-geometry" (the joint
/// palette besides the object's uniforms) and "gltf-material"; vertex buffers
/// scene::vertex_buffer_layout() and scene::skin_buffer_layout().
const std::shared_ptr<const passes::ObjectKind>& gltf_skinned_mesh_kind();

/// "<node name or node N>: <mesh name or mesh N> #<primitive>": the name of draw item `item`.
std::string gltf_item_name(const scene::Scene& scene, uint32_t item);

/// One draw item of a GpuScene's scene.
class GltfObject final : public passes::Object {
public:
    /// `draw_item` indexes gpu->scene().draw_items (a programming error when out of range); a
    /// skinned item is deformed by the GpuScene's palette (the scene's static pose).
    GltfObject(std::shared_ptr<const GpuScene> gpu, uint32_t draw_item);
    /// An item placed by the draw items of `placements` instead: a copy of gpu's scene that an
    /// animation poses (scene::pose), read at every draw. Its draw items must be gpu's scene's.
    GltfObject(std::shared_ptr<const GpuScene> gpu, std::shared_ptr<const scene::Scene> placements,
               uint32_t draw_item);
    /// With a joint palette for the placements' skins: a skinned draw item (DrawItem::skin) is
    /// then of the kind "gltf-skinned-mesh" and binds its skin's range of `palette`. Without one
    /// (or for an item without a skin) the item is drawn undeformed.
    GltfObject(std::shared_ptr<const GpuScene> gpu, std::shared_ptr<const scene::Scene> placements,
               std::shared_ptr<const SkinPalette> palette, uint32_t draw_item);

    [[nodiscard]] const std::shared_ptr<const passes::ObjectKind>& kind() const override {
        return skinned_ ? gltf_skinned_mesh_kind() : gltf_mesh_kind();
    }
    /// "<node name or node N>: <mesh name or mesh N> #<primitive>".
    [[nodiscard]] std::string name() const override { return name_; }
    /// No culling for double-sided materials, back faces culled otherwise; clockwise front
    /// faces where the world matrix mirrors (DrawItem::flips_winding).
    [[nodiscard]] rhi::RasterState raster() const override;
    /// Binds GltfObjectUniforms and the material's textures (the fallback texture where it has
    /// none; only what the program has: the shadow map's has no textures), the scene's buffers,
    /// and draws the primitive's range.
    Status render(passes::DrawContext& context) const override;

    [[nodiscard]] const scene::DrawItem& item() const;
    [[nodiscard]] const scene::Material& material() const;
    [[nodiscard]] scene::AlphaMode alpha_mode() const { return material().alpha_mode; }
    /// World bounds of the primitive (for sorting and framing), as placed now.
    [[nodiscard]] scene::Bounds world_bounds() const;

private:
    std::shared_ptr<const GpuScene> gpu_;
    std::shared_ptr<const scene::Scene> placements_;
    std::shared_ptr<const SkinPalette> palette_;
    uint32_t draw_item_;
    bool skinned_ = false;
    std::string name_;
};

}  // namespace loom::renderer
