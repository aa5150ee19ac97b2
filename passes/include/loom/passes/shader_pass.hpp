#pragma once
// Shader passes: frame-graph passes that carry shader parts and decide how objects are drawn —
// the pass side of the pass/object protocol (Hafner, ELS 2019, §4, Listing 1):
//
//   paper                        loom::passes
//   register-object-for-pass     register_object(pass, object)   → make_program, cached per kind
//   shader-program-for-pass      program_for(pass, object)
//   make-pass-shader-program     ShaderPass::make_program(kind)   → coerce_shader per stage
//   coerce-pass-shader           ShaderPass::coerce_shader(kind, stage)
//   render-with                  render_with(pass, context, object) → object.render() by default
//   render                       Object::render(context)
//
// A ShaderPass is an fg::Pass: its ports come from the PassParts it adds (the union of their
// ports), and the executor runs its execute() with the ports resolved to textures. Passes that
// draw objects keep the objects registered with them and draw them every frame
// (draw_objects()); post-process passes draw no objects and use their own program
// (own_program()), composed from their parts alone.
//
//   auto gbuffer = std::make_unique<GeometryPass>(config);
//   register_object(*gbuffer, cube);     // composes and compiles "geometry/pbr-mesh" once
//   register_object(*gbuffer, sphere);   // same kind: same program
//   graph.add_pass(std::move(gbuffer));

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/pass_context.hpp"
#include "loom/passes/composer.hpp"
#include "loom/passes/draw_source.hpp"
#include "loom/passes/object.hpp"
#include "loom/passes/program.hpp"
#include "loom/passes/shader_part.hpp"
#include "loom/passes/uniform_set.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::passes {

/// The fixed-function state of a pipeline a pass builds for one of its programs.
struct PipelineState {
    std::vector<rhi::Format> color_formats;
    rhi::Format depth_format = rhi::Format::Undefined;
    rhi::DepthState depth{};
    rhi::RasterState raster{};
    std::vector<rhi::BlendState> blend;
};

/// Field-by-field equality (the rhi descriptions have no operator==).
bool operator==(const PipelineState& a, const PipelineState& b);

/// Builds the bind group of one descriptor set of a program by resource name, checking each
/// name against the program's reflection (and uniform block sizes against the C++ struct).
/// The first error is kept and returned by status().
class Bindings {
public:
    Bindings(const Program& program, rhi::CommandList& commands, uint32_t set);

    /// Copies `value` into per-frame uniform memory and binds it to the block `block`.
    template <class T>
    Bindings& uniforms(std::string_view block, const T& value) {
        return uniform_bytes(block, std::as_bytes(std::span<const T, 1>(&value, 1)));
    }
    Bindings& uniform_bytes(std::string_view block, std::span<const std::byte> data);
    /// Binds a range of a buffer the caller keeps (a uniform set in its pool, a storage buffer
    /// of per-object records) to the uniform block or storage buffer `name`. A uniform block's
    /// declared size must equal the range's size (when the range has one).
    Bindings& buffer(std::string_view name, const rhi::BufferBinding& range);
    /// Binds a texture and sampler to the sampler variable `name`.
    Bindings& texture(std::string_view name, rhi::TextureHandle texture, rhi::SamplerHandle sampler);

    [[nodiscard]] const rhi::BindGroup& group() const { return group_; }
    [[nodiscard]] Status status() const;
    /// commands.set_bind_group(set, group()) unless an error was recorded or nothing was added;
    /// returns status().
    Status bind();

private:
    Result<ResourceSlot> find(std::string_view name);

    const Program& program_;
    rhi::CommandList& commands_;
    uint32_t set_;
    rhi::BindGroup group_;
    std::optional<Error> error_;
};

/// Settings every standard pass shares.
struct PassConfig {
    /// Compiles the passes' programs; share one between the passes of a renderer. Null: the
    /// pass makes its own.
    std::shared_ptr<ShaderLibrary> library;
    /// Format of every colour port (position, normal, albedo, colour, high-pass, bloom, final):
    /// one spec for all, so that the frame graph can share their textures.
    rhi::Format color_format = rhi::Format::RGBA16Float;
    /// Output ports also ask for CopySrc usage, so that set_capture() can copy them. Leave it
    /// the same on every backend: it is part of the plan.
    bool capturable = false;
};

/// The spec of the colour ports: config.color_format at the frame size (plus CopySrc when
/// capturable).
fg::TextureSpec color_spec(const PassConfig& config);

/// A texture a pass copied one of its outputs to (see ShaderPass::set_capture).
struct CapturedTexture {
    std::string port;
    rhi::TextureHandle texture;
};

