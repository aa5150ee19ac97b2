#include "object_scene.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include <glm/gtc/matrix_transform.hpp>

#include "loom/passes/geometry_buffers.hpp"
#include "loom/passes/retained_mesh.hpp"

namespace loom::test {
namespace {

/// An ellipsoid with `rings` latitude bands and `segments` longitude sectors; radii within 1.
SceneMesh ellipsoid(std::string name, uint32_t rings, uint32_t segments, glm::vec3 radii, glm::vec4 tint) {
    SceneMesh mesh;
    mesh.name = std::move(name);
    const float pi = 3.14159265358979f;
    for (uint32_t r = 0; r <= rings; ++r) {
        const float theta = pi * static_cast<float>(r) / static_cast<float>(rings);
        for (uint32_t s = 0; s <= segments; ++s) {
            const float phi = 2.0f * pi * static_cast<float>(s) / static_cast<float>(segments);
            const glm::vec3 unit(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            passes::MeshVertex v;
            v.position = unit * radii;
            v.normal = glm::normalize(unit / radii);
            v.uv0 = glm::vec2(static_cast<float>(s) / static_cast<float>(segments),
                              static_cast<float>(r) / static_cast<float>(rings));
            v.color = tint;
            mesh.vertices.push_back(v);
        }
    }
    // Counter-clockwise seen from outside; the triangles touching a pole are left out of their
    // degenerate half.
    const uint32_t row = segments + 1;
    for (uint32_t r = 0; r < rings; ++r) {
        for (uint32_t s = 0; s < segments; ++s) {
            const uint32_t a = r * row + s, b = a + 1, c = a + row, d = c + 1;
            if (r != 0) mesh.indices.insert(mesh.indices.end(), {a, b, c});
            if (r + 1 != rings) mesh.indices.insert(mesh.indices.end(), {b, d, c});
        }
    }
    return mesh;
}

auto state_key(const ObjectScene& scene, const SceneObject& object) {
    const SceneMaterial& material = scene.materials[object.material];
    const bool mirrored = glm::determinant(glm::mat3(object.model)) < 0.0f;
    return std::make_tuple(material.checker, material.value.material.double_sided, mirrored, object.material);
}

}  // namespace

passes::MeshSurface plain_surface() {
    passes::MeshSurface surface;
    surface.material.metallic_factor = 0.0f;
    surface.material.roughness_factor = 0.5f;
    return surface;
}

ObjectScene make_object_scene(const ObjectSceneSpec& spec) {
    ObjectScene scene;
    std::mt19937 random(spec.seed);
    auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(random); };
    auto integer = [&](uint32_t lo, uint32_t hi) { return std::uniform_int_distribution<uint32_t>(lo, hi)(random); };

