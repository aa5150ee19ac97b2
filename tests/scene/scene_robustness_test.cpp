// Systematic damage to valid files: every number in a document replaced by hostile values,
// every truncation of a GLB file, corrupted bytes in its headers. Each load must either succeed
// or return one clean, one-line error naming the file — under ASan/UBSan this also proves that
// nothing reads out of bounds.
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "loom/image_io/image_io.hpp"
#include "loom/rhi/log.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom_test/test_support.hpp"
#include "scene_test_util.hpp"

namespace loom::test {
namespace {

using Layout = GltfBuilder::Layout;

struct Outcome {
    std::size_t loaded = 0;
    std::size_t failed = 0;
};

// Files are written once under fresh names: truncating and rewriting one file is slow on
// file systems that discard freed blocks.

// Loads `path` and checks that a failure is clean; counts the outcome.
void load_and_check(const std::filesystem::path& path, Outcome& outcome, const std::string& what) {
    auto result = gltf::load(path);
    if (result) {
        ++outcome.loaded;
        return;
    }
    ++outcome.failed;
    const Error& error = result.error();
    EXPECT_TRUE(error.code == ErrorCode::Parse || error.code == ErrorCode::Io) << what << ": " << error.to_string();
    EXPECT_EQ(error.message.find('\n'), std::string::npos) << what << ": " << error.message;
    EXPECT_EQ(error.message.rfind(path.string() + ": ", 0), 0u) << what << ": " << error.message;
}

// A small but complete document: textured, normal-mapped, sparse, with a camera and a
// two-level hierarchy, so that every part of the importer sees the damage.
GltfBuilder complete_document(const std::filesystem::path& dir) {
    GltfBuilder builder;
    builder.add_quad(false, 0);
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    EXPECT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    const std::vector<unsigned char> png = read_bytes(dir / "pixel.png");
    builder.json()["images"] = nlohmann::json::array({{{"bufferView", builder.add_view(png)}, {"mimeType", "image/png"}}});
    builder.json()["samplers"] = nlohmann::json::array({{{"minFilter", 9987}, {"wrapS", 33071}}});
    builder.json()["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
    builder.json()["materials"] = nlohmann::json::array(
        {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 0}}}, {"metallicFactor", 0.5}}},
          {"normalTexture", {{"index", 0}, {"scale", 1.0}}},
          {"alphaMode", "MASK"},
          {"alphaCutoff", 0.5}}});
    // A sparse substitution on the positions.
    const int sparse_indices = builder.add_view(std::vector<uint16_t>{1, 3});
    const int sparse_values = builder.add_view(std::vector<float>{2, 0, 0, 0, 2, 0});
    builder.json()["accessors"][0]["sparse"] = {{"count", 2},
                                                {"indices", {{"bufferView", sparse_indices}, {"componentType", kUnsignedShort}}},
                                                {"values", {{"bufferView", sparse_values}}}};
    builder.json()["cameras"] = nlohmann::json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}, {"zfar", 50}}}}});
    builder.json()["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}, {"children", {2}}});
    builder.json()["nodes"].push_back({{"mesh", 0}, {"scale", {2, 2, 2}}});
    builder.json()["scenes"][0]["nodes"].push_back(1);
    return builder;
}

// Every place in `value` that holds a number, as JSON pointers.
void number_pointers(const nlohmann::json& value, const nlohmann::json::json_pointer& where,
                     std::vector<nlohmann::json::json_pointer>& out) {
    if (value.is_number()) {
        out.push_back(where);
    } else if (value.is_array()) {
        for (std::size_t i = 0; i < value.size(); ++i) number_pointers(value[i], where / i, out);
    } else if (value.is_object()) {
        for (const auto& [key, child] : value.items()) number_pointers(child, where / key, out);
    }
}

TEST(SceneRobustness, EveryNumberReplacedByHostileValues) {
    const std::filesystem::path dir = synthetic_dir("hostile_numbers");
    const GltfBuilder builder = complete_document(dir);
    ScopedLogCapture capture;  // some replacements only cause warnings
    ASSERT_TRUE(gltf::load(builder.write(dir, "intact", Layout::Binary)))
        << "the intact document must load";
    std::vector<nlohmann::json::json_pointer> pointers;
    number_pointers(builder.document(Layout::Binary, ""), nlohmann::json::json_pointer(), pointers);
    ASSERT_GT(pointers.size(), 60u);
    const std::vector<nlohmann::json> hostile = {
        -1, 0, 1, 3, 255, 65535, 2147483647, 4294967296ull, 9007199254740991ull, 18446744073709551615ull, 1e300, -0.5,
        "7", nullptr,
    };
    Outcome outcome;
    std::size_t case_index = 0;
    for (const auto& pointer : pointers) {
        for (const nlohmann::json& value : hostile) {
            const std::string what = pointer.to_string() + " = " + value.dump();
            const std::filesystem::path path = builder.write(dir, "case" + std::to_string(case_index++), Layout::Binary,
                                                             [&](nlohmann::json& doc) { doc[pointer] = value; });
            load_and_check(path, outcome, what);
        }
    }
    // Most damage is caught; some values are harmless where they land (a scale of 3).
    EXPECT_GT(outcome.failed, outcome.loaded);
    EXPECT_GT(outcome.loaded, 0u);
    std::cout << "  " << outcome.failed << " damaged documents rejected, " << outcome.loaded << " still valid\n";
}

