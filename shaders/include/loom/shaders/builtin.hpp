#pragma once
// The built-in shaders, compiled to SPIR-V at build time (a broken shader breaks the build),
// and the shared GLSL snippets of shaders/include/ for composing shaders at run time.

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::shaders {

/// A built-in shader compiled at build time, by its path relative to shaders/ ("triangle.vert").
/// The GL source and reflection are rebuilt from the embedded SPIR-V on first use and cached.
/// An unknown name is an InvalidArgument error listing the known names.
loom::Result<rhi::ShaderModule> builtin(std::string_view name);

/// The names of every built-in shader, sorted.
std::vector<std::string> builtin_names();

/// Shared snippets under shaders/include/ by include name (e.g. "loom/common.glsl"), embedded for
/// runtime composition: pass this as ShaderCompilerOptions::virtual_files.
const std::map<std::string, std::string>& include_files();

}  // namespace loom::shaders
