#include "json_structure.hpp"

#include <cmath>
#include <cstdlib>
#include <unordered_set>
#include <vector>

#include "json_document.hpp"

namespace loom::fg {
namespace {

// One open object or array.
struct Container {
    bool object = false;
    std::string path;                      // JSON pointer, as graph-file errors write it; "" for the top level
    std::unordered_set<std::string> keys;  // objects: the keys seen so far
    std::string key;                       // objects: the key whose value comes next
    bool expect_key = true;                // objects: the next string is a key
    std::size_t index = 0;                 // arrays: the element that comes next
};

}  // namespace

std::string json_pointer_token(std::string_view key) {
    std::string token;
    token.reserve(key.size());
    for (char c : key) {
        if (c == '~') token += "~0";
        else if (c == '/') token += "~1";
        else token += c;
    }
    return token;
}

namespace {

std::string member_path(const Container& parent) {
    if (parent.object) return parent.path + "/" + json_pointer_token(parent.key);
    return parent.path + "/" + std::to_string(parent.index);
}

// The key's text as the parser will see it (escapes decoded), so "a" and "\u0061" are one key.
// Not a valid string: the parser reports it later with its position.
std::string decode_key(std::string_view quoted) {
    if (auto decoded = detail::decode_json_string(quoted)) return std::move(*decoded);
    return std::string(quoted);
}

bool is_number_char(char c) {
    return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E';
}

std::string excerpt(std::string_view text) {
    constexpr std::size_t kMax = 40;
    if (text.size() <= kMax) return std::string(text);
    return std::string(text.substr(0, kMax)) + "...";
}

}  // namespace

std::optional<JsonStructureProblem> check_json_structure(std::string_view text, std::size_t max_depth) {
    std::vector<Container> open;
    std::size_t line = 1;
    std::size_t column = 1;
    auto advance_over = [&](std::size_t from, std::size_t to) {
        for (std::size_t k = from; k < to && k < text.size(); ++k) {
            if (text[k] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
    };

    std::size_t i = 0;
    while (i < text.size()) {
        const char c = text[i];
        if (c == '"') {
            std::size_t end = i + 1;
            while (end < text.size() && text[end] != '"') end += text[end] == '\\' ? 2 : 1;
            end = std::min(end + 1, text.size());  // one past the closing quote
            if (!open.empty() && open.back().object && open.back().expect_key) {
                Container& object = open.back();
                std::string key = decode_key(text.substr(i, end - i));
                object.key = key;
                object.expect_key = false;
                if (!object.keys.insert(std::move(key)).second) {
                    return JsonStructureProblem{line, column,
                                                "duplicate key \"" + excerpt(object.key) + "\" at " +
                                                    member_path(object)};
                }
            }
            advance_over(i, end);
            i = end;
            continue;
        }
        if (c == '-' || (c >= '0' && c <= '9')) {
            std::size_t end = i;
            while (end < text.size() && is_number_char(text[end])) ++end;
            const std::string token(text.substr(i, end - i));
            const double value = std::strtod(token.c_str(), nullptr);
            if (!std::isfinite(value)) {
                const std::string where = open.empty() ? "the top level" : member_path(open.back());
                return JsonStructureProblem{line, column,
                                            "the number " + excerpt(token) + " at " + where +
                                                " is out of range (beyond a double)"};
            }
            advance_over(i, end);
            i = end;
            continue;
        }
        if (c == '{' || c == '[') {
            std::string path = open.empty() ? "" : member_path(open.back());
            if (open.size() >= max_depth) {
                return JsonStructureProblem{line, column,
                                            "nested deeper than " + std::to_string(max_depth) + " levels at " +
                                                (path.empty() ? "the top level" : path)};
            }
            Container container;
            container.object = c == '{';
            container.path = std::move(path);
            open.push_back(std::move(container));
        } else if (c == '}' || c == ']') {
            if (!open.empty()) open.pop_back();
        } else if (c == ',' && !open.empty()) {
            if (open.back().object) {
                open.back().expect_key = true;
            } else {
                ++open.back().index;
            }
        }
        advance_over(i, i + 1);
        ++i;
    }
    return std::nullopt;
}

}  // namespace loom::fg