class ShaderPass : public fg::Pass {
public:
    /// A pass with no parts yet; `library` compiles its programs (null: a library of its own).
    ShaderPass(std::string name, std::shared_ptr<ShaderLibrary> library = nullptr);
    /// Destroys the GPU objects the pass created (pipelines, shaders, samplers, captures): the
    /// device they were made on must outlive the pass (or call release_gpu() first).
    ~ShaderPass() override;
    ShaderPass(const ShaderPass&) = delete;
    ShaderPass& operator=(const ShaderPass&) = delete;
    ShaderPass(ShaderPass&&) = delete;
    ShaderPass& operator=(ShaderPass&&) = delete;

    using fg::Pass::add;
    /// Adds a part: its ports (merged as fg::Pass::add does) and its shader code.
    ShaderPass& add(const PassPart& part);
    /// Adds shader code that declares no ports (e.g. the full-screen vertex stage).
    ShaderPass& add_shader(ShaderPart part);
    /// Adds a define to every program of the pass.
    ShaderPass& define(std::string name, std::string value);
    /// The pass's shader parts in composition order.
    [[nodiscard]] const std::vector<ShaderPart>& shader_parts() const { return parts_; }
    [[nodiscard]] const std::shared_ptr<ShaderLibrary>& library() const { return library_; }

    // ---- the protocol ------------------------------------------------------------------------

    /// Prepares the program for `object`'s kind (composing and compiling it the first time the
    /// kind is seen) and adds the object to those the pass draws. Errors: the composition or
    /// compile error (naming pass, kind, stage and line), a different kind under a name already
    /// registered.
    virtual Status register_object(std::shared_ptr<const Object> object);
    /// The program used for `object`; nullptr when its kind was never registered.
    [[nodiscard]] const Program* program_for(const Object& object) const;
    /// The program for objects of `kind`, composed and compiled the first time the kind is seen
    /// (register_object's first half; a draw source calls it for the kinds it draws).
    /// Errors: as register_object.
    Result<const Program*> prepare_kind(const std::shared_ptr<const ObjectKind>& kind);
    /// The program prepared for `kind`; nullptr when its kind was never prepared.
    [[nodiscard]] const Program* program_for_kind(const ObjectKind& kind) const;
    /// Composes and compiles the program for `kind` (null: the pass's own program).
    virtual Result<std::shared_ptr<const Program>> make_program(const ObjectKind* kind);
    /// The composed source of one stage for `kind` (null: the pass's own).
    [[nodiscard]] virtual Result<shader_compiler::ShaderSource> coerce_shader(const ObjectKind* kind, rhi::ShaderStage stage) const;
    /// Draws one object; by default calls object.render(context). A pass overrides it to take
    /// control of how objects are drawn.
    virtual Status render_with(DrawContext& context, const Object& object);

    /// Objects registered, in registration order.
    [[nodiscard]] const std::vector<std::shared_ptr<const Object>>& objects() const { return objects_; }
    /// Drops every registered object (programs stay cached).
    void clear_objects() { objects_.clear(); }
    /// Programs composed so far, one per object kind (plus the pass's own, once made).
    [[nodiscard]] std::size_t program_count() const { return programs_.size(); }
    /// The draw source whose draw list this pass draws after its registered objects
    /// (draw_objects()), or null.
    [[nodiscard]] DrawSource* draw_source() const { return draw_source_; }
    /// Makes draw_objects() end with `source`'s draw list for this pass. A source calls it when
    /// it takes the pass on; a pass that is destroyed calls source.detach(*this). InvalidState,
    /// naming the pass, when another source is attached.
    Status attach_draw_source(DrawSource& source);
    /// Forgets `source` when it is this pass's (a source calls it from its detach()).
    void detach_draw_source(const DrawSource& source);
    /// The pass's own program (no object), composed on first use.
    Result<const Program*> own_program();

    // ---- capture -------------------------------------------------------------------------------

    /// When on, execute() ends by copying every output port's texture into a texture the pass
    /// owns (created at the port's format and size), readable after the frame with captured().
    /// The outputs are then moved back into their attachment state, as the pass left them. The
    /// ports need CopySrc usage (PassConfig::capturable).
    void set_capture(bool capture) { capture_ = capture; }
    [[nodiscard]] bool capture() const { return capture_; }
    /// The copies of the latest captured frame, in port order.
    [[nodiscard]] std::vector<CapturedTexture> captured() const;

    /// Destroys the GPU objects (they are made again on the next execute(), e.g. on another device).
    /// Passes that keep helper programs release theirs too.
    virtual void release_gpu();
    /// Bytes uploaded for the pass's own uniform sets (pass_uniforms) since the pass was made.
    [[nodiscard]] uint64_t pass_uniform_bytes() const { return pass_uniform_stats_.bytes; }

protected:
    /// Whether the object's parts are composed into `stage` (default: yes, in every stage).
    [[nodiscard]] virtual bool uses_object_parts(rhi::ShaderStage stage) const;

