#include "json_document.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <span>

// For one thing only: writing a double in an error message exactly as nlohmann::json::dump()
// wrote it (its own shortest-digits algorithm), so that messages quoting a number stay the same.
#include <nlohmann/json.hpp>

#include "json_structure.hpp"
#include "text.hpp"

namespace loom::fg::detail {
namespace {

// The tokens of nlohmann::json's lexer, named as its messages name them.
enum class Token : uint8_t {
    None,  // no expectation to name
    True,
    False,
    Null,
    String,
    Number,
    BeginArray,
    BeginObject,
    EndArray,
    EndObject,
    NameSeparator,
    ValueSeparator,
    LexerError,
    EndOfInput,
    LiteralOrValue,
};

const char* token_name(Token token) {
    switch (token) {
    case Token::True: return "true literal";
    case Token::False: return "false literal";
    case Token::Null: return "null literal";
    case Token::String: return "string literal";
    case Token::Number: return "number literal";
    case Token::BeginArray: return "'['";
    case Token::BeginObject: return "'{'";
    case Token::EndArray: return "']'";
    case Token::EndObject: return "'}'";
    case Token::NameSeparator: return "':'";
    case Token::ValueSeparator: return "','";
    case Token::LexerError: return "<parse error>";
    case Token::EndOfInput: return "end of input";
    case Token::LiteralOrValue: return "'[', '{', or a literal";
    case Token::None: break;
    }
    return "<uninitialized>";
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

// A string token that starts at text[start] (a '"'): where it ends, or the index of the byte
// that made it invalid (text.size() when the text ended first), as nlohmann's lexer reads it:
// escapes as RFC 8259 has them with surrogates in pairs, no control characters, well-formed
// UTF-8 (no overlong forms, surrogates or code points past U+10FFFF).
struct StringScan {
    bool ok = false;
    bool escaped = false;
    std::size_t end = 0;    // ok: one past the closing quote
    std::size_t error = 0;  // not ok: the offending byte
};

StringScan scan_string(std::string_view text, std::size_t start) {
    StringScan scan;
    const std::size_t size = text.size();
    auto fail = [&](std::size_t at) {
        scan.error = at;
        return scan;
    };
    // Four hex digits from `at`: the code point, or -1 with `bad` the first byte that is none.
    auto code_unit = [&](std::size_t at, std::size_t& bad) {
        int value = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const int digit = at + k < size ? hex_value(text[at + k]) : -1;
            if (digit < 0) {
                bad = at + k;
                return -1;
            }
            value = value * 16 + digit;
        }
        return value;
    };
    std::size_t i = start + 1;
    while (true) {
        if (i >= size) return fail(size);
        const auto c = static_cast<unsigned char>(text[i]);
        if (c == '"') break;
        if (c >= 0x20 && c < 0x80 && c != '\\') {
            ++i;
            continue;
        }
        if (c < 0x20) return fail(i);
        if (c == '\\') {
            scan.escaped = true;
            if (i + 1 >= size) return fail(size);
            switch (text[i + 1]) {
            case '"': case '\\': case '/': case 'b': case 'f': case 'n': case 'r': case 't':
                i += 2;
                continue;
            case 'u': break;
            default: return fail(i + 1);
            }
            std::size_t bad = 0;
            const int first = code_unit(i + 2, bad);
            if (first < 0) return fail(bad);
            if (first >= 0xDC00 && first <= 0xDFFF) return fail(i + 5);
            if (first < 0xD800 || first > 0xDBFF) {
                i += 6;
                continue;
            }
            // A high surrogate: "\u" and a low one must follow.
            const std::size_t next = i + 6;
            if (next >= size) return fail(size);
            if (text[next] != '\\') return fail(next);
            if (next + 1 >= size) return fail(size);
            if (text[next + 1] != 'u') return fail(next + 1);
            const int second = code_unit(next + 2, bad);
            if (second < 0) return fail(bad);
            if (second < 0xDC00 || second > 0xDFFF) return fail(next + 5);
            i = next + 6;
            continue;
        }
        // UTF-8: the ranges each continuation byte must be in, by lead byte.
        std::array<std::pair<unsigned char, unsigned char>, 3> ranges{};
        std::size_t continuations = 0;
        constexpr std::pair<unsigned char, unsigned char> kAny{0x80, 0xBF};
        if (c >= 0xC2 && c <= 0xDF) {
            ranges = {kAny};
            continuations = 1;
        } else if (c == 0xE0) {
            ranges = {std::pair<unsigned char, unsigned char>{0xA0, 0xBF}, kAny};
            continuations = 2;
        } else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) {
            ranges = {kAny, kAny};
            continuations = 2;
        } else if (c == 0xED) {
            ranges = {std::pair<unsigned char, unsigned char>{0x80, 0x9F}, kAny};
            continuations = 2;
        } else if (c == 0xF0) {
            ranges = {std::pair<unsigned char, unsigned char>{0x90, 0xBF}, kAny, kAny};
            continuations = 3;
        } else if (c >= 0xF1 && c <= 0xF3) {
            ranges = {kAny, kAny, kAny};
            continuations = 3;
        } else if (c == 0xF4) {
            ranges = {std::pair<unsigned char, unsigned char>{0x80, 0x8F}, kAny, kAny};
            continuations = 3;
        } else {
            return fail(i);
        }
        for (std::size_t k = 1; k <= continuations; ++k) {
            if (i + k >= size) return fail(size);
            const auto byte = static_cast<unsigned char>(text[i + k]);
            if (byte < ranges[k - 1].first || byte > ranges[k - 1].second) return fail(i + k);
        }
        i += continuations + 1;
    }
    scan.ok = true;
    scan.end = i + 1;
    return scan;
}

void append_utf8(std::string& out, uint32_t code_point) {
    if (code_point < 0x80) {
        out += static_cast<char>(code_point);
    } else if (code_point < 0x800) {
        out += static_cast<char>(0xC0 | (code_point >> 6));
        out += static_cast<char>(0x80 | (code_point & 0x3F));
    } else if (code_point < 0x10000) {
        out += static_cast<char>(0xE0 | (code_point >> 12));
        out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (code_point & 0x3F));
    } else {
        out += static_cast<char>(0xF0 | (code_point >> 18));
        out += static_cast<char>(0x80 | ((code_point >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((code_point >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (code_point & 0x3F));
    }
}

// Appends the contents of a string token that scan_string accepted (between its quotes),
// escapes decoded.
void decode_string(std::string_view contents, std::string& out) {
    for (std::size_t i = 0; i < contents.size(); ++i) {
        if (contents[i] != '\\') {
            out += contents[i];
            continue;
        }
        const char escape = contents[++i];
        switch (escape) {
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
            auto unit = [&](std::size_t at) {
                uint32_t value = 0;
                for (std::size_t k = 0; k < 4; ++k) value = value * 16 + static_cast<uint32_t>(hex_value(contents[at + k]));
                return value;
            };
            uint32_t code_point = unit(i + 1);
            i += 4;
            if (code_point >= 0xD800 && code_point <= 0xDBFF) {
                code_point = 0x10000 + ((code_point - 0xD800) << 10) + (unit(i + 3) - 0xDC00);
                i += 6;
            }
            append_utf8(out, code_point);
            break;
        }
        default: out += escape; break;  // '"', '\\', '/'
        }
    }
}

// A number token at text[start] ('-' or a digit), read by nlohmann's lexer's state machine.
struct NumberScan {
    bool ok = false;
    JsonType type = JsonType::Unsigned;
    std::size_t end = 0;    // ok: one past the last character
    std::size_t error = 0;  // not ok: the offending character (text.size(): the text ended)
};

NumberScan scan_number(std::string_view text, std::size_t start) {
    NumberScan scan;
    const std::size_t size = text.size();
    auto digit_at = [&](std::size_t at) { return at < size && is_digit(text[at]); };
    auto fail = [&](std::size_t at) {
        scan.error = at;
        return scan;
    };
    std::size_t i = start;
    if (text[i] == '-') {
        scan.type = JsonType::Integer;
        ++i;
        if (!digit_at(i)) return fail(i);
    }
    if (text[i] == '0') {
        ++i;
    } else {
        while (digit_at(i)) ++i;
    }
    if (i < size && text[i] == '.') {
        scan.type = JsonType::Float;
        ++i;
        if (!digit_at(i)) return fail(i);
        while (digit_at(i)) ++i;
    }
    if (i < size && (text[i] == 'e' || text[i] == 'E')) {
        scan.type = JsonType::Float;
        ++i;
        if (i < size && (text[i] == '+' || text[i] == '-')) ++i;
        if (!digit_at(i)) return fail(i);
        while (digit_at(i)) ++i;
    }
    scan.ok = true;
    scan.end = i;
    return scan;
}

// Decimal digits (an optional '-' first) into 64 bits; nullopt past them, where nlohmann's lexer
// (strtoull / strtoll) fell back to a double.
std::optional<uint64_t> whole_magnitude(std::string_view digits) {
    uint64_t value = 0;
    for (char c : digits) {
        const auto digit = static_cast<uint64_t>(c - '0');
        if (value > (std::numeric_limits<uint64_t>::max() - digit) / 10) return std::nullopt;
        value = value * 10 + digit;
    }
    return value;
}

}  // namespace

// Reads a text into a JsonDocument; on failure, says where and why (fail_*).
class JsonParser {
public:
    JsonParser(std::string_view text, std::size_t max_depth, JsonDocument& document)
        : text_(text), max_depth_(max_depth), document_(document) {}

    // Builds the document; false when the text is refused (then error() says why).
    bool run();
    JsonError error() const;

private:
    enum class Failure : uint8_t { None, Syntax, Structure, Overflow };
    struct Frame {
        std::size_t first_child;  // index in pending_
        bool object;
    };

    void skip_space() {
        while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    }
    bool at_end() const { return pos_ >= text_.size() || text_[pos_] == '\0'; }

    bool read_value();   // the value at pos_ (after spaces): pushes its node (opens a container)
    bool read_key();     // an object's key at pos_ (after spaces) into key_
    bool close_container();
    bool read_string(JsonDocument::Span& span);
    bool read_number();

    // A syntax error at the token at pos_, which is not what `context` expects.
    bool fail_unexpected(const char* context, Token expected, Token expected_after_lexer_error);
    bool fail_lexer(std::size_t at, const char* context, Token expected);
    bool fail_structure(std::size_t at, Failure failure);
    std::string token_string(std::size_t end) const;

    std::string_view text_;
    std::size_t max_depth_;
    JsonDocument& document_;
    std::size_t pos_ = 0;
    std::vector<JsonDocument::Node> pending_;  // values of the open containers, in order
    std::vector<Frame> open_;
    JsonDocument::Span key_;  // the key of the member whose value comes next
    bool opened_ = false;     // read_value opened a container: its first value comes next
    // Where the last string or number token began: nlohmann's lexer quotes the text from there
    // to the error ("last read").
    std::size_t token_start_ = 0;

    Failure failure_ = Failure::None;
    std::size_t error_at_ = 0;  // the byte the error was found at (text_.size(): the end)
    std::string syntax_message_;
};

bool JsonParser::run() {
    const std::size_t size = text_.size();
    document_.text_ = text_;
    // A byte order mark is skipped; nlohmann refused a partial one.
    if (size > 0 && static_cast<unsigned char>(text_[0]) == 0xEF) {
        if (size < 2 || static_cast<unsigned char>(text_[1]) != 0xBB) return fail_lexer(1, "value", Token::None);
        if (size < 3 || static_cast<unsigned char>(text_[2]) != 0xBF) return fail_lexer(2, "value", Token::None);
        pos_ = 3;
    }
    document_.nodes_.resize(1);  // the root's place
    // About one node per ten bytes of a graph file: room for one per eight (untouched room
    // costs address space only).
    document_.nodes_.reserve(size / 8 + 16);
    pending_.reserve(256);
    open_.reserve(std::min<std::size_t>(max_depth_, 64));

    skip_space();
    if (!read_value()) return false;
    while (!open_.empty()) {
        const bool object = open_.back().object;
        const char close = object ? '}' : ']';
        skip_space();
        if (opened_) {
            // The first member or element, or the end of an empty container.
            opened_ = false;
            if (pos_ < size && text_[pos_] == close) {
                ++pos_;
                if (!close_container()) return false;
                continue;
            }
        } else {
            // After a member or element.
            const char c = pos_ < size ? text_[pos_] : '\0';
            if (c == close) {
                ++pos_;
                if (!close_container()) return false;
                continue;
            }
            if (c != ',') {
                return object ? fail_unexpected("object", Token::EndObject, Token::EndObject)
                              : fail_unexpected("array", Token::EndArray, Token::EndArray);
            }
            ++pos_;
            skip_space();
        }
        if (object && !read_key()) return false;
        if (!read_value()) return false;
    }
    skip_space();
    // nlohmann's lexer takes a NUL byte for the end of the input: what follows it is not read.
    if (!at_end()) return fail_unexpected("value", Token::EndOfInput, Token::EndOfInput);
    document_.nodes_[0] = pending_.front();
    return true;
}

bool JsonParser::read_value() {
    const std::size_t size = text_.size();
    if (pos_ >= size) return fail_unexpected("value", Token::LiteralOrValue, Token::None);
    JsonDocument::Node node;
    node.set_key(key_);
    const char c = text_[pos_];
    switch (c) {
    case '{':
    case '[': {
        if (open_.size() >= max_depth_) return fail_structure(pos_, Failure::Structure);
        const bool object = c == '{';
        node.type = object ? JsonType::Object : JsonType::Array;
        node.first = 0;
        pending_.push_back(node);
        open_.push_back(Frame{pending_.size(), object});
        opened_ = true;  // run() reads what it holds
        ++pos_;
        return true;
    }
    case '"': {
        JsonDocument::Span span;
        if (!read_string(span)) return fail_lexer(error_at_, "value", Token::None);
        node.type = JsonType::String;
        node.string_offset = span.offset;
        node.count = span.length;
        node.string_decoded = span.decoded;
        pending_.push_back(node);
        return true;
    }
    case 't':
    case 'f':
    case 'n': {
        const std::string_view literal = c == 't' ? "true" : c == 'f' ? "false" : "null";
        if (text_.substr(pos_, literal.size()) != literal) return fail_unexpected("value", Token::LiteralOrValue, Token::None);
        node.type = c == 't' ? JsonType::True : c == 'f' ? JsonType::False : JsonType::Null;
        pos_ += literal.size();
        pending_.push_back(node);
        return true;
    }
    default:
        if (c == '-' || is_digit(c)) return read_number();
        return fail_unexpected("value", Token::LiteralOrValue, Token::None);
    }
}

bool JsonParser::read_key() {
    if (pos_ >= text_.size() || text_[pos_] != '"') return fail_unexpected("object key", Token::String, Token::String);
    if (!read_string(key_)) return fail_lexer(error_at_, "object key", Token::String);
    skip_space();
    if (pos_ >= text_.size() || text_[pos_] != ':') {
        return fail_unexpected("object separator", Token::NameSeparator, Token::NameSeparator);
    }
    ++pos_;
    skip_space();
    return true;
}

bool JsonParser::read_string(JsonDocument::Span& span) {
    token_start_ = pos_;
    const StringScan scan = scan_string(text_, pos_);
    if (!scan.ok) {
        error_at_ = scan.error;
        return false;
    }
    const std::string_view contents = text_.substr(pos_ + 1, scan.end - pos_ - 2);
    if (contents.size() > std::numeric_limits<uint32_t>::max()) {
        // Beyond what a span records; no graph file comes near (a 4 GiB string).
        error_at_ = pos_;
        return false;
    }
    if (scan.escaped) {
        std::string& strings = document_.strings_;
        const std::size_t offset = strings.size();
        decode_string(contents, strings);
        span = {offset, static_cast<uint32_t>(strings.size() - offset), true};
    } else {
        span = {pos_ + 1, static_cast<uint32_t>(contents.size()), false};
    }
    pos_ = scan.end;
    return true;
}

bool JsonParser::read_number() {
    token_start_ = pos_;
    const NumberScan scan = scan_number(text_, pos_);
    if (!scan.ok) return fail_lexer(scan.error, "value", Token::None);
    const std::string_view token = text_.substr(pos_, scan.end - pos_);
    JsonDocument::Node node;
    node.set_key(key_);
    node.type = JsonType::Float;
    if (scan.type == JsonType::Unsigned) {
        if (auto value = whole_magnitude(token)) {
            node.type = JsonType::Unsigned;
            node.unsigned_value = *value;
        }
    } else if (scan.type == JsonType::Integer) {
        auto magnitude = whole_magnitude(token.substr(1));
        constexpr uint64_t kMinMagnitude = uint64_t{1} << 63;  // of std::numeric_limits<int64_t>::min()
        if (magnitude && *magnitude <= kMinMagnitude) {
            node.type = JsonType::Integer;
            node.integer_value = *magnitude == kMinMagnitude ? std::numeric_limits<int64_t>::min()
                                                             : -static_cast<int64_t>(*magnitude);
        }
    }
    if (node.type == JsonType::Float) {
        // strtod, as nlohmann converted: the same rounding, and the locale's decimal point (which
        // nlohmann wrote into the token for '.').
        std::array<char, 64> small{};
        std::string large;
        char* buffer = small.data();
        if (token.size() >= small.size()) {
            large.assign(token);
            buffer = large.data();
        } else {
            std::copy(token.begin(), token.end(), small.begin());
        }
        const char* point = std::localeconv()->decimal_point;
        const char decimal_point = point && *point ? *point : '.';
        for (std::size_t k = 0; k < token.size(); ++k) {
            if (buffer[k] == '.') buffer[k] = decimal_point;
        }
        node.float_value = std::strtod(buffer, nullptr);
        if (!std::isfinite(node.float_value)) {
            pos_ = scan.end;
            return fail_structure(scan.end - 1, Failure::Overflow);
        }
    }
    pending_.push_back(node);
    pos_ = scan.end;
    return true;
}

bool JsonParser::close_container() {
    const Frame frame = open_.back();
    open_.pop_back();
    const std::size_t count = pending_.size() - frame.first_child;
    JsonDocument::Node& container = pending_[frame.first_child - 1];
    if (frame.object && count > 1) {
        // A key given twice. The structure check names the first repeat; this only finds one.
        const auto members = std::span(pending_).subspan(frame.first_child);
        bool repeated = false;
        if (count <= 16) {
            for (std::size_t a = 1; a < count && !repeated; ++a) {
                const std::string_view key = document_.view(members[a].key());
                for (std::size_t b = 0; b < a; ++b) {
                    if (same_name(document_.view(members[b].key()), key)) {
                        repeated = true;
                        break;
                    }
                }
            }
        } else {
            std::vector<std::string_view> keys;
            keys.reserve(count);
            for (const auto& member : members) keys.push_back(document_.view(member.key()));
            std::sort(keys.begin(), keys.end());
            repeated = std::adjacent_find(keys.begin(), keys.end()) != keys.end();
        }
        if (repeated) return fail_structure(pos_ - 1, Failure::Structure);
    }
    auto& nodes = document_.nodes_;
    container.first = nodes.size();
    container.count = count;
    nodes.insert(nodes.end(), pending_.begin() + static_cast<std::ptrdiff_t>(frame.first_child), pending_.end());
    pending_.resize(frame.first_child);
    return true;
}

bool JsonParser::fail_unexpected(const char* context, Token expected, Token expected_after_lexer_error) {
    // The token nlohmann's lexer reads at pos_, and the last byte it reads for it.
    const std::size_t size = text_.size();
    skip_space();
    Token token = Token::LexerError;
    std::size_t last = pos_;
    if (pos_ >= size) {
        token = Token::EndOfInput;
        last = size;
    } else {
        const char c = text_[pos_];
        switch (c) {
        case '\0': token = Token::EndOfInput; break;
        case '[': token = Token::BeginArray; break;
        case '{': token = Token::BeginObject; break;
        case ']': token = Token::EndArray; break;
        case '}': token = Token::EndObject; break;
        case ':': token = Token::NameSeparator; break;
        case ',': token = Token::ValueSeparator; break;
        case 't':
        case 'f':
        case 'n': {
            const std::string_view literal = c == 't' ? "true" : c == 'f' ? "false" : "null";
            std::size_t k = 1;
            while (k < literal.size() && pos_ + k < size && text_[pos_ + k] == literal[k]) ++k;
            if (k < literal.size()) return fail_lexer(pos_ + k, context, expected_after_lexer_error);
            token = c == 't' ? Token::True : c == 'f' ? Token::False : Token::Null;
            last = pos_ + literal.size() - 1;
            break;
        }
        case '"': {
            token_start_ = pos_;
            const StringScan scan = scan_string(text_, pos_);
            if (!scan.ok) return fail_lexer(scan.error, context, expected_after_lexer_error);
            token = Token::String;
            last = scan.end - 1;
            break;
        }
        default:
            if (c == '-' || is_digit(c)) {
                token_start_ = pos_;
                const NumberScan scan = scan_number(text_, pos_);
                if (!scan.ok) return fail_lexer(scan.error, context, expected_after_lexer_error);
                token = Token::Number;
                last = scan.end - 1;
                break;
            }
            return fail_lexer(pos_, context, expected_after_lexer_error);
        }
    }
    failure_ = Failure::Syntax;
    error_at_ = last;
    syntax_message_ = std::string("syntax error while parsing ") + context + " - unexpected " + token_name(token);
    if (expected != Token::None) syntax_message_ += std::string("; expected ") + token_name(expected);
    return false;
}

bool JsonParser::fail_lexer(std::size_t at, const char* context, Token expected) {
    failure_ = Failure::Syntax;
    error_at_ = at;
    // nlohmann's lexer names the problem first ("invalid string: ..."), but the graph file's
    // message keeps only what follows the last ": ", which is in the quoted text from here on.
    syntax_message_ = std::string("syntax error while parsing ") + context + " - invalid token; last read: '" +
                      token_string(at + 1) + "'";
    if (expected != Token::None) syntax_message_ += std::string("; expected ") + token_name(expected);
    return false;
}

bool JsonParser::fail_structure(std::size_t at, Failure failure) {
    failure_ = failure;
    error_at_ = at;
    return false;
}

// The text nlohmann's lexer had read since the last string or number began, up to `end`,
// control characters written <U+XXXX>.
std::string JsonParser::token_string(std::size_t end) const {
    end = std::min(end, text_.size());
    std::string out;
    for (std::size_t i = std::min(token_start_, end); i < end; ++i) {
        const auto c = static_cast<unsigned char>(text_[i]);
        if (c <= 0x1F) {
            std::array<char, 9> escaped{};
            std::snprintf(escaped.data(), escaped.size(), "<U+%.4X>", c);
            out += escaped.data();
        } else {
            out += static_cast<char>(c);
        }
    }
    return out;
}

JsonError JsonParser::error() const {
    // The structure check ran before the parser and reported first, wherever the text broke.
    if (auto problem = check_json_structure(text_, max_depth_)) return {problem->line, problem->column, problem->message};
    const std::size_t offset = std::min(error_at_, text_.size());
    JsonError error;
    error.line = 1;
    error.column = 1;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text_[i] == '\n') {
            ++error.line;
            error.column = 1;
        } else {
            ++error.column;
        }
    }
    switch (failure_) {
    case Failure::Syntax: {
        // nlohmann's message, "parse error at line L, column C: <message>", cut after its last
        // ": " by the graph file reader.
        const std::size_t colon = syntax_message_.rfind(": ");
        error.message = "invalid JSON: " + (colon == std::string::npos ? syntax_message_ : syntax_message_.substr(colon + 2));
        break;
    }
    case Failure::Overflow:
        error.line = 0;
        error.message = "invalid JSON: number overflow parsing '" + token_string(error_at_ + 1) + "'";
        break;
    default:
        // The structure check finds whatever this parser refuses as structure.
        error.message = "invalid JSON structure";
        break;
    }
    return error;
}

