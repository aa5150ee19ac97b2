// Reflection is exact: bindings, std140/std430 layouts, texture kinds, formats, stage
// variables, push constants, workgroup size; and out-of-range or unsupported resources fail.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "shader_test_util.hpp"

namespace loom::test {
namespace {

using rhi::BaseType;
using rhi::BlockMember;
using rhi::ShaderStage;
using rhi::TextureKind;
using rhi::ValueType;
using ::testing::HasSubstr;

constexpr ValueType scalar(BaseType base) { return ValueType{base, 1, 1, 0}; }
constexpr ValueType vec(BaseType base, uint32_t n, uint32_t array = 0) { return ValueType{base, n, 1, array}; }
constexpr ValueType mat(uint32_t columns, uint32_t rows) { return ValueType{BaseType::Float, rows, columns, 0}; }

constexpr const char* kMaterialShader = R"(#version 450
layout(set = 1, binding = 1) uniform Material {
    mat4 mvp;
    vec3 color;
    float intensity;
    vec2 uv[2];
} material;
layout(set = 0, binding = 3) uniform Frame {
    float time;
    ivec2 size;
    uint frame;
} frame;
layout(location = 0) in vec3 v_normal;
layout(location = 0) out vec4 albedo;
layout(location = 2) out uvec2 ids;
void main() {
    albedo = material.mvp * vec4(material.color * material.intensity, material.uv[1].x + frame.time);
    ids = uvec2(frame.frame, uint(frame.size.x));
}
)";

TEST(ShaderReflection, UniformBlockStd140Layout) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    const auto& blocks = module.reflection.uniform_blocks;
    ASSERT_EQ(blocks.size(), 2u);

    // Sorted by (set, binding): Frame (0, 3) first.
    EXPECT_EQ(blocks[0].name, "Frame");
    EXPECT_EQ(blocks[0].set, 0u);
    EXPECT_EQ(blocks[0].binding, 3u);
    EXPECT_EQ(blocks[0].size, 20u);  // last member end; not rounded up to 16
    ASSERT_EQ(blocks[0].members.size(), 3u);
    EXPECT_EQ(blocks[0].members[0], (BlockMember{"time", scalar(BaseType::Float), 0, 4, 0, 0}));
    EXPECT_EQ(blocks[0].members[1], (BlockMember{"size", vec(BaseType::Int, 2), 8, 8, 0, 0}));
    EXPECT_EQ(blocks[0].members[2], (BlockMember{"frame", scalar(BaseType::Uint), 16, 4, 0, 0}));

    const auto& material = blocks[1];
    EXPECT_EQ(material.name, "Material");
    EXPECT_EQ(material.set, 1u);
    EXPECT_EQ(material.binding, 1u);
    EXPECT_EQ(material.size, 112u);
    ASSERT_EQ(material.members.size(), 4u);
    EXPECT_EQ(material.members[0], (BlockMember{"mvp", mat(4, 4), 0, 64, 0, 16}));
    EXPECT_EQ(material.members[1], (BlockMember{"color", vec(BaseType::Float, 3), 64, 12, 0, 0}));
    EXPECT_EQ(material.members[2], (BlockMember{"intensity", scalar(BaseType::Float), 76, 4, 0, 0}));
    EXPECT_EQ(material.members[3], (BlockMember{"uv", vec(BaseType::Float, 2, 2), 80, 32, 16, 0}));
}

TEST(ShaderReflection, FragmentOutputsAndNoInputs) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    EXPECT_TRUE(module.reflection.inputs.empty());  // only vertex inputs are reflected
    ASSERT_EQ(module.reflection.outputs.size(), 2u);
    EXPECT_EQ(module.reflection.outputs[0], (rhi::StageVariable{"albedo", 0, vec(BaseType::Float, 4)}));
    EXPECT_EQ(module.reflection.outputs[1], (rhi::StageVariable{"ids", 2, vec(BaseType::Uint, 2)}));
}

TEST(ShaderReflection, VertexInputs) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("inputs.vert", ShaderStage::Vertex, R"(#version 450
layout(location = 3) in vec4 weights;
layout(location = 0) in vec3 position;
layout(location = 1) in ivec4 joints;
layout(location = 2) in float scale;
layout(location = 4) in mat4 instance_transform;
layout(location = 0) out vec3 v_position;
void main() {
    v_position = position * scale + weights.xyz + vec3(joints.xyz);
    gl_Position = instance_transform * vec4(position, 1.0);
}
)"));
    const auto& inputs = module.reflection.inputs;
    ASSERT_EQ(inputs.size(), 5u);
    EXPECT_EQ(inputs[0], (rhi::StageVariable{"position", 0, vec(BaseType::Float, 3)}));
    EXPECT_EQ(inputs[1], (rhi::StageVariable{"joints", 1, vec(BaseType::Int, 4)}));
    EXPECT_EQ(inputs[2], (rhi::StageVariable{"scale", 2, scalar(BaseType::Float)}));
    EXPECT_EQ(inputs[3], (rhi::StageVariable{"weights", 3, vec(BaseType::Float, 4)}));
    EXPECT_EQ(inputs[4], (rhi::StageVariable{"instance_transform", 4, mat(4, 4)}));
    EXPECT_TRUE(module.reflection.outputs.empty());  // vertex outputs are not reflected
}

