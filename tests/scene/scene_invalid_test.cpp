// Broken glTF files: every file under <data>/gltf/invalid/ (walked, so new files are covered)
// and synthetic ones written by the tests. Each must give one clean one-line error naming the
// file and, where the Khronos validator's report gives one, the JSON pointer — never a crash.
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom_test/test_support.hpp"
#include "scene_test_util.hpp"

namespace loom::test {
namespace {

using Layout = GltfBuilder::Layout;

// What the validator's report says about a file: the pointers of its errors and whether one
// of them is an I/O error.
struct Report {
    std::vector<std::string> pointers;
    bool io = false;
};

std::optional<Report> read_report(const std::filesystem::path& file) {
    const std::filesystem::path report_path = file.string() + ".report.json";
    std::ifstream stream(report_path);
    if (!stream) return std::nullopt;
    const nlohmann::json report = nlohmann::json::parse(stream);
    Report result;
    // A string member, or "" (written out: GCC 12 at -O3 warns about nlohmann's value()).
    auto text = [](const nlohmann::json& object, const char* key) {
        const auto found = object.find(key);
        return found != object.end() && found->is_string() ? found->get<std::string>() : std::string();
    };
    for (const nlohmann::json& message : report.at("issues").at("messages")) {
        const auto severity = message.find("severity");
        if (severity == message.end() || *severity != 0) continue;  // errors only
        const std::string pointer = text(message, "pointer");
        if (!pointer.empty()) result.pointers.push_back(pointer);
        if (text(message, "code") == "IO_ERROR") result.io = true;
    }
    return result;
}

bool is_model_file(const std::filesystem::path& path) {
    return path.extension() == ".gltf" || path.extension() == ".glb";
}

// Loads `path`, expecting a clean error: the right code, one line, naming the file.
Error expect_load_error(const std::filesystem::path& path, const gltf::LoadOptions& options = {}) {
    auto result = gltf::load(path, options);
    if (result) {
        ADD_FAILURE() << path << " loaded although it is broken";
        return Error{};
    }
    const Error& error = result.error();
    EXPECT_TRUE(error.code == ErrorCode::Parse || error.code == ErrorCode::Io || error.code == ErrorCode::InvalidArgument)
        << error.to_string();
    EXPECT_EQ(error.message.find('\n'), std::string::npos) << "not one line: " << error.message;
    EXPECT_NE(error.message.find(path.string()), std::string::npos) << "does not name the file: " << error.message;
    return error;
}

TEST(SceneInvalidFiles, EveryFileInTheInvalidDirectoryGivesACleanError) {
    LOOM_REQUIRE_DATA_DIR(data);
    const std::filesystem::path dir = gltf_models(data) / "invalid";
    ASSERT_TRUE(std::filesystem::is_directory(dir)) << dir;
    std::size_t files = 0;
    std::size_t with_pointer = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        if (!entry.is_regular_file() || !is_model_file(entry.path())) continue;
        ++files;
        SCOPED_TRACE(entry.path().string());
        const Error error = expect_load_error(entry.path());
        std::cout << "  " << std::filesystem::relative(entry.path(), dir).string() << " -> " << error.to_string() << "\n";
        const std::optional<Report> report = read_report(entry.path());
        if (!report) continue;
        EXPECT_EQ(error.code, report->io ? ErrorCode::Io : ErrorCode::Parse) << error.to_string();
        if (report->pointers.empty()) continue;
        ++with_pointer;
        bool named = false;
        for (const std::string& pointer : report->pointers) named |= error.message.find(pointer) != std::string::npos;
        EXPECT_TRUE(named) << "the message names none of the report's pointers (first: " << report->pointers.front()
                           << "): " << error.message;
    }
    // The data set as committed: 20 broken files, 6 of them with pointers in their reports.
    EXPECT_GE(files, 20u);
    EXPECT_GE(with_pointer, 6u);
}

TEST(SceneInvalidFiles, MissingAndUnreadableMainFiles) {
    const std::filesystem::path dir = synthetic_dir("missing_main");
    EXPECT_EQ(expect_load_error(dir / "does_not_exist.gltf").code, ErrorCode::Io);
    std::filesystem::create_directories(dir / "folder.gltf");
    EXPECT_EQ(expect_load_error(dir / "folder.gltf").code, ErrorCode::Io);
}

// ---- synthetic broken files -------------------------------------------------------------

// A valid textured, normal-mapped quad with a camera node; tests break one thing each.
class BrokenFile : public ::testing::Test {
protected:
    void SetUp() override {
        const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir_ = synthetic_dir(std::string(info->test_suite_name()) + "." + info->name());
        builder_.json()["materials"] = nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
        builder_.add_quad(true, 0);
        const std::vector<unsigned char> png = tiny_png(dir_);
        builder_.json()["images"] = nlohmann::json::array({{{"bufferView", builder_.add_view(png)}, {"mimeType", "image/png"}}});
        builder_.json()["samplers"] = nlohmann::json::array({nlohmann::json::object()});
        builder_.json()["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
        builder_.json()["cameras"] = nlohmann::json::array(
            {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}});
        builder_.json()["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 3}}});
        builder_.json()["scenes"][0]["nodes"].push_back(1);
    }

    // A 2x2 PNG made with the project's own writer (in the test's own directory: ctest runs
    // tests in parallel processes).
    static std::vector<unsigned char> tiny_png(const std::filesystem::path& dir) {
        rhi::Image image(2, 2, rhi::Format::RGBA8Unorm);
        image.store(0, 0, {1.0, 0.0, 0.0, 1.0});
        const std::filesystem::path path = dir / "tiny.png";
        EXPECT_TRUE(image_io::write_png(image, path).ok());
        return read_bytes(path);
    }

    // Writes the document (after `edit`) in every layout and expects each to fail with `code`
    // and a message containing the file followed by `pointer` (or a longer pointer starting
    // with it), and `phrase`.
    void expect_error(const std::function<void(nlohmann::json&)>& edit, const std::string& pointer, const std::string& phrase,
                      ErrorCode code = ErrorCode::Parse, const gltf::LoadOptions& options = {}) {
        for (const Layout layout : {Layout::External, Layout::Embedded, Layout::Binary}) {
            // A fresh name per file: rewriting one file is slow where freed blocks are discarded.
            const std::filesystem::path path = builder_.write(dir_, "broken" + std::to_string(written_++), layout, edit);
            SCOPED_TRACE(path.string());
            const Error error = expect_load_error(path, options);
            EXPECT_EQ(error.code, code) << error.to_string();
            EXPECT_NE(error.message.find(path.string() + ": " + pointer), std::string::npos)
                << "expected pointer " << pointer << " in: " << error.message;
            EXPECT_NE(error.message.find(phrase), std::string::npos) << "expected '" << phrase << "' in: " << error.message;
        }
    }

    std::filesystem::path dir_;
    GltfBuilder builder_;
    int written_ = 0;
};

TEST_F(BrokenFile, TheUnbrokenFileLoads) {
    for (const Layout layout : {Layout::External, Layout::Embedded, Layout::Binary}) {
        auto scene = gltf::load(builder_.write(dir_, "valid" + std::to_string(static_cast<int>(layout)), layout));
        ASSERT_TRUE(scene) << scene.error().to_string();
        EXPECT_EQ(scene->draw_items.size(), 1u);
        EXPECT_EQ(scene->cameras.size(), 1u);
        EXPECT_EQ(scene->images.size(), 1u);
        EXPECT_TRUE(scene->warnings.empty());
    }
}

TEST_F(BrokenFile, IndexPastTheVertexCount) {
    std::vector<uint16_t> indices = {0, 1, 2, 0, 2, 4};  // 4 vertices
    const int view = builder_.add_view(indices);
    const int accessor = builder_.add_accessor(view, kUnsignedShort, 6, "SCALAR");
    expect_error([&](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["indices"] = accessor; },
                 "/meshes/0/primitives/0/indices", "index 4 (element 5) is past the vertex count 4");
}

TEST_F(BrokenFile, PrimitiveRestartIndex) {
    const int accessor = builder_.add_indices({0, 1, 2, 65535, 0, 2}, kUnsignedShort);
    expect_error([&](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["indices"] = accessor; },
                 "/meshes/0/primitives/0/indices", "index 65535");
}

TEST_F(BrokenFile, AccessorPastItsBufferView) {
    expect_error([](nlohmann::json& doc) { doc["accessors"][0]["count"] = 5; },  // POSITION view holds 4
                 "/accessors/0", "of buffer view 0, which has byteLength 48");
    expect_error([](nlohmann::json& doc) { doc["accessors"][0]["byteOffset"] = 4; }, "/accessors/0", "needs bytes [4, 52)");
}

TEST_F(BrokenFile, BufferViewPastItsBuffer) {
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][1]["byteLength"] = doc["buffers"][0]["byteLength"]; },
                 "/bufferViews/1", "exceeds the byteLength");
}

