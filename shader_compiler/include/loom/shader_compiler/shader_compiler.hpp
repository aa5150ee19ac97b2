#pragma once
// GLSL 450 (Vulkan-style set/binding) -> glslang -> SPIR-V -> SPIRV-Cross -> GL GLSL 450 and
// reflection. Used at build time for the built-in shaders (so a broken shader breaks the build)
// and at run time for shaders composed from pass and object parts (with a cache).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "loom/rhi/result.hpp"
#include "loom/rhi/handles.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::rhi {
class Device;
}

namespace loom::shader_compiler {

/// One stage of GLSL source to compile, with its name and defines.
struct ShaderSource {
    std::string name;  ///< file name or composed name; compile errors say "name:line: ..."
    rhi::ShaderStage stage = rhi::ShaderStage::Vertex;
    std::string code;  ///< GLSL 450 source, with or without a #version line
    std::vector<std::pair<std::string, std::string>> defines;  ///< NAME, value
};

/// Resolves `#include "x"` to source text; returns nullopt if not found.
using IncludeResolver = std::function<std::optional<std::string>(const std::string& requested,
                                                                 const std::string& includer)>;

/// Where a ShaderCompiler finds includes, and how it compiles.
struct ShaderCompilerOptions {
    /// Directories searched for #include, in order (after `virtual_files`).
    std::vector<std::filesystem::path> include_dirs;
    /// In-memory files (e.g. the embedded shared snippets of shaders/), by include name.
    std::map<std::string, std::string> virtual_files;
    /// Emit debug info / skip optimisation.
    bool debug_info = false;
    /// Called with the path of every #include resolved from disk (include_dirs or relative to
    /// the includer), e.g. to write a build dependency file. Not called for virtual_files.
    std::function<void(const std::filesystem::path& resolved)> on_include;
};

/// Compiles GLSL to a rhi::ShaderModule. Thread-compatible: one compiler per thread, or guard it.
class ShaderCompiler {
public:
    /// A compiler with these include paths and in-memory files.
    explicit ShaderCompiler(ShaderCompilerOptions options = {});
    ~ShaderCompiler();
    ShaderCompiler(const ShaderCompiler&) = delete;
    ShaderCompiler& operator=(const ShaderCompiler&) = delete;

    /// Compiles one stage. Errors are ShaderCompile with "name:line: message" for every
    /// diagnostic glslang reported (lines of included files name the included file).
    Result<rhi::ShaderModule> compile(const ShaderSource& source);

    /// Like compile(), but returns the cached module when the same source (name, stage, code,
    /// defines) was compiled before by this compiler.
    Result<rhi::ShaderModule> compile_cached(const ShaderSource& source);

    /// Compiles `source` and creates the shader on `device` (the module is not kept): inline
    /// GLSL to a shader handle in one call, compile errors and the device's alike.
    Result<rhi::ShaderHandle> create_shader(rhi::Device& device, const ShaderSource& source);

    /// Builds the GL source and reflection of already-compiled SPIR-V (used for the SPIR-V
    /// embedded at build time).
    static Result<rhi::ShaderModule> from_spirv(std::string name, rhi::ShaderStage stage, std::span<const uint32_t> spirv);

    /// Checks without a GL context that `module.gl_source` is valid GLSL 450 core (glslang,
    /// OpenGL rules). A ShaderCompile error names the module and the offending lines.
    static Status check_gl_source(const rhi::ShaderModule& module);

    /// Number of modules held by the compile_cached() cache.
    [[nodiscard]] std::size_t cache_size() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace loom::shader_compiler
