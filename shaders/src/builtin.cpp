#include "loom/shaders/builtin.hpp"

#include <mutex>

#include "loom/shader_compiler/shader_compiler.hpp"
#include "loom_shaders_embedded.hpp"

namespace loom::shaders {
namespace {

namespace embedded = loom::shaders::embedded;

/// Modules already rebuilt from their SPIR-V; builtin() may be called from several threads.
struct ModuleCache {
    std::mutex mutex;
    std::map<std::string, rhi::ShaderModule, std::less<>> modules;
};

ModuleCache& module_cache() {
    static ModuleCache cache;
    return cache;
}

std::string known_names() {
    std::string out;
    for (const auto& shader : embedded::embedded_shaders()) {
        if (!out.empty()) out += ", ";
        out += shader.name;
    }
    return out;
}

}  // namespace

loom::Result<rhi::ShaderModule> builtin(std::string_view name) {
    ModuleCache& cache = module_cache();
    std::lock_guard lock(cache.mutex);
    if (auto it = cache.modules.find(name); it != cache.modules.end()) return it->second;

    for (const auto& shader : embedded::embedded_shaders()) {
        if (shader.name != name) continue;
        auto module = shader_compiler::ShaderCompiler::from_spirv(std::string(name), shader.stage, shader.spirv);
        if (!module) return module.take_error();
        cache.modules.emplace(std::string(name), *module);
        return module;
    }
    return make_error(ErrorCode::InvalidArgument,
                      "unknown built-in shader \"" + std::string(name) + "\" (known: " + known_names() + ")");
}

std::vector<std::string> builtin_names() {
    std::vector<std::string> names;
    for (const auto& shader : embedded::embedded_shaders()) names.emplace_back(shader.name);
    return names;
}

const std::map<std::string, std::string>& include_files() {
    static const std::map<std::string, std::string> files = [] {
        std::map<std::string, std::string> out;
        for (const auto& text : embedded::embedded_texts()) out.emplace(text.name, text.text);
        return out;
    }();
    return files;
}

}  // namespace loom::shaders