TEST(SceneRobustness, EveryTruncationOfAGlbFails) {
    const std::filesystem::path dir = synthetic_dir("truncated_glb");
    const GltfBuilder builder = complete_document(dir);
    const std::vector<unsigned char> bytes = read_bytes(builder.write(dir, "intact", Layout::Binary));
    ASSERT_GT(bytes.size(), 100u);
    Outcome outcome;
    for (std::size_t length = 0; length < bytes.size(); ++length) {
        const std::filesystem::path path = dir / ("cut" + std::to_string(length) + ".glb");
        write_bytes(path, std::vector<unsigned char>(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(length)));
        load_and_check(path, outcome, "length " + std::to_string(length));
    }
    EXPECT_EQ(outcome.loaded, 0u);
    EXPECT_EQ(outcome.failed, bytes.size());
}

TEST(SceneRobustness, UnknownPngChunkTypeBytesStayOneLine) {
    // Found by fuzz/gltf_import: stb_image names an unknown critical PNG chunk by its four type
    // bytes, straight from the file, so a type with a newline split the importer's error.
    const std::filesystem::path dir = synthetic_dir("png_chunk_type");
    rhi::Image pixel(1, 1, rhi::Format::RGBA8Unorm);
    ASSERT_TRUE(image_io::write_png(pixel, dir / "pixel.png").ok());
    std::vector<unsigned char> png = read_bytes(dir / "pixel.png");
    // After the signature (8 bytes) and IHDR (25): an empty chunk of type "\n\xffAB" (critical:
    // bit 5 of its first byte is clear) and its CRC, which stb_image does not check.
    const std::vector<unsigned char> chunk{0, 0, 0, 0, '\n', 0xff, 'A', 'B', 0, 0, 0, 0};
    png.insert(png.begin() + 33, chunk.begin(), chunk.end());
    GltfBuilder builder;
    builder.add_quad(false, 0);
    builder.json()["images"] = nlohmann::json::array({{{"bufferView", builder.add_view(png)}, {"mimeType", "image/png"}}});
    builder.json()["textures"] = nlohmann::json::array({{{"source", 0}}});
    builder.json()["materials"] = nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
    const std::filesystem::path path = builder.write(dir, "chunk", Layout::Binary);
    auto result = gltf::load(path);
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, ErrorCode::Parse);
    EXPECT_EQ(result.error().message.find('\n'), std::string::npos) << result.error().message;
    EXPECT_NE(result.error().message.find("cannot decode image: \\x0a\\xffAB PNG chunk not known"), std::string::npos)
        << result.error().message;
}

TEST(SceneRobustness, CorruptedGlbHeaderBytes) {
    const std::filesystem::path dir = synthetic_dir("corrupted_glb");
    const GltfBuilder builder = complete_document(dir);
    const std::vector<unsigned char> bytes = read_bytes(builder.write(dir, "intact", Layout::Binary));
    // The 20 header bytes, then the BIN chunk header (after the JSON chunk).
    const std::size_t json_length = bytes[12] | (bytes[13] << 8) | (bytes[14] << 16) | (std::size_t{bytes[15]} << 24);
    std::vector<std::size_t> positions;
    for (std::size_t i = 0; i < 20; ++i) positions.push_back(i);
    for (std::size_t i = 0; i < 8; ++i) positions.push_back(20 + json_length + i);
    Outcome outcome;
    for (const std::size_t position : positions) {
        for (const unsigned char value : {0x00, 0x01, 0x7f, 0x80, 0xff}) {
            if (bytes[position] == value) continue;
            std::vector<unsigned char> corrupted = bytes;
            corrupted[position] = value;
            const std::filesystem::path path =
                dir / ("byte" + std::to_string(position) + "_" + std::to_string(value) + ".glb");
            write_bytes(path, corrupted);
            load_and_check(path, outcome, "byte " + std::to_string(position) + " = " + std::to_string(value));
        }
    }
    // A corrupted header byte is always caught (lengths, magic, version, chunk types).
    EXPECT_EQ(outcome.loaded, 0u);
}

}  // namespace
}  // namespace loom::test
