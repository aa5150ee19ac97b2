#include "loom/passes/shader_part.hpp"

#include <algorithm>

#include "loom/shaders/builtin.hpp"

namespace loom::passes {

ShaderPart::ShaderPart(std::string name, uint32_t bindings) : name_(std::move(name)), bindings_(bindings) {}

ShaderPart& ShaderPart::stage(rhi::ShaderStage stage, std::string code, std::string origin) {
    auto same_stage = [stage](const StageCode& s) { return s.stage == stage; };
    if (auto it = std::find_if(stages_.begin(), stages_.end(), same_stage); it != stages_.end()) {
        it->code = std::move(code);
        it->origin = std::move(origin);
    } else {
        stages_.push_back(StageCode{stage, std::move(origin), std::move(code)});
    }
    return *this;
}

ShaderPart& ShaderPart::stage_file(rhi::ShaderStage stage, std::string_view file) {
    const auto& files = shaders::include_files();
    if (auto it = files.find(std::string(file)); it != files.end()) {
        return this->stage(stage, it->second, std::string(file));
    }
    return set_problem("its " + std::string(rhi::shader_stage_name(stage)) + " code file " + fg::quoted_name(file) +
                       " is not embedded (shaders::include_files())");
}

ShaderPart& ShaderPart::set_problem(std::string problem) {
    if (!problem_) problem_ = std::move(problem);
    return *this;
}

const StageCode* ShaderPart::code(rhi::ShaderStage stage) const {
    for (const StageCode& s : stages_) {
        if (s.stage == stage) return &s;
    }
    return nullptr;
}

std::string ShaderPart::define() const {
    std::string out = "LOOM_PART_";
    for (char c : name_) {
        if (c >= 'a' && c <= 'z') {
            out += static_cast<char>(c - 'a' + 'A');
        } else if ((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9')) {
            out += c;
        } else {
            out += '_';
        }
    }
    return out;
}

}  // namespace loom::passes
