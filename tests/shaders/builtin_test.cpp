// The built-in shaders compiled at build time load by name with their reflection; unknown
// names fail listing the known ones; every GLSL file under shaders/include/ is embedded, and the
// embedded snippets compile shaders at run time.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "loom/shaders/builtin.hpp"
#include "shader_test_util.hpp"

namespace loom::test {
namespace {

using rhi::BaseType;
using rhi::ShaderStage;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

rhi::ShaderModule load(std::string_view name) {
    auto module = shaders::builtin(name);
    EXPECT_TRUE(module.ok()) << (module.ok() ? "" : module.error().to_string());
    return module.ok() ? std::move(module).value() : rhi::ShaderModule{};
}

TEST(BuiltinShaders, NamesAreListed) {
    EXPECT_THAT(shaders::builtin_names(),
                ElementsAre("blit.frag", "fullscreen.vert", "triangle.frag", "triangle.vert"));
}

TEST(BuiltinShaders, EveryBuiltinLoadsWithValidGlSource) {
    for (const auto& name : shaders::builtin_names()) {
        auto module = load(name);
        EXPECT_EQ(module.name, name);
        EXPECT_FALSE(module.spirv.empty()) << name;
        EXPECT_EQ(module.spirv[0], 0x07230203u) << name;
        EXPECT_EQ(module.stage, name.ends_with(".vert") ? ShaderStage::Vertex : ShaderStage::Fragment) << name;
        auto status = shader_compiler::ShaderCompiler::check_gl_source(module);
        EXPECT_TRUE(status.ok()) << name << ": " << status.error().message;
    }
}

TEST(BuiltinShaders, TriangleReflection) {
    auto vert = load("triangle.vert");
    EXPECT_THAT(vert.reflection.inputs,
                ElementsAre(rhi::StageVariable{"position", 0, {BaseType::Float, 2, 1, 0}},
                            rhi::StageVariable{"color", 1, {BaseType::Float, 3, 1, 0}}));
    EXPECT_TRUE(vert.reflection.uniform_blocks.empty());
    auto frag = load("triangle.frag");
    EXPECT_THAT(frag.reflection.outputs, ElementsAre(rhi::StageVariable{"frag_color", 0, {BaseType::Float, 4, 1, 0}}));
    EXPECT_TRUE(frag.reflection.textures.empty());
}

TEST(BuiltinShaders, FullscreenAndBlit) {
    auto vert = load("fullscreen.vert");
    EXPECT_TRUE(vert.reflection.inputs.empty());  // no vertex buffer
    EXPECT_THAT(vert.gl_source, HasSubstr("gl_VertexID"));
    auto frag = load("blit.frag");
    ASSERT_EQ(frag.reflection.textures.size(), 1u);
    EXPECT_EQ(frag.reflection.textures[0],
              (rhi::SampledTexture{"source", 0, 0, rhi::TextureKind::Tex2D, false, BaseType::Float, 0}));
    EXPECT_THAT(frag.gl_source, HasSubstr("layout(binding = 0) uniform sampler2D source;"));
    EXPECT_THAT(frag.reflection.outputs, ElementsAre(rhi::StageVariable{"frag_color", 0, {BaseType::Float, 4, 1, 0}}));
}

TEST(BuiltinShaders, SecondLoadComesFromTheCacheUnchanged) {
    auto first = load("blit.frag");
    auto second = load("blit.frag");
    EXPECT_EQ(first.spirv, second.spirv);
    EXPECT_EQ(first.gl_source, second.gl_source);
    EXPECT_EQ(first.reflection.textures, second.reflection.textures);
}

TEST(BuiltinShaders, UnknownNameListsKnownNames) {
    auto module = shaders::builtin("nope.frag");
    ASSERT_FALSE(module.ok());
    EXPECT_EQ(module.error().code, ErrorCode::InvalidArgument);
    EXPECT_THAT(module.error().message, HasSubstr("nope.frag"));
    EXPECT_THAT(module.error().message, HasSubstr("blit.frag, fullscreen.vert, triangle.frag, triangle.vert"));
}

TEST(BuiltinShaders, EveryGlslFileUnderIncludeIsEmbeddedVerbatim) {
    // shaders/CMakeLists.txt finds them by a glob: a new file needs no list entry.
    const std::filesystem::path root = LOOM_SHADER_INCLUDE_DIR;
    const auto& files = shaders::include_files();
    std::size_t found = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".glsl") continue;
        ++found;
        const std::string name = entry.path().lexically_relative(root).generic_string();
        auto it = files.find(name);
        ASSERT_NE(it, files.end()) << name << " is not embedded";
        std::ifstream in(entry.path(), std::ios::binary);
        std::ostringstream text;
        text << in.rdbuf();
        EXPECT_EQ(it->second, text.str()) << name;
    }
    EXPECT_GT(found, 0u);
    EXPECT_EQ(files.size(), found);  // and nothing else
}

TEST(BuiltinShaders, EmbeddedSnippetsComposeShadersAtRunTime) {
    const auto& files = shaders::include_files();
    ASSERT_TRUE(files.contains("loom/common.glsl"));
    EXPECT_THAT(files.at("loom/common.glsl"), HasSubstr("linear_to_srgb"));

    shader_compiler::ShaderCompilerOptions options;
    options.virtual_files = files;
    shader_compiler::ShaderCompiler compiler(options);
    auto module = compile_ok(compiler, source("tonemap.frag", ShaderStage::Fragment, R"(#version 450
#include "loom/common.glsl"
layout(set = 0, binding = 0) uniform sampler2D hdr;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    vec3 c = texture(hdr, uv).rgb;
    color = vec4(linear_to_srgb(c / (1.0 + luminance(c))), 1.0);
}
)"));
    EXPECT_TRUE(shader_compiler::ShaderCompiler::check_gl_source(module).ok());
}

}  // namespace
}  // namespace loom::test
