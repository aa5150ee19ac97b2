#pragma once
// A glTF scene in the retained object layer (loom/passes/retained_scene.hpp), the LPSG way:
// every opaque and masked draw item is a Shape submitted once — its primitive's geometry in the
// layer's shared buffers, its material one MaterialUniforms set with the material's textures,
// its world matrix an InputParam — and the pipeline's shadow, masked-shadow, geometry and forward
// passes draw them from render queues sorted by state. Posing an animation sets the world
// matrices of the items that moved and nothing else: the next frame uploads their records
// (128 bytes each) and rebuilds no queue.
//
//   auto gltf = RetainedGltfScene::create(device, prepared);            // uploads the textures
//   auto pipeline = DeferredPipeline::create(device, (*gltf)->pipeline_scene(viewpoint));
//   for (float t : times) { (*gltf)->pose(0, t); (*pipeline)->render(frame); }
//
// Skinned items are shapes of the kind "retained-gltf-skinned-mesh": their geometry carries the
// influences with joint indices into the scene's SkinPalette, which the layer binds for every
// batch (RetainedScene::set_shared_buffer); posing writes the joint matrices of the skins that
// moved (64 bytes per joint) and their records stay as they are (the identity).
//
// Blended items are drawn by the transparent pass as GltfObjects, sorted back to front every
// frame: they read their placement from the posed scene and their geometry from the GpuScene's
// buffers (uploaded only when the scene has blended items).

#include <cstdint>
#include <memory>
#include <vector>

#include "loom/passes/object.hpp"
#include "loom/passes/param.hpp"
#include "loom/passes/retained_scene.hpp"
#include "loom/passes/shape.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/renderer/scene_objects.hpp"
#include "loom/renderer/skin_palette.hpp"

namespace loom::renderer {

/// The kind "retained-gltf-mesh": parts "retained-gltf-geometry" (scene::Vertex placed by the
/// object's record) and "gltf-material"; vertex buffers scene::vertex_buffer_layout() and the
/// per-instance object index (passes::object_index_layout()). It draws exactly what
/// "gltf-mesh" draws.
const std::shared_ptr<const passes::ObjectKind>& retained_gltf_mesh_kind();
/// The kind "retained-gltf-skinned-mesh" of skinned draw items: parts
/// "retained-gltf-skinned-geometry" (the layer's shared buffer "JointMatrices" besides the
/// record and the material) and "gltf-material"; vertex buffers scene::vertex_buffer_layout(),
/// scene::skin_buffer_layout() (joint indices into the whole palette) and the object index.
const std::shared_ptr<const passes::ObjectKind>& retained_gltf_skinned_mesh_kind();

class RetainedGltfScene : public std::enable_shared_from_this<RetainedGltfScene> {
public:
    /// Uploads the textures (and the geometry of blended items, which GltfObjects draw), makes
    /// one geometry per primitive drawn, one material per material used, and submits one shape
    /// per opaque or masked draw item. Errors: the device's, naming the buffer or texture.
    static Result<std::shared_ptr<RetainedGltfScene>> create(rhi::Device& device,
                                                             std::shared_ptr<const PreparedScene> prepared,
                                                             passes::RetainedConfig config = {});
    RetainedGltfScene(const RetainedGltfScene&) = delete;
    RetainedGltfScene& operator=(const RetainedGltfScene&) = delete;

    /// What the pipeline draws, seen from `viewpoint`: `retained` is this scene's layer (it
    /// keeps this object alive), `blended` the blended items with bounds that follow the pose.
    /// Masked items cast cut-out shadows through the masked shadow pass, as in
    /// gltf_pipeline_scene(). Give it to one pipeline at a time: a pass draws one layer, and a
    /// layer draws on one device.
    PipelineScene pipeline_scene(const SceneViewpoint& viewpoint);

    /// Poses the scene's animation `animation` at `time` seconds (scene::pose): the moved opaque
    /// and masked items get their new world matrix (uploaded by the next frame), the joint
    /// matrices of the skins whose joints moved are written to the palette, the moved blended
    /// items and the scene's bounds follow. Returns the draw items that moved. An index
    /// the file does not have, or a negative or non-finite time, is an InvalidArgument error.
    Result<std::vector<uint32_t>> pose(uint32_t animation, float time);

    /// The scene as posed now (the prepared scene before the first pose).
    [[nodiscard]] const scene::Scene& scene() const { return *posed_; }
    [[nodiscard]] const GpuScene& gpu() const { return *gpu_; }
    [[nodiscard]] passes::RetainedScene& retained() { return *retained_; }
    [[nodiscard]] const passes::RetainedScene& retained() const { return *retained_; }
    /// The shape of draw item `item`; null for blended items and items with no indices.
    [[nodiscard]] const passes::Shape* shape(uint32_t item) const;
    /// Shapes submitted (opaque and masked draw items) and materials made for them.
    [[nodiscard]] std::size_t shape_count() const { return retained_->size(); }
    [[nodiscard]] std::size_t material_count() const { return retained_->material_count(); }
    /// The joint palette of the scene's skins (null without skins): bytes_written() counts what
    /// posing wrote.
    [[nodiscard]] const SkinPalette* skin_palette() const { return palette_.get(); }

private:
    RetainedGltfScene() = default;
    Status build(passes::RetainedConfig config);

    std::shared_ptr<const GpuScene> gpu_;
    /// A copy of the prepared scene without its images, posed by pose().
    std::shared_ptr<scene::Scene> posed_;
    std::shared_ptr<passes::RetainedScene> retained_;
    std::shared_ptr<SkinPalette> palette_;
    /// Per draw item: its shape's world matrix and its shape (null where it has none).
    std::vector<std::shared_ptr<passes::InputParam<glm::mat4>>> models_;
    std::vector<std::shared_ptr<passes::Shape>> shapes_;
    /// GltfObjects of the blended items.
    std::vector<std::shared_ptr<const GltfObject>> blended_;
    bool masked_ = false;
};

}  // namespace loom::renderer
