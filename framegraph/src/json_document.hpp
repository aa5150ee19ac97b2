#pragma once
// Internal: the JSON reader of graph files. One pass over the text builds a read-only document
// (every value in one flat array, a container's children side by side, strings and keys as
// views of the text unless they hold escapes) and refuses what a graph file must not hold.
//
// It reads JSON exactly as nlohmann::json (3.11) did when graph files were read with it: the same
// texts are accepted (RFC 8259, a leading UTF-8 byte order mark, and anything after a NUL byte
// that follows the document ignored), numbers are unsigned, signed or double by the same rules,
// and a text that is not JSON gets the same message at the same line and column. The checks of
// check_json_structure (json_structure.hpp) happen in the same pass; when any check or the syntax
// fails, the text is given to check_json_structure, whose findings come first as they did when
// it ran before the parser.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace loom::fg::detail {

enum class JsonType : uint8_t { Null, False, True, String, Unsigned, Integer, Float, Array, Object };

/// Why a text was refused. `line` is 0 for the one refusal without a place (a number the
/// parser could not convert, which the structure check finds first in practice).
struct JsonError {
    std::size_t line = 0;
    std::size_t column = 0;
    std::string message;  // "invalid JSON: ..." or the structure check's message
};

class JsonDocument;

/// One value of a JsonDocument: a handle, valid as long as the document.
class JsonValue {
public:
    [[nodiscard]] JsonType type() const;
    [[nodiscard]] bool is_object() const { return type() == JsonType::Object; }
    [[nodiscard]] bool is_array() const { return type() == JsonType::Array; }
    [[nodiscard]] bool is_string() const { return type() == JsonType::String; }
    [[nodiscard]] bool is_boolean() const { return type() == JsonType::True || type() == JsonType::False; }
    /// Unsigned, signed or double.
    [[nodiscard]] bool is_number() const {
        return type() == JsonType::Unsigned || type() == JsonType::Integer || type() == JsonType::Float;
    }
    /// Written without fraction or exponent, within 64 bits (signed when negative).
    [[nodiscard]] bool is_number_integer() const {
        return type() == JsonType::Unsigned || type() == JsonType::Integer;
    }
    [[nodiscard]] bool is_number_unsigned() const { return type() == JsonType::Unsigned; }

    /// Elements of an array, members of an object; 0 for any other value.
    [[nodiscard]] std::size_t size() const;
    [[nodiscard]] bool empty() const { return size() == 0; }
    /// Element `i` of an array, or the value of member `i` of an object (i < size()).
    [[nodiscard]] JsonValue operator[](std::size_t i) const;
    /// The key of member `i` of an object, escapes decoded.
    [[nodiscard]] std::string_view key(std::size_t i) const;
    /// The member called `key` of an object (keys are unique); nullopt when there is none or
    /// this is no object.
    [[nodiscard]] std::optional<JsonValue> find(std::string_view key) const;
    [[nodiscard]] bool contains(std::string_view key) const { return find(key).has_value(); }
    /// The member called `key` of an object that contains() it.
    [[nodiscard]] JsonValue at(std::string_view key) const { return *find(key); }

    /// A string's text, escapes decoded.
    [[nodiscard]] std::string_view string() const;
    [[nodiscard]] bool boolean() const { return type() == JsonType::True; }
    /// A number converted as nlohmann::json's get<T>() converts it (static_cast from the stored
    /// unsigned, signed or double value).
    [[nodiscard]] int64_t as_int64() const;
    [[nodiscard]] uint64_t as_uint64() const;
    [[nodiscard]] double as_double() const;

    /// The value as nlohmann::json::dump() wrote it (no spaces, object members sorted by key),
    /// stopped once it is longer than `limit` bytes: the first `limit` + 1 bytes or fewer.
    [[nodiscard]] std::string dump(std::size_t limit) const;

private:
    friend class JsonDocument;
    JsonValue(const JsonDocument* document, std::size_t index) : document_(document), index_(index) {}
    void dump_into(std::string& out, std::size_t limit) const;

    const JsonDocument* document_ = nullptr;
    std::size_t index_ = 0;
};

/// A parsed JSON text. It refers to the text (keep the text alive while the document is used).
class JsonDocument {
public:
    /// Reads `text`, refusing objects and arrays nested deeper than `max_depth`, a key repeated
    /// in one object and numbers beyond a double (as check_json_structure) and any text that
    /// is not JSON.
    static std::variant<JsonDocument, JsonError> parse(std::string_view text, std::size_t max_depth);

    [[nodiscard]] JsonValue root() const { return JsonValue(this, 0); }

private:
    friend class JsonValue;
    friend class JsonParser;

    // Where a string (or key) is: in the text, or decoded into strings_ when it has escapes.
    struct Span {
        std::size_t offset = 0;
        uint32_t length = 0;
        bool decoded = false;
    };
    // 32 bytes (a Span member would pad it to 48): a graph file has about one node per ten
    // bytes of text, so the nodes outweigh the text.
    struct Node {
        union {
            uint64_t unsigned_value;
            int64_t integer_value;
            double float_value;
            std::size_t first;  // containers: index of the first child in nodes_
            std::size_t string_offset;
        };
        std::size_t count = 0;  // containers: children; strings: their length
        std::size_t key_offset = 0;  // members of objects: their key (a Span)
        uint32_t key_length = 0;
        JsonType type = JsonType::Null;
        bool key_decoded = false;
        bool string_decoded = false;
        Node() : unsigned_value(0) {}

        [[nodiscard]] Span key() const { return {key_offset, key_length, key_decoded}; }
        void set_key(const Span& span) {
            key_offset = span.offset;
            key_length = span.length;
            key_decoded = span.decoded;
        }
    };

    [[nodiscard]] std::string_view view(const Span& span) const {
        return (span.decoded ? std::string_view(strings_) : text_).substr(span.offset, span.length);
    }

    std::string_view text_;
    std::vector<Node> nodes_;  // nodes_[0] is the root
    std::string strings_;      // decoded strings and keys
};

/// The text of `quoted`, a JSON string token (quotes included), escapes decoded; nullopt when
/// it is not exactly one valid string token.
std::optional<std::string> decode_json_string(std::string_view quoted);

}  // namespace loom::fg::detail
