#pragma once
// The importer's own validation of a glTF document, done on the JSON before tinygltf loads it:
// every reference, enumeration, range and size the file declares, the node hierarchy, required
// extensions and the asset version, and every URI (data URIs decoded, files read). Problems are
// reported with the JSON pointer of the offending value. What can only be checked on the data
// itself (index values, sparse indices, images) is checked by the converter.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "loom/rhi/result.hpp"
#include "loom/gltf/gltf.hpp"

namespace loom::gltf::detail {


/// What the validator needs to know about the file besides its JSON.
struct ValidationInput {
    std::string file_label;                ///< names the file in messages
    std::filesystem::path base_dir;        ///< where relative URIs are resolved
    std::string tinygltf_base_dir;         ///< the base directory string given to tinygltf
    bool is_glb = false;
    std::optional<std::span<const unsigned char>> glb_bin;  ///< the GLB BIN chunk, if there is one
    const LoadOptions* options = nullptr;
};

/// What validation produces besides "valid".
struct ValidationOutput {
    /// Contents of the files URIs name, keyed by the path tinygltf asks for (see
    /// tinygltf_url_decode); buffers are cut to their declared byteLength.
    std::map<std::string, std::vector<unsigned char>> files;
    /// Non-fatal findings, already formatted "<file>: <pointer>: <what>".
    std::vector<std::string> warnings;
    /// Buffers without data (no uri outside a GLB, or a URI the importer does not fetch): legal
    /// while nothing reads them; the converter rejects any accessor that does.
    std::set<uint64_t> unavailable_buffers;
    /// Every buffer's "uri" as tinygltf must see it: tinygltf is given the document as JSON
    /// text (also for GLB files), so the GLB BIN chunk and unavailable buffers are served as
    /// files under these names; keyed by buffer index, with the byteLength to declare.
    std::map<uint64_t, std::pair<std::string, uint64_t>> buffer_rewrites;
    /// Index accessors without a bufferView (all zeros by the specification, which tinygltf
    /// rejects): each gets a zero-filled buffer and view, served as a file under this name
    /// (with its byte length), keyed by accessor index.
    std::map<uint64_t, std::pair<std::string, uint64_t>> zero_index_accessors;
    /// JSON pointers of integer properties written with a fraction ("1.0"), accepted as the
    /// integer; tinygltf, which reads only integers there, is given the integer.
    std::vector<std::string> integers_written_as_floats;
    /// Images whose data URI tinygltf does not take (WebP with EXT_texture_webp; data URIs
    /// without ";base64"): served as files under these names, keyed by image index.
    std::map<uint64_t, std::string> image_rewrites;
};

/// Validates the parsed document. The error is ErrorCode::Io for files that cannot be read,
/// ErrorCode::Parse otherwise, and its message is "<file>: <pointer>: <what>".
[[nodiscard]] Result<ValidationOutput> validate_document(const nlohmann::json& root, const ValidationInput& input);

/// Formats a message the importer's way: "<file>: <pointer>: <what>", or "<file>: <what>"
/// for the document root.
[[nodiscard]] std::string located_message(const std::string& file_label, const std::string& pointer,
                                          const std::string& what);

}  // namespace loom::gltf::detail
