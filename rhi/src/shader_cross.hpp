#pragma once
// SPIR-V -> reflection and GL GLSL 450 with SPIRV-Cross (internal to loom::rhi).

#include <cstdint>
#include <span>
#include <string>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::rhi::detail {

/// Reflects `spirv` and cross-compiles it to GLSL 450 core for GL with bindings remapped by
/// gl_binding_point() and push constants as a uniform block at kGlPushConstantBinding.
/// Errors (ShaderCompile) name the shader and, where one is at fault, the resource.
Result<ShaderModule> module_from_spirv(std::string name, ShaderStage stage, std::span<const uint32_t> spirv);

}  // namespace loom::rhi::detail
