#include "loom/renderer/gltf_scene.hpp"

#include "loom/gltf/gltf.hpp"

namespace loom::renderer {

Result<std::shared_ptr<const renderer::PreparedScene>> load_gltf_scene(const std::filesystem::path& path) {
    auto scene = gltf::load(path);
    if (!scene) return scene.take_error();
    return renderer::prepare_scene(std::move(*scene));
}

PipelineScene gltf_pipeline_scene(const std::shared_ptr<const renderer::GpuScene>& gpu,
                                  const renderer::SceneViewpoint& viewpoint,
                                  std::shared_ptr<const scene::Scene> placements,
                                  std::shared_ptr<const SkinPalette> palette) {
    const renderer::SceneObjects objects = renderer::make_scene_objects(gpu, placements, palette);
    PipelineScene scene = gltf_view(gpu->scene(), viewpoint, objects.bounds);
    for (const auto& object : objects.opaque) {
        // Cut-out surfaces cast cut-out shadows: through the masked shadow pass.
        (object->alpha_mode() == scene::AlphaMode::Mask ? scene.masked_shadow_casters : scene.shadow_casters).push_back(object);
        scene.opaque.push_back(object);
    }
    // With placements, an object reads the posed scene it keeps alive.
    for (const auto& object : objects.blended) scene.blended.push_back(blended_gltf_object(object, placements != nullptr));
    return scene;
}

BlendedObject blended_gltf_object(const std::shared_ptr<const GltfObject>& object, bool moves) {
    BlendedObject blended{object, object->world_bounds(), nullptr};
    if (moves) blended.moving_bounds = [object] { return object->world_bounds(); };
    return blended;
}

PipelineScene gltf_view(const scene::Scene& scene, const renderer::SceneViewpoint& viewpoint, const scene::Bounds& bounds) {
    PipelineScene view;
    view.name = scene.source;
    view.camera = [viewpoint](float aspect) { return viewpoint.camera(aspect); };
    // The camera's orientation does not depend on the aspect ratio; only its distance may.
    view.light = renderer::viewer_sun(viewpoint.camera(1.0f));
    view.bounds = bounds;
    view.shadow_bounds = bounds;
    return view;
}

std::string describe_gltf_scene(const scene::Scene& scene, const PipelineScene& content,
                                const renderer::SceneViewpoint& viewpoint) {
    return std::to_string(content.opaque.size()) + " opaque and " + std::to_string(content.blended.size()) +
           " blended draw item(s), " + std::to_string(scene.materials.size()) + " material(s), " +
           std::to_string(scene.images.size()) + " image(s); " + viewpoint.describe();
}

}  // namespace loom::renderer
