#include "inspect_test_support.hpp"

#include <cstdint>
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>
#include <sys/wait.h>
#define ZLIB_CONST
#include <zlib.h>

#include "loom_test/test_support.hpp"

namespace loom::inspect_test {

std::filesystem::path test_dir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::filesystem::path dir =
        loom::test::output_dir() / "loom_inspect" / (std::string(info->test_suite_name()) + "." + info->name());
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
    std::filesystem::create_directories(dir);
    return std::filesystem::absolute(dir);
}

void write_file(const std::filesystem::path& path, std::string_view text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

ToolRun run(const std::string& program, const std::string& arguments) {
    static int runs = 0;
    const std::filesystem::path dir = loom::test::output_dir() / "loom_inspect" / "runs";
    std::filesystem::create_directories(dir);
    // One pair of files per run: the tests of this program run in separate processes, each
    // named by its own test.
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string stem = std::string(info->test_suite_name()) + "." + info->name() + "." + std::to_string(runs++);
    const auto out = dir / (stem + ".out");
    const auto err = dir / (stem + ".err");
    const std::string command = "\"" + program + "\" " + arguments + " >" + quoted(out) + " 2>" + quoted(err);
    const int raw = std::system(command.c_str());
    ToolRun result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    result.out = read_file(out);
    result.err = read_file(err);
    return result;
}

namespace {

std::optional<std::string> from_base64(std::string_view text) {
    std::string out;
    uint32_t group = 0;
    int bits = 0;
    for (char c : text) {
        int value = -1;
        if (c >= 'A' && c <= 'Z') value = c - 'A';
        else if (c >= 'a' && c <= 'z') value = c - 'a' + 26;
        else if (c >= '0' && c <= '9') value = c - '0' + 52;
        else if (c == '+') value = 62;
        else if (c == '/') value = 63;
        else if (c == '=') break;
        else return std::nullopt;
        group = group << 6 | static_cast<uint32_t>(value);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out += static_cast<char>((group >> bits) & 0xff);
        }
    }
    return out;
}

std::optional<std::string> inflate_raw(std::string_view compressed, std::size_t size) {
    z_stream stream{};
    if (inflateInit2(&stream, -15) != Z_OK) return std::nullopt;
    std::string out(size, '\0');
    stream.next_in = reinterpret_cast<const Bytef*>(compressed.data());
    stream.avail_in = static_cast<uInt>(compressed.size());
    stream.next_out = reinterpret_cast<Bytef*>(out.data());
    stream.avail_out = static_cast<uInt>(out.size());
    const int status = inflate(&stream, Z_FINISH);
    const bool whole = status == Z_STREAM_END && stream.avail_out == 0 && stream.avail_in == 0;
    inflateEnd(&stream);
    if (!whole) return std::nullopt;
    return out;
}

}  // namespace

nlohmann::json embedded_input(std::string_view page) {
    const std::string_view element = from_element(page, "loom-input");
    const std::size_t start = element.find('>');
    const std::size_t end = element.find("</script>");
    // The element's start tag from its id on: the text's length.
    const auto size = attribute_values(element.substr(0, start), "data-bytes");
    if (start == std::string_view::npos || end == std::string_view::npos || size.size() != 1) {
        ADD_FAILURE() << "no #loom-input element with data-bytes in the page";
        return nullptr;
    }
    const auto compressed = from_base64(element.substr(start + 1, end - start - 1));
    if (!compressed) {
        ADD_FAILURE() << "#loom-input is not base64";
        return nullptr;
    }
    const auto text = inflate_raw(*compressed, std::stoull(size.front()));
    if (!text) {
        ADD_FAILURE() << "#loom-input is not a raw DEFLATE stream of " << size.front() << " bytes";
        return nullptr;
    }
    return nlohmann::json::parse(*text);
}

}  // namespace loom::inspect_test
