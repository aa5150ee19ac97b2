#pragma once
// The inspector page: page/inspector.html with its style, scripts and the inspector input
// embedded, so that one file opens offline in any browser (no network, no other file).

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/result.hpp"

namespace loom::inspect {

/// Writes the page for `input` (an inspector input document, see input_files.hpp) titled
/// `title`. The input's JSON text is embedded compressed (deflate_raw) and in base64, which has
/// no '<' and so cannot end the element it is in, whatever the names in it; the page inflates
/// it (page/inflate.js). A 10,000-pass plan's page is a seventeenth of its JSON text.
void write_page(std::ostream& out, const nlohmann::json& input, std::string_view title);

/// write_page into the file `path`. Io error naming the file when it cannot be written (also
/// when zlib cannot compress the input, e.g. out of memory); what was written of it is removed.
Status write_page_file(const std::filesystem::path& path, const nlohmann::json& input, std::string_view title);

/// The page of `executor`'s latest frame into `path`, as `--inspect` and loom-inspect make it in
/// two steps: the inspector input (executor_run_record with `graph`, `options` and `source`, see
/// inspect_input.hpp), checked as loom-inspect checks an input file (parse_input), then the page
/// titled `title`. Errors: executor_run_record's; Parse when the input fails the checks;
/// write_page_file's.
Status write_executor_page(const std::filesystem::path& path, const fg::Executor& executor, const fg::FrameGraph& graph,
                           const fg::PlanOptions& options, std::string source, std::string_view title);

/// `bytes` as a raw DEFLATE stream (RFC 1951: zlib's deflate without the zlib header), at zlib's
/// compression `level` (0 writes stored blocks only) with zlib's `strategy` (0 is
/// Z_DEFAULT_STRATEGY; Z_FIXED writes fixed Huffman codes only).
std::string deflate_raw(std::string_view bytes, int level = 6, int strategy = 0);

/// `bytes` in base64 (RFC 4648, the standard alphabet, padded with '=').
std::string base64(std::string_view bytes);

}  // namespace loom::inspect
