#include "engine_scene.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "loom/gltf/gltf.hpp"
#include "loom/scene/scene.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include "procedural_scene.hpp"

namespace loom::engine {
namespace {

constexpr float kPi = 3.14159265f;

/// The courtyard under construction: one mesh, material and draw item per object.
class SceneBuilder {
public:
    void add(const std::string& name, const deferred::MeshData& mesh, const scene::Material& material, const glm::mat4& world) {
        scene::Primitive primitive;
        primitive.vertices.reserve(mesh.vertices.size());
        for (const passes::MeshVertex& v : mesh.vertices) {
            primitive.vertices.push_back(scene::Vertex{v.position, v.normal, v.tangent, v.uv0, v.uv1, v.color});
            primitive.bounds.extend(v.position);
        }
        primitive.indices = mesh.indices;
        primitive.material = static_cast<uint32_t>(scene_.materials.size());
        scene_.materials.push_back(material);
        scene_.meshes.push_back(scene::Mesh{name, {std::move(primitive)}});

        scene::Node node;
        node.name = name;
        node.local = world;
        node.world = world;
        node.mesh = static_cast<uint32_t>(scene_.meshes.size() - 1);
        scene_.nodes.push_back(node);
        scene::DrawItem item;
        item.node = static_cast<uint32_t>(scene_.nodes.size() - 1);
        item.mesh = *node.mesh;
        item.primitive = 0;
        item.material = scene_.meshes.back().primitives[0].material;
        set_transform(item, world, scene_.meshes.back().primitives[0].bounds);
        scene_.draw_items.push_back(item);
    }

    /// Appends every draw item of `model`, moved by `placement`, with its meshes, materials,
    /// textures and images (indices shifted past the courtyard's).
    void append(scene::Scene model, const glm::mat4& placement) {
        const auto mesh_offset = static_cast<uint32_t>(scene_.meshes.size());
        const auto material_offset = static_cast<uint32_t>(scene_.materials.size());
        const auto texture_offset = static_cast<uint32_t>(scene_.textures.size());
        const auto image_offset = static_cast<uint32_t>(scene_.images.size());
        const auto node_offset = static_cast<uint32_t>(scene_.nodes.size());
        for (scene::Mesh& mesh : model.meshes) {
            for (scene::Primitive& primitive : mesh.primitives) primitive.material += material_offset;
            scene_.meshes.push_back(std::move(mesh));
        }
        for (scene::Material& material : model.materials) {
            for (auto* ref : {&material.base_color_texture, &material.metallic_roughness_texture, &material.normal_texture,
                              &material.occlusion_texture, &material.emissive_texture}) {
                if (ref->has_value()) (*ref)->texture += texture_offset;
            }
            scene_.materials.push_back(std::move(material));
        }
        for (scene::Texture& texture : model.textures) {
            texture.image += image_offset;
            scene_.textures.push_back(std::move(texture));
        }
        for (scene::TextureImage& image : model.images) scene_.images.push_back(std::move(image));
        for (scene::Node& node : model.nodes) {
            if (node.parent) *node.parent += node_offset;
            for (uint32_t& child : node.children) child += node_offset;
            if (node.mesh) *node.mesh += mesh_offset;
            node.world = placement * node.world;
            scene_.nodes.push_back(std::move(node));
        }
        for (scene::DrawItem item : model.draw_items) {
            item.node += node_offset;
            item.mesh += mesh_offset;
            item.material += material_offset;
            const scene::Bounds local = scene_.meshes[item.mesh].primitives[item.primitive].bounds;
            set_transform(item, placement * item.world, local);
            scene_.draw_items.push_back(item);
        }
        for (std::string& warning : model.warnings) scene_.warnings.push_back(std::move(warning));
    }

