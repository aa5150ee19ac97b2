#pragma once
// Shader parts and pass parts. A ShaderPart is shader code: a named piece of GLSL per stage that
// programs are composed from; passes and object kinds each carry them. A PassPart is a
// ShaderPart and the frame-graph ports that go with it (an fg::PortSet) under one name, so that
// a pass composed from pass parts gets the union of their ports and the concatenation of their
// code (the paper's deferred pass, built from Listings 3-5 by inheritance).
//
// Conventions every part follows (shaders/include/loom/passes/interface.glsl): resources are
// declared with `layout(set = LOOM_SET, binding = LOOM_BINDING(k))`, k counting the part's own
// resources from 0; the composer numbers parts one after another. Pass parts live in set 0,
// object parts in set 1.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::passes {

/// Descriptor set of the resources of pass parts and of object parts.
inline constexpr uint32_t kPassSet = 0;
inline constexpr uint32_t kObjectSet = 1;

/// The GLSL one part contributes to one stage.
struct StageCode {
    rhi::ShaderStage stage = rhi::ShaderStage::Vertex;
    /// Where the code comes from (an embedded file name such as "loom/parts/blit.frag.glsl",
    /// or "inline"); shown in the #line name of composed sources, so errors point at it.
    std::string origin;
    std::string code;

    friend bool operator==(const StageCode&, const StageCode&) = default;
};

/// Shader code: a named piece of GLSL for one or more stages, and the number of resources it
/// declares (the k of LOOM_BINDING(k) runs over 0..bindings-1, the same in every stage). No
/// ports: a pass's ports come with PassParts.
class ShaderPart {
public:
    explicit ShaderPart(std::string name, uint32_t bindings = 0);

    /// Adds (or replaces) the code of `stage`.
    ShaderPart& stage(rhi::ShaderStage stage, std::string code, std::string origin = "inline");
    /// Adds the code of `stage` from an embedded shader file (shaders::include_files(), e.g.
    /// "loom/parts/blit.frag.glsl"). A file that is not embedded is the part's problem (below),
    /// naming the file.
    ShaderPart& stage_file(rhi::ShaderStage stage, std::string_view file);
    /// Marks the part as one no program can be composed with (the first problem is kept):
    /// composing it fails with an InvalidArgument error naming the pass, the part and `problem`.
    /// For code that makes parts where it cannot return an error (pass constructors, object
    /// kinds).
    ShaderPart& set_problem(std::string problem);

    [[nodiscard]] const std::string& name() const { return name_; }
    [[nodiscard]] uint32_t bindings() const { return bindings_; }
    /// The code for `stage`, or nullptr when the part has none there.
    [[nodiscard]] const StageCode* code(rhi::ShaderStage stage) const;
    [[nodiscard]] const std::vector<StageCode>& stages() const { return stages_; }
    /// Why no program can be composed with the part, or nullopt.
    [[nodiscard]] const std::optional<std::string>& problem() const { return problem_; }
    /// The macro defined for every program this part takes part in: "LOOM_PART_" and the name
    /// in upper case with every other character than A-Z, 0-9 turned into '_'
    /// ("high-pass-render" -> LOOM_PART_HIGH_PASS_RENDER).
    [[nodiscard]] std::string define() const;

    friend bool operator==(const ShaderPart&, const ShaderPart&) = default;

private:
    std::string name_;
    uint32_t bindings_ = 0;
    std::vector<StageCode> stages_;
    std::optional<std::string> problem_;
};

/// Ports and shader code under one name: the port set a pass adds to its ports and the shader
/// part it adds to its code (ShaderPass::add). The paper's "deferred-render", "shadow-render" and
/// "high-pass-render" classes are PassParts.
struct PassPart {
    fg::PortSet ports;
    ShaderPart shader;

    PassPart(std::string name, uint32_t bindings = 0) : ports(name), shader(std::move(name), bindings) {}
    [[nodiscard]] const std::string& name() const { return shader.name(); }
};

}  // namespace loom::passes
