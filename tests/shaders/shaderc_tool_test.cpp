// loom-shaderc, the build-time compiler: a broken shader fails with "file:line: message"; a good
// one produces the SPIR-V words and a depfile naming every included file.

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

const fs::path kDataDir = LOOM_SHADER_TEST_DATA;

struct RunResult {
    int exit_code = -1;
    std::string output;  // stdout and stderr
};

RunResult run(const std::string& arguments) {
    const std::string command = std::string("\"") + LOOM_SHADERC_PATH + "\" " + arguments + " 2>&1";
    RunResult result;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return result;
    std::array<char, 512> buffer{};
    while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) result.output += buffer.data();
    const int status = pclose(pipe);
    result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

std::string quoted(const fs::path& path) {
    // Appended (GCC 12 -O3 warns falsely about "literal" + std::string: -Wrestrict, bug 105651).
    std::string out = "\"";
    out += path.string();
    out += '"';
    return out;
}

fs::path scratch_dir() {
    const fs::path dir = output_dir() / "shaderc_tool_test";
    fs::create_directories(dir);
    return dir;
}

TEST(ShadercTool, BrokenShaderFailsWithFileAndLine) {
    const fs::path out = scratch_dir() / "broken.frag.cpp";
    const auto result = run(quoted(kDataDir / "broken.frag") + " -o " + quoted(out) + " --symbol broken");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_THAT(result.output, HasSubstr((kDataDir / "broken.frag").string() +
                                         ":7: 'undeclared_name' : undeclared identifier"));
}

TEST(ShadercTool, WritesWordsAndDepfile) {
    const fs::path out = scratch_dir() / "uses_include.frag.cpp";
    const fs::path dep = scratch_dir() / "uses_include.frag.cpp.d";
    const auto result = run(quoted(kDataDir / "uses_include.frag") + " -o " + quoted(out) + " --symbol uses_include" +
                            " --depfile " + quoted(dep) + " -I " + quoted(kDataDir / "include"));
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const std::string cpp = read_text(out);
    EXPECT_THAT(cpp, HasSubstr("extern const std::uint32_t uses_include_words[] = {\n    0x07230203u,"));
    EXPECT_THAT(cpp, HasSubstr("extern const std::size_t uses_include_word_count = "));
    const std::string deps = read_text(dep);
    EXPECT_THAT(deps, HasSubstr(out.generic_string() + ":"));
    EXPECT_THAT(deps, HasSubstr("uses_include.frag"));
    EXPECT_THAT(deps, HasSubstr("include/lib/tint.glsl"));
    EXPECT_THAT(deps, HasSubstr("include/lib/scale.glsl"));
}

TEST(ShadercTool, MissingIncludeDirectoryFails) {
    const fs::path out = scratch_dir() / "no_dirs.frag.cpp";
    const auto result = run(quoted(kDataDir / "uses_include.frag") + " -o " + quoted(out) + " --symbol no_dirs");
    EXPECT_EQ(result.exit_code, 1);
    EXPECT_THAT(result.output, HasSubstr("uses_include.frag:2:"));
    EXPECT_THAT(result.output, HasSubstr("lib/tint.glsl"));
}

TEST(ShadercTool, EmbedsTextVerbatim) {
    const fs::path out = scratch_dir() / "tint.glsl.cpp";
    const auto result = run("--text " + quoted(kDataDir / "include/lib/tint.glsl") + " -o " + quoted(out) +
                            " --symbol tint_text");
    ASSERT_EQ(result.exit_code, 0) << result.output;
    const std::string cpp = read_text(out);
    EXPECT_THAT(cpp, HasSubstr("extern const char tint_text_text[] ="));
    EXPECT_THAT(cpp, HasSubstr("#include \\\"scale.glsl\\\"\\n"));
    EXPECT_THAT(cpp, HasSubstr("extern const std::size_t tint_text_size = " +
                               std::to_string(read_text(kDataDir / "include/lib/tint.glsl").size()) + ";"));
}

TEST(ShadercTool, UnknownExtensionAndBadArgumentsFail) {
    const auto bad_stage = run(quoted(kDataDir / "include/lib/tint.glsl") + " -o " +
                               quoted(scratch_dir() / "x.cpp") + " --symbol x");
    EXPECT_EQ(bad_stage.exit_code, 1);
    EXPECT_THAT(bad_stage.output, HasSubstr("unknown shader stage"));
    const auto usage = run("--bogus");
    EXPECT_NE(usage.exit_code, 0);
    EXPECT_THAT(usage.output, HasSubstr("usage"));
    EXPECT_THAT(usage.output, Not(HasSubstr("Segmentation")));
}

}  // namespace
}  // namespace loom::test
