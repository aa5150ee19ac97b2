// The GL GLSL made by SPIRV-Cross: bindings remapped with gl_binding_point, no descriptor sets,
// push constants as a UBO at kGlPushConstantBinding, explicit locations kept, no clip-space or
// y-flip fixups, gl_VertexIndex as gl_VertexID; and it is valid GLSL 450 core.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

using rhi::ShaderStage;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr const char* kBindingsVertex = R"(#version 450
layout(set = 1, binding = 1) uniform Camera { mat4 view_projection; } camera;
layout(set = 0, binding = 2) uniform Object { mat4 model; } object;
layout(set = 2, binding = 5, std430) readonly buffer Offsets { vec4 offsets[]; } offsets;
layout(push_constant) uniform Push { vec4 tint; uint index; } push;
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
layout(location = 0) out vec3 v_color;
void main() {
    v_color = color * push.tint.rgb;
    gl_Position = camera.view_projection * object.model * vec4(position + offsets.offsets[push.index].xyz, 1.0);
}
)";

TEST(ShaderGlSource, BindingsAreRemapped) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("bindings.vert", ShaderStage::Vertex, kBindingsVertex));
    const std::string& gl = module.gl_source;
    static_assert(rhi::gl_binding_point(1, 1) == 17);
    EXPECT_THAT(gl, HasSubstr("layout(binding = 17, std140) uniform Camera"));
    EXPECT_THAT(gl, HasSubstr("layout(binding = 2, std140) uniform Object"));
    EXPECT_THAT(gl, HasSubstr("layout(binding = 37, std430) readonly buffer Offsets"));
    EXPECT_THAT(gl, Not(HasSubstr("set =")));
    // The reflection keeps the Vulkan-style points.
    ASSERT_EQ(module.reflection.uniform_blocks.size(), 2u);
    EXPECT_EQ(module.reflection.uniform_blocks[1].set, 1u);
    EXPECT_EQ(module.reflection.uniform_blocks[1].binding, 1u);
}

TEST(ShaderGlSource, PushConstantsBecomeAUniformBufferAtTheReservedBinding) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("bindings.vert", ShaderStage::Vertex, kBindingsVertex));
    static_assert(rhi::kGlPushConstantBinding == 64);
    EXPECT_THAT(module.gl_source, HasSubstr("layout(binding = 64, std140) uniform Push"));
    EXPECT_THAT(module.gl_source, Not(HasSubstr("push_constant")));
}

TEST(ShaderGlSource, SamplersAndImagesAreRemapped) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("textures.frag", ShaderStage::Fragment, R"(#version 450
layout(set = 3, binding = 4) uniform sampler2D albedo;
layout(set = 1, binding = 0, rgba8) uniform writeonly image2D target;
layout(location = 0) in vec2 uv;
layout(location = 1) out vec4 color;
void main() {
    color = texture(albedo, uv);
    imageStore(target, ivec2(uv * 16.0), color);
}
)"));
    EXPECT_THAT(module.gl_source, HasSubstr("layout(binding = 52) uniform sampler2D albedo;"));
    EXPECT_THAT(module.gl_source, HasSubstr("layout(binding = 16, rgba8) uniform writeonly image2D target;"));
    EXPECT_THAT(module.gl_source, HasSubstr("layout(location = 0) in vec2 uv;"));
    EXPECT_THAT(module.gl_source, HasSubstr("layout(location = 1) out vec4 color;"));
    EXPECT_TRUE(shader_compiler::ShaderCompiler::check_gl_source(module).ok());
}

TEST(ShaderGlSource, KeepsLocationsAndAddsNoClipSpaceFixups) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("bindings.vert", ShaderStage::Vertex, kBindingsVertex));
    const std::string& gl = module.gl_source;
    EXPECT_THAT(gl, HasSubstr("layout(location = 0) in vec3 position;"));
    EXPECT_THAT(gl, HasSubstr("layout(location = 1) in vec3 color;"));
    EXPECT_THAT(gl, HasSubstr("layout(location = 0) out vec3 v_color;"));
    // fixup_clipspace would rewrite z as 2z - w, flip_vert_y would negate y.
    EXPECT_THAT(gl, Not(HasSubstr("gl_Position.z =")));
    EXPECT_THAT(gl, Not(HasSubstr("gl_Position.y = -")));
    EXPECT_THAT(gl, HasSubstr("#version 450"));
    EXPECT_THAT(gl, Not(HasSubstr(" es")));
}

