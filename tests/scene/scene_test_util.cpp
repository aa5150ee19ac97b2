#include <algorithm>
#include "scene_test_util.hpp"

#include <fstream>
#include <map>
#include <memory>
#include <mutex>

#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

std::string base64(const std::vector<unsigned char>& bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t b0 = bytes[i];
        const uint32_t b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0;
        const uint32_t b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const uint32_t group = (b0 << 16) | (b1 << 8) | b2;
        text += kAlphabet[(group >> 18) & 63];
        text += kAlphabet[(group >> 12) & 63];
        text += i + 1 < bytes.size() ? kAlphabet[(group >> 6) & 63] : '=';
        text += i + 2 < bytes.size() ? kAlphabet[group & 63] : '=';
    }
    return text;
}

void append_u32(std::vector<unsigned char>& out, uint32_t value) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<unsigned char>((value >> (8 * i)) & 0xffu));
}

}  // namespace

GltfBuilder::GltfBuilder() { doc_ = {{"asset", {{"version", "2.0"}, {"generator", "loom scene tests"}}}}; }

int GltfBuilder::add_view(const void* data, std::size_t size, std::optional<uint32_t> stride) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    const std::size_t offset = bin_.size();
    const auto* bytes = static_cast<const unsigned char*>(data);
    bin_.insert(bin_.end(), bytes, bytes + size);
    nlohmann::json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}};
    if (stride) view["byteStride"] = *stride;
    doc_["bufferViews"].push_back(view);
    return static_cast<int>(doc_["bufferViews"].size() - 1);
}

