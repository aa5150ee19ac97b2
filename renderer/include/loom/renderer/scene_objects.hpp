#pragma once
// A glTF scene as objects for the passes: one GltfObject per draw item, split by how passes
// draw them, and the views of it (its cameras, or one that frames its bounds).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "loom/passes/view.hpp"
#include "loom/rhi/result.hpp"
#include "loom/scene/camera.hpp"
#include "loom/scene/scene.hpp"
#include "loom/renderer/gltf_object.hpp"
#include "loom/renderer/gpu_scene.hpp"

namespace loom::renderer {

/// The objects of a GpuScene, in draw-item order.
struct SceneObjects {
    std::shared_ptr<const GpuScene> gpu;
    /// alphaMode OPAQUE and MASK: the G-buffer (or forward) pass and the shadow map draw them.
    std::vector<std::shared_ptr<const GltfObject>> opaque;
    /// alphaMode BLEND: the transparent pass draws them, back to front; they cast no shadow.
    std::vector<std::shared_ptr<const GltfObject>> blended;
    /// World bounds of every object (the scene's bounds; empty scenes: a unit box at the origin).
    scene::Bounds bounds;
};

/// One GltfObject per draw item of `gpu`'s scene (items with no indices are skipped), placed by
/// `placements` when given (a copy of the scene that an animation poses: GltfObject reads it at
/// every draw), skinned items deformed by `palette` when given (the placements' skins). Without
/// placements, skinned items are deformed by the GpuScene's own palette (its static pose), and
/// `palette` is not used.
SceneObjects make_scene_objects(std::shared_ptr<const GpuScene> gpu,
                                std::shared_ptr<const scene::Scene> placements = nullptr,
                                std::shared_ptr<const SkinPalette> palette = nullptr);

/// How a glTF scene is looked at: the file's camera `camera` (an index into Scene::cameras), or
/// when none is asked for the first camera of the file, or when it has none, a camera that
/// frames the scene's bounds (loom::scene::frame_bounds). A perspective camera keeps its vertical
/// field of view but takes the picture's aspect ratio, not its own (which would stretch the
/// picture; glTF leaves the choice to the renderer). An index the file does not have is an
/// InvalidArgument error saying how many cameras there are.
class SceneViewpoint {
public:
    static Result<SceneViewpoint> choose(const scene::Scene& scene, std::optional<uint32_t> camera = std::nullopt);

    /// The camera for a viewport of aspect ratio width / height.
    [[nodiscard]] scene::CameraMatrices camera(float aspect) const;
    /// "camera 0 'name'" or "framing the bounds".
    [[nodiscard]] std::string describe() const;

private:
    std::optional<scene::Camera> file_camera_;
    std::optional<uint32_t> index_;
    scene::Bounds bounds_;
};

/// The light of a glTF scene (files bring none): a white sun from above, behind and to the left
/// of the viewer, so that the side the camera sees is lit and shadows fall away from it.
passes::DirectionalLight viewer_sun(const scene::CameraMatrices& camera);

}  // namespace loom::renderer