TEST(ShaderGlSource, VertexAndInstanceIndexHaveVulkanSemantics) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("indices.vert", ShaderStage::Vertex, R"(#version 450
void main() {
    gl_Position = vec4(float(gl_VertexIndex), float(gl_InstanceIndex), 0.0, 1.0);
}
)"));
    // GL's gl_VertexID already counts from `first` (and includes basevertex), like gl_VertexIndex.
    EXPECT_THAT(module.gl_source, HasSubstr("float(gl_VertexID)"));
    // gl_InstanceID does not include the base instance: SPIRV-Cross adds it back.
    EXPECT_THAT(module.gl_source, HasSubstr("gl_InstanceID + SPIRV_Cross_BaseInstance"));
    EXPECT_TRUE(shader_compiler::ShaderCompiler::check_gl_source(module).ok());
}

TEST(ShaderGlSource, ValidGlslForEveryKindOfResource) {
    shader_compiler::ShaderCompiler compiler;
    const std::vector<shader_compiler::ShaderSource> sources = {
        source("bindings.vert", ShaderStage::Vertex, kBindingsVertex),
        source("compute.comp", ShaderStage::Compute, R"(#version 450
layout(local_size_x = 16, local_size_y = 16) in;
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba16f) uniform writeonly image2D dst;
layout(set = 1, binding = 0, std430) buffer Histogram { uint bins[256]; } histogram;
layout(push_constant) uniform Params { vec2 texel; float exposure; } params;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    vec4 c = textureLod(src, (vec2(p) + 0.5) * params.texel, 0.0) * params.exposure;
    atomicAdd(histogram.bins[uint(clamp(c.r, 0.0, 1.0) * 255.0)], 1u);
    imageStore(dst, p, c);
}
)"),
        source("shadow.frag", ShaderStage::Fragment, R"(#version 450
layout(set = 0, binding = 0) uniform sampler2DShadow shadow_map;
layout(set = 0, binding = 1) uniform samplerCube sky;
layout(set = 0, binding = 2) uniform sampler2DArray layers;
layout(location = 0) in vec4 v_shadow_coord;
layout(location = 0) out vec4 color;
void main() {
    float lit = texture(shadow_map, v_shadow_coord.xyz);
    if (lit < 0.01) discard;
    color = lit * texture(sky, v_shadow_coord.xyz) + texture(layers, v_shadow_coord.xyz);
}
)"),
    };
    for (const auto& src : sources) {
        auto module = compile_ok(compiler, src);
        auto status = shader_compiler::ShaderCompiler::check_gl_source(module);
        EXPECT_TRUE(status.ok()) << src.name << ": " << status.error().message << "\n" << module.gl_source;
    }
}

TEST(ShaderGlSource, PushConstantsThatStd140CannotExpressAreAnError) {
    // std430 gives float[4] a stride of 4; a GL uniform block (std140) cannot: the bytes the
    // backends upload would land in the wrong members, so this must not compile.
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("weights.frag", ShaderStage::Fragment, R"(#version 450
layout(push_constant) uniform Push { float weights[4]; } push;
layout(location = 0) out vec4 color;
void main() { color = vec4(push.weights[1]); }
)"));
    EXPECT_THAT(message, HasSubstr("weights.frag"));
    EXPECT_THAT(message, HasSubstr("std140"));
}

TEST(ShaderGlSource, CheckRejectsInvalidGlsl) {
    // check_gl_source is a real check: a Vulkan-only construct fails it with the module's name.
    rhi::ShaderModule module;
    module.name = "vulkan_only.frag";
    module.stage = ShaderStage::Fragment;
    module.gl_source =
        "#version 450\n"
        "layout(push_constant) uniform Push { vec4 c; } push;\n"
        "layout(location = 0) out vec4 color;\n"
        "void main() { color = push.c; }\n";
    auto status = shader_compiler::ShaderCompiler::check_gl_source(module);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::ShaderCompile);
    EXPECT_THAT(status.error().message, HasSubstr("vulkan_only.frag:2:"));
}

}  // namespace
}  // namespace loom::test
