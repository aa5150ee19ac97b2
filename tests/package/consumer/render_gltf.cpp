// Draws a glTF file through the installed (or subproject) loom::gltf and loom::renderer, the
// way an engine would: writes a small model (a red square facing +Z, with its buffer in a .bin
// file), imports it (gltf::load), uploads it once per backend (renderer::GpuScene), and
// renders the Figure 2 pipeline (renderer::DeferredPipeline) from a camera that frames it.
// Checks two texels of the picture: the middle is the square's red, a corner is the hazy sky.
// Exit status 0 when every backend drew both.
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "every_backend.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/renderer/gltf_scene.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/renderer/scene_objects.hpp"
#include "loom/rhi/device.hpp"

namespace {

using namespace loom;

// Four corners of a unit square in the XY plane, normals +Z, then two counter-clockwise
// triangles (seen from +Z) as u16 indices.
std::vector<char> square_buffer() {
    const std::array<float, 12> positions{-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::array<float, 12> normals{0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::array<uint16_t, 6> indices{0, 1, 2, 0, 2, 3};
    std::vector<char> bytes(sizeof positions + sizeof normals + sizeof indices);
    std::memcpy(bytes.data(), positions.data(), sizeof positions);
    std::memcpy(bytes.data() + sizeof positions, normals.data(), sizeof normals);
    std::memcpy(bytes.data() + sizeof positions + sizeof normals, indices.data(), sizeof indices);
    return bytes;
}

constexpr const char* kSquareGltf = R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0, "name": "square"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0,
                                          "roughnessFactor": 1}}],
  "buffers": [{"uri": "square.bin", "byteLength": 108}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 96, "byteLength": 12}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "min": [-1, -1, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ]
})";

Status write_square(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    const std::vector<char> buffer = square_buffer();
    std::ofstream bin(dir / "square.bin", std::ios::binary);
    bin.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    std::ofstream gltf(dir / "square.gltf");
    gltf << kSquareGltf;
    if (!bin || !gltf) return Error{ErrorCode::Io, "cannot write the model into " + dir.string()};
    return {};
}

Status render(rhi::Device& device, const std::shared_ptr<const renderer::PreparedScene>& prepared) {
    auto viewpoint = renderer::SceneViewpoint::choose(prepared->scene);
    if (!viewpoint) return viewpoint.take_error();
    auto gpu = renderer::GpuScene::create(device, prepared);
    if (!gpu) return gpu.take_error();
    renderer::PipelineSettings settings;
    settings.shadow_map_size = 256;
    auto pipeline = renderer::DeferredPipeline::create(device, renderer::gltf_pipeline_scene(*gpu, *viewpoint), settings);
    if (!pipeline) return pipeline.take_error();
    constexpr uint32_t kWidth = 64, kHeight = 48;
    LOOM_TRY((*pipeline)->render({kWidth, kHeight}));
    LOOM_TRY(device.wait_idle());
    auto picture = device.read_texture((*pipeline)->final_texture());
    if (!picture) return picture.take_error();
    const auto middle = picture->load(kWidth / 2, kHeight / 2);
    const auto corner = picture->load(1, 1);
    const bool red = middle[0] > 0.25 && middle[0] > 2.0 * middle[1] && middle[0] > 2.0 * middle[2];
    // The sky behind the square is a bright blue-grey haze (about 0.84, 0.85, 0.87).
    const bool sky = corner[1] > 0.5 && corner[2] >= corner[0];
    if (!red || !sky) {
        return Error{ErrorCode::Backend, "middle texel (" + std::to_string(middle[0]) + ", " + std::to_string(middle[1]) +
                                             ", " + std::to_string(middle[2]) + ") should be red, corner (" +
                                             std::to_string(corner[0]) + ", " + std::to_string(corner[1]) + ", " +
                                             std::to_string(corner[2]) + ") the sky"};
    }
    return {};
}

}  // namespace

int main() {
    const consumer::LoggedErrors logged;
    const std::filesystem::path dir = std::filesystem::current_path() / "render_gltf_model";
    if (auto written = write_square(dir); !written) {
        std::fprintf(stderr, "render_gltf: %s\n", written.error().to_string().c_str());
        return 1;
    }
    auto scene = gltf::load(dir / "square.gltf");
    if (!scene) {
        std::fprintf(stderr, "render_gltf: %s\n", scene.error().to_string().c_str());
        return 1;
    }
    const auto prepared = renderer::prepare_scene(std::move(*scene));
    const int failures = consumer::on_every_backend(
        "render_gltf", "drew the red square on the sky", [&](rhi::Device& device) { return render(device, prepared); });
    if (failures < 0) return 1;
    if (logged.count() > 0) std::fprintf(stderr, "render_gltf: %d error(s) logged\n", logged.count());
    return failures == 0 && logged.count() == 0 ? 0 : 1;
}