std::variant<JsonDocument, JsonError> JsonDocument::parse(std::string_view text, std::size_t max_depth) {
    JsonDocument document;
    JsonParser parser(text, max_depth, document);
    if (!parser.run()) return parser.error();
    // The parser stops at a NUL byte after the document; the structure check, which ran before
    // it, read (and refused) what follows as well.
    if (const auto nul = text.find('\0'); nul != std::string_view::npos) {
        if (auto problem = check_json_structure(text, max_depth)) return JsonError{problem->line, problem->column, problem->message};
    }
    return document;
}

std::optional<std::string> decode_json_string(std::string_view quoted) {
    if (quoted.empty() || quoted.front() != '"') return std::nullopt;
    const StringScan scan = scan_string(quoted, 0);
    if (!scan.ok || scan.end != quoted.size()) return std::nullopt;
    std::string out;
    decode_string(quoted.substr(1, quoted.size() - 2), out);
    return out;
}

// --- JsonValue

JsonType JsonValue::type() const { return document_->nodes_[index_].type; }

std::size_t JsonValue::size() const {
    const auto& node = document_->nodes_[index_];
    return node.type == JsonType::Array || node.type == JsonType::Object ? node.count : 0;
}

JsonValue JsonValue::operator[](std::size_t i) const { return JsonValue(document_, document_->nodes_[index_].first + i); }

