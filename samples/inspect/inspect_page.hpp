#pragma once
// The inspector page: page/inspector.html with its style, script and the inspector input
// embedded, so that one file opens offline in any browser (no network, no other file).

#include <iosfwd>
#include <string_view>

#include <nlohmann/json.hpp>

namespace loom::inspect {

/// Writes the page for `input` (an inspector input document, see input_files.hpp) titled
/// `title`. The input is embedded as JSON inside a <script> element, with every '<' escaped so
/// that no name in it can end the element.
void write_page(std::ostream& out, const nlohmann::json& input, std::string_view title);

}  // namespace loom::inspect
