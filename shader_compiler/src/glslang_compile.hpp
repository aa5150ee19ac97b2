#pragma once
// GLSL 450 -> SPIR-V with glslang (internal to loom::shader_compiler). Kept apart from the SPIRV-Cross half
// because glslang and SPIRV-Cross ship different copies of spirv.hpp that must not meet in one
// translation unit.

#include <cstdint>
#include <string>
#include <vector>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::shader_compiler::detail {

/// Compiles one stage to SPIR-V 1.5 for Vulkan. Errors are ShaderCompile, one
/// "name:line: message" line per diagnostic.
Result<std::vector<uint32_t>> compile_glsl_to_spirv(const ShaderSource& source,
                                                    const ShaderCompilerOptions& options);

/// Checks that GLSL meant for OpenGL (no Vulkan semantics) parses and links as one stage;
/// used to validate SPIRV-Cross output without a GL context. Errors are ShaderCompile.
Status check_gl_glsl(const std::string& name, rhi::ShaderStage stage, const std::string& code);

}  // namespace loom::shader_compiler::detail