TEST_F(BrokenFile, BufferLongerThanItsData) {
    expect_error([](nlohmann::json& doc) { doc["buffers"][0]["byteLength"] = doc["buffers"][0]["byteLength"].get<int>() + 4; },
                 "/buffers/0", "byteLength");
}

TEST_F(BrokenFile, NodeCycles) {
    expect_error([](nlohmann::json& doc) { doc["nodes"][1]["children"] = {1}; }, "/nodes/1", "cycle of children (1 -> 1)");
    expect_error(
        [](nlohmann::json& doc) {
            doc["nodes"].push_back({{"children", {3}}});
            doc["nodes"].push_back({{"children", {4}}});
            doc["nodes"].push_back({{"children", {2}}});
        },
        "/nodes/2", "cycle of children (2 -> 3 -> 4 -> 2)");
}

TEST_F(BrokenFile, NodeWithSeveralParents) {
    expect_error(
        [](nlohmann::json& doc) {
            doc["nodes"].push_back({{"children", {1}}});
            doc["nodes"].push_back({{"children", {1}}});
            doc["scenes"][0]["nodes"] = {0, 2, 3};
        },
        "/nodes/3/children/0", "node 1 is already a child of node 2");
}

TEST_F(BrokenFile, SceneListsANonRootNode) {
    expect_error(
        [](nlohmann::json& doc) {
            doc["nodes"][0]["children"] = {1};
            doc["scenes"][0]["nodes"] = {0, 1};
        },
        "/scenes/0/nodes/1", "not a root node");
}