TEST(ShaderReflection, StorageBuffers) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("particles.comp", ShaderStage::Compute, R"(#version 450
layout(local_size_x = 64) in;
struct Particle { vec4 position; vec4 velocity; };
layout(std430, set = 0, binding = 0) readonly buffer Input { uint count; float dt; Particle particles[]; } input_buffer;
layout(std430, set = 0, binding = 1) buffer Output { vec3 bounds; float total; } output_buffer;
void main() {
    output_buffer.total += input_buffer.particles[gl_GlobalInvocationID.x].velocity.x * input_buffer.dt;
    output_buffer.bounds = vec3(float(input_buffer.count));
}
)"));
    const auto& buffers = module.reflection.storage_buffers;
    ASSERT_EQ(buffers.size(), 2u);
    EXPECT_EQ(buffers[0].name, "Input");
    EXPECT_EQ(buffers[0].set, 0u);
    EXPECT_EQ(buffers[0].binding, 0u);
    EXPECT_TRUE(buffers[0].read_only);
    EXPECT_EQ(buffers[0].size, 16u);  // the trailing runtime array is not counted
    ASSERT_EQ(buffers[0].members.size(), 3u);
    EXPECT_EQ(buffers[0].members[0].name, "count");
    EXPECT_EQ(buffers[0].members[1].offset, 4u);
    EXPECT_EQ(buffers[0].members[2].name, "particles");
    EXPECT_EQ(buffers[0].members[2].offset, 16u);
    EXPECT_EQ(buffers[0].members[2].array_stride, 32u);
    EXPECT_EQ(buffers[0].members[2].type.base, BaseType::Struct);

    EXPECT_EQ(buffers[1].name, "Output");
    EXPECT_EQ(buffers[1].binding, 1u);
    EXPECT_FALSE(buffers[1].read_only);
    EXPECT_EQ(buffers[1].size, 16u);  // std430: vec3 at 0, float at 12
    ASSERT_EQ(buffers[1].members.size(), 2u);
    EXPECT_EQ(buffers[1].members[1], (BlockMember{"total", scalar(BaseType::Float), 12, 4, 0, 0}));

    EXPECT_EQ(module.reflection.workgroup_size[0], 64u);
    EXPECT_EQ(module.reflection.workgroup_size[1], 1u);
    EXPECT_EQ(module.reflection.workgroup_size[2], 1u);
}

TEST(ShaderReflection, SamplerKinds) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("samplers.frag", ShaderStage::Fragment, R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D albedo;
layout(set = 0, binding = 1) uniform sampler2DArray layers;
layout(set = 0, binding = 2) uniform sampler3D volume;
layout(set = 0, binding = 3) uniform samplerCube sky;
layout(set = 0, binding = 4) uniform sampler2DShadow shadow_map;
layout(set = 0, binding = 5) uniform isampler2D ids;
layout(set = 0, binding = 6) uniform usampler2D masks;
layout(set = 2, binding = 0) uniform sampler2D many[4];
layout(set = 1, binding = 0) uniform sampler2DArrayShadow cascades;
layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    color = texture(albedo, uv) + texture(layers, vec3(uv, 1.0)) + texture(volume, vec3(uv, 0.5))
          + texture(sky, vec3(uv, 1.0)) + vec4(texture(shadow_map, vec3(uv, 0.5)))
          + vec4(texture(ids, uv)) + vec4(texture(masks, uv)) + texture(many[2], uv)
          + vec4(texture(cascades, vec4(uv, 0.0, 0.5)));
}
)"));
    using T = rhi::SampledTexture;
    const auto& textures = module.reflection.textures;
    ASSERT_EQ(textures.size(), 9u);
    EXPECT_EQ(textures[0], (T{"albedo", 0, 0, TextureKind::Tex2D, false, BaseType::Float, 0}));
    EXPECT_EQ(textures[1], (T{"layers", 0, 1, TextureKind::Tex2DArray, false, BaseType::Float, 0}));
    EXPECT_EQ(textures[2], (T{"volume", 0, 2, TextureKind::Tex3D, false, BaseType::Float, 0}));
    EXPECT_EQ(textures[3], (T{"sky", 0, 3, TextureKind::Cube, false, BaseType::Float, 0}));
    EXPECT_EQ(textures[4], (T{"shadow_map", 0, 4, TextureKind::Tex2D, true, BaseType::Float, 0}));
    EXPECT_EQ(textures[5], (T{"ids", 0, 5, TextureKind::Tex2D, false, BaseType::Int, 0}));
    EXPECT_EQ(textures[6], (T{"masks", 0, 6, TextureKind::Tex2D, false, BaseType::Uint, 0}));
    EXPECT_EQ(textures[7], (T{"cascades", 1, 0, TextureKind::Tex2DArray, true, BaseType::Float, 0}));
    EXPECT_EQ(textures[8], (T{"many", 2, 0, TextureKind::Tex2D, false, BaseType::Float, 4}));
}

