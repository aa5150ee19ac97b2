// GLSL 450 -> SPIR-V through glslang: process-wide initialisation, #include resolution,
// defines, and turning glslang's info log into "name:line: message" diagnostics.

#include "glslang_compile.hpp"

#include <filesystem>
#include <fstream>
#include <list>
#include <mutex>
#include <sstream>
#include <string_view>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

namespace loom::shader_compiler::detail {

// Everything this library makes is an rhi::ShaderModule and its reflection.
using namespace loom::rhi;
namespace {

/// glslang keeps global tables: InitializeProcess exactly once, FinalizeProcess at exit.
class GlslangProcess {
public:
    GlslangProcess() { glslang::InitializeProcess(); }
    ~GlslangProcess() { glslang::FinalizeProcess(); }
    GlslangProcess(const GlslangProcess&) = delete;
    GlslangProcess& operator=(const GlslangProcess&) = delete;
};

void ensure_glslang_initialized() {
    static const GlslangProcess process;  // C++11 guarantees thread-safe, once-only construction
    (void)process;
}

EShLanguage to_glslang_stage(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex: return EShLangVertex;
        case ShaderStage::Fragment: return EShLangFragment;
        case ShaderStage::Compute: return EShLangCompute;
    }
    return EShLangVertex;
}

std::optional<std::string> read_text_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return std::move(text).str();
}

/// Resolves `#include "x"`: the virtual files first, then the include directories, then the
/// directory of the including file. The resolved name becomes the file name in diagnostics.
class Includer final : public glslang::TShader::Includer {
public:
    explicit Includer(const ShaderCompilerOptions& options) : options_(options) {}

    IncludeResult* includeLocal(const char* requested, const char* includer, size_t /*depth*/) override {
        return resolve(requested, includer, /*relative=*/true);
    }

    IncludeResult* includeSystem(const char* requested, const char* includer, size_t /*depth*/) override {
        return resolve(requested, includer, /*relative=*/false);
    }

    void releaseInclude(IncludeResult* result) override {
        // Storage (texts_) lives as long as the includer, which outlives the parse.
        delete result;
    }

private:
    IncludeResult* resolve(const std::string& requested, const std::string& includer, bool relative) {
        if (auto it = options_.virtual_files.find(requested); it != options_.virtual_files.end()) {
            return make_result(requested, it->second);
        }
        for (const auto& dir : options_.include_dirs) {
            if (auto found = try_file(dir / requested)) return found;
        }
        if (relative) {
            const std::filesystem::path base = std::filesystem::path(includer).parent_path();
            if (auto found = try_file(base / requested)) return found;
        }
        // A failed include carries the explanation as its text; glslang reports it at the
        // #include line of the includer.
        std::string message = "cannot find include file \"" + requested + "\" included from " + includer;
        return make_result("", std::move(message));
    }

    IncludeResult* try_file(const std::filesystem::path& candidate) {
        auto text = read_text_file(candidate);
        if (!text) return nullptr;
        const std::filesystem::path resolved = candidate.lexically_normal();
        if (options_.on_include) options_.on_include(resolved);
        return make_result(resolved.generic_string(), std::move(*text));
    }

    IncludeResult* make_result(std::string name, std::string text) {
        const std::string& stored = texts_.emplace_back(std::move(text));
        return new IncludeResult(name, stored.data(), stored.size(), nullptr);
    }

    const ShaderCompilerOptions& options_;
    std::list<std::string> texts_;  // stable addresses for glslang
};

std::string_view trim(std::string_view text) {
    while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.remove_suffix(1);
    return text;
}

/// Turns glslang's info log ("ERROR: name:12: 'x' : undeclared identifier") into one
/// "name:12: message" line per diagnostic, dropping the summary lines.
std::string format_diagnostics(const std::string& log, const std::string& fallback_name) {
    std::string out;
    std::istringstream lines(log);
    std::string line;
    while (std::getline(lines, line)) {
        std::string_view text = trim(line);
        std::string prefix;
        if (text.starts_with("ERROR: ")) {
            text.remove_prefix(7);
        } else if (text.starts_with("WARNING: ")) {
            text.remove_prefix(9);
            prefix = "warning: ";
        } else {
            continue;  // blank lines, "N compilation errors", linker chatter
        }
        text = trim(text);
        if (text.empty() || text.find("compilation errors") != std::string_view::npos ||
            text.find("compilation terminated") != std::string_view::npos) {
            continue;
        }
        // "name:line: message" already; a diagnostic without a location gets the shader name.
        const bool located = text.find(':') != std::string_view::npos &&
                             text.find(": ") != std::string_view::npos &&
                             text.substr(0, text.find(": ")).find(':') != std::string_view::npos;
        if (!out.empty()) out += '\n';
        if (located) {
            const std::size_t colon = text.find(": ");
            out += std::string(text.substr(0, colon + 2)) + prefix + std::string(text.substr(colon + 2));
        } else {
            out += fallback_name + ": " + prefix + std::string(text);
        }
    }
    if (out.empty()) out = fallback_name + ": " + std::string(trim(log));
    return out;
}

