#include "inspect_page.hpp"

#include <ostream>
#include <string>

namespace loom::inspect {
namespace assets {
// page_assets.cpp, generated from page/ at build time (embed_page.cmake).
extern const char* const kHTML;
extern const char* const kCSS;
extern const char* const kJS;
}  // namespace assets

namespace {

std::string escape_html(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

// JSON text safe inside <script>: '<' occurs only inside JSON strings, where \u003c means the
// same character, so no "</script>" or "<!--" can appear in the element.
std::string script_safe_json(const nlohmann::json& input) {
    const std::string text = input.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        if (c == '<') {
            out += "\\u003c";
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace

void write_page(std::ostream& out, const nlohmann::json& input, std::string_view title) {
    // The template marks each insertion with an HTML comment; each appears once, in this order.
    const std::string_view page = assets::kHTML;
    const std::pair<std::string_view, std::string> parts[] = {
        {"<!--loom:title-->", escape_html(title)},
        {"<!--loom:style-->", assets::kCSS},
        {"<!--loom:data-->", script_safe_json(input)},
        {"<!--loom:script-->", assets::kJS},
    };
    std::size_t at = 0;
    for (const auto& [marker, text] : parts) {
        const std::size_t found = page.find(marker, at);
        if (found == std::string_view::npos) continue;  // a template without the marker: nothing to insert
        out << page.substr(at, found - at) << text;
        at = found + marker.size();
    }
    out << page.substr(at);
}

}  // namespace loom::inspect
