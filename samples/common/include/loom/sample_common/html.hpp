#pragma once
// Text for the HTML pages the tools write (loom-inspect's page, loom-compare's report, the soak
// plot's SVG). No GPU and no other loom library: the GPU-free tools link it alone.

#include <string>
#include <string_view>

namespace loom::samples {

/// `text` with &, <, > and " replaced by their character references, so that it is text in an
/// element and may stand in a double-quoted attribute value, whatever it holds.
std::string escape_html(std::string_view text);

}  // namespace loom::samples
