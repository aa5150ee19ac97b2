// ShaderCompiler: glslang (GLSL -> SPIR-V) followed by SPIRV-Cross (reflection, GL GLSL), with
// a per-compiler cache for shaders composed at run time.

#include "loom/shader_compiler/shader_compiler.hpp"

#include <unordered_map>

#include "loom/rhi/device.hpp"

#include "spirv_cross.hpp"
#include "glslang_compile.hpp"

namespace loom::shader_compiler {

// Everything this library makes is an rhi::ShaderModule and its reflection.
using namespace loom::rhi;

struct ShaderCompiler::Impl {
    ShaderCompilerOptions options;
    std::unordered_map<std::string, ShaderModule> cache;
};

namespace {

/// A cache key that distinguishes every (name, stage, code, defines): each part is prefixed
/// with its length so no two different sources serialise alike.
std::string cache_key(const ShaderSource& source) {
    std::string key;
    auto append = [&key](std::string_view part) {
        key += std::to_string(part.size());
        key += ':';
        key += part;
    };
    append(source.name);
    append(shader_stage_name(source.stage));
    append(source.code);
    for (const auto& [name, value] : source.defines) {
        append(name);
        append(value);
    }
    return key;
}

}  // namespace

ShaderCompiler::ShaderCompiler(ShaderCompilerOptions options) : impl_(std::make_unique<Impl>()) {
    impl_->options = std::move(options);
}

ShaderCompiler::~ShaderCompiler() = default;

Result<ShaderModule> ShaderCompiler::compile(const ShaderSource& source) {
    auto spirv = detail::compile_glsl_to_spirv(source, impl_->options);
    if (!spirv) return spirv.take_error();
    return detail::module_from_spirv(source.name, source.stage, *spirv);
}

Result<ShaderModule> ShaderCompiler::compile_cached(const ShaderSource& source) {
    std::string key = cache_key(source);
    if (auto it = impl_->cache.find(key); it != impl_->cache.end()) return it->second;
    auto module = compile(source);
    if (module) impl_->cache.emplace(std::move(key), *module);
    return module;
}

Result<rhi::ShaderHandle> ShaderCompiler::create_shader(rhi::Device& device, const ShaderSource& source) {
    auto module = compile(source);
    if (!module) return module.take_error();
    return device.create_shader(*module);
}

Result<ShaderModule> ShaderCompiler::from_spirv(std::string name, ShaderStage stage, std::span<const uint32_t> spirv) {
    return detail::module_from_spirv(std::move(name), stage, spirv);
}

Status ShaderCompiler::check_gl_source(const ShaderModule& module) {
    return detail::check_gl_glsl(module.name, module.stage, module.gl_source);
}

std::size_t ShaderCompiler::cache_size() const { return impl_->cache.size(); }

}  // namespace loom::shader_compiler
