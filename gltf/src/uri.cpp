#include "uri.hpp"

#include <array>
#include <cctype>

namespace loom::gltf::detail {

namespace {

constexpr std::string_view kDataScheme = "data:";
constexpr std::string_view kBase64Marker = ";base64";

constexpr std::array<std::string_view, 7> kTinygltfMediaTypes = {
    "application/octet-stream", "image/jpeg", "image/png", "image/bmp",
    "image/gif", "text/plain", "application/gltf-buffer",
};

bool iequals_prefix(std::string_view text, std::string_view prefix) {
    if (text.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i) {
        if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
    }
    return true;
}

// RFC 2045 token characters (media type names, parameter names).
bool is_token_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u <= 32 || u >= 127) return false;
    return std::string_view("()<>@,;:\\\"/[]?=").find(c) == std::string_view::npos;
}

bool is_token(std::string_view text) {
    if (text.empty()) return false;
    for (const char c : text) {
        if (!is_token_char(c)) return false;
    }
    return true;
}

// "type/subtype" followed by any number of ";attribute=value"; empty is allowed (RFC 2397's
// default media type).
bool is_valid_media_type(std::string_view media) {
    if (media.empty()) return true;
    std::size_t start = 0;
    bool first = true;
    while (true) {
        const std::size_t end = media.find(';', start);
        const std::string_view part = media.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
        if (first) {
            const std::size_t slash = part.find('/');
            if (slash == std::string_view::npos || !is_token(part.substr(0, slash)) || !is_token(part.substr(slash + 1))) {
                return false;
            }
            first = false;
        } else {
            const std::size_t equals = part.find('=');
            if (equals == std::string_view::npos || !is_token(part.substr(0, equals)) || equals + 1 >= part.size()) {
                return false;
            }
        }
        if (end == std::string_view::npos) return true;
        start = end + 1;
    }
}

int base64_value(char c) {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
}

std::string describe_char(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 33 && u < 127) return std::string("'") + c + "'";
    static constexpr char kHex[] = "0123456789abcdef";
    return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
}

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

bool is_data_uri(std::string_view uri) { return iequals_prefix(uri, kDataScheme); }

Result<DataUri> decode_data_uri(std::string_view uri) {
    if (!is_data_uri(uri)) return make_error(ErrorCode::Parse, "not a data URI");
    const std::size_t comma = uri.find(',');
    if (comma == std::string_view::npos) return make_error(ErrorCode::Parse, "data URI has no ',' before its data");
    const std::string_view header = uri.substr(kDataScheme.size(), comma - kDataScheme.size());
    DataUri result;
    result.base64 = header.size() >= kBase64Marker.size() &&
                    header.substr(header.size() - kBase64Marker.size()) == kBase64Marker;
    result.media_type = std::string(result.base64 ? header.substr(0, header.size() - kBase64Marker.size()) : header);
    if (!is_valid_media_type(result.media_type)) {
        return make_error(ErrorCode::Parse, "data URI has a malformed media type '" + result.media_type + "'");
    }
    if (!result.base64) {
        // RFC 2397 without ";base64": the data are the URI's characters, percent-escapes decoded.
        for (std::size_t i = comma + 1; i < uri.size(); ++i) {
            if (uri[i] != '%') {
                result.data.push_back(static_cast<unsigned char>(uri[i]));
                continue;
            }
            if (i + 2 >= uri.size() || hex_value(uri[i + 1]) < 0 || hex_value(uri[i + 2]) < 0) {
                return make_error(ErrorCode::Parse, "malformed percent escape at character " + std::to_string(i) + " of the URI");
            }
            result.data.push_back(static_cast<unsigned char>(hex_value(uri[i + 1]) * 16 + hex_value(uri[i + 2])));
            i += 2;
        }
        return result;
    }

    const std::string_view payload = uri.substr(comma + 1);
    const std::size_t payload_offset = comma + 1;
    if (payload.empty()) return make_error(ErrorCode::Parse, "data URI has no data");
    if (payload.size() % 4 != 0) {
        return make_error(ErrorCode::Parse, "data URI's base64 data has length " + std::to_string(payload.size()) +
                                                ", which is not a multiple of 4");
    }
    std::size_t padding = 0;
    if (payload.back() == '=') padding = payload[payload.size() - 2] == '=' ? 2 : 1;
    result.data.reserve(payload.size() / 4 * 3);
    for (std::size_t i = 0; i < payload.size(); i += 4) {
        uint32_t group = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const std::size_t position = i + k;
            const char c = payload[position];
            int value = base64_value(c);
            if (c == '=' && position >= payload.size() - padding) value = 0;
            if (value < 0) {
                return make_error(ErrorCode::Parse, "invalid base64 data (" + describe_char(c) + " at character " +
                                                        std::to_string(payload_offset + position) + " of the URI)");
            }
            group = (group << 6) | static_cast<uint32_t>(value);
        }
        const bool last = i + 4 == payload.size();
        const std::size_t bytes = last ? 3 - padding : 3;
        for (std::size_t k = 0; k < bytes; ++k) {
            result.data.push_back(static_cast<unsigned char>((group >> (16 - 8 * k)) & 0xffu));
        }
    }
    return result;
}

bool tinygltf_decodes_media_type(std::string_view media_type) {
    for (const std::string_view type : kTinygltfMediaTypes) {
        if (media_type == type) return true;
    }
    return false;
}

std::string_view tinygltf_media_types() {
    return "application/octet-stream, application/gltf-buffer, image/png, image/jpeg, image/bmp, image/gif, "
           "text/plain";
}

bool has_uri_scheme(std::string_view uri) {
    // RFC 3986: scheme = ALPHA *( ALPHA / DIGIT / "+" / "-" / "." ) ":"
    if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
    for (std::size_t i = 1; i < uri.size(); ++i) {
        const auto c = static_cast<unsigned char>(uri[i]);
        if (c == ':') return true;
        if (!std::isalnum(c) && c != '+' && c != '-' && c != '.') return false;
    }
    return false;
}

Result<std::string> percent_decode(std::string_view uri) {
    std::string result;
    result.reserve(uri.size());
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            result += uri[i];
            continue;
        }
        if (i + 2 >= uri.size() || hex_value(uri[i + 1]) < 0 || hex_value(uri[i + 2]) < 0) {
            return make_error(ErrorCode::Parse, "malformed percent escape at character " + std::to_string(i) + " of the URI");
        }
        result += static_cast<char>(hex_value(uri[i + 1]) * 16 + hex_value(uri[i + 2]));
        i += 2;
    }
    return result;
}

std::string tinygltf_url_decode(std::string_view uri) {
    // Mirrors tinygltf 2.7's dlib::urldecode: '+' is a space, "%XY" is decoded whenever two
    // characters follow (invalid hex digits count as 0).
    auto lenient_hex = [](char c) { return hex_value(c) < 0 ? 0 : hex_value(c); };
    std::string result;
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') {
            result += ' ';
        } else if (uri[i] == '%' && uri.size() > i + 2) {
            result += static_cast<char>(lenient_hex(uri[i + 1]) * 16 + lenient_hex(uri[i + 2]));
            i += 2;
        } else {
            result += uri[i];
        }
    }
    return result;
}

}  // namespace loom::gltf::detail
