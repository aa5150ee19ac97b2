#pragma once
// glTF 2.0 import (.gltf with external or embedded data, .glb). tinygltf parses the file; the
// importer validates everything tinygltf does not (references, ranges, strides, index values,
// the node hierarchy, required extensions, the asset version, URIs) and reports the first
// problem as one line: "<file>: <JSON pointer>: <what is wrong>", e.g.
//   "model.gltf: /meshes/0/primitives/1/indices: index 7 (element 5) is past the vertex count 4"
// with ErrorCode::Io for files that cannot be read (the file itself or a file a URI names) and
// ErrorCode::Parse for everything else. A bad file never crashes the importer.
//
// Decisions where glTF leaves room (see also LoadOptions):
// - Triangle strips and fans become triangle lists; points and lines are skipped with a
//   warning, as are primitives without POSITION.
// - Only relative file URIs and base64 data URIs of the media types tinygltf decodes are
//   supported. Missing files are errors (Io), also for images.
// - Supported extensionsRequired: KHR_mesh_quantization (integer attributes are converted to
//   floats). Any other required extension is an error; unknown used extensions are ignored.
// - Skins, morph targets and animations are not imported (the static pose is used), with a
//   warning. TEXCOORD_2 and above are ignored; a texture using such a set falls back to set 0
//   with a warning.
// - Only the images and textures that materials use are decoded and appear in the scene.

#include <cstdint>
#include <filesystem>
#include <optional>

#include "loom/rhi/result.hpp"
#include "loom/scene/scene.hpp"

namespace loom::gltf {

/// How normals are generated for primitives that have none.
enum class NormalGeneration : uint8_t {
    Flat,    ///< face normals, vertices unshared (what the glTF specification requires)
    Smooth,  ///< area-weighted average over triangles sharing a vertex index
};

/// When tangents are generated for primitives that have none.
enum class TangentGeneration : uint8_t {
    WhenNormalMapped,  ///< only if the primitive's material has a normal texture
    Always,            ///< for every primitive (from UV set 0 unless a normal texture says otherwise)
    Never,             ///< Vertex::tangent keeps its default
};

/// Options of load().
struct LoadOptions {
    /// Which glTF scene to flatten into draw items; by default the file's `scene`, else scene
    /// 0, else (a file without scenes) every root node.
    std::optional<uint32_t> scene;
    NormalGeneration normals = NormalGeneration::Flat;
    TangentGeneration tangents = TangentGeneration::WhenNormalMapped;
    /// Largest element count accepted for one accessor. It protects against files that
    /// declare huge zero-filled (sparse) accessors, which need memory but no data; raising it
    /// far lets such a file exhaust memory (the load then fails with ErrorCode::OutOfMemory).
    uint64_t max_accessor_elements = uint64_t{1} << 24;
    /// Largest accepted image width or height (checked before any pixel memory is allocated).
    uint32_t max_image_dimension = 16384;
};

/// Loads a .gltf or .glb file (the format is recognised by the GLB magic, and files named
/// *.glb must be GLB) and everything it references. Warnings go to scene::Scene::warnings and are
/// logged through loom::log at Warning level (source "gltf"); errors are returned, not logged.
Result<scene::Scene> load(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace loom::gltf
