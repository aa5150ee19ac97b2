#pragma once
// A check of a JSON text's structure: what JSON allows but a graph file must not contain, found
// in one loose pass (it reads any text, JSON or not) with memory bounded by the nesting limit.
// It ran before nlohmann::json parsed graph files; JsonDocument (json_document.hpp) now makes
// the same checks while it parses, and runs this one when it refuses a text, so that the
// structure problems are still reported first, with the same messages, wherever a text breaks.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace loom::fg {

/// Where and what the structure check found (1-based line and column).
struct JsonStructureProblem {
    std::size_t line = 1;
    std::size_t column = 1;
    std::string message;
};

/// One reference token of an RFC 6901 JSON pointer: '~' written "~0" and '/' written "~1".
std::string json_pointer_token(std::string_view key);

/// The first of: an object or array nested deeper than `max_depth`, a key repeated in one
/// object (located by JSON pointer as the graph-file errors write them: /passes/0/outputs/1/name), a number a
/// double cannot hold (1e400). Text that is not JSON at all is left to the parser.
std::optional<JsonStructureProblem> check_json_structure(std::string_view text, std::size_t max_depth);

}  // namespace loom::fg
