// #include "name": virtual files, then include directories, then the includer's directory;
// errors inside included files name that file and its line; a missing include names both files.

#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

namespace fs = std::filesystem;
using rhi::ShaderStage;
using ::testing::HasSubstr;

const fs::path kDataDir = LOOM_SHADER_TEST_DATA;

constexpr const char* kUsesCommon =
    "#version 450\n"
    "#include \"lib/common.glsl\"\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() {\n"
    "    color = vec4(half_of(1.0));\n"
    "}\n";

TEST(ShaderIncludes, VirtualFileIsIncluded) {
    shader_compiler::ShaderCompilerOptions options;
    options.virtual_files["lib/common.glsl"] = "float half_of(float x) { return x * 0.5; }\n";
    shader_compiler::ShaderCompiler compiler(options);
    auto module = compile_ok(compiler, source("main.frag", ShaderStage::Fragment, kUsesCommon));
    EXPECT_FALSE(module.spirv.empty());
}

TEST(ShaderIncludes, ErrorInsideIncludedFileNamesThatFileAndLine) {
    shader_compiler::ShaderCompilerOptions options;
    options.virtual_files["lib/common.glsl"] =
        "// helpers\n"
        "float half_of(float x) {\n"
        "    return x * not_declared;\n"
        "}\n";
    shader_compiler::ShaderCompiler compiler(options);
    const std::string message = compile_error(compiler, source("main.frag", ShaderStage::Fragment, kUsesCommon));
    EXPECT_THAT(message, HasSubstr("lib/common.glsl:3: 'not_declared' : undeclared identifier"));
}

TEST(ShaderIncludes, LinesAfterAnIncludeKeepTheirNumbers) {
    shader_compiler::ShaderCompilerOptions options;
    options.virtual_files["lib/common.glsl"] = "// one\n// two\n// three\nfloat half_of(float x) { return x * 0.5; }\n";
    shader_compiler::ShaderCompiler compiler(options);
    const std::string code =
        "#version 450\n"
        "#include \"lib/common.glsl\"\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() {\n"
        "    color = vec4(half_of(SCALE));\n"
        "    color = vec4(after_include);\n"
        "}\n";
    const std::string message =
        compile_error(compiler, source("after.frag", ShaderStage::Fragment, code, {{"SCALE", "2.0"}}));
    EXPECT_THAT(message, HasSubstr("after.frag:6: 'after_include' : undeclared identifier"));
}

TEST(ShaderIncludes, MissingIncludeNamesItAndTheIncluder) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("needs_lib.frag", ShaderStage::Fragment,
                                                                "#version 450\n"
                                                                "\n"
                                                                "#include \"no/such_file.glsl\"\n"
                                                                "void main() {}\n"));
    EXPECT_THAT(message, HasSubstr("needs_lib.frag:3:"));
    EXPECT_THAT(message, HasSubstr("no/such_file.glsl"));
    EXPECT_THAT(message, HasSubstr("included from needs_lib.frag"));
}

TEST(ShaderIncludes, IncludeDirectoryAndRelativeToIncluder) {
    // uses_include.frag includes "lib/tint.glsl" (found in data/include), which includes
    // "scale.glsl" relative to itself.
    shader_compiler::ShaderCompilerOptions options;
    options.include_dirs = {kDataDir / "include"};
    std::vector<fs::path> seen;
    options.on_include = [&](const fs::path& resolved) { seen.push_back(resolved); };
    shader_compiler::ShaderCompiler compiler(options);
    const std::string code = read_text(kDataDir / "uses_include.frag");
    ASSERT_FALSE(code.empty());
    auto module = compile_ok(compiler, source((kDataDir / "uses_include.frag").string(), ShaderStage::Fragment, code));
    EXPECT_FALSE(module.spirv.empty());
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0], (kDataDir / "include/lib/tint.glsl").lexically_normal());
    EXPECT_EQ(seen[1], (kDataDir / "include/lib/scale.glsl").lexically_normal());
}

TEST(ShaderIncludes, VirtualFilesComeBeforeIncludeDirectories) {
    shader_compiler::ShaderCompilerOptions options;
    options.include_dirs = {kDataDir / "include"};
    // Shadows data/include/lib/tint.glsl; the disk version would compile, this one must not.
    options.virtual_files["lib/tint.glsl"] = "vec3 tint(vec3 c) { return c * from_virtual_file; }\n";
    shader_compiler::ShaderCompiler compiler(options);
    const std::string code = read_text(kDataDir / "uses_include.frag");
    const std::string message = compile_error(compiler, source("uses_include.frag", ShaderStage::Fragment, code));
    EXPECT_THAT(message, HasSubstr("lib/tint.glsl:1: 'from_virtual_file' : undeclared identifier"));
}

TEST(ShaderIncludes, ErrorInFileFromIncludeDirectoryNamesItsPath) {
    const fs::path dir = output_dir() / "shader_includes_test";
    fs::create_directories(dir / "inc");
    {
        std::ofstream out(dir / "inc" / "bad.glsl");
        out << "// line 1\n// line 2\nvec3 broken() { return vec3(oops); }\n";
    }
    shader_compiler::ShaderCompilerOptions options;
    options.include_dirs = {dir / "inc"};
    shader_compiler::ShaderCompiler compiler(options);
    const std::string message = compile_error(compiler, source("user.frag", ShaderStage::Fragment,
                                                                "#version 450\n"
                                                                "#include \"bad.glsl\"\n"
                                                                "void main() {}\n"));
    EXPECT_THAT(message, HasSubstr((dir / "inc" / "bad.glsl").lexically_normal().generic_string() +
                                   ":3: 'oops' : undeclared identifier"));
}

}  // namespace
}  // namespace loom::test
