#include "loom/passes/composer.hpp"

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
    return "pass '" + composition.pass + "', object kind '" +
           (composition.object ? composition.object->name() : std::string("none")) + "', " +
           std::string(rhi::shader_stage_name(stage)) + " stage";
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

Result<rhi::ShaderSource> compose_stage(const Composition& composition, rhi::ShaderStage stage) {
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

    rhi::ShaderSource source;
    source.name = composition.pass + "/" + (composition.object ? composition.object->name() : std::string("own")) + "." +
                  std::string(stage_suffix(stage));
    source.stage = stage;
    source.code = std::move(code);
    return source;
}

ShaderLibrary::ShaderLibrary() {
    rhi::ShaderCompilerOptions options;
    options.virtual_files = shaders::include_files();
    compiler_ = std::make_unique<rhi::ShaderCompiler>(std::move(options));
}

ShaderLibrary::~ShaderLibrary() = default;

Result<rhi::ShaderModule> ShaderLibrary::compile(const rhi::ShaderSource& source, const std::string& context) {
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
