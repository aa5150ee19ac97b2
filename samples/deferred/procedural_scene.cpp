#include "procedural_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace loom::deferred {
namespace {

constexpr float kPi = 3.14159265358979f;

passes::MeshVertex vertex(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& uv) {
    passes::MeshVertex v;
    v.position = position;
    v.normal = normal;
    v.uv0 = uv;
    return v;
}

/// Makes every triangle counter-clockwise seen from the side its vertex normals point to, so
/// that back-face culling keeps the outside whatever order a generator produced.
void orient_triangles(MeshData& mesh) {
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const passes::MeshVertex& a = mesh.vertices[mesh.indices[i]];
        const passes::MeshVertex& b = mesh.vertices[mesh.indices[i + 1]];
        const passes::MeshVertex& c = mesh.vertices[mesh.indices[i + 2]];
        const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
        if (glm::dot(face, a.normal + b.normal + c.normal) < 0.0f) std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }
}

/// A (columns+1) x (rows+1) grid of vertices from `at(u, v)` in [0,1]^2, two triangles per cell.
template <class Point>
MeshData make_grid(uint32_t columns, uint32_t rows, Point at) {
    MeshData mesh;
    for (uint32_t r = 0; r <= rows; ++r) {
        for (uint32_t c = 0; c <= columns; ++c) {
            const glm::vec2 uv(static_cast<float>(c) / static_cast<float>(columns),
                               static_cast<float>(r) / static_cast<float>(rows));
            mesh.vertices.push_back(at(uv));
        }
    }
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < columns; ++c) {
            const uint32_t i = r * (columns + 1) + c;
            const uint32_t right = i + 1, down = i + columns + 1, diagonal = down + 1;
            mesh.indices.insert(mesh.indices.end(), {i, right, diagonal, i, diagonal, down});
        }
    }
    orient_triangles(mesh);
    return mesh;
}

void append(MeshData& into, const MeshData& part) {
    const auto base = static_cast<uint32_t>(into.vertices.size());
    into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
    for (uint32_t index : part.indices) into.indices.push_back(base + index);
}

glm::mat4 place(const glm::vec3& position, float yaw_degrees = 0.0f, const glm::vec3& tilt_axis = {1, 0, 0},
                float tilt_degrees = 0.0f) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), position);
    m = glm::rotate(m, glm::radians(yaw_degrees), glm::vec3(0, 1, 0));
    if (tilt_degrees != 0.0f) m = glm::rotate(m, glm::radians(tilt_degrees), tilt_axis);
    return m;
}

passes::MeshSurface material(const glm::vec3& albedo, float metallic, float roughness, float glow = 0.0f) {
    passes::MeshSurface m;
    m.material.base_color_factor = glm::vec4(albedo, 1.0f);
    m.material.metallic_factor = metallic;
    m.material.roughness_factor = roughness;
    // Glowing materials emit in their own colour (what the G-buffer stores exactly).
    m.material.emissive_factor = albedo * glow;
    return m;
}

}  // namespace

MeshData make_plane(float size_x, float size_z, uint32_t cells) {
    return make_grid(cells, cells, [&](glm::vec2 uv) {
        return vertex({(uv.x - 0.5f) * size_x, 0.0f, (uv.y - 0.5f) * size_z}, {0, 1, 0}, uv);
    });
}

MeshData make_box(const glm::vec3& size) {
    MeshData mesh;
    const glm::vec3 h = size * 0.5f;
    // Each face: its normal and two in-plane axes spanning it.
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
        const glm::vec3 a = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 b = glm::cross(n, a);
        append(mesh, make_grid(1, 1, [&](glm::vec2 uv) {
                   const glm::vec3 p = n + a * (uv.x * 2.0f - 1.0f) + b * (uv.y * 2.0f - 1.0f);
                   return vertex(p * h, n, uv);
               }));
    }
    return mesh;
}

MeshData make_sphere(float radius, uint32_t segments, uint32_t rings) {
    return make_grid(segments, rings, [&](glm::vec2 uv) {
        const float phi = uv.x * 2.0f * kPi;
        const float theta = uv.y * kPi;
        const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        return vertex(n * radius, n, uv);
    });
}

MeshData make_torus(float major_radius, float minor_radius, uint32_t segments, uint32_t sides) {
    return make_grid(segments, sides, [&](glm::vec2 uv) {
        const float u = uv.x * 2.0f * kPi;
        const float v = uv.y * 2.0f * kPi;
        const glm::vec3 n(std::cos(v) * std::cos(u), std::sin(v), std::cos(v) * std::sin(u));
        const glm::vec3 ring(std::cos(u) * major_radius, 0.0f, std::sin(u) * major_radius);
        return vertex(ring + n * minor_radius, n, uv);
    });
}

scene::Bounds scene_bounds(const std::vector<SceneItem>& items, bool only_casters) {
    scene::Bounds bounds;
    for (const SceneItem& item : items) {
        if (only_casters && !item.casts_shadow) continue;
        for (const passes::MeshVertex& v : item.mesh.vertices) bounds.extend(glm::vec3(item.model * glm::vec4(v.position, 1.0f)));
    }
    return bounds;
}

scene::Bounds shadow_region(const scene::Bounds& casters, const glm::vec3& towards_light) {
    scene::Bounds region = casters;
    region.min.y = std::min(region.min.y, 0.0f);
    const glm::vec3 l = glm::normalize(towards_light);
    if (l.y <= 1e-3f) return region;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? casters.max.x : casters.min.x, (i & 2) ? casters.max.y : casters.min.y,
                               (i & 4) ? casters.max.z : casters.min.z);
        const glm::vec3 on_ground = corner - l * (corner.y / l.y);
        region.min = glm::min(region.min, on_ground);
        region.max = glm::max(region.max, on_ground);
    }
    return region;
}