    scene::Scene finish() {
        scene_.bounds = {};
        for (const scene::DrawItem& item : scene_.draw_items) scene_.bounds.extend(item.world_bounds);
        return std::move(scene_);
    }

private:
    static void set_transform(scene::DrawItem& item, const glm::mat4& world, const scene::Bounds& local) {
        item.world = world;
        const glm::mat3 linear(world);
        item.normal_matrix = glm::transpose(glm::inverse(linear));
        item.flips_winding = glm::determinant(linear) < 0.0f;
        item.world_bounds = local.transformed(world);
    }

    scene::Scene scene_;
};

scene::Material material(const std::string& name, const glm::vec3& color, float roughness, float metallic = 0.0f) {
    scene::Material m;
    m.name = name;
    m.base_color_factor = glm::vec4(color, 1.0f);
    m.roughness_factor = roughness;
    m.metallic_factor = metallic;
    return m;
}

glm::mat4 at(const glm::vec3& position) { return glm::translate(glm::mat4(1.0f), position); }

/// A colour of the hue wheel (h in 0..1), fully saturated.
glm::vec3 hue(float h) {
    const glm::vec3 k(0.0f, 2.0f / 3.0f, 1.0f / 3.0f);
    glm::vec3 c;
    for (int i = 0; i < 3; ++i) c[i] = std::clamp(std::abs(std::fmod(h + k[i], 1.0f) * 6.0f - 3.0f) - 1.0f, 0.0f, 1.0f);
    return c;
}

void add_courtyard(SceneBuilder& builder, bool centre_props) {
    builder.add("ground", deferred::make_plane(28.0f, 28.0f, 8), material("stone floor", {0.36f, 0.35f, 0.33f}, 0.8f), glm::mat4(1.0f));
    const deferred::MeshData pillar = deferred::make_box({0.6f, 3.2f, 0.6f});
    const deferred::MeshData sphere = deferred::make_sphere(0.55f, 32, 16);
    const deferred::MeshData crate = deferred::make_box({0.9f, 0.9f, 0.9f});
    for (int i = 0; i < 10; ++i) {
        const float angle = 2.0f * kPi * static_cast<float>(i) / 10.0f;
        const glm::vec3 ring(std::cos(angle) * 6.0f, 0.0f, std::sin(angle) * 6.0f);
        builder.add("pillar " + std::to_string(i), pillar, material("sandstone", {0.72f, 0.62f, 0.48f}, 0.7f),
                    at(ring + glm::vec3(0.0f, 1.6f, 0.0f)));
        const float between = angle + kPi / 10.0f;
        const glm::vec3 inner(std::cos(between) * 4.6f, 0.55f, std::sin(between) * 4.6f);
        if (i % 2 == 0) {
            builder.add("sphere " + std::to_string(i), sphere,
                        material(i % 4 == 0 ? "polished brass" : "glazed clay",
                                 i % 4 == 0 ? glm::vec3(0.95f, 0.74f, 0.38f) : glm::vec3(0.2f, 0.38f, 0.7f),
                                 i % 4 == 0 ? 0.25f : 0.35f, i % 4 == 0 ? 1.0f : 0.0f),
                        at(inner));
        } else {
            builder.add("crate " + std::to_string(i), crate, material("painted wood", {0.55f, 0.2f, 0.16f}, 0.6f),
                        at(inner - glm::vec3(0.0f, 0.1f, 0.0f)) * glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0)));
        }
    }
    if (centre_props) {
        builder.add("torus", deferred::make_torus(1.0f, 0.35f, 48, 24), material("gold", {1.0f, 0.78f, 0.34f}, 0.3f, 1.0f),
                    at({0.0f, 1.35f, 0.0f}) * glm::rotate(glm::mat4(1.0f), 1.2f, glm::vec3(1, 0, 0.3f)));
        builder.add("crate stack", crate, material("painted wood", {0.25f, 0.5f, 0.28f}, 0.6f), at({1.6f, 0.45f, 1.1f}));
        builder.add("crate top", crate, material("painted wood", {0.6f, 0.6f, 0.62f}, 0.5f),
                    at({1.6f, 1.35f, 1.1f}) * glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0, 1, 0)));
    }
}

