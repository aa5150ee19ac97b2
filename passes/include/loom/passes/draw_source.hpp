#pragma once
// Draw sources: what a ShaderPass draws besides the objects registered with it. A source keeps
// a draw list for each pass it serves (the retained scene, retained_scene.hpp, keeps a render
// queue) and records it when the pass asks. The pass knows its source only through this
// interface, so that the pass depends on no source; a source knows the pass (shader_pass.hpp).
//
//   source.attach(pass)     → pass.attach_draw_source(source)   (the source's own API)
//   pass.draw_objects(...)  → the registered objects, then source.draw(context)
//   ~ShaderPass()           → source.detach(pass)

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/handles.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {
class PassContext;
}

namespace loom::passes {

class ObjectKind;
class Program;
class ShaderPass;
struct PipelineState;

/// What a draw source gets when a pass asks it to draw: the pass, the pass's frame, and the
/// pass's pipelines, samplers and set 0, which the pass makes and keeps as it does for its own
/// objects. The pass's render pass is open.
class DrawSourceContext {
public:
    virtual ~DrawSourceContext() = default;

    /// The pass that draws; a source finds the pass's draw list by it.
    [[nodiscard]] virtual const ShaderPass& pass() const = 0;
    /// The frame the pass records: device, command list, resolved ports.
    [[nodiscard]] virtual fg::PassContext& pass_context() = 0;
    /// The pipeline state the pass draws with; a source may change the raster state per draw.
    [[nodiscard]] virtual const PipelineState& state() const = 0;
    /// The pass's pipeline for `program` with `state` and `kind`'s vertex buffers, made on first
    /// use.
    virtual Result<rhi::PipelineHandle> pipeline(const Program& program, const PipelineState& state,
                                                 const ObjectKind& kind) = 0;
    /// The pass's sampler with `desc`, made on first use.
    virtual Result<rhi::SamplerHandle> sampler(const rhi::SamplerDesc& desc) = 0;
    /// Binds the pass's own resources (set 0) for `program`. Call it after every pipeline change:
    /// the pass's set follows the pipeline's layout.
    virtual Status bind_pass_set(const Program& program) = 0;
};

/// Gives a pass the draw list it draws after its registered objects.
class DrawSource {
public:
    virtual ~DrawSource() = default;

    /// Records `context.pass()`'s draw list (ShaderPass::draw_objects calls it after the pass's
    /// registered objects). A pass the source does not serve draws nothing.
    virtual Status draw(DrawSourceContext& context) = 0;
    /// Forgets `pass` and calls pass.detach_draw_source(*this). A pass that is destroyed calls
    /// it.
    virtual void detach(ShaderPass& pass) = 0;
};

}  // namespace loom::passes
