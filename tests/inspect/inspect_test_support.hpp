#pragma once
// Running the tools for the inspector tests, and reading what they wrote (the pages are opened
// in headless Chromium with loom_test/browser.hpp).

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "loom_test/browser.hpp"

namespace loom::inspect_test {

using loom::test::attribute_of;
using loom::test::attribute_values;
using loom::test::dump_dom;
using loom::test::from_element;
using loom::test::quoted;
using loom::test::read_file;

struct ToolRun {
    int status = -1;
    std::string out;
    std::string err;
};

/// A directory of its own for the running test (ctest runs the tests in parallel), emptied.
std::filesystem::path test_dir();

/// Runs `program` with `arguments` (already quoted where needed) in the shell.
ToolRun run(const std::string& program, const std::string& arguments);

void write_file(const std::filesystem::path& path, std::string_view text);

/// The inspector input a page written by loom-inspect embeds (#loom-input: the JSON text as a
/// raw DEFLATE stream in base64, the text data-bytes long), decoded here with zlib. Fails the
/// test and returns null when the element is missing or does not decode to its stated length.
nlohmann::json embedded_input(std::string_view page);

}  // namespace loom::inspect_test
