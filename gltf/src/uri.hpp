#pragma once
// URIs in glTF files: base64 data URIs (strictly checked, so that tinygltf's lenient decoder
// only ever sees valid input) and relative file references (percent-decoded).

#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/result.hpp"

namespace loom::gltf::detail {


/// True when `uri` uses the data: scheme.
[[nodiscard]] bool is_data_uri(std::string_view uri);

/// A decoded data URI.
struct DataUri {
    std::string media_type;  ///< as written (may be empty)
    std::vector<unsigned char> data;
    bool base64 = true;      ///< ";base64,"; else the data were percent-encoded
};

/// Parses "data:[<media type>][;base64],<data>" (RFC 2397): decodes a base64 payload strictly
/// (alphabet, padding, length), or percent-escapes in one without ";base64". The error message
/// says what is wrong and where, without naming the file.
[[nodiscard]] Result<DataUri> decode_data_uri(std::string_view uri);

/// True for the data URI media types tinygltf decodes (it treats any other data URI as a file
/// name).
[[nodiscard]] bool tinygltf_decodes_media_type(std::string_view media_type);

/// The media types of tinygltf_decodes_media_type(), for messages.
[[nodiscard]] std::string_view tinygltf_media_types();

/// True when `uri` starts with a scheme ("http:", "file:", ...).
[[nodiscard]] bool has_uri_scheme(std::string_view uri);

/// Decodes %XX escapes strictly (a '%' must be followed by two hex digits); '+' stays '+'.
[[nodiscard]] Result<std::string> percent_decode(std::string_view uri);

/// What tinygltf makes of a file URI before looking the file up: %XX decoded leniently and
/// '+' turned into a space. Used only to serve tinygltf the file the importer resolved.
[[nodiscard]] std::string tinygltf_url_decode(std::string_view uri);

}  // namespace loom::gltf::detail
