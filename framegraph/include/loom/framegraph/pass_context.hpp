#pragma once
// What a pass sees while it executes: the device, the command list, the frame, and its ports
// resolved to real textures. The executor (executor.hpp) makes one per pass per frame.
//
//   Status execute(PassContext& ctx) override {
//       ctx.begin_render_pass({{"color", {0, 0, 0, 1}}, "normal"}, "depth");  // the plan's load/store
//       auto& cmd = ctx.commands();
//       cmd.set_pipeline(pipeline_);
//       cmd.set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("shadow_map"), sampler_));
//       cmd.draw(3);
//       ctx.end_render_pass();
//       return {};
//   }
//
// Inputs are already in ShaderRead (DepthRead for depth) and storage ports in Storage when
// execute() runs; attachments need nothing (begin_render_pass moves them). Timers belong to
// the executor (one per pass): a pass must not call begin_timer/end_timer.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "loom/framegraph/plan.hpp"
#include "loom/framegraph/resolved_spec.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

struct PassSchedule;
struct PortSchedule;
class FrameState;

/// A colour attachment by port name, with the clear value used when the plan clears it (the
/// port's first write in the frame).
struct ColorPort {
    std::string port;
    std::array<double, 4> clear{0.0, 0.0, 0.0, 0.0};
    /// The pass writes every texel: a first write need not clear (DontCare instead of Clear).
    bool writes_every_texel = false;
    /// The mip level and layer rendered to; by default the first of the port's range.
    std::optional<uint32_t> mip;
    std::optional<uint32_t> layer;

    ColorPort(const char* name) : port(name) {}                // NOLINT(implicit): {"albedo", ...}
    ColorPort(std::string name) : port(std::move(name)) {}     // NOLINT(implicit)
    ColorPort(std::string_view name) : port(name) {}           // NOLINT(implicit)
    ColorPort(std::string name, std::array<double, 4> clear_value) : port(std::move(name)), clear(clear_value) {}
};

/// A depth/stencil attachment by port name, with the values used when the plan clears it.
struct DepthPort {
    std::string port;
    float clear_depth = 1.0f;
    uint32_t clear_stencil = 0;
    bool writes_every_texel = false;  ///< see ColorPort
    std::optional<uint32_t> mip;      ///< see ColorPort
    std::optional<uint32_t> layer;

    DepthPort(const char* name) : port(name) {}             // NOLINT(implicit)
    DepthPort(std::string name) : port(std::move(name)) {}  // NOLINT(implicit)
    DepthPort(std::string_view name) : port(name) {}        // NOLINT(implicit)
    DepthPort(std::string name, float depth, uint32_t stencil = 0)
        : port(std::move(name)), clear_depth(depth), clear_stencil(stencil) {}
};

/// The execution-time view of one pass. Errors a pass makes through it (an unknown port, a port
/// without a texture used as attachment) are recorded, name the pass and the port, and fail
/// the frame; the call then does nothing (or returns a null handle).
class PassContext {
public:
    PassContext(FrameState& frame, uint32_t position);
    PassContext(const PassContext&) = delete;
    PassContext& operator=(const PassContext&) = delete;

    /// The device the frame runs on.
    [[nodiscard]] rhi::Device& device() const;
    /// Where the pass records. Inside the executor it forwards to the frame's command list and
    /// checks that the pass leaves it balanced (render passes ended, debug groups popped).
    [[nodiscard]] rhi::CommandList& commands() const;
    /// The name of the pass.
    [[nodiscard]] const std::string& pass_name() const;
    /// Position of the pass in Plan::order.
    [[nodiscard]] uint32_t position() const { return position_; }
    /// The plan being executed.
    [[nodiscard]] const Plan& plan() const;
    /// This pass in the plan (its ports and their resources).
    [[nodiscard]] const PlanPass& plan_pass() const;
    /// Frames the executor has run before this one (0 for the first).
    [[nodiscard]] uint64_t frame_index() const;
    /// The frame size the plan was made for.
    [[nodiscard]] Extent2D frame_size() const;

    /// True when `port` is a port of this pass with a texture behind it.
    [[nodiscard]] bool has_texture(std::string_view port) const;
    /// The texture behind `port`: null for an unconnected optional port (no error); an unknown
    /// port name or a buffer port records an error and returns null.
    [[nodiscard]] rhi::TextureHandle texture(std::string_view port);
    /// The resolved spec (format, extent, samples, mips, layers, usage) of `port`'s texture;
    /// nullptr when it has none.
    [[nodiscard]] const ResolvedSpec* spec(std::string_view port);
    /// Shorthand for spec(port)->extent; {0, 0} when the port has no texture.
    [[nodiscard]] Extent2D extent(std::string_view port);
    /// The mip levels and layers `port` uses, with concrete counts (bind it with
    /// rhi::BindGroup::texture(binding, texture, sampler, range) to sample only those).
    [[nodiscard]] rhi::TextureRange range(std::string_view port);
    /// The size of the first mip level of `port`'s range ({0, 0} without a texture).
    [[nodiscard]] Extent2D range_extent(std::string_view port);
    /// True when `port` is a buffer port of this pass with a buffer behind it.
    [[nodiscard]] bool has_buffer(std::string_view port) const;
    /// The buffer behind buffer port `port`: null for an unconnected optional port (no error);
    /// an unknown port or a texture port records an error and returns null.
    [[nodiscard]] rhi::BufferHandle buffer(std::string_view port);
    /// The size in bytes of the buffer behind `port` (the plan's, or an imported buffer's); 0
    /// when it has none.
    [[nodiscard]] uint64_t buffer_size(std::string_view port);

    /// For a history port: true once it holds a real earlier frame (false on the first frame
    /// and after the history was recreated, e.g. by a resize; it then reads zeros, depth 1).
    [[nodiscard]] bool history_valid(std::string_view port);

    /// The attachment for `port` with the plan's load and store actions.
    [[nodiscard]] rhi::ColorAttachment color_attachment(const ColorPort& port);
    /// The depth attachment for `port` with the plan's load and store actions.
    [[nodiscard]] rhi::DepthAttachment depth_attachment(const DepthPort& port);
    /// A render pass over named attachment ports (labelled with the pass name), for passes that
    /// want to adjust it before commands().begin_render_pass(desc).
    [[nodiscard]] rhi::RenderPassDesc render_pass(std::span<const ColorPort> colors,
                                                  const std::optional<DepthPort>& depth = std::nullopt);
    /// Begins a render pass over named attachment ports with the plan's load/store actions.
    void begin_render_pass(std::span<const ColorPort> colors, const std::optional<DepthPort>& depth = std::nullopt);
    /// Begins a render pass over named attachment ports (see above).
    void begin_render_pass(std::initializer_list<ColorPort> colors, const std::optional<DepthPort>& depth = std::nullopt) {
        begin_render_pass(std::span<const ColorPort>(colors.begin(), colors.size()), depth);
    }
    /// A render pass with depth only (e.g. a shadow map).
    void begin_depth_pass(const DepthPort& depth) { begin_render_pass(std::span<const ColorPort>{}, depth); }
    /// Ends the render pass begun through this context.
    void end_render_pass();

    /// Records an error for this pass (it fails the frame; the message gets the pass name).
    void fail(Error error);
    /// The first error recorded for this pass, if any.
    [[nodiscard]] Status status() const;

private:
    const PortSchedule* find(std::string_view port, bool record_error);
    // find(port, true), and an error when the port is not of `type`.
    const PortSchedule* find_typed(std::string_view port, ResourceType type);

    FrameState& frame_;
    uint32_t position_;
};

}  // namespace loom::fg