TEST_F(BrokenFile, MissingReferences) {
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["material"] = 3; },
                 "/meshes/0/primitives/0/material", "material 3 does not exist (the file has 1 materials)");
    expect_error([](nlohmann::json& doc) { doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = 1; },
                 "/materials/0/pbrMetallicRoughness/baseColorTexture/index", "texture 1 does not exist");
    expect_error([](nlohmann::json& doc) { doc["textures"][0]["source"] = 2; }, "/textures/0/source", "image 2 does not exist");
    expect_error([](nlohmann::json& doc) { doc["textures"][0]["sampler"] = 1; }, "/textures/0/sampler", "sampler 1 does not exist");
    expect_error([](nlohmann::json& doc) { doc["images"][0]["bufferView"] = 99; }, "/images/0/bufferView",
                 "buffer view 99 does not exist");
    expect_error([](nlohmann::json& doc) { doc["nodes"][0]["mesh"] = 1; }, "/nodes/0/mesh", "mesh 1 does not exist");
    expect_error([](nlohmann::json& doc) { doc["nodes"][1]["camera"] = 5; }, "/nodes/1/camera", "camera 5 does not exist");
    expect_error([](nlohmann::json& doc) { doc["nodes"][0]["children"] = {7}; }, "/nodes/0/children/0", "node 7 does not exist");
    expect_error([](nlohmann::json& doc) { doc["scenes"][0]["nodes"] = {2}; }, "/scenes/0/nodes/0", "node 2 does not exist");
    expect_error([](nlohmann::json& doc) { doc["scene"] = 1; }, "/scene", "scene 1 does not exist");
    expect_error([](nlohmann::json& doc) { doc["accessors"][1]["bufferView"] = 40; }, "/accessors/1/bufferView",
                 "buffer view 40 does not exist");
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["buffer"] = 1; }, "/bufferViews/0/buffer",
                 "buffer 1 does not exist (the file has 1 buffers)");
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 17; },
                 "/meshes/0/primitives/0/attributes/NORMAL", "accessor 17 does not exist");
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["indices"] = -1; },
                 "/meshes/0/primitives/0/indices", "must be at least 0");
}

TEST_F(BrokenFile, UnsupportedRequiredExtension) {
    expect_error(
        [](nlohmann::json& doc) {
            doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
            doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
        },
        "/extensionsRequired/0", "required extension 'KHR_draco_mesh_compression' is not supported");
}