/// Lights on three rings over the courtyard, low above the ground, each a colour of the hue wheel.
std::vector<PointLight> scatter_lights(uint32_t count) {
    std::vector<PointLight> lights;
    lights.reserve(count);
    for (uint32_t i = 0; i < count; ++i) {
        const float t = static_cast<float>(i) / static_cast<float>(count);
        const float ring = 2.6f + 4.2f * static_cast<float>(i % 3) + 0.35f * static_cast<float>((i / 3) % 4);
        const float angle = 2.0f * kPi * t * 3.0f + 0.37f * static_cast<float>(i % 3);
        const float height = 0.45f + 0.6f * static_cast<float>((i * 7) % 5) / 4.0f;
        PointLight light;
        light.position_radius = glm::vec4(std::cos(angle) * ring, height, std::sin(angle) * ring, 2.2f);
        light.color = glm::vec4(hue(std::fmod(t * 5.0f, 1.0f)) * 0.9f, 0.0f);
        lights.push_back(light);
    }
    return lights;
}

}  // namespace

Result<EngineScene> make_engine_scene(const SceneSettings& settings) {
    if (settings.lights == 0 || settings.lights > kMaxLights) {
        return make_error(ErrorCode::InvalidArgument, "lights: " + std::to_string(settings.lights) +
                                                          " is out of range (1.." + std::to_string(kMaxLights) + ")");
    }
    SceneBuilder builder;
    add_courtyard(builder, settings.model.empty());
    std::string model_line = "the courtyard's own centrepiece";
    if (!settings.model.empty()) {
        auto model = gltf::load(settings.model);
        if (!model) return model.take_error();
        if (model->draw_items.empty() || model->bounds.empty()) {
            return make_error(ErrorCode::InvalidArgument, settings.model.string() + ": the scene draws nothing");
        }
        // Largest side 2.5 units, centred on the courtyard, standing on the ground.
        const scene::Bounds bounds = model->bounds;
        const glm::vec3 size = bounds.size();
        const float scale = 2.5f / std::max({size.x, size.y, size.z, 1e-6f});
        const glm::vec3 centre = bounds.center();
        const glm::mat4 placement = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, (centre.y - bounds.min.y) * scale, 0.0f)) *
                                    glm::scale(glm::mat4(1.0f), glm::vec3(scale)) * glm::translate(glm::mat4(1.0f), -centre);
        model_line = settings.model.filename().string() + " (" + std::to_string(model->draw_items.size()) + " draw items)";
        builder.append(std::move(*model), placement);
    }

    EngineScene out;
    scene::Scene scene = builder.finish();
    out.description = std::to_string(scene.draw_items.size()) + " draw items, " + std::to_string(scene.materials.size()) +
                      " materials, " + std::to_string(scene.images.size()) + " images, " + std::to_string(settings.lights) +
                      " point lights; centre: " + model_line;
    for (const std::string& warning : scene.warnings) out.description += "\n  warning: " + warning;
    out.prepared = renderer::prepare_scene(std::move(scene));
    out.lights = scatter_lights(settings.lights);
    out.towards_sun = glm::normalize(glm::vec3(-0.55f, 0.45f, -0.35f));
    out.sun_color = glm::vec3(2.4f, 1.7f, 1.1f);
    out.sky_zenith = glm::vec3(0.06f, 0.11f, 0.26f);
    out.sky_horizon = glm::vec3(0.42f, 0.28f, 0.2f);
    out.ground_color = glm::vec3(0.09f, 0.075f, 0.06f);
    out.eye = glm::vec3(8.2f, 4.6f, 9.4f);
    out.target = glm::vec3(0.0f, 0.9f, 0.0f);
    return out;
}

}  // namespace loom::engine
