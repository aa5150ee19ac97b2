#pragma once
// SPIR-V -> reflection and GL GLSL 450 with SPIRV-Cross (internal to loom::shader_compiler).

#include <cstdint>
#include <span>
#include <string>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::shader_compiler::detail {

/// Reflects `spirv` and cross-compiles it to GLSL 450 core for GL with bindings remapped by
/// gl_binding_point() and push constants as a uniform block at kGlPushConstantBinding.
/// Errors (ShaderCompile) name the shader and, where one is at fault, the resource.
Result<rhi::ShaderModule> module_from_spirv(std::string name, rhi::ShaderStage stage, std::span<const uint32_t> spirv);

}  // namespace loom::shader_compiler::detail