TEST_F(BrokenFile, TextureTransformWithThreeOffsets) {
    expect_error(
        [](nlohmann::json& doc) {
            doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"]["KHR_texture_transform"]["offset"] = {1, 2, 3};
        },
        "/materials/0/pbrMetallicRoughness/baseColorTexture/extensions/KHR_texture_transform/offset", "");
}

TEST_F(BrokenFile, NegativeEmissiveStrength) {
    expect_error(
        [](nlohmann::json& doc) {
            doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
            doc["materials"][0]["extensions"]["KHR_materials_emissive_strength"]["emissiveStrength"] = -2.0;
        },
        "/materials/0/extensions/KHR_materials_emissive_strength/emissiveStrength", "must be >= 0.0, got -2.0");
}

TEST_F(BrokenFile, WrongAssetVersion) {
    expect_error([](nlohmann::json& doc) { doc["asset"]["version"] = "1.0"; }, "/asset/version",
                 "glTF version 1.0 is not supported");
    expect_error([](nlohmann::json& doc) { doc["asset"]["version"] = "two"; }, "/asset/version", "is not a glTF version");
    expect_error([](nlohmann::json& doc) { doc["asset"]["minVersion"] = "2.1"; }, "/asset/minVersion", "requires glTF 2.1");
    expect_error([](nlohmann::json& doc) { doc["asset"].erase("version"); }, "/asset",
                 "required property 'version' is missing");
}

TEST_F(BrokenFile, OverflowSizedCountsAndOffsets) {
    const uint64_t huge = (uint64_t{1} << 53) - 1;
    expect_error([&](nlohmann::json& doc) { doc["accessors"][0]["count"] = huge; }, "/accessors/0/count",
                 "exceeds the importer's limit");
    expect_error([&](nlohmann::json& doc) { doc["bufferViews"][0]["byteOffset"] = huge; }, "/bufferViews/0",
                 "exceeds the byteLength");
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["byteLength"] = std::numeric_limits<uint64_t>::max(); },
                 "/bufferViews/0/byteLength", "must be at most 9007199254740991");
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["byteLength"] = 1e300; }, "/bufferViews/0/byteLength",
                 "must be an integer");
    expect_error([](nlohmann::json& doc) { doc["accessors"][0]["byteOffset"] = -8; }, "/accessors/0/byteOffset",
                 "must be at least 0");
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["material"] = 4294967296ull; },
                 "/meshes/0/primitives/0/material", "must be at most 2147483647");
    // Even with the element limit lifted, a huge accessor fails on its range, not on memory.
    gltf::LoadOptions unlimited;
    unlimited.max_accessor_elements = std::numeric_limits<uint64_t>::max();
    expect_error([&](nlohmann::json& doc) { doc["accessors"][0]["count"] = huge; }, "/accessors/0", "needs bytes [0, ",
                 ErrorCode::Parse, unlimited);
    expect_error(
        [&](nlohmann::json& doc) {
            doc["accessors"][0]["count"] = huge;
            doc["accessors"][0].erase("bufferView");
        },
        "/accessors/0/count", "exceeds the importer's limit");
}

TEST_F(BrokenFile, ByteStrideProblems) {
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["byteStride"] = 6; }, "/bufferViews/0/byteStride",
                 "must be a multiple of 4");
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["byteStride"] = 256; }, "/bufferViews/0/byteStride",
                 "must be at most 252");
    expect_error([](nlohmann::json& doc) { doc["bufferViews"][0]["byteStride"] = 8; }, "/accessors/0",
                 "element size 12 exceeds the byteStride 8");
    const int strided = builder_.add_view(std::vector<uint16_t>{0, 0, 1, 0, 2, 0, 0, 0, 2, 0, 3, 0}, 4);
    const int strided_indices = builder_.add_accessor(strided, kUnsignedShort, 6, "SCALAR");
    expect_error([&](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["indices"] = strided_indices; },
                 "/meshes/0/primitives/0/indices", "has a byteStride (indices must be tightly packed)");
}

