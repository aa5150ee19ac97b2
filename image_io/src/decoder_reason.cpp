#include "decoder_reason.hpp"

#include <stb_image.h>

namespace loom::image_io::detail {

std::string decoder_reason() {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    const char* reason = stbi_failure_reason();
    for (const char* c = reason != nullptr ? reason : "unknown reason"; *c != '\0'; ++c) {
        const auto byte = static_cast<unsigned char>(*c);
        if (byte < 0x20 || byte >= 0x7f) {
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += *c;
        }
    }
    return out;
}

}  // namespace loom::image_io::detail
