#include "loom/passes/composer.hpp"

#include <algorithm>
#include <optional>
#include <string_view>

#include "loom/framegraph/pass.hpp"
#include "loom/shaders/builtin.hpp"

namespace loom::passes {
namespace {

std::string_view stage_suffix(rhi::ShaderStage stage) {
    switch (stage) {
        case rhi::ShaderStage::Vertex: return "vert";
        case rhi::ShaderStage::Fragment: return "frag";
        case rhi::ShaderStage::Compute: return "comp";
    }
    return "unknown";
}

std::string_view stage_define(rhi::ShaderStage stage) {
    switch (stage) {
        case rhi::ShaderStage::Vertex: return "LOOM_STAGE_VERTEX";
        case rhi::ShaderStage::Fragment: return "LOOM_STAGE_FRAGMENT";
        case rhi::ShaderStage::Compute: return "LOOM_STAGE_COMPUTE";
    }
    return "LOOM_STAGE_UNKNOWN";
}

std::string describe(const Composition& composition, rhi::ShaderStage stage) {
    return "pass " + fg::quoted_name(composition.pass) + ", object kind " +
           fg::quoted_name(composition.object ? composition.object->name() : std::string("none")) + ", " +
           std::string(rhi::shader_stage_name(stage)) + " stage";
}

// Why `text` cannot be a name written into the composed source, or nullopt. Names go into
// `#line 1 "<owner>, part <name> (<origin>)"` directives, so a newline would start a line of
// GLSL of the name's choosing (and a '"' or '\\' end or escape the directive's string) instead
// of being reported with the part's name.
std::optional<std::string> source_name_problem(std::string_view text) {
    if (text.empty()) return "is empty";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) return "contains a control character (code " + std::to_string(byte) + ")";
        if (c == '"' || c == '\\') return std::string("contains '") + c + "', which would end the #line name";
    }
    return std::nullopt;
}

// A #define's name: a GLSL identifier.
bool is_identifier(std::string_view name) {
    if (name.empty() || (name.front() >= '0' && name.front() <= '9')) return false;
    return std::all_of(name.begin(), name.end(), [](char c) {
        return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
    });
}

// Every name and #define of the composition that goes into the source (see
// source_name_problem), and every part's problem (ShaderPart::problem), checked before any of
// it is written.
Status check_parts_and_names(const Composition& composition, rhi::ShaderStage stage) {
    auto bad = [&](const std::string& what, std::string_view text, const std::string& problem) {
        return make_error(ErrorCode::InvalidArgument,
                          describe(composition, stage) + ": " + what + " " + fg::quoted_name(text) + " " + problem);
    };
    if (auto problem = source_name_problem(composition.pass)) return bad("the pass name", composition.pass, *problem);
    auto check_part = [&](const ShaderPart& part) -> Status {
        if (part.problem()) {
            return make_error(ErrorCode::InvalidArgument,
                              describe(composition, stage) + ": part " + fg::quoted_name(part.name()) + ": " +
                                  *part.problem());
        }
        if (auto problem = source_name_problem(part.name())) return bad("the part name", part.name(), *problem);
        for (const StageCode& code : part.stages()) {
            if (auto problem = source_name_problem(code.origin)) {
                return bad("part '" + part.name() + "': the code origin", code.origin, *problem);
            }
        }
        return {};
    };
    if (composition.object) {
        const std::string& kind = composition.object->name();
        if (auto problem = source_name_problem(kind)) return bad("the object kind name", kind, *problem);
        for (const ShaderPart& part : composition.object->parts()) LOOM_TRY(check_part(part));
    }
    for (const ShaderPart* part : composition.pass_parts) LOOM_TRY(check_part(*part));
    for (const auto& [name, value] : composition.defines) {
        if (!is_identifier(name)) return bad("the define", name, "is not a GLSL identifier");
        for (const char c : value) {
            const auto byte = static_cast<unsigned char>(c);
            if (byte < 0x20 || byte == 0x7f) {
                return bad("the value of define " + name + ",", value,
                           "contains a control character (code " + std::to_string(byte) + ")");
            }
        }
    }
    return {};
}