TEST_F(BrokenFile, AttributeProblems) {
    expect_error([](nlohmann::json& doc) { doc["accessors"][1]["count"] = 3; }, "/meshes/0/primitives/0/attributes/",
                 "all attributes of a primitive need the same count");
    expect_error([](nlohmann::json& doc) { doc["accessors"][1]["type"] = "VEC4"; }, "/accessors/1",
                 "");  // the view no longer holds 4 VEC4s
    expect_error(
        [](nlohmann::json& doc) {
            doc["accessors"][1]["type"] = "VEC2";
            doc["accessors"][1]["count"] = 4;
            doc["accessors"][1].erase("min");  // bounds of the VEC3 it was
            doc["accessors"][1].erase("max");
        },
        "/meshes/0/primitives/0/attributes/NORMAL", "accessor 1 is VEC2 FLOAT, which NORMAL cannot use");
    expect_error([](nlohmann::json& doc) { doc["accessors"][2]["componentType"] = 5124; }, "/accessors/2/componentType",
                 "5124 is not a valid component type");
    expect_error(
        [](nlohmann::json& doc) {
            doc["accessors"][3]["type"] = "VEC2";
            doc["accessors"][3]["count"] = 3;
        },
        "/meshes/0/primitives/0/indices", "accessor 3 is VEC2 UNSIGNED_SHORT; indices must be SCALAR");
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["mode"] = 7; }, "/meshes/0/primitives/0/mode",
                 "must be at most 6");
}

TEST_F(BrokenFile, NonFiniteVertexData) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const int positions = builder_.add_floats({0, 0, 0, 1, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3");
    expect_error([&](nlohmann::json& doc) { doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = positions; },
                 "/accessors/" + std::to_string(positions), "element 2 component 1 is not a finite number");
}

TEST_F(BrokenFile, SparseAccessorProblems) {
    // Sparse indices (u8) and values for the POSITION accessor.
    const int indices_view = builder_.add_view(std::vector<uint8_t>{2, 1, 0, 0});
    const int values_view = builder_.add_view(std::vector<float>{0, 0, 5, 0, 0, 6});
    // Two substitutions whose indices (2, 1) are out of order.
    auto sparse = [&](nlohmann::json& doc) {
        doc["accessors"][0]["sparse"] = {{"count", 2},
                                         {"indices", {{"bufferView", indices_view}, {"componentType", kUnsignedByte}}},
                                         {"values", {{"bufferView", values_view}}}};
    };
    expect_error(sparse, "/accessors/0/sparse/indices", "not strictly increasing (element 1 is 1, after 2)");
    expect_error(
        [&](nlohmann::json& doc) {
            sparse(doc);
            doc["accessors"][0]["sparse"]["count"] = 3;
        },
        "/accessors/0/sparse/values", "sparse values needs bytes [0, 36)");
    expect_error(
        [&](nlohmann::json& doc) {
            sparse(doc);
            doc["accessors"][0]["sparse"]["count"] = 5;
        },
        "/accessors/0/sparse/count", "must be at most 4");
    expect_error(
        [&](nlohmann::json& doc) {
            sparse(doc);
            doc["accessors"][0]["sparse"]["indices"]["componentType"] = kFloat;
        },
        "/accessors/0/sparse/indices/componentType", "is not an index component type");
}

TEST_F(BrokenFile, SparseIndexPastTheCount) {
    const int indices_view = builder_.add_view(std::vector<uint8_t>{1, 9, 0, 0});
    const int values_view = builder_.add_view(std::vector<float>{0, 0, 5, 0, 0, 6});
    expect_error(
        [&](nlohmann::json& doc) {
            doc["accessors"][0]["sparse"] = {{"count", 2},
                                             {"indices", {{"bufferView", indices_view}, {"componentType", kUnsignedByte}}},
                                             {"values", {{"bufferView", values_view}}}};
        },
        "/accessors/0/sparse/indices", "sparse index 9 (element 1) is past the accessor's count 4");
}

TEST_F(BrokenFile, BadUris) {
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "data:image/png;base64,iVB%"}}; }, "/images/0/uri",
                 "invalid base64 data ('%' at character 25 of the URI)");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "data:image/png;base64,abc"}}; }, "/images/0/uri",
                 "not a multiple of 4");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "data:image/png,raw%zzbytes"}}; }, "/images/0/uri",
                 "malformed percent escape at character 18 of the URI");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "data:image/webp;base64,AAAA"}}; }, "/images/0/uri",
                 "media type 'image/webp' is not supported");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "https://example.com/a.png"}}; }, "/images/0/uri",
                 "has a scheme");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "/etc/hostname"}}; }, "/images/0/uri",
                 "is not a relative file path");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "bad%zzname.png"}}; }, "/images/0/uri",
                 "malformed percent escape");
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "missing%20image.png"}}; }, "/images/0/uri",
                 "file 'missing image.png' not found", ErrorCode::Io);
    expect_error([](nlohmann::json& doc) { doc["images"][0] = {{"uri", "a.png"}, {"bufferView", 0}}; }, "/images/0",
                 "exactly one of 'uri' and 'bufferView'");
    expect_error([](nlohmann::json& doc) { doc["images"][0].erase("mimeType"); }, "/images/0",
                 "required property 'mimeType' is missing");
}