SceneContent procedural_scene() {
    SceneContent scene;
    auto add = [&](std::string name, MeshData mesh, passes::MeshSurface m, glm::mat4 model, bool checker = false) {
        scene.items.push_back(SceneItem{std::move(name), std::move(mesh), m, model, checker});
    };

    passes::MeshSurface ground = material({0.72f, 0.70f, 0.66f}, 0.0f, 0.8f);
    ground.checker.secondary_color = glm::vec4(0.20f, 0.22f, 0.26f, 1.0f);
    ground.checker.cells_per_unit = 1.0f;
    add("ground", make_plane(200.0f, 200.0f, 100), ground, glm::mat4(1.0f), true);
    scene.items.back().casts_shadow = false;  // nothing lies below it

    add("pillar", make_box({0.6f, 2.6f, 0.6f}), material({0.88f, 0.82f, 0.72f}, 0.0f, 0.55f),
        place({-2.7f, 1.3f, -1.6f}, -30.0f));
    add("red cube", make_box({1.2f, 1.2f, 1.2f}), material({0.75f, 0.08f, 0.06f}, 0.0f, 0.45f),
        place({-1.7f, 0.6f, 1.0f}, -25.0f));
    add("green cube", make_box({0.55f, 0.55f, 0.55f}), material({0.12f, 0.55f, 0.18f}, 0.0f, 0.35f),
        place({-1.6f, 1.475f, 0.95f}, 10.0f));
    add("chrome sphere", make_sphere(0.85f, 64, 32), material({0.95f, 0.93f, 0.88f}, 1.0f, 0.12f),
        place({0.35f, 0.85f, -0.5f}));
    add("blue sphere", make_sphere(0.55f, 48, 24), material({0.08f, 0.22f, 0.85f}, 0.0f, 0.12f),
        place({2.1f, 0.55f, 1.3f}));
    add("gold torus", make_torus(0.7f, 0.24f, 64, 24), material({1.0f, 0.74f, 0.30f}, 1.0f, 0.28f),
        place({2.1f, 0.94f, -1.9f}, -35.0f, {1, 0, 0}, 90.0f));
    add("lamp", make_sphere(0.3f, 32, 16), material({1.0f, 0.42f, 0.1f}, 0.0f, 0.5f, 14.0f),
        place({-0.45f, 0.3f, 2.45f}));
    add("neon bar", make_box({0.14f, 1.5f, 0.14f}), material({0.15f, 0.75f, 1.0f}, 0.0f, 0.5f, 9.0f),
        place({0.95f, 0.75f, 2.05f}, 15.0f));

    scene.light.direction = glm::normalize(glm::vec3(-0.8f, 0.62f, 0.05f));
    scene.light.color = glm::vec3(1.0f, 0.93f, 0.82f);
    scene.light.intensity = 3.4f;
    scene.eye = glm::vec3(6.4f, 3.4f, 7.6f);
    scene.target = glm::vec3(0.0f, 0.75f, 0.1f);
    scene.yfov = glm::radians(36.0f);
    scene.environment.fog_density = 0.05f;
    scene.environment.fog_start = 14.0f;
    scene.bounds = scene_bounds(scene.items);
    scene.shadow_bounds = shadow_region(scene_bounds(scene.items, true), scene.light.direction);
    return scene;
}

Result<renderer::PipelineScene> procedural_pipeline_scene(rhi::Device& device, const SceneContent& content) {
    renderer::PipelineScene scene;
    scene.name = "builtin";
    const auto pbr = passes::pbr_mesh_kind();
    const auto checker = passes::checker_mesh_kind();
    for (const SceneItem& item : content.items) {
        auto mesh = passes::GpuMesh::create(device, item.mesh.vertices, item.mesh.indices, item.name);
        if (!mesh) return mesh.take_error();
        auto object = std::make_shared<passes::MeshObject>(item.name, item.checker ? checker : pbr, *mesh, item.model,
                                                           item.surface);
        // Only casters go into the shadow map (the ground has nothing below it to shadow).
        if (item.casts_shadow) scene.shadow_casters.push_back(object);
        scene.opaque.push_back(object);
    }
    const glm::vec3 eye = content.eye, target = content.target;
    const float yfov = content.yfov;
    scene.camera = [eye, target, yfov](float aspect) {
        scene::CameraMatrices camera;
        camera.view = glm::lookAtRH(eye, target, glm::vec3(0.0f, 1.0f, 0.0f));
        camera.projection = glm::perspectiveRH_ZO(yfov, aspect, 0.1f, 150.0f);
        camera.position = eye;
        return camera;
    };
    scene.light = content.light;
    scene.environment = content.environment;
    scene.bounds = content.bounds;
    scene.shadow_bounds = content.shadow_bounds;
    return scene;
}

Result<std::unique_ptr<renderer::DeferredPipeline>> create_procedural_pipeline(rhi::Device& device,
                                                                              const SceneContent& content,
                                                                              const renderer::PipelineSettings& settings) {
    auto scene = procedural_pipeline_scene(device, content);
    if (!scene) return scene.take_error();
    return renderer::DeferredPipeline::create(device, std::move(*scene), settings);
}

}  // namespace loom::deferred
