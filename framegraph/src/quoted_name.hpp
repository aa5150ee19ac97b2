#pragma once
// Internal: how errors print a user's name unquoted (quoted: fg::quoted_name, pass.hpp).

#include <string>
#include <string_view>

namespace loom::fg::detail {

/// `name` with control characters written as \n, \t or \xNN: a user's name (or a "pass.port"
/// reference made of two) as an error may print it unquoted, still on one line.
std::string printable_name(std::string_view name);

}  // namespace loom::fg::detail