TEST_F(BrokenFile, MissingBufferFile) {
    for (const Layout layout : {Layout::External, Layout::Binary}) {
        const std::filesystem::path path = builder_.write(dir_, "missing_bin", layout, [](nlohmann::json& doc) {
            doc["buffers"].push_back({{"uri", "nowhere.bin"}, {"byteLength", 4}});
        });
        const Error error = expect_load_error(path);
        EXPECT_EQ(error.code, ErrorCode::Io);
        EXPECT_NE(error.message.find("/buffers/1/uri: file 'nowhere.bin' not found"), std::string::npos) << error.message;
    }
}

TEST_F(BrokenFile, BufferWithoutUriOutsideAGlb) {
    const std::filesystem::path path =
        builder_.write(dir_, "no_uri", Layout::External, [](nlohmann::json& doc) { doc["buffers"][0].erase("uri"); });
    const Error error = expect_load_error(path);
    // Such a buffer is legal until something reads it: the first reader is the error.
    EXPECT_NE(error.message.find("/images/0: reads buffer view"), std::string::npos) << error.message;
    EXPECT_NE(error.message.find("whose data is unavailable"), std::string::npos) << error.message;
}

TEST_F(BrokenFile, UndecodableImage) {
    const int garbage = builder_.add_view(std::vector<uint8_t>{0x89, 'P', 'N', 'G', 1, 2, 3, 4});
    expect_error([&](nlohmann::json& doc) { doc["images"][0]["bufferView"] = garbage; }, "/images/0", "cannot decode image");
}

TEST_F(BrokenFile, ImageLargerThanTheLimit) {
    gltf::LoadOptions options;
    options.max_image_dimension = 1;  // the test image is 2x2
    expect_error([](nlohmann::json&) {}, "/images/0", "image size 2x2 exceeds the importer's limit of 1", ErrorCode::Parse,
                 options);
}