/// Appends one part's code with its set, its first binding and a #line naming it.
void append_part(std::string& out, const std::string& owner, const ShaderPart& part, const StageCode& code,
                 uint32_t set, uint32_t first_binding) {
    out += "#define LOOM_SET " + std::to_string(set) + "\n";
    out += "#define LOOM_BINDING(k) (" + std::to_string(first_binding) + " + (k))\n";
    out += "#line 1 \"" + owner + ", part " + part.name() + " (" + code.origin + ")\"\n";
    out += code.code;
    if (!code.code.empty() && code.code.back() != '\n') out += '\n';
    out += "#undef LOOM_BINDING\n#undef LOOM_SET\n";
}

}  // namespace

Result<shader_compiler::ShaderSource> compose_stage(const Composition& composition, rhi::ShaderStage stage) {
    LOOM_TRY(check_parts_and_names(composition, stage));
    const bool with_object = composition.object != nullptr && composition.use_object_parts;

    // Resources are numbered over the parts in order, whether or not a part has code in this
    // stage, so that every stage agrees on them.
    uint32_t object_bindings = 0;
    if (composition.object) {
        for (const ShaderPart& part : composition.object->parts()) object_bindings += part.bindings();
    }
    uint32_t pass_bindings = 0;
    for (const ShaderPart* part : composition.pass_parts) pass_bindings += part->bindings();
    if (object_bindings > rhi::kMaxBindingsPerGroup || pass_bindings > rhi::kMaxBindingsPerGroup) {
        return make_error(ErrorCode::InvalidArgument,
                          describe(composition, stage) + ": the parts declare " +
                              std::to_string(std::max(object_bindings, pass_bindings)) +
                              " resources in one set; at most " + std::to_string(rhi::kMaxBindingsPerGroup) +
                              " fit");
    }

    std::string code = "#version 450\n";
    code += "#define " + std::string(stage_define(stage)) + " 1\n";
    if (with_object) code += "#define LOOM_OBJECT 1\n";
    if (composition.object) {
        for (const ShaderPart& part : composition.object->parts()) code += "#define " + part.define() + " 1\n";
    }
    for (const ShaderPart* part : composition.pass_parts) code += "#define " + part->define() + " 1\n";
    for (const auto& [name, value] : composition.defines) code += "#define " + name + " " + value + "\n";
    code += "#include \"loom/passes/interface.glsl\"\n";

    bool any_code = false;
    if (with_object) {
        uint32_t binding = 0;
        const std::string owner = "object kind " + composition.object->name();
        for (const ShaderPart& part : composition.object->parts()) {
            if (const StageCode* stage_code = part.code(stage)) {
                append_part(code, owner, part, *stage_code, kObjectSet, binding);
                any_code = true;
            }
            binding += part.bindings();
        }
    }
    bool pass_code = false;
    uint32_t binding = 0;
    const std::string owner = "pass " + composition.pass;
    for (const ShaderPart* part : composition.pass_parts) {
        if (const StageCode* stage_code = part->code(stage)) {
            append_part(code, owner, *part, *stage_code, kPassSet, binding);
            pass_code = true;
        }
        binding += part->bindings();
    }
    if (!pass_code) {
        return make_error(ErrorCode::InvalidArgument,
                          describe(composition, stage) + ": no part of the pass has code for this stage" +
                              (any_code ? " (only the object's parts do)" : ""));
    }

    shader_compiler::ShaderSource source;
    source.name = composition.pass + "/" + (composition.object ? composition.object->name() : std::string("own")) + "." +
                  std::string(stage_suffix(stage));
    source.stage = stage;
    source.code = std::move(code);
    return source;
}

ShaderLibrary::ShaderLibrary() {
    shader_compiler::ShaderCompilerOptions options;
    options.virtual_files = shaders::include_files();
    compiler_ = std::make_unique<shader_compiler::ShaderCompiler>(std::move(options));
}

ShaderLibrary::~ShaderLibrary() = default;

Result<rhi::ShaderModule> ShaderLibrary::compile(const shader_compiler::ShaderSource& source, const std::string& context) {
    ++requests_;
    const std::size_t before = compiler_->cache_size();
    auto module = compiler_->compile_cached(source);
    // Failed sources are not cached, so they are compiled (and fail) on every request.
    if (!module || compiler_->cache_size() != before) ++compilations_;
    if (!module) {
        Error error = module.take_error();
        if (error.code == ErrorCode::ShaderCompile) {
            error.message = context + ":\n" + error.message;
        } else {
            error.message = context + ": " + error.message;
        }
        return error;
    }
    return module;
}

}  // namespace loom::passes
