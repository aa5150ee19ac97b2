#pragma once
// Turns a validated, loaded tinygltf model into a loom::scene::Scene: materials with their
// textures and decoded images, meshes in the fixed vertex layout (with generated normals and
// tangents), the node hierarchy, and the chosen glTF scene flattened into draw items and
// camera instances.

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "loom/rhi/result.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom/scene/scene.hpp"

namespace loom::gltf::detail {


/// Converts `model` (which validate_document() accepted and tinygltf loaded; encoded image
/// bytes are in Image::image). Data checks that need the data itself — index values, sparse
/// indices, non-finite floats, image decoding — are made here, with the same message format.
/// Accessors reading `unavailable_buffers` are errors. Warnings are appended to `warnings`.
[[nodiscard]] Result<scene::Scene> convert_model(const tinygltf::Model& model, const std::string& file_label,
                                          const LoadOptions& options, const std::set<uint64_t>& unavailable_buffers,
                                          std::vector<std::string>& warnings);

}  // namespace loom::gltf::detail
