#pragma once
// Helpers for the loom::scene tests: a builder for small synthetic glTF files (JSON + one
// binary buffer, written as .gltf with an embedded or external buffer, or as .glb), loading
// with a per-process cache for the big real models, and scene comparison.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "loom/gltf/gltf.hpp"
#include "loom/scene/scene.hpp"

namespace loom::test {

/// glTF component type values.
inline constexpr int kByte = 5120;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kShort = 5122;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;

/// Builds a glTF document and its single binary buffer.
class GltfBuilder {
public:
    /// How write() stores the buffer.
    enum class Layout { Embedded, External, Binary };

    GltfBuilder();

    /// The document being built (buffers[0] is added by document()/write()).
    nlohmann::json& json() { return doc_; }

    /// Appends bytes to the buffer (at a 4-byte aligned offset) with a buffer view over them;
    /// returns the view's index.
    int add_view(const void* data, std::size_t size, std::optional<uint32_t> stride = std::nullopt);
    template <class T>
    int add_view(const std::vector<T>& values, std::optional<uint32_t> stride = std::nullopt) {
        return add_view(values.data(), values.size() * sizeof(T), stride);
    }

    /// Adds an accessor; returns its index.
    int add_accessor(int view, int component_type, uint64_t count, const std::string& type, uint64_t byte_offset = 0,
                     bool normalized = false);
    /// A view and a tightly packed FLOAT accessor over `values` (count = size / components).
    int add_floats(const std::vector<float>& values, const std::string& type);
    /// A view and an index accessor of the given component type over `indices`.
    int add_indices(const std::vector<uint32_t>& indices, int component_type = kUnsignedShort);

    /// Appends a mesh with the given primitives; returns its index.
    int add_mesh(const nlohmann::json& primitives);
    /// Appends a node; returns its index.
    int add_node(const nlohmann::json& node);
    /// Sets scenes to one scene with these root nodes.
    void set_scene(const std::vector<int>& nodes);

    /// A quad in the z = 0 plane, (0,0)..(1,1), counter-clockwise seen from +Z, with
    /// TEXCOORD_0 (v down the image: uv (0,0) at the top-left corner (0,1,0)) and u16 indices;
    /// with NORMAL (0,0,1) when asked. Adds mesh, node and scene; returns the mesh index.
    int add_quad(bool with_normals, std::optional<int> material = std::nullopt);

    /// The finished document, with buffers[0] naming the buffer as the layout stores it.
    [[nodiscard]] nlohmann::json document(Layout layout, const std::string& bin_name) const;

    /// Writes `<dir>/<stem>.gltf` (+ `<stem>.bin`) or `<dir>/<stem>.glb`; `edit` may change the
    /// finished document first (to break it on purpose). Returns the main file's path.
    std::filesystem::path write(const std::filesystem::path& dir, const std::string& stem, Layout layout,
                                const std::function<void(nlohmann::json&)>& edit = {}) const;

    /// The binary buffer so far.
    [[nodiscard]] const std::vector<unsigned char>& bin() const { return bin_; }

private:
    nlohmann::json doc_;
    std::vector<unsigned char> bin_;
};

/// A GLB file of the given JSON text and BIN chunk (no BIN chunk when `bin` is nullopt), each
/// padded as the specification requires.
std::vector<unsigned char> make_glb(const std::string& json_text, const std::optional<std::vector<unsigned char>>& bin);

/// Writes bytes to a file, creating its directory.
void write_bytes(const std::filesystem::path& path, const std::vector<unsigned char>& bytes);
void write_text(const std::filesystem::path& path, const std::string& text);
/// The bytes of a file (empty when it cannot be read).
std::vector<unsigned char> read_bytes(const std::filesystem::path& path);

/// A fresh (emptied) directory for the synthetic files of one test, under output_dir().
std::filesystem::path synthetic_dir(const std::string& name);

/// The real glTF models directory (<data>/gltf).
std::filesystem::path gltf_models(const std::filesystem::path& data_dir);

/// Loads a real model once per process (decoding its images is the slow part); fails the
/// test and returns nullptr when it does not load.
const scene::Scene* load_cached(const std::filesystem::path& path);

/// Expects two scenes to be identical in everything but their source and warning texts:
/// nodes, meshes (every vertex and index), materials, textures, image pixels, draw items,
/// cameras and bounds.
void expect_same_scene(const scene::Scene& a, const scene::Scene& b);

/// Bytes of a value, for building buffers of mixed types.
template <class T>
std::vector<unsigned char> bytes_of(const std::vector<T>& values) {
    std::vector<unsigned char> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    return bytes;
}

}  // namespace loom::test
