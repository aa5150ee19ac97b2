#pragma once
// Composing a stage from parts (the paper's `coerce-pass-shader`) and compiling it.
//
// The composed source of a stage is, in order: `#version 450`, LOOM_STAGE_<STAGE>, LOOM_OBJECT
// when the object's parts take part, one LOOM_PART_<NAME> per part (of the object and the pass),
// the pass's extra defines, the interface include (loom/passes/interface.glsl), then every part
// that has code for the stage — the object's parts first (set 1), then the pass's (set 0) —
// each preceded by its LOOM_SET / LOOM_BINDING(k) and a `#line 1 "<pass or kind>, part <name>
// (<origin>)"` directive, so that a compiler message names the part and the line in it.

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "loom/passes/object.hpp"
#include "loom/passes/shader_part.hpp"
#include "loom/rhi/result.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::passes {

/// Everything one composed stage is made of.
struct Composition {
    std::string pass;                        ///< the pass's name
    std::vector<const ShaderPart*> pass_parts;
    const ObjectKind* object = nullptr;      ///< null: the pass's own program
    /// False leaves the object's parts out of this stage (a pass that ignores the material).
    bool use_object_parts = true;
    std::vector<std::pair<std::string, std::string>> defines;
};

/// The composed source of `stage`, named "<pass>/<kind>.<vert|frag>". Errors (InvalidArgument):
/// a stage no part has code for, more resources in a set than rhi::kMaxBindingsPerGroup, a
/// pass, kind or part name or a code origin that is empty or holds a control character, '"' or
/// '\\' (they are written into #line directives), a define whose name is not a GLSL identifier
/// or whose value holds a control character; each names the pass, the kind and the stage.
Result<shader_compiler::ShaderSource> compose_stage(const Composition& composition, rhi::ShaderStage stage);

/// Compiles composed sources: one shader_compiler::ShaderCompiler with loom's shader snippets
/// (shaders::include_files()) as virtual files and its cache (compile_cached), shared by the
/// passes of a renderer so that equal sources compile once.
class ShaderLibrary {
public:
    ShaderLibrary();
    ~ShaderLibrary();
    ShaderLibrary(const ShaderLibrary&) = delete;
    ShaderLibrary& operator=(const ShaderLibrary&) = delete;

    /// Compiles (or finds in the cache) a composed stage. A ShaderCompile error is prefixed with
    /// `context` (e.g. "pass 'deferred', object kind 'none', fragment stage").
    Result<rhi::ShaderModule> compile(const shader_compiler::ShaderSource& source, const std::string& context);

    /// Sources compiled so far (cache misses).
    [[nodiscard]] uint64_t compilations() const { return compilations_; }
    /// compile() calls so far (hits and misses).
    [[nodiscard]] uint64_t requests() const { return requests_; }

private:
    std::unique_ptr<shader_compiler::ShaderCompiler> compiler_;
    uint64_t compilations_ = 0;
    uint64_t requests_ = 0;
};

}  // namespace loom::passes