TEST(ShaderReflection, StorageImages) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("images.comp", ShaderStage::Compute, R"(#version 450
layout(local_size_x = 8, local_size_y = 4, local_size_z = 2) in;
layout(set = 0, binding = 0, rgba8) uniform writeonly image2D target;
layout(set = 0, binding = 1, r32f) uniform readonly image2D depth;
layout(set = 0, binding = 2, rgba16f) uniform image3D volume;
layout(set = 0, binding = 3, r32ui) uniform uimage2DArray counters;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    vec4 v = imageLoad(volume, ivec3(p, 0));
    imageStore(volume, ivec3(p, 1), v);
    imageStore(target, p, vec4(imageLoad(depth, p).r));
    imageAtomicAdd(counters, ivec3(p, 0), 1u);
}
)"));
    using I = rhi::StorageImage;
    const auto& images = module.reflection.storage_images;
    ASSERT_EQ(images.size(), 4u);
    EXPECT_EQ(images[0], (I{"target", 0, 0, TextureKind::Tex2D, "rgba8", false, true}));
    EXPECT_EQ(images[1], (I{"depth", 0, 1, TextureKind::Tex2D, "r32f", true, false}));
    EXPECT_EQ(images[2], (I{"volume", 0, 2, TextureKind::Tex3D, "rgba16f", false, false}));
    EXPECT_EQ(images[3], (I{"counters", 0, 3, TextureKind::Tex2DArray, "r32ui", false, false}));
    EXPECT_EQ(module.reflection.workgroup_size[0], 8u);
    EXPECT_EQ(module.reflection.workgroup_size[1], 4u);
    EXPECT_EQ(module.reflection.workgroup_size[2], 2u);
}

TEST(ShaderReflection, PushConstants) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("push.vert", ShaderStage::Vertex, R"(#version 450
layout(push_constant) uniform Push {
    mat4 model;
    vec4 tint;
    float scale;
    uint id;
} push;
layout(location = 0) in vec3 position;
void main() {
    gl_Position = push.model * vec4(position * push.scale + push.tint.xyz + float(push.id), 1.0);
}
)"));
    ASSERT_EQ(module.reflection.push_constants.size(), 1u);
    const auto& block = module.reflection.push_constants[0];
    EXPECT_EQ(block.name, "Push");
    EXPECT_EQ(block.size, 88u);
    ASSERT_EQ(block.members.size(), 4u);
    EXPECT_EQ(block.members[0], (BlockMember{"model", mat(4, 4), 0, 64, 0, 16}));
    EXPECT_EQ(block.members[1], (BlockMember{"tint", vec(BaseType::Float, 4), 64, 16, 0, 0}));
    EXPECT_EQ(block.members[2], (BlockMember{"scale", scalar(BaseType::Float), 80, 4, 0, 0}));
    EXPECT_EQ(block.members[3], (BlockMember{"id", scalar(BaseType::Uint), 84, 4, 0, 0}));
    EXPECT_TRUE(module.reflection.uniform_blocks.empty());
}

TEST(ShaderReflection, FromSpirvGivesTheSameReflection) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    auto rebuilt = shader_compiler::ShaderCompiler::from_spirv("material.frag", ShaderStage::Fragment, module.spirv);
    ASSERT_TRUE(rebuilt.ok()) << rebuilt.error().to_string();
    const auto& a = module.reflection;
    const auto& b = rebuilt->reflection;
    EXPECT_EQ(a.uniform_blocks, b.uniform_blocks);
    EXPECT_EQ(a.storage_buffers, b.storage_buffers);
    EXPECT_EQ(a.textures, b.textures);
    EXPECT_EQ(a.storage_images, b.storage_images);
    EXPECT_EQ(a.inputs, b.inputs);
    EXPECT_EQ(a.outputs, b.outputs);
    EXPECT_EQ(a.push_constants, b.push_constants);
    EXPECT_EQ(rebuilt->gl_source, module.gl_source);
    EXPECT_EQ(rebuilt->spirv, module.spirv);
    EXPECT_EQ(rebuilt->name, "material.frag");
    EXPECT_EQ(rebuilt->stage, ShaderStage::Fragment);
    EXPECT_EQ(rebuilt->entry_point, "main");
}