    for (uint32_t i = 0; i < spec.meshes; ++i) {
        const glm::vec3 radii(uniform(0.55f, 1.0f), uniform(0.55f, 1.0f), uniform(0.55f, 1.0f));
        const glm::vec4 tint(uniform(0.7f, 1.0f), uniform(0.7f, 1.0f), uniform(0.7f, 1.0f), 1.0f);
        scene.meshes.push_back(ellipsoid("mesh " + std::to_string(i), integer(2, 4), integer(3, 7), radii, tint));
    }
    for (uint32_t i = 0; i < spec.materials; ++i) {
        SceneMaterial m;
        scene::Material& material = m.value.material;
        material.base_color_factor = glm::vec4(uniform(0.05f, 1.0f), uniform(0.05f, 1.0f), uniform(0.05f, 1.0f), 1.0f);
        m.value.checker.secondary_color = glm::vec4(uniform(0.0f, 0.3f), uniform(0.0f, 0.3f), uniform(0.0f, 0.3f), 1.0f);
        material.metallic_factor = uniform(0.0f, 1.0f);
        material.roughness_factor = uniform(0.1f, 1.0f);
        m.value.checker.cells_per_unit = uniform(2.0f, 6.0f);
        if (i % 7 == 3) material.emissive_factor = glm::vec3(material.base_color_factor) * 2.0f;
        material.double_sided = i % 6 == 5;
        m.checker = i % 5 == 2;
        scene.materials.push_back(m);
    }
    const auto side = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(spec.objects))));
    for (uint32_t i = 0; i < spec.objects; ++i) {
        SceneObject object;
        object.mesh = integer(0, spec.meshes - 1);
        object.material = integer(0, spec.materials - 1);
        const float x = static_cast<float>(i % side) - 0.5f * static_cast<float>(side - 1);
        const float z = static_cast<float>(i / side) - 0.5f * static_cast<float>(side - 1);
        const float scale = uniform(0.3f, 0.45f);  // radius <= 1: inside the unit cell
        glm::mat4 model = glm::translate(glm::mat4(1.0f), glm::vec3(x, scale, z));
        model = glm::rotate(model, uniform(0.0f, 6.28318f), glm::vec3(0.0f, 1.0f, 0.0f));
        model = glm::scale(model, glm::vec3(i % 20 == 7 ? -scale : scale, scale, scale));
        object.model = model;
        scene.objects.push_back(object);
    }
    std::shuffle(scene.objects.begin(), scene.objects.end(), random);

    const float extent = static_cast<float>(side);
    scene.camera.position = glm::vec3(0.0f, extent * 0.9f, -extent * 0.55f);
    scene.camera.view = glm::lookAtRH(scene.camera.position, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
    scene.camera.projection = glm::perspectiveRH_ZO(glm::radians(60.0f), 1.0f, 0.1f, extent * 4.0f);
    return scene;
}

uint64_t distinct_state_keys(const ObjectScene& scene) {
    std::set<decltype(state_key(scene, scene.objects[0]))> keys;
    for (const SceneObject& object : scene.objects) keys.insert(state_key(scene, object));
    return keys.size();
}

uint64_t distinct_key_mesh_pairs(const ObjectScene& scene) {
    std::set<std::pair<decltype(state_key(scene, scene.objects[0])), uint32_t>> pairs;
    for (const SceneObject& object : scene.objects) pairs.insert({state_key(scene, object), object.mesh});
    return pairs.size();
}

Result<NaiveObjects> make_naive_objects(rhi::Device& device, const ObjectScene& scene) {
    NaiveObjects out;
    for (const SceneMesh& mesh : scene.meshes) {
        auto gpu = passes::GpuMesh::create(device, mesh.vertices, mesh.indices, mesh.name);
        if (!gpu) return gpu.take_error();
        out.meshes.push_back(*gpu);
    }
    const auto pbr = passes::pbr_mesh_kind();
    const auto checker = passes::checker_mesh_kind();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const SceneMaterial& material = scene.materials[object.material];
        out.objects.push_back(std::make_shared<passes::MeshObject>("object " + std::to_string(i),
                                                                   material.checker ? checker : pbr,
                                                                   out.meshes[object.mesh], object.model, material.value));
    }
    return out;
}

Result<RetainedObjects> make_retained_objects(const ObjectScene& scene) {
    RetainedObjects out;
    for (const SceneMesh& mesh : scene.meshes) {
        auto geometry = passes::make_mesh_geometry(mesh.name, mesh.vertices, mesh.indices);
        if (!geometry) return geometry.take_error();
        out.geometries.push_back(*geometry);
    }
    for (std::size_t i = 0; i < scene.materials.size(); ++i) {
        out.materials.push_back(passes::make_mesh_material("material " + std::to_string(i), scene.materials[i].value));
    }
    const auto pbr = passes::retained_pbr_mesh_kind();
    const auto checker = passes::retained_checker_mesh_kind();
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        auto model = std::make_shared<passes::InputParam<glm::mat4>>(object.model);
        out.models.push_back(model);
        out.shapes.push_back(std::make_shared<passes::Shape>(
            "object " + std::to_string(i), scene.materials[object.material].checker ? checker : pbr,
            out.geometries[object.mesh], out.materials[object.material], model));
    }
    return out;
}

}  // namespace loom::test