TEST_F(BrokenFile, BadCamerasAndMaterials) {
    expect_error([](nlohmann::json& doc) { doc["cameras"][0]["perspective"]["yfov"] = 0; }, "/cameras/0/perspective/yfov",
                 "must be > 0");
    expect_error([](nlohmann::json& doc) { doc["cameras"][0]["perspective"]["zfar"] = 0.05; }, "/cameras/0/perspective/zfar",
                 "must be > 0.1");
    expect_error([](nlohmann::json& doc) { doc["cameras"][0]["type"] = "fisheye"; }, "/cameras/0/type",
                 "is not 'perspective' or 'orthographic'");
    expect_error([](nlohmann::json& doc) { doc["cameras"][0] = {{"type", "orthographic"}, {"orthographic", {{"xmag", 0}, {"ymag", 1}, {"znear", 0}, {"zfar", 1}}}}; },
                 "/cameras/0/orthographic/xmag", "must not be zero");
    expect_error([](nlohmann::json& doc) { doc["materials"][0]["alphaMode"] = "CUTOUT"; }, "/materials/0/alphaMode",
                 "is not OPAQUE, MASK or BLEND");
    expect_error([](nlohmann::json& doc) { doc["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1}; },
                 "/materials/0/pbrMetallicRoughness/baseColorFactor", "must have 4 elements");
    expect_error([](nlohmann::json& doc) { doc["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 2; },
                 "/materials/0/pbrMetallicRoughness/metallicFactor", "must be >= 0.0 and <= 1.0, got 2.0");
    expect_error([](nlohmann::json& doc) { doc["samplers"][0]["wrapS"] = 1234; }, "/samplers/0/wrapS", "is not a valid wrapS");
    expect_error([](nlohmann::json& doc) { doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; doc["nodes"][0]["scale"] = {1, 1, 1}; },
                 "/nodes/0/matrix", "both 'matrix' and translation/rotation/scale");
}

TEST_F(BrokenFile, WrongJsonTypes) {
    expect_error([](nlohmann::json& doc) { doc["meshes"] = {{"primitives", 3}}; }, "/meshes",
                 "must be an array");  // an object, not an array of meshes
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"] = 3; }, "/meshes/0/primitives", "must be an array");
    expect_error([](nlohmann::json& doc) { doc["nodes"][0] = 5; }, "/nodes/0", "must be an object");
    expect_error([](nlohmann::json& doc) { doc["meshes"][0]["primitives"] = nlohmann::json::array(); }, "/meshes/0/primitives",
                 "at least one primitive");
}

TEST_F(BrokenFile, DeeplyNestedExtras) {
    std::string extras;
    for (int i = 0; i < 100000; ++i) extras += '[';
    for (int i = 0; i < 100000; ++i) extras += ']';
    const std::filesystem::path path = builder_.write(dir_, "deep", Layout::External);
    // Splice the nested array into the written JSON text (nlohmann would recurse building it).
    const std::vector<unsigned char> bytes = read_bytes(path);
    std::string text(bytes.begin(), bytes.end());
    text.insert(text.find('{') + 1, "\"extras\": " + extras + ",");
    write_text(path, text);
    const Error error = expect_load_error(path);
    EXPECT_NE(error.message.find("JSON nesting is deeper than 256 levels"), std::string::npos) << error.message;
}

TEST(SceneInvalidGlb, SyntheticContainerProblems) {
    const std::filesystem::path dir = synthetic_dir("glb");
    const std::string json_text = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":8}]})";
    struct Case {
        std::string name;
        std::vector<unsigned char> bytes;
        std::string phrase;
    };
    std::vector<Case> cases;
    cases.push_back({"no_bin", make_glb(json_text, std::nullopt), "/buffers/0: buffer has no uri and the GLB file has no BIN chunk"});
    cases.push_back({"short_bin", make_glb(json_text, std::vector<unsigned char>(4, 0)),
                     "/buffers/0/byteLength: byteLength 8 exceeds the GLB BIN chunk's 4 bytes"});
    std::vector<unsigned char> truncated = make_glb(json_text, std::vector<unsigned char>(8, 0));
    truncated.resize(truncated.size() - 4);
    cases.push_back({"truncated", truncated, "GLB: declared length"});
    std::vector<unsigned char> overlong = make_glb(json_text, std::vector<unsigned char>(8, 0));
    overlong[12] = 0xff;  // JSON chunk length far past the end
    overlong[13] = 0xff;
    cases.push_back({"overlong_chunk", overlong, "does not fit in the file"});
    std::vector<unsigned char> bin_first = make_glb(json_text, std::vector<unsigned char>(8, 0));
    bin_first[16] = 'B';  // first chunk type no longer JSON
    cases.push_back({"bin_first", bin_first, "first chunk has type"});
    cases.push_back({"json_bom", make_glb("\xEF\xBB\xBF" + json_text, std::nullopt), "byte order mark"});
    for (const Case& c : cases) {
        const std::filesystem::path path = dir / (c.name + ".glb");
        write_bytes(path, c.bytes);
        SCOPED_TRACE(c.name);
        const Error error = expect_load_error(path);
        EXPECT_NE(error.message.find(c.phrase), std::string::npos) << error.message;
    }
}

TEST(SceneInvalidJson, RootAndAssetProblems) {
    const std::filesystem::path dir = synthetic_dir("json");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"[1, 2]", "the JSON root is not an object"},
        {"{}", "required property 'asset' is missing"},
        {R"({"asset": 2})", "/asset: must be an object"},
        {R"({"asset": {"version": "2.0"}, "nodes": [{"children": [0]}]})", "/nodes/0: node 0 is part of a cycle of children (0 -> 0)"},
        {"{\"asset\": {\"version\": \"2.0\"}", "invalid JSON: parse error"},
    };
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::filesystem::path path = dir / ("case" + std::to_string(i) + ".gltf");
        write_text(path, cases[i].first);
        SCOPED_TRACE(cases[i].first);
        const Error error = expect_load_error(path);
        EXPECT_EQ(error.code, ErrorCode::Parse);
        EXPECT_NE(error.message.find(cases[i].second), std::string::npos) << error.message;
    }
}

}  // namespace
}  // namespace loom::test