std::string_view JsonValue::key(std::size_t i) const {
    return document_->view(document_->nodes_[document_->nodes_[index_].first + i].key());
}

std::optional<JsonValue> JsonValue::find(std::string_view key) const {
    const auto& node = document_->nodes_[index_];
    if (node.type != JsonType::Object) return std::nullopt;
    // Graph readers ask for many keys of small objects, most of them absent.
    for (std::size_t i = 0; i < node.count; ++i) {
        if (same_name(document_->view(document_->nodes_[node.first + i].key()), key)) {
            return JsonValue(document_, node.first + i);
        }
    }
    return std::nullopt;
}

std::string_view JsonValue::string() const {
    const auto& node = document_->nodes_[index_];
    if (node.type != JsonType::String) return {};
    return document_->view({node.string_offset, static_cast<uint32_t>(node.count), node.string_decoded});
}

int64_t JsonValue::as_int64() const {
    const auto& node = document_->nodes_[index_];
    switch (node.type) {
    case JsonType::Unsigned: return static_cast<int64_t>(node.unsigned_value);
    case JsonType::Integer: return node.integer_value;
    case JsonType::Float:
        // Only whole numbers are read as integers; a double is never converted out of range.
        if (node.float_value > -9.2e18 && node.float_value < 9.2e18) return static_cast<int64_t>(node.float_value);
        return 0;
    default: return 0;
    }
}

