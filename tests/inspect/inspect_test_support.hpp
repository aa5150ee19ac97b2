#pragma once
// Running the tools and headless Chromium for the inspector tests, and reading what they wrote.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace loom::inspect_test {

struct ToolRun {
    int status = -1;
    std::string out;
    std::string err;
};

/// A directory of its own for the running test (ctest runs the tests in parallel), emptied.
std::filesystem::path test_dir();

/// Runs `program` with `arguments` (already quoted where needed) in the shell.
ToolRun run(const std::string& program, const std::string& arguments);

std::string read_file(const std::filesystem::path& path);
void write_file(const std::filesystem::path& path, std::string_view text);
std::string quoted(const std::filesystem::path& path);

/// The Chromium to run: $LOOM_CHROMIUM, else chromium or chromium-browser on the PATH.
std::optional<std::string> find_chromium();

/// The DOM of `page` (opened at `fragment`, e.g. "#pass=blur") once its scripts ran, as
/// Chromium's --dump-dom prints it, in a window of 1600x4000 so that the lists show all rows of a
/// small plan. Chromium's own messages go to chromium.log in `dir`.
ToolRun dump_dom(const std::string& chromium, const std::filesystem::path& page, std::string_view fragment,
                 const std::filesystem::path& dir);

/// The text from the start tag holding `id="ID"` to the end of the document (the first such
/// element: the page's template comes before its scripts, whose text could name the id too).
std::string_view from_element(std::string_view dom, std::string_view id);

/// The values of every `attribute="..."` in `text`, in order, with &amp; &lt; &gt; &quot; decoded.
std::vector<std::string> attribute_values(std::string_view text, std::string_view attribute);

/// The value of `attribute` in the first start tag of `tag` ("body") that has attributes.
std::optional<std::string> attribute_of(std::string_view dom, std::string_view tag, std::string_view attribute);

/// The inspector input a page written by loom-inspect embeds (#loom-input: the JSON text as a
/// raw DEFLATE stream in base64, the text data-bytes long), decoded here with zlib. Fails the
/// test and returns null when the element is missing or does not decode to its stated length.
nlohmann::json embedded_input(std::string_view page);

}  // namespace loom::inspect_test

/// Skips the test with a visible message when Chromium is missing, or fails it under CI=true.
#define LOOM_REQUIRE_CHROMIUM(var)                                                                   \
    const std::optional<std::string> var##_found = ::loom::inspect_test::find_chromium();           \
    if (!var##_found) {                                                                              \
        if (::loom::test::running_in_ci()) FAIL() << "chromium not found (scripts/install-deps.sh) and CI=true"; \
        GTEST_SKIP() << "chromium not found: the inspector page is not opened (install it: scripts/install-deps.sh)"; \
    }                                                                                                \
    const std::string var = *var##_found
