#pragma once
// The pages loom's tools write (loom-inspect's inspector, loom-compare's report) opened in
// headless Chromium, and what the tests read from the DOM it dumps. Chromium is Debian's
// `chromium` (scripts/install-deps.sh); LOOM_REQUIRE_CHROMIUM skips a test without it.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom_test/test_support.hpp"

namespace loom::test {

/// The whole file (empty when it cannot be read).
std::string read_file(const std::filesystem::path& path);

/// `path` in double quotes, for a shell command line.
std::string quoted(const std::filesystem::path& path);

/// The Chromium to run: $LOOM_CHROMIUM, else chromium or chromium-browser on the PATH.
std::optional<std::string> find_chromium();

struct PageDump {
    int status = -1;  ///< Chromium's exit status
    std::string dom;  ///< the document once its scripts ran, as --dump-dom prints it
    std::string log;  ///< Chromium's own messages
};

/// Opens `page` at `fragment` (e.g. "#pass=blur") in headless Chromium with a fresh profile in
/// `dir`, no network, sync or updates, in a window of 1600x4000, and dumps the DOM after the
/// page's load event (its scripts ran, its images loaded). The DOM goes to dom.html and
/// Chromium's messages to chromium.log in `dir`.
PageDump dump_dom(const std::string& chromium, const std::filesystem::path& page, std::string_view fragment,
                  const std::filesystem::path& dir);

/// The text from the start tag holding `id="ID"` to the end of the document (the first such
/// element: a page's markup comes before its scripts, whose text could name the id too).
std::string_view from_element(std::string_view dom, std::string_view id);

/// The values of every `attribute="..."` in `text`, in order, with &amp; &lt; &gt; &quot; decoded.
std::vector<std::string> attribute_values(std::string_view text, std::string_view attribute);

/// The value of `attribute` in the first start tag of `tag` ("body") that has attributes.
std::optional<std::string> attribute_of(std::string_view dom, std::string_view tag, std::string_view attribute);

}  // namespace loom::test

/// Skips the test with a visible message when Chromium is missing, or fails it under CI=true.
#define LOOM_REQUIRE_CHROMIUM(var)                                                                   \
    const std::optional<std::string> var##_found = ::loom::test::find_chromium();                   \
    if (!var##_found) {                                                                              \
        if (::loom::test::running_in_ci()) FAIL() << "chromium not found (scripts/install-deps.sh) and CI=true"; \
        GTEST_SKIP() << "chromium not found: the page is not opened (install it: scripts/install-deps.sh)"; \
    }                                                                                                \
    const std::string var = *var##_found
