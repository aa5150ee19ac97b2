#pragma once
// glTF files as pipeline scenes: loom::gltf imports the file into loom::scene's model, this
// library turns its draw items into GltfObjects ("gltf-mesh") and uploads geometry and textures
// once per device (GpuScene); the camera is the file's (first, or the one asked for) or one that
// frames the scene, and the light is a sun behind the viewer (files bring none).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/rhi/result.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/renderer/scene_objects.hpp"

namespace loom::renderer {

/// Imports `path` (gltf::load) and prepares it for upload (prepare_scene). Errors are the
/// importer's: one line naming the file and what is wrong.
Result<std::shared_ptr<const renderer::PreparedScene>> load_gltf_scene(const std::filesystem::path& path);

/// The pipeline scene of `gpu`'s scene seen from `viewpoint`: opaque and masked objects go to
/// the geometry (or forward) pass and cast shadows (masked ones through the masked shadow pass,
/// cut out), blended ones go to the transparent pass and cast none. The GpuScene may be shared
/// by several pipelines on its device. With `placements` (a copy of the scene an animation
/// poses), the objects are drawn where it places them, and the blended ones are sorted by the
/// bounds it gives them at every frame; the pipeline's bounds stay those of the first pose. With
/// `palette` (the placements' joint matrices, written by the caller after each pose), skinned
/// items are deformed by their joints.
PipelineScene gltf_pipeline_scene(const std::shared_ptr<const renderer::GpuScene>& gpu,
                                  const renderer::SceneViewpoint& viewpoint,
                                  std::shared_ptr<const scene::Scene> placements = nullptr,
                                  std::shared_ptr<const SkinPalette> palette = nullptr);

/// A pipeline scene without objects yet, as a glTF scene is seen: named after its file, the
/// camera of `viewpoint`, the viewer's sun (viewer_sun), `bounds` for the position map and the
/// shadow map.
PipelineScene gltf_view(const scene::Scene& scene, const renderer::SceneViewpoint& viewpoint, const scene::Bounds& bounds);

/// A blended glTF object for the transparent pass, sorted by its bounds now or, when it `moves`
/// (it reads a scene that is posed again), by the bounds it has at every frame.
BlendedObject blended_gltf_object(const std::shared_ptr<const GltfObject>& object, bool moves);

/// "3 opaque and 1 blended draw item(s), 2 material(s), 4 image(s); camera 0 'name'": what
/// `content` (made from `scene`) draws and from where.
std::string describe_gltf_scene(const scene::Scene& scene, const PipelineScene& content,
                                const renderer::SceneViewpoint& viewpoint);

}  // namespace loom::renderer
