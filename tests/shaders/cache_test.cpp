// compile_cached(): the same (name, stage, code, defines) is compiled once per compiler.

#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

using rhi::ShaderStage;

constexpr const char* kCode =
    "#version 450\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(VALUE); }\n";

TEST(ShaderCache, SameSourceHitsTheCache) {
    shader_compiler::ShaderCompiler compiler;
    EXPECT_EQ(compiler.cache_size(), 0u);
    auto first = compiler.compile_cached(source("cached.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}}));
    ASSERT_TRUE(first.ok()) << first.error().to_string();
    EXPECT_EQ(compiler.cache_size(), 1u);
    auto second = compiler.compile_cached(source("cached.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}}));
    ASSERT_TRUE(second.ok());
    EXPECT_EQ(compiler.cache_size(), 1u);
    EXPECT_EQ(second->spirv, first->spirv);
    EXPECT_EQ(second->gl_source, first->gl_source);
}

TEST(ShaderCache, EveryPartOfTheKeyMatters) {
    shader_compiler::ShaderCompiler compiler;
    auto compile = [&](std::string name, ShaderStage stage, std::string code,
                       std::vector<std::pair<std::string, std::string>> defines) {
        auto module = compiler.compile_cached(source(std::move(name), stage, std::move(code), std::move(defines)));
        EXPECT_TRUE(module.ok()) << module.error().to_string();
        return module.ok() ? module->spirv : std::vector<uint32_t>{};
    };
    const auto a = compile("a.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}});
    const auto b = compile("a.frag", ShaderStage::Fragment, kCode, {{"VALUE", "0.5"}});  // defines
    EXPECT_EQ(compiler.cache_size(), 2u);
    EXPECT_NE(a, b);  // the define changed the constant
    compile("b.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}});  // name
    EXPECT_EQ(compiler.cache_size(), 3u);
    compile("a.frag", ShaderStage::Fragment, std::string(kCode) + "\n", {{"VALUE", "1.0"}});  // code
    EXPECT_EQ(compiler.cache_size(), 4u);
    compile("a.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}, {"UNUSED", ""}});  // define list
    EXPECT_EQ(compiler.cache_size(), 5u);
    compile("a.frag", ShaderStage::Fragment, kCode, {{"VALUE", "1.0"}});  // hit
    EXPECT_EQ(compiler.cache_size(), 5u);
}

TEST(ShaderCache, FailuresAreNotCached) {
    shader_compiler::ShaderCompiler compiler;
    auto bad = compiler.compile_cached(source("bad.frag", ShaderStage::Fragment, kCode));  // VALUE undefined
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(compiler.cache_size(), 0u);
    auto again = compiler.compile_cached(source("bad.frag", ShaderStage::Fragment, kCode));
    ASSERT_FALSE(again.ok());
    EXPECT_EQ(again.error().message, bad.error().message);
}

TEST(ShaderDefines, ValuesReachTheShader) {
    shader_compiler::ShaderCompiler compiler;
    const std::string code =
        "#version 450\n"
        "layout(set = 0, binding = 0) uniform Lights { vec4 colors[LIGHT_COUNT]; } lights;\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() {\n"
        "#ifdef USE_SECOND\n"
        "    color = lights.colors[1];\n"
        "#else\n"
        "    color = lights.colors[0];\n"
        "#endif\n"
        "}\n";
    auto three = compile_ok(compiler, source("lights.frag", ShaderStage::Fragment, code, {{"LIGHT_COUNT", "3"}}));
    ASSERT_EQ(three.reflection.uniform_blocks.size(), 1u);
    EXPECT_EQ(three.reflection.uniform_blocks[0].size, 48u);
    auto five = compile_ok(compiler, source("lights.frag", ShaderStage::Fragment, code,
                                            {{"LIGHT_COUNT", "5"}, {"USE_SECOND", "1"}}));
    ASSERT_EQ(five.reflection.uniform_blocks.size(), 1u);
    EXPECT_EQ(five.reflection.uniform_blocks[0].size, 80u);
    EXPECT_NE(five.gl_source.find("lights.colors[1]"), std::string::npos) << five.gl_source;
    EXPECT_EQ(three.gl_source.find("lights.colors[1]"), std::string::npos) << three.gl_source;
}

}  // namespace
}  // namespace loom::test
