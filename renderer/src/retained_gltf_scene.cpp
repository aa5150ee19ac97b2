#include "loom/renderer/retained_gltf_scene.hpp"

#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
#include <span>
#include <string>
#include <utility>

#include "loom/passes/retained_mesh.hpp"
#include "loom/renderer/gltf_scene.hpp"
#include "loom/scene/mesh.hpp"

#include "gltf_material_block.hpp"

namespace loom::renderer {
namespace {

/// The passes of DeferredPipeline that draw a retained item (Shape::passes): the shadow map it
/// casts into (cut out through its material when masked) and both lit passes (the pipeline has
/// one of them).
std::vector<std::string> passes_of(scene::AlphaMode mode) {
    return {mode == scene::AlphaMode::Mask ? "masked-shadow" : "shadow", "geometry", "forward"};
}

/// The material as the retained kind binds it: its MaterialUniforms (fixed: glTF materials do
/// not change) and a texture for each of the part's samplers (the GpuScene's white one where the
/// material has none), sampled as the file says.
std::shared_ptr<passes::GpuMaterial> make_material(const GpuScene& gpu, uint32_t index) {
    const scene::Material& material = gpu.scene().materials[index];
    const GltfMaterialBlock block = gltf_material_block(material);
    auto uniforms = std::make_shared<passes::UniformSet>(
        "MaterialUniforms", passes::UpdateFrequency::PerMaterial, static_cast<uint32_t>(sizeof(GltfMaterialBlock)),
        [block](std::span<std::byte> bytes) { std::memcpy(bytes.data(), &block, sizeof(block)); },
        std::vector<std::shared_ptr<passes::ParamNode>>{});
    std::vector<passes::MaterialTexture> textures;
    const auto refs = gltf_texture_refs(material);
    for (std::size_t i = 0; i < refs.size(); ++i) {
        passes::MaterialTexture texture;
        texture.name = std::string(kGltfSamplers[i]);
        if (refs[i]->has_value()) {
            texture.texture = gpu.texture((*refs[i])->texture).texture;
            texture.sampler = gpu.scene().textures[(*refs[i])->texture].sampler;
        } else {
            texture.texture = gpu.fallback().texture;
        }
        textures.push_back(std::move(texture));
    }
    std::string name = material.name.empty() ? "material " + std::to_string(index) : material.name;
    return std::make_shared<passes::GpuMaterial>(std::move(name), std::move(uniforms), std::move(textures),
                                                 material.double_sided ? rhi::CullMode::None : rhi::CullMode::Back);
}

}  // namespace

const std::shared_ptr<const passes::ObjectKind>& retained_gltf_skinned_mesh_kind() {
    static const std::shared_ptr<const passes::ObjectKind> kind =
        make_gltf_kind("retained-gltf-skinned-mesh", "retained-gltf-skinned-geometry",
                       {scene::vertex_buffer_layout(), scene::skin_buffer_layout(), passes::object_index_layout()});
    return kind;
}

const std::shared_ptr<const passes::ObjectKind>& retained_gltf_mesh_kind() {
    static const std::shared_ptr<const passes::ObjectKind> kind = make_gltf_kind(
        "retained-gltf-mesh", "retained-gltf-geometry", {scene::vertex_buffer_layout(), passes::object_index_layout()});
    return kind;
}

Result<std::shared_ptr<RetainedGltfScene>> RetainedGltfScene::create(rhi::Device& device,
                                                                     std::shared_ptr<const PreparedScene> prepared,
                                                                     passes::RetainedConfig config) {
    bool any_blended = false;
    for (const scene::DrawItem& item : prepared->scene.draw_items) {
        any_blended |= prepared->scene.materials[item.material].alpha_mode == scene::AlphaMode::Blend;
    }
    auto gpu = GpuScene::create(device, prepared, any_blended ? GpuSceneContent::All : GpuSceneContent::TexturesOnly);
    if (!gpu) return gpu.take_error();
    std::shared_ptr<RetainedGltfScene> scene(new RetainedGltfScene());
    scene->gpu_ = std::move(*gpu);
    scene->posed_ = std::make_shared<scene::Scene>(scene::copy_without_images(prepared->scene));
    if (!scene->posed_->skins.empty()) {
        auto palette = SkinPalette::create(device, *scene->posed_);
        if (!palette) return palette.take_error();
        scene->palette_ = std::move(*palette);
    }
    LOOM_TRY(scene->build(config));
    return scene;
}

Status RetainedGltfScene::build(passes::RetainedConfig config) {
    retained_ = std::make_shared<passes::RetainedScene>(config);
    if (palette_) retained_->set_shared_buffer("JointMatrices", palette_->whole());
    const scene::Scene& scene = *posed_;
    models_.resize(scene.draw_items.size());
    shapes_.resize(scene.draw_items.size());
    // By mesh, primitive and skin (a skinned primitive's joint indices point at its skin's
    // joints in the palette; kNoSkin for unskinned ones).
    constexpr uint32_t kNoSkin = UINT32_MAX;
    std::map<std::tuple<uint32_t, uint32_t, uint32_t>, std::shared_ptr<const passes::Geometry>> geometries;
    std::map<uint32_t, std::shared_ptr<passes::GpuMaterial>> materials;
    for (uint32_t i = 0; i < scene.draw_items.size(); ++i) {
        const scene::DrawItem& item = scene.draw_items[i];
        const scene::Primitive& primitive = scene.meshes[item.mesh].primitives[item.primitive];
        if (primitive.indices.empty()) continue;
        const scene::AlphaMode mode = scene.materials[item.material].alpha_mode;
        if (mode == scene::AlphaMode::Blend) {
            blended_.push_back(std::make_shared<const GltfObject>(gpu_, posed_, palette_, i));
            continue;
        }
        const bool skinned = item.skin && palette_ && !primitive.skin.empty();
        std::shared_ptr<const passes::Geometry>& geometry =
            geometries[{item.mesh, item.primitive, skinned ? *item.skin : kNoSkin}];
        if (!geometry) {
            const std::span<const std::byte> bytes = std::as_bytes(std::span<const scene::Vertex>(primitive.vertices));
            std::vector<rhi::VertexBufferLayout> layouts{scene::vertex_buffer_layout()};
            std::vector<std::vector<std::byte>> streams{std::vector<std::byte>(bytes.begin(), bytes.end())};
            if (skinned) {
                std::vector<scene::SkinInfluences> influences = primitive.skin;
                const uint32_t base = palette_->base(*item.skin);
                for (scene::SkinInfluences& influence : influences) influence.joints += glm::uvec4(base);
                const std::span<const std::byte> skin_bytes = std::as_bytes(std::span<const scene::SkinInfluences>(influences));
                layouts.push_back(scene::skin_buffer_layout());
                streams.emplace_back(skin_bytes.begin(), skin_bytes.end());
            }
            auto made = passes::Geometry::create(
                scene.source + " mesh " + std::to_string(item.mesh) + " #" + std::to_string(item.primitive) +
                    (skinned ? " skin " + std::to_string(*item.skin) : ""),
                std::move(layouts), std::move(streams), static_cast<uint32_t>(primitive.vertices.size()), primitive.indices);
            if (!made) return made.take_error();
            geometry = *made;
        }
        std::shared_ptr<passes::GpuMaterial>& material = materials[item.material];
        if (!material) material = make_material(*gpu_, item.material);
        models_[i] = std::make_shared<passes::InputParam<glm::mat4>>(item.world);
        auto shape = std::make_shared<passes::Shape>(gltf_item_name(scene, i),
                                                     skinned ? retained_gltf_skinned_mesh_kind() : retained_gltf_mesh_kind(),
                                                     geometry, material, models_[i]);
        shape->passes = passes_of(mode);
        masked_ |= mode == scene::AlphaMode::Mask;
        LOOM_TRY(retained_->submit(shape));
        shapes_[i] = std::move(shape);
    }
    return {};
}

PipelineScene RetainedGltfScene::pipeline_scene(const SceneViewpoint& viewpoint) {
    // The bounds of what is drawn, as gltf_pipeline_scene() takes them.
    scene::Bounds bounds;
    for (std::size_t i = 0; i < shapes_.size(); ++i) {
        if (shapes_[i]) bounds.extend(posed_->draw_items[i].world_bounds);
    }
    for (const auto& object : blended_) bounds.extend(object->world_bounds());
    if (bounds.empty()) bounds = scene::Bounds{glm::vec3(-0.5f), glm::vec3(0.5f)};
    PipelineScene pipeline = gltf_view(*posed_, viewpoint, bounds);
    // The layer keeps this object (the GpuScene's textures, the posed scene) alive.
    pipeline.retained = std::shared_ptr<passes::RetainedScene>(shared_from_this(), retained_.get());
    pipeline.retained_masked_shadows = masked_;
    for (const auto& object : blended_) pipeline.blended.push_back(blended_gltf_object(object, true));
    return pipeline;
}

Result<std::vector<uint32_t>> RetainedGltfScene::pose(uint32_t animation, float time) {
    if (animation >= posed_->animations.size()) {
        return make_error(ErrorCode::InvalidArgument, posed_->source + ": animation " + std::to_string(animation) +
                                                          " does not exist (the scene has " +
                                                          std::to_string(posed_->animations.size()) + " animation(s))");
    }
    if (!std::isfinite(time) || time < 0.0f) {
        return make_error(ErrorCode::InvalidArgument,
                          posed_->source + ": animation time " + std::to_string(time) + " is not a time (seconds >= 0)");
    }
    std::vector<uint32_t> moved = scene::pose(*posed_, posed_->animations[animation], time);
    std::vector<bool> skins_to_write(posed_->skins.size(), false);
    for (uint32_t item : moved) {
        const std::optional<uint32_t> skin = posed_->draw_items[item].skin;
        if (skin) {
            skins_to_write[*skin] = true;
        } else if (models_[item]) {
            models_[item]->set(posed_->draw_items[item].world);
        }
    }
    for (uint32_t s = 0; s < skins_to_write.size(); ++s) {
        if (skins_to_write[s] && palette_) LOOM_TRY(palette_->write(*posed_, s));
    }
    return moved;
}

const passes::Shape* RetainedGltfScene::shape(uint32_t item) const {
    return item < shapes_.size() ? shapes_[item].get() : nullptr;
}

}  // namespace loom::renderer
