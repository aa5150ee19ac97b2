#include "synthetic_scene.hpp"

#include <cmath>
#include <string>

namespace loom::test {

SceneBuilder::SceneBuilder() { scene_.source = "synthetic.gltf"; }

uint32_t SceneBuilder::material(const scene::Material& material) {
    scene_.materials.push_back(material);
    return static_cast<uint32_t>(scene_.materials.size() - 1);
}

uint32_t SceneBuilder::texture(const rhi::Image& image, const rhi::SamplerDesc& sampler) {
    scene::TextureImage entry;
    entry.name = "image " + std::to_string(scene_.images.size());
    entry.source = static_cast<uint32_t>(scene_.images.size());
    entry.image = image;
    scene_.images.push_back(entry);
    scene::Texture texture;
    texture.name = entry.name;
    texture.image = entry.source;
    texture.sampler = sampler;
    scene_.textures.push_back(texture);
    return static_cast<uint32_t>(scene_.textures.size() - 1);
}

uint32_t SceneBuilder::quad(uint32_t material, const glm::mat4& world, const glm::vec4& color) {
    scene::Primitive primitive;
    const glm::vec2 corners[4] = {{-1, 1}, {1, 1}, {1, -1}, {-1, -1}};
    for (const glm::vec2& corner : corners) {
        scene::Vertex v;
        v.position = glm::vec3(corner, 0.0f);
        v.normal = glm::vec3(0, 0, 1);
        v.tangent = glm::vec4(1, 0, 0, 1);
        v.uv0 = glm::vec2(corner.x * 0.5f + 0.5f, 0.5f - corner.y * 0.5f);
        v.uv1 = glm::vec2(1.0f - v.uv0.x, v.uv0.y);
        v.color = color;
        primitive.vertices.push_back(v);
        primitive.bounds.extend(v.position);
    }
    // Counter-clockwise seen from +z.
    primitive.indices = {0, 3, 2, 0, 2, 1};
    primitive.material = material;
    scene::Mesh mesh;
    mesh.name = "quad " + std::to_string(scene_.meshes.size());
    mesh.primitives.push_back(primitive);
    scene_.meshes.push_back(mesh);

    scene::Node node;
    node.name = mesh.name;
    node.local = world;
    node.world = world;
    node.mesh = static_cast<uint32_t>(scene_.meshes.size() - 1);
    scene_.nodes.push_back(node);

    scene::DrawItem item;
    item.node = static_cast<uint32_t>(scene_.nodes.size() - 1);
    item.mesh = *node.mesh;
    item.primitive = 0;
    item.material = material;
    item.world = world;
    const glm::mat3 m(world);
    item.normal_matrix = glm::mat3(glm::cross(m[1], m[2]), glm::cross(m[2], m[0]), glm::cross(m[0], m[1]));
    item.flips_winding = glm::determinant(m) < 0.0f;
    if (item.flips_winding) item.normal_matrix = -item.normal_matrix;
    item.world_bounds = primitive.bounds.transformed(world);
    scene_.draw_items.push_back(item);
    scene_.bounds.extend(item.world_bounds);
    return static_cast<uint32_t>(scene_.draw_items.size() - 1);
}

void SceneBuilder::camera(float distance) {
    scene::Camera camera;
    camera.name = "test camera";
    camera.world = glm::mat4(1.0f);
    camera.world[3] = glm::vec4(0.0f, 0.0f, distance, 1.0f);
    scene::PerspectiveProjection projection;
    projection.yfov = 1.0471976f;
    projection.znear = 0.1f;
    projection.zfar = 100.0f;
    camera.projection = projection;
    scene_.cameras = {camera};
}

rhi::SamplerDesc nearest_sampler() {
    rhi::SamplerDesc desc;
    desc.name = "nearest";
    desc.min_filter = rhi::Filter::Nearest;
    desc.mag_filter = rhi::Filter::Nearest;
    desc.max_lod = 0.0f;
    return desc;
}

rhi::Image image_of(uint32_t width, uint32_t height, rhi::Format format, const std::vector<std::array<uint8_t, 4>>& texels) {
    rhi::Image image(width, height, format);
    for (uint32_t i = 0; i < width * height; ++i) {
        for (uint32_t c = 0; c < 4; ++c) image.pixels[i * 4 + c] = static_cast<std::byte>(texels[i][c]);
    }
    return image;
}

double srgb_to_linear(uint8_t value) {
    const double s = value / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
}

}  // namespace loom::test