    /// The pipeline of `program` with `state` (and `kind`'s vertex buffers), made on first use.
    Result<rhi::PipelineHandle> pipeline(rhi::Device& device, const Program& program, const PipelineState& state,
                                         const ObjectKind* kind);
    /// A sampler with `desc`, made on first use.
    Result<rhi::SamplerHandle> sampler(rhi::Device& device, const rhi::SamplerDesc& desc);
    /// A nearest-filtering, edge-clamping sampler (for texelFetch inputs).
    Result<rhi::SamplerHandle> nearest_sampler(rhi::Device& device);

    /// Draws every registered object inside the current render pass: grouped by program, each
    /// group with its pipeline (`state` with the object's raster state) and `bind_pass` called to
    /// bind the pass's resources (set 0) for the program; then render_with() per object. Then,
    /// when the pass has a draw source, the source's draw list for this pass (DrawSource::draw).
    using PassBinder = std::function<Status(Bindings& pass_set)>;
    Status draw_objects(fg::PassContext& context, const PipelineState& state, const PassBinder& bind_pass);

    /// Draws a full-screen triangle with the pass's own program; `bind_pass` binds set 0.
    Status draw_fullscreen(fg::PassContext& context, const PipelineState& state, const PassBinder& bind_pass);

    /// Formats of the colour ports `ports` and of `depth` (may be empty) as the plan resolved them.
    static Result<PipelineState> attachment_state(fg::PassContext& context, std::span<const std::string> colors,
                                                  std::string_view depth = {});

    /// Copies the outputs when capture() is on (standard passes call it at the end of execute()).
    Status record_capture(fg::PassContext& context);

    /// Binds the pass's uniform block `block` from a buffer the pass keeps (a per-pass uniform
    /// set), writing `bytes` into it only when they differ from the bytes it holds: a camera
    /// that did not move costs no upload. Call it from a PassBinder (the pass's device is known
    /// there).
    Status bind_pass_uniforms(Bindings& set, std::string_view block, std::span<const std::byte> bytes);
    template <class T>
    Status pass_uniforms(Bindings& set, std::string_view block, const T& value) {
        return bind_pass_uniforms(set, block, std::as_bytes(std::span<const T, 1>(&value, 1)));
    }

private:
    Status use_device(rhi::Device& device);
    Result<std::pair<rhi::ShaderHandle, rhi::ShaderHandle>> shaders_of(const Program& program);

    struct PipelineEntry {
        const Program* program = nullptr;
        PipelineState state;
        std::string kind;
        rhi::PipelineHandle handle;
    };
    struct SamplerEntry {
        rhi::SamplerDesc desc;
        rhi::SamplerHandle handle;
    };
    struct CaptureEntry {
        std::string port;
        rhi::TextureDesc desc;
        rhi::TextureHandle texture;
    };

    std::shared_ptr<ShaderLibrary> library_;
    std::vector<ShaderPart> parts_;
    std::vector<std::pair<std::string, std::string>> defines_;
    /// Programs by object kind name ("" for the pass's own), with the kind they were made for.
    std::map<std::string, std::pair<std::shared_ptr<const ObjectKind>, std::shared_ptr<const Program>>, std::less<>> programs_;
    std::vector<std::shared_ptr<const Object>> objects_;

    rhi::Device* device_ = nullptr;
    std::map<const Program*, std::pair<rhi::ShaderHandle, rhi::ShaderHandle>> shaders_;
    std::vector<PipelineEntry> pipelines_;
    std::vector<SamplerEntry> samplers_;
    std::vector<CaptureEntry> captures_;
    bool capture_ = false;
    /// The pass's own uniform sets (bind_pass_uniforms), one pool of one slot per block.
    std::map<std::string, std::unique_ptr<UniformSetPool>, std::less<>> pass_sets_;
    UploadStats pass_uniform_stats_;
    DrawSource* draw_source_ = nullptr;
};

// The protocol as free functions, as the paper names it.

/// register-object-for-pass: see ShaderPass::register_object.
inline Status register_object(ShaderPass& pass, std::shared_ptr<const Object> object) {
    return pass.register_object(std::move(object));
}
/// shader-program-for-pass: see ShaderPass::program_for.
inline const Program* program_for(const ShaderPass& pass, const Object& object) { return pass.program_for(object); }
/// render-with: see ShaderPass::render_with.
inline Status render_with(ShaderPass& pass, DrawContext& context, const Object& object) {
    return pass.render_with(context, object);
}

}  // namespace loom::passes
