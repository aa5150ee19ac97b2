#pragma once
// JSON pointers (RFC 6901) naming the place in a glTF document an error is about, in the style
// of the Khronos glTF validator: "/meshes/0/primitives/1/indices".

#include <cstdint>
#include <string>
#include <string_view>

namespace loom::gltf::detail {


/// An immutable JSON pointer built by appending object keys and array indices.
class JsonPointer {
public:
    JsonPointer() = default;

    /// This pointer extended by an object key ('~' and '/' are escaped as RFC 6901 says).
    [[nodiscard]] JsonPointer operator/(std::string_view key) const {
        JsonPointer result = *this;
        result.text_ += '/';
        for (const char c : key) {
            if (c == '~') {
                result.text_ += "~0";
            } else if (c == '/') {
                result.text_ += "~1";
            } else {
                result.text_ += c;
            }
        }
        return result;
    }
    [[nodiscard]] JsonPointer operator/(const char* key) const { return *this / std::string_view(key); }

    /// This pointer extended by an array index.
    [[nodiscard]] JsonPointer operator/(uint64_t index) const {
        JsonPointer result = *this;
        result.text_ += '/';
        result.text_ += std::to_string(index);
        return result;
    }

    /// The pointer text; "" is the document root.
    [[nodiscard]] const std::string& str() const { return text_; }
    [[nodiscard]] bool is_root() const { return text_.empty(); }

private:
    std::string text_;
};

}  // namespace loom::gltf::detail