int GltfBuilder::add_accessor(int view, int component_type, uint64_t count, const std::string& type, uint64_t byte_offset,
                              bool normalized) {
    nlohmann::json accessor = {{"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) accessor["bufferView"] = view;
    if (byte_offset != 0) accessor["byteOffset"] = byte_offset;
    if (normalized) accessor["normalized"] = true;
    doc_["accessors"].push_back(accessor);
    return static_cast<int>(doc_["accessors"].size() - 1);
}

int GltfBuilder::add_floats(const std::vector<float>& values, const std::string& type) {
    const uint64_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    const int view = add_view(values);
    const int accessor = add_accessor(view, kFloat, values.size() / components, type);
    // Bounds as glTF requires them for POSITION (harmless elsewhere): the exact extremes.
    nlohmann::json min = nlohmann::json::array();
    nlohmann::json max = nlohmann::json::array();
    for (uint64_t c = 0; c < components && values.size() >= components; ++c) {
        float low = values[c];
        float high = values[c];
        for (std::size_t i = c; i < values.size(); i += components) {
            low = std::min(low, values[i]);
            high = std::max(high, values[i]);
        }
        min.push_back(low);
        max.push_back(high);
    }
    if (!min.empty()) {
        doc_["accessors"][static_cast<std::size_t>(accessor)]["min"] = min;
        doc_["accessors"][static_cast<std::size_t>(accessor)]["max"] = max;
    }
    return accessor;
}

int GltfBuilder::add_indices(const std::vector<uint32_t>& indices, int component_type) {
    int view = -1;
    if (component_type == kUnsignedByte) {
        view = add_view(std::vector<uint8_t>(indices.begin(), indices.end()));
    } else if (component_type == kUnsignedShort) {
        view = add_view(std::vector<uint16_t>(indices.begin(), indices.end()));
    } else {
        view = add_view(indices);
    }
    return add_accessor(view, component_type, indices.size(), "SCALAR");
}

int GltfBuilder::add_mesh(const nlohmann::json& primitives) {
    doc_["meshes"].push_back({{"primitives", primitives}});
    return static_cast<int>(doc_["meshes"].size() - 1);
}

int GltfBuilder::add_node(const nlohmann::json& node) {
    doc_["nodes"].push_back(node);
    return static_cast<int>(doc_["nodes"].size() - 1);
}

void GltfBuilder::set_scene(const std::vector<int>& nodes) {
    doc_["scenes"] = nlohmann::json::array({{{"nodes", nodes}}});
    doc_["scene"] = 0;
}

int GltfBuilder::add_quad(bool with_normals, std::optional<int> material) {
    nlohmann::json attributes;
    attributes["POSITION"] = add_floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
    if (with_normals) attributes["NORMAL"] = add_floats({0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
    attributes["TEXCOORD_0"] = add_floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
    nlohmann::json primitive = {{"attributes", attributes}, {"indices", add_indices({0, 1, 2, 0, 2, 3})}};
    if (material) primitive["material"] = *material;
    const int mesh = add_mesh(nlohmann::json::array({primitive}));
    set_scene({add_node({{"mesh", mesh}})});
    return mesh;
}

nlohmann::json GltfBuilder::document(Layout layout, const std::string& bin_name) const {
    nlohmann::json doc = doc_;
    if (!bin_.empty()) {
        nlohmann::json buffer = {{"byteLength", bin_.size()}};
        if (layout == Layout::Embedded) buffer["uri"] = "data:application/octet-stream;base64," + base64(bin_);
        if (layout == Layout::External) buffer["uri"] = bin_name;
        doc["buffers"] = nlohmann::json::array({buffer});
    }
    return doc;
}

std::filesystem::path GltfBuilder::write(const std::filesystem::path& dir, const std::string& stem, Layout layout,
                                         const std::function<void(nlohmann::json&)>& edit) const {
    nlohmann::json doc = document(layout, stem + ".bin");
    if (edit) edit(doc);
    if (layout == Layout::Binary) {
        const std::filesystem::path path = dir / (stem + ".glb");
        write_bytes(path, make_glb(doc.dump(), bin_.empty() ? std::nullopt : std::optional(bin_)));
        return path;
    }
    if (layout == Layout::External && !bin_.empty()) write_bytes(dir / (stem + ".bin"), bin_);
    const std::filesystem::path path = dir / (stem + ".gltf");
    write_text(path, doc.dump(2));
    return path;
}

std::vector<unsigned char> make_glb(const std::string& json_text, const std::optional<std::vector<unsigned char>>& bin) {
    std::string json_chunk = json_text;
    while (json_chunk.size() % 4 != 0) json_chunk += ' ';
    std::vector<unsigned char> bin_chunk = bin.value_or(std::vector<unsigned char>{});
    while (bin_chunk.size() % 4 != 0) bin_chunk.push_back(0);
    const std::size_t total = 12 + 8 + json_chunk.size() + (bin ? 8 + bin_chunk.size() : 0);
    std::vector<unsigned char> out;
    append_u32(out, 0x46546C67);
    append_u32(out, 2);
    append_u32(out, static_cast<uint32_t>(total));
    append_u32(out, static_cast<uint32_t>(json_chunk.size()));
    append_u32(out, 0x4E4F534A);
    out.insert(out.end(), json_chunk.begin(), json_chunk.end());
    if (bin) {
        append_u32(out, static_cast<uint32_t>(bin_chunk.size()));
        append_u32(out, 0x004E4942);
        out.insert(out.end(), bin_chunk.begin(), bin_chunk.end());
    }
    return out;
}

void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream stream(path, std::ios::binary | std::ios::trunc);
    stream.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    ASSERT_TRUE(stream.good()) << "cannot write " << path;
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    write_bytes(path, std::vector<unsigned char>(text.begin(), text.end()));
}

std::vector<unsigned char> read_bytes(const std::filesystem::path& path) {
    std::ifstream stream(path, std::ios::binary);
    std::vector<unsigned char> bytes;
    if (!stream) return bytes;
    stream.seekg(0, std::ios::end);
    const std::streamoff size = stream.tellg();
    stream.seekg(0, std::ios::beg);
    if (size <= 0) return bytes;
    bytes.resize(static_cast<std::size_t>(size));
    stream.read(reinterpret_cast<char*>(bytes.data()), size);
    return bytes;
}

std::filesystem::path synthetic_dir(const std::string& name) {
    const std::filesystem::path dir = output_dir() / "scene-synthetic" / name;
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir, ec);
    return dir;
}

std::filesystem::path gltf_models(const std::filesystem::path& data_dir) { return data_dir / "gltf"; }

const scene::Scene* load_cached(const std::filesystem::path& path) {
    static std::mutex mutex;
    static std::map<std::filesystem::path, std::unique_ptr<scene::Scene>> cache;
    std::lock_guard lock(mutex);
    auto& slot = cache[path];
    if (!slot) {
        auto loaded = gltf::load(path);
        if (!loaded) {
            ADD_FAILURE() << "loading " << path << " failed: " << loaded.error().to_string();
            cache.erase(path);
            return nullptr;
        }
        slot = std::make_unique<scene::Scene>(std::move(*loaded));
    }
    return slot.get();
}

namespace {

void expect_same_material(const scene::Material& a, const scene::Material& b, std::size_t index) {
    EXPECT_TRUE(a == b) << "material " << index << " (" << a.name << " / " << b.name << ") differs";
}

void expect_same_sampler(const rhi::SamplerDesc& a, const rhi::SamplerDesc& b, std::size_t index) {
    EXPECT_EQ(a.min_filter, b.min_filter) << "texture " << index;
    EXPECT_EQ(a.mag_filter, b.mag_filter) << "texture " << index;
    EXPECT_EQ(a.mipmap_filter, b.mipmap_filter) << "texture " << index;
    EXPECT_EQ(a.address_u, b.address_u) << "texture " << index;
    EXPECT_EQ(a.address_v, b.address_v) << "texture " << index;
    EXPECT_EQ(a.max_lod, b.max_lod) << "texture " << index;
}

}  // namespace

void expect_same_scene(const scene::Scene& a, const scene::Scene& b) {
    EXPECT_EQ(a.warnings.size(), b.warnings.size());
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (std::size_t n = 0; n < a.nodes.size(); ++n) {
        EXPECT_EQ(a.nodes[n].name, b.nodes[n].name);
        EXPECT_EQ(a.nodes[n].parent, b.nodes[n].parent);
        EXPECT_EQ(a.nodes[n].children, b.nodes[n].children);
        EXPECT_EQ(a.nodes[n].world, b.nodes[n].world) << "node " << n;
        EXPECT_EQ(a.nodes[n].mesh, b.nodes[n].mesh);
        EXPECT_EQ(a.nodes[n].camera, b.nodes[n].camera);
    }
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t m = 0; m < a.meshes.size(); ++m) {
        ASSERT_EQ(a.meshes[m].primitives.size(), b.meshes[m].primitives.size()) << "mesh " << m;
        for (std::size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
            const scene::Primitive& pa = a.meshes[m].primitives[p];
            const scene::Primitive& pb = b.meshes[m].primitives[p];
            EXPECT_TRUE(pa.vertices == pb.vertices) << "mesh " << m << " primitive " << p << " vertices differ";
            EXPECT_TRUE(pa.indices == pb.indices) << "mesh " << m << " primitive " << p << " indices differ";
            EXPECT_EQ(pa.material, pb.material);
            EXPECT_EQ(pa.bounds, pb.bounds);
            EXPECT_EQ(pa.from_file, pb.from_file);
            EXPECT_EQ(pa.generated, pb.generated);
        }
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t m = 0; m < a.materials.size(); ++m) expect_same_material(a.materials[m], b.materials[m], m);
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (std::size_t t = 0; t < a.textures.size(); ++t) {
        EXPECT_EQ(a.textures[t].image, b.textures[t].image);
        expect_same_sampler(a.textures[t].sampler, b.textures[t].sampler, t);
    }
    ASSERT_EQ(a.images.size(), b.images.size());
    for (std::size_t i = 0; i < a.images.size(); ++i) {
        EXPECT_EQ(a.images[i].source, b.images[i].source);
        EXPECT_EQ(a.images[i].image.width, b.images[i].image.width);
        EXPECT_EQ(a.images[i].image.height, b.images[i].image.height);
        EXPECT_EQ(a.images[i].image.format, b.images[i].image.format);
        EXPECT_TRUE(a.images[i].image.pixels == b.images[i].image.pixels) << "image " << i << " pixels differ";
    }
    ASSERT_EQ(a.draw_items.size(), b.draw_items.size());
    for (std::size_t d = 0; d < a.draw_items.size(); ++d) {
        const scene::DrawItem& da = a.draw_items[d];
        const scene::DrawItem& db = b.draw_items[d];
        EXPECT_EQ(da.node, db.node);
        EXPECT_EQ(da.mesh, db.mesh);
        EXPECT_EQ(da.primitive, db.primitive);
        EXPECT_EQ(da.material, db.material);
        EXPECT_EQ(da.world, db.world);
        EXPECT_EQ(da.normal_matrix, db.normal_matrix);
        EXPECT_EQ(da.flips_winding, db.flips_winding);
        EXPECT_EQ(da.world_bounds, db.world_bounds);
    }
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (std::size_t c = 0; c < a.cameras.size(); ++c) {
        EXPECT_EQ(a.cameras[c].name, b.cameras[c].name);
        EXPECT_EQ(a.cameras[c].world, b.cameras[c].world);
        EXPECT_TRUE(a.cameras[c].projection == b.cameras[c].projection) << "camera " << c;
    }
    EXPECT_EQ(a.bounds, b.bounds);
}

}  // namespace loom::test