uint64_t JsonValue::as_uint64() const {
    const auto& node = document_->nodes_[index_];
    if (node.type == JsonType::Unsigned) return node.unsigned_value;
    return static_cast<uint64_t>(as_int64());
}

double JsonValue::as_double() const {
    const auto& node = document_->nodes_[index_];
    switch (node.type) {
    case JsonType::Unsigned: return static_cast<double>(node.unsigned_value);
    case JsonType::Integer: return static_cast<double>(node.integer_value);
    case JsonType::Float: return node.float_value;
    default: return 0.0;
    }
}

namespace {

// A string as nlohmann::json::dump() quoted it: '"' and '\\' escaped, control characters as
// \b \f \n \r \t or \u00xx, everything else (valid UTF-8: the parser checked) as it is.
void append_quoted(std::string& out, std::string_view text) {
    out += '"';
    for (char c : text) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) <= 0x1F) {
                std::array<char, 7> escaped{};
                std::snprintf(escaped.data(), escaped.size(), "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                out += escaped.data();
            } else {
                out += c;
            }
        }
    }
    out += '"';
}

template <class Integer>
void append_integer(std::string& out, Integer value) {
    std::array<char, 24> digits{};
    const auto result = std::to_chars(digits.data(), digits.data() + digits.size(), value);
    out.append(digits.data(), result.ptr);
}

}  // namespace

