#include "loom/renderer/scene_objects.hpp"

#include <string>
#include <variant>

#include <glm/glm.hpp>

namespace loom::renderer {

SceneObjects make_scene_objects(std::shared_ptr<const GpuScene> gpu, std::shared_ptr<const scene::Scene> placements,
                                std::shared_ptr<const SkinPalette> palette) {
    SceneObjects objects;
    objects.gpu = gpu;
    const scene::Scene& scene = placements ? *placements : gpu->scene();
    scene::Bounds bounds;
    for (uint32_t i = 0; i < scene.draw_items.size(); ++i) {
        if (gpu->prepared().geometry.range(scene.draw_items[i]).index_count == 0) continue;
        // Without placements: the scene itself, in its own pose (and its GpuScene's palette).
        auto object = placements ? std::make_shared<const GltfObject>(gpu, placements, palette, i)
                                 : std::make_shared<const GltfObject>(gpu, i);
        bounds.extend(scene.draw_items[i].world_bounds);
        (object->alpha_mode() == scene::AlphaMode::Blend ? objects.blended : objects.opaque).push_back(std::move(object));
    }
    if (bounds.empty()) bounds = scene::Bounds{glm::vec3(-0.5f), glm::vec3(0.5f)};
    objects.bounds = bounds;
    return objects;
}

Result<SceneViewpoint> SceneViewpoint::choose(const scene::Scene& scene, std::optional<uint32_t> camera) {
    SceneViewpoint viewpoint;
    viewpoint.bounds_ = scene.bounds;
    if (camera && *camera >= scene.cameras.size()) {
        return make_error(ErrorCode::InvalidArgument,
                          scene.source + ": camera " + std::to_string(*camera) + " does not exist (the scene has " +
                              std::to_string(scene.cameras.size()) + " camera(s))");
    }
    if (!camera && !scene.cameras.empty()) camera = 0;
    if (camera) {
        viewpoint.index_ = camera;
        viewpoint.file_camera_ = scene.cameras[*camera];
        // The picture's own aspect ratio: a camera's would stretch it (glTF leaves the choice).
        if (auto* perspective = std::get_if<scene::PerspectiveProjection>(&viewpoint.file_camera_->projection)) {
            perspective->aspect_ratio.reset();
        }
    }
    return viewpoint;
}

scene::CameraMatrices SceneViewpoint::camera(float aspect) const {
    const scene::Camera camera = file_camera_ ? *file_camera_ : scene::frame_bounds(bounds_, aspect);
    return camera.matrices(aspect);
}

std::string SceneViewpoint::describe() const {
    if (!index_) return "framing the bounds";
    std::string text = "camera " + std::to_string(*index_);
    if (!file_camera_->name.empty()) text += " '" + file_camera_->name + "'";
    return text;
}

passes::DirectionalLight viewer_sun(const scene::CameraMatrices& camera) {
    // Rows of the view matrix's rotation: the camera's right and backward axes in world space.
    const glm::vec3 right(camera.view[0][0], camera.view[1][0], camera.view[2][0]);
    const glm::vec3 back(camera.view[0][2], camera.view[1][2], camera.view[2][2]);
    passes::DirectionalLight light;
    light.direction = glm::normalize(-0.45f * right + 0.55f * back + 0.9f * glm::vec3(0.0f, 1.0f, 0.0f));
    light.color = glm::vec3(1.0f, 0.96f, 0.9f);
    light.intensity = 3.0f;
    return light;
}

}  // namespace loom::renderer
