#pragma once
// The binary glTF container (GLB): a 12-byte header, a JSON chunk and an optional BIN chunk.
// Checked completely here, before tinygltf sees the bytes.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "loom/rhi/result.hpp"

namespace loom::gltf::detail {


/// The chunks of a valid GLB file (views into the file's bytes).
struct GlbChunks {
    std::string_view json;
    std::optional<std::span<const unsigned char>> bin;
    std::size_t trailing_bytes = 0;  ///< bytes after the declared length, ignored
};

/// True when the bytes start with the GLB magic "glTF".
[[nodiscard]] bool has_glb_magic(std::span<const unsigned char> file);

/// Splits a GLB file into its chunks, checking magic, version 2, the declared length against
/// the file size (bytes beyond it are ignored and counted), chunk headers, lengths and
/// alignment, and the chunk order. The error message
/// says what is wrong, without naming the file.
[[nodiscard]] Result<GlbChunks> parse_glb(std::span<const unsigned char> file);

}  // namespace loom::gltf::detail