/// Defines go in glslang's preamble: it is processed after the #version line and does not
/// count towards the source's line numbers, so errors keep the lines of the file as written.
std::string make_preamble(const ShaderSource& source) {
    std::string preamble = "#extension GL_GOOGLE_include_directive : require\n";
    for (const auto& [name, value] : source.defines) {
        preamble += "#define " + name + " " + value + "\n";
    }
    return preamble;
}

}  // namespace

Result<std::vector<uint32_t>> compile_glsl_to_spirv(const ShaderSource& source,
                                                    const ShaderCompilerOptions& options) {
    ensure_glslang_initialized();
    const EShLanguage stage = to_glslang_stage(source.stage);
    const std::string name = source.name.empty() ? std::string("<shader>") : source.name;

    glslang::TShader shader(stage);
    const char* code = source.code.c_str();
    const int length = static_cast<int>(source.code.size());
    const char* names = name.c_str();
    shader.setStringsWithLengthsAndNames(&code, &length, &names, 1);
    const std::string preamble = make_preamble(source);
    shader.setPreamble(preamble.c_str());
    shader.setEntryPoint("main");
    shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
    shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_2);
    // SPIR-V 1.5: accepted by Vulkan 1.2+ (lavapipe is 1.3) and parsed by Debian's SPIRV-Cross.
    shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_5);

    // Cascading errors: report every diagnostic, not only the first one.
    const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules | EShMsgCascadingErrors);
    Includer includer(options);
    // Default version 450 core when the source has no #version line.
    if (!shader.parse(GetDefaultResources(), 450, ECoreProfile, false, false, messages, includer)) {
        return make_error(ErrorCode::ShaderCompile, format_diagnostics(shader.getInfoLog(), name));
    }

    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) {
        return make_error(ErrorCode::ShaderCompile, format_diagnostics(program.getInfoLog(), name));
    }

    glslang::SpvOptions spv_options;
    spv_options.generateDebugInfo = options.debug_info;
    spv_options.disableOptimizer = true;  // keep every declared resource and name for reflection
    spv::SpvBuildLogger logger;
    std::vector<uint32_t> spirv;
    glslang::GlslangToSpv(*program.getIntermediate(stage), spirv, &logger, &spv_options);
    const std::string spv_messages = logger.getAllMessages();
    if (spirv.empty()) {
        return make_error(ErrorCode::ShaderCompile, name + ": SPIR-V generation failed: " + spv_messages);
    }
    return spirv;
}

Status check_gl_glsl(const std::string& name, ShaderStage stage, const std::string& code) {
    ensure_glslang_initialized();
    const EShLanguage lang = to_glslang_stage(stage);
    glslang::TShader shader(lang);
    const char* text = code.c_str();
    const int length = static_cast<int>(code.size());
    const char* names = name.c_str();
    shader.setStringsWithLengthsAndNames(&text, &length, &names, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientOpenGL, 450);
    shader.setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
    shader.setEnvTarget(glslang::EShTargetNone, glslang::EShTargetSpv_1_0);
    const auto messages = EShMsgDefault;
    if (!shader.parse(GetDefaultResources(), 450, ECoreProfile, false, true, messages)) {
        return make_error(ErrorCode::ShaderCompile,
                          "GL source of " + format_diagnostics(shader.getInfoLog(), name));
    }
    glslang::TProgram program;
    program.addShader(&shader);
    if (!program.link(messages)) {
        return make_error(ErrorCode::ShaderCompile,
                          "GL source of " + format_diagnostics(program.getInfoLog(), name));
    }
    return {};
}

}  // namespace loom::shader_compiler::detail