std::string JsonValue::dump(std::size_t limit) const {
    std::string out;
    dump_into(out, limit);
    return out;
}

// Recursive, but no deeper than the document nests (JsonDocument::parse's max_depth).
void JsonValue::dump_into(std::string& out, std::size_t limit) const {
    if (out.size() > limit) return;
    const auto& node = document_->nodes_[index_];
    switch (node.type) {
    case JsonType::Null: out += "null"; break;
    case JsonType::True: out += "true"; break;
    case JsonType::False: out += "false"; break;
    case JsonType::Unsigned: append_integer(out, node.unsigned_value); break;
    case JsonType::Integer: append_integer(out, node.integer_value); break;
    case JsonType::Float: out += nlohmann::json(node.float_value).dump(); break;
    case JsonType::String: append_quoted(out, string()); break;
    case JsonType::Array:
        out += '[';
        for (std::size_t i = 0; i < node.count && out.size() <= limit; ++i) {
            if (i > 0) out += ',';
            (*this)[i].dump_into(out, limit);
        }
        out += ']';
        break;
    case JsonType::Object: {
        // nlohmann::json kept members in a std::map: sorted by key, byte by byte.
        std::vector<std::size_t> order(node.count);
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
        out += '{';
        for (std::size_t i = 0; i < order.size() && out.size() <= limit; ++i) {
            if (i > 0) out += ',';
            append_quoted(out, key(order[i]));
            out += ':';
            (*this)[order[i]].dump_into(out, limit);
        }
        out += '}';
        break;
    }
    }
}

}  // namespace loom::fg::detail
