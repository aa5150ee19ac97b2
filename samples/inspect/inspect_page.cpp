#include "inspect_page.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>

#define ZLIB_CONST
#include <zlib.h>

#include "input_files.hpp"
#include "inspect_input.hpp"
#include "loom/sample_common/html.hpp"

namespace loom::inspect {
namespace assets {
// page_assets.cpp, generated from page/ at build time (embed_page.cmake).
extern const char* const kHTML;
extern const char* const kCSS;
extern const char* const kINFLATE;
extern const char* const kJS;
}  // namespace assets

std::string deflate_raw(std::string_view bytes, int level, int strategy) {
    z_stream stream{};
    // windowBits -15: a 32 KiB window and no zlib header or checksum, as the page's inflater reads.
    if (deflateInit2(&stream, level, Z_DEFLATED, -15, 8, strategy) != Z_OK) {
        throw std::runtime_error("zlib: cannot start deflate (level " + std::to_string(level) + ", strategy " +
                                 std::to_string(strategy) + ")");
    }
    std::string out;
    std::array<char, 1 << 16> chunk{};
    std::size_t at = 0;
    int flush = Z_NO_FLUSH;
    while (flush != Z_FINISH) {
        // zlib counts its input in 32-bit units.
        const std::size_t part = std::min<std::size_t>(bytes.size() - at, std::size_t{1} << 30);
        stream.next_in = reinterpret_cast<const Bytef*>(bytes.data() + at);
        stream.avail_in = static_cast<uInt>(part);
        at += part;
        flush = at == bytes.size() ? Z_FINISH : Z_NO_FLUSH;
        do {
            stream.next_out = reinterpret_cast<Bytef*>(chunk.data());
            stream.avail_out = static_cast<uInt>(chunk.size());
            if (deflate(&stream, flush) == Z_STREAM_ERROR) {
                deflateEnd(&stream);
                throw std::runtime_error("zlib: deflate failed");
            }
            out.append(chunk.data(), chunk.size() - stream.avail_out);
        } while (stream.avail_out == 0);
    }
    deflateEnd(&stream);
    return out;
}

std::string base64(std::string_view bytes) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    const auto byte = [&](std::size_t at) { return static_cast<uint32_t>(static_cast<unsigned char>(bytes[at])); };
    for (; i + 3 <= bytes.size(); i += 3) {
        const uint32_t group = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
        for (int shift = 18; shift >= 0; shift -= 6) out += kAlphabet[(group >> shift) & 63];
    }
    if (const std::size_t rest = bytes.size() - i; rest > 0) {
        const uint32_t group = byte(i) << 16 | (rest == 2 ? byte(i + 1) << 8 : 0);
        out += kAlphabet[(group >> 18) & 63];
        out += kAlphabet[(group >> 12) & 63];
        out += rest == 2 ? kAlphabet[(group >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

void write_page(std::ostream& out, const nlohmann::json& input, std::string_view title) {
    // ASCII: every other character escaped (\u....), so that the page may decode it byte by byte.
    const std::string text = input.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
    // The template marks each insertion with an HTML comment; each appears once, in this order.
    const std::string_view page = assets::kHTML;
    const std::pair<std::string_view, std::string> parts[] = {
        {"<!--loom:title-->", samples::escape_html(title)},
        {"<!--loom:style-->", assets::kCSS},
        {"<!--loom:data-bytes-->", std::to_string(text.size())},
        {"<!--loom:data-->", base64(deflate_raw(text))},
        {"<!--loom:inflate-->", assets::kINFLATE},
        {"<!--loom:script-->", assets::kJS},
    };
    std::size_t at = 0;
    for (const auto& [marker, part] : parts) {
        const std::size_t found = page.find(marker, at);
        if (found == std::string_view::npos) continue;  // a template without the marker: nothing to insert
        out << page.substr(at, found - at) << part;
        at = found + marker.size();
    }
    out << page.substr(at);
}

Status write_page_file(const std::filesystem::path& path, const nlohmann::json& input, std::string_view title) {
    std::ofstream out(path, std::ios::binary);
    if (!out) return make_error(ErrorCode::Io, "cannot write " + path.string());
    std::string why;
    try {
        write_page(out, input, title);
    } catch (const std::exception& e) {
        why = std::string(": ") + e.what();
    }
    out.close();
    if (out && why.empty()) return {};
    // The file was opened (made or emptied) here: no half page is left to be taken for one.
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
    return make_error(ErrorCode::Io, "cannot write " + path.string() + why);
}

Status write_executor_page(const std::filesystem::path& path, const fg::Executor& executor, const fg::FrameGraph& graph,
                           const fg::PlanOptions& options, std::string source, std::string_view title) {
    auto run = executor_run_record(executor, graph, options, std::move(source));
    if (!run) return run.take_error();
    std::ostringstream text;
    write_input(text, *executor.plan(), *run);
    auto input = parse_input(std::move(text).str(), path, {});
    if (!input) return input.take_error();
    return write_page_file(path, *input, title);
}

}  // namespace loom::inspect
