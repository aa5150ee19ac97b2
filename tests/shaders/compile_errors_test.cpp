// Compile errors name the file and the line as written, with or without defines and #version.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

using rhi::ShaderStage;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(ShaderCompileErrors, ReportsFileAndLine) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("err.frag", ShaderStage::Fragment,
                                                                "#version 450\n"
                                                                "layout(location = 0) out vec4 color;\n"
                                                                "\n"
                                                                "void main() {\n"
                                                                "    color = vec4(missing_value);\n"
                                                                "}\n"));
    EXPECT_THAT(message, HasSubstr("err.frag:5: 'missing_value' : undeclared identifier"));
    EXPECT_THAT(message, Not(HasSubstr("ERROR")));
    EXPECT_THAT(message, Not(HasSubstr("compilation errors")));
}

TEST(ShaderCompileErrors, ReportsEveryDiagnosticOnItsOwnLine) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("two.frag", ShaderStage::Fragment,
                                                                "#version 450\n"
                                                                "layout(location = 0) out vec4 color;\n"
                                                                "void main() {\n"
                                                                "    color = vec4(first);\n"
                                                                "    color = vec4(second);\n"
                                                                "    float x = 1.0\n"
                                                                "}\n"));
    EXPECT_THAT(message, HasSubstr("two.frag:4: 'first' : undeclared identifier\n"));
    EXPECT_THAT(message, HasSubstr("two.frag:5: 'second' : undeclared identifier\n"));
    EXPECT_THAT(message, HasSubstr("two.frag:7: "));
    EXPECT_THAT(message, HasSubstr("syntax error"));
}

TEST(ShaderCompileErrors, DefinesDoNotShiftLines) {
    shader_compiler::ShaderCompiler compiler;
    const std::string code =
        "#version 450\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() {\n"
        "    color = vec4(BRIGHTNESS);\n"
        "    color = vec4(typo_here);\n"
        "}\n";
    const std::string message = compile_error(
        compiler, source("defines.frag", ShaderStage::Fragment, code, {{"BRIGHTNESS", "0.5"}, {"OTHER", "1"}}));
    EXPECT_THAT(message, HasSubstr("defines.frag:5: 'typo_here' : undeclared identifier"));
    EXPECT_THAT(message, Not(HasSubstr("BRIGHTNESS")));  // the define took effect
}

TEST(ShaderCompileErrors, MissingVersionGetsVersion450AndKeepsLines) {
    shader_compiler::ShaderCompiler compiler;
    const std::string code =
        "layout(location = 0) out vec4 color;\n"
        "void main() {\n"
        "    color = vec4(VALUE);\n"
        "    color = vec4(nope);\n"
        "}\n";
    const std::string message =
        compile_error(compiler, source("noversion.frag", ShaderStage::Fragment, code, {{"VALUE", "1.0"}}));
    EXPECT_THAT(message, HasSubstr("noversion.frag:4: 'nope' : undeclared identifier"));

    // Without the error it compiles as GLSL 450 (which has layout(location) on outputs).
    auto module = compile_ok(compiler, source("noversion.frag", ShaderStage::Fragment,
                                              "layout(location = 0) out vec4 color;\n"
                                              "void main() { color = vec4(VALUE); }\n",
                                              {{"VALUE", "1.0"}}));
    EXPECT_FALSE(module.spirv.empty());
}

TEST(ShaderCompileErrors, UndefinedMacroWithoutItsDefineFails) {
    shader_compiler::ShaderCompiler compiler;
    const std::string code =
        "#version 450\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() { color = vec4(VALUE); }\n";
    EXPECT_THAT(compile_error(compiler, source("needs_define.frag", ShaderStage::Fragment, code)),
                HasSubstr("needs_define.frag:3: 'VALUE' : undeclared identifier"));
    auto module = compile_ok(compiler, source("needs_define.frag", ShaderStage::Fragment, code, {{"VALUE", "0.25"}}));
    EXPECT_FALSE(module.spirv.empty());
}

TEST(ShaderCompileErrors, StageMismatchIsAnError) {
    shader_compiler::ShaderCompiler compiler;
    // gl_Position does not exist in a fragment shader.
    const std::string message = compile_error(compiler, source("wrong_stage.frag", ShaderStage::Fragment,
                                                                "#version 450\n"
                                                                "void main() { gl_Position = vec4(0.0); }\n"));
    EXPECT_THAT(message, HasSubstr("wrong_stage.frag:2:"));
}

TEST(ShaderCompileErrors, LinkErrorNamesTheShader) {
    shader_compiler::ShaderCompiler compiler;
    // No main(): parsing succeeds, linking fails.
    const std::string message = compile_error(compiler, source("nomain.vert", ShaderStage::Vertex,
                                                                "#version 450\n"
                                                                "void helper() {}\n"));
    EXPECT_THAT(message, HasSubstr("nomain.vert"));
    EXPECT_THAT(message, HasSubstr("main"));
}

}  // namespace
}  // namespace loom::test
