#pragma once
// Internal: text helpers. Strings are built by appending: GCC 12 at -O3 warns falsely
// (-Wrestrict, GCC bug 105651) about `"literal" + std::to_string(n)`; appending to one string
// avoids the pattern. Names are compared by same_name.

#include <concepts>
#include <string>
#include <string_view>

namespace loom::fg::detail {

/// Appends every part to `out`: text as is, integers in decimal.
template <class... Parts>
void append(std::string& out, const Parts&... parts) {
    auto one = [&out](const auto& part) {
        if constexpr (std::integral<std::decay_t<decltype(part)>>) {
            out += std::to_string(part);
        } else {
            out += std::string_view(part);
        }
    };
    (one(parts), ...);
}

/// a == b for the short names and keys compared by the thousand while graphs are read and
/// declared: most differ in length or first byte, which settle it without a call to memcmp.
inline bool same_name(std::string_view a, std::string_view b) {
    if (a.size() != b.size()) return false;
    return a.empty() || (a.front() == b.front() && a == b);
}

/// The concatenation of the parts (see append).
template <class... Parts>
std::string concat(const Parts&... parts) {
    std::string out;
    append(out, parts...);
    return out;
}

}  // namespace loom::fg::detail