TEST(ShaderReflection, DebugInfoKeepsTheReflection) {
    shader_compiler::ShaderCompiler plain;
    shader_compiler::ShaderCompilerOptions options;
    options.debug_info = true;
    shader_compiler::ShaderCompiler debug(options);
    auto a = compile_ok(plain, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    auto b = compile_ok(debug, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    EXPECT_GT(b.spirv.size(), a.spirv.size());  // line info and source were added
    EXPECT_EQ(a.reflection.uniform_blocks, b.reflection.uniform_blocks);
    EXPECT_EQ(a.reflection.outputs, b.reflection.outputs);
}

TEST(ShaderReflection, FromSpirvRejectsWrongStageAndGarbage) {
    shader_compiler::ShaderCompiler compiler;
    auto module = compile_ok(compiler, source("material.frag", ShaderStage::Fragment, kMaterialShader));
    auto wrong = shader_compiler::ShaderCompiler::from_spirv("material.frag", ShaderStage::Vertex, module.spirv);
    ASSERT_FALSE(wrong.ok());
    EXPECT_EQ(wrong.error().code, ErrorCode::ShaderCompile);
    EXPECT_THAT(wrong.error().message, HasSubstr("material.frag"));
    EXPECT_THAT(wrong.error().message, HasSubstr("vertex"));

    const std::vector<uint32_t> garbage = {1, 2, 3, 4, 5, 6};
    auto bad = shader_compiler::ShaderCompiler::from_spirv("garbage.spv", ShaderStage::Vertex, garbage);
    ASSERT_FALSE(bad.ok());
    EXPECT_THAT(bad.error().message, HasSubstr("garbage.spv"));

    std::vector<uint32_t> truncated(module.spirv.begin(), module.spirv.begin() + 20);
    auto cut = shader_compiler::ShaderCompiler::from_spirv("truncated.spv", ShaderStage::Fragment, truncated);
    ASSERT_FALSE(cut.ok());
    EXPECT_THAT(cut.error().message, HasSubstr("truncated.spv"));
}

TEST(ShaderReflection, SetOutOfRangeNamesShaderAndResource) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("far_set.frag", ShaderStage::Fragment, R"(#version 450
layout(set = 4, binding = 0) uniform sampler2D too_far;
layout(location = 0) out vec4 color;
void main() { color = texture(too_far, vec2(0.5)); }
)"));
    EXPECT_THAT(message, HasSubstr("far_set.frag"));
    EXPECT_THAT(message, HasSubstr("'too_far'"));
    EXPECT_THAT(message, HasSubstr("set 4"));
}

TEST(ShaderReflection, BindingOutOfRangeNamesShaderAndResource) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("far_binding.vert", ShaderStage::Vertex, R"(#version 450
layout(set = 3, binding = 16) uniform Far { vec4 v; } far;
void main() { gl_Position = far.v; }
)"));
    EXPECT_THAT(message, HasSubstr("far_binding.vert"));
    EXPECT_THAT(message, HasSubstr("'Far'"));
    EXPECT_THAT(message, HasSubstr("binding 16"));

    // The largest legal point compiles.
    auto ok = compile_ok(compiler, source("edge.vert", ShaderStage::Vertex, R"(#version 450
layout(set = 3, binding = 15) uniform Edge { vec4 v; } edge;
void main() { gl_Position = edge.v; }
)"));
    ASSERT_EQ(ok.reflection.uniform_blocks.size(), 1u);
    EXPECT_EQ(ok.reflection.uniform_blocks[0].set, 3u);
    EXPECT_EQ(ok.reflection.uniform_blocks[0].binding, 15u);
}

TEST(ShaderReflection, SeparateImagesAndSamplersAreRejected) {
    shader_compiler::ShaderCompiler compiler;
    const std::string message = compile_error(compiler, source("separate.frag", ShaderStage::Fragment, R"(#version 450
layout(set = 0, binding = 0) uniform texture2D color_texture;
layout(set = 0, binding = 1) uniform sampler linear_sampler;
layout(location = 0) out vec4 color;
void main() { color = texture(sampler2D(color_texture, linear_sampler), vec2(0.5)); }
)"));
    EXPECT_THAT(message, HasSubstr("separate.frag"));
    EXPECT_THAT(message, HasSubstr("'color_texture'"));
    EXPECT_THAT(message, HasSubstr("'linear_sampler'"));
    EXPECT_THAT(message, HasSubstr("not supported"));
}

}  // namespace
}  // namespace loom::test
