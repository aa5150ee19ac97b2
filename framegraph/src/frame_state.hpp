#pragma once
// The executor's state while it records one frame: what PassContext reads, and the command list
// passes record into. Internal to loom_framegraph.

#include <optional>
#include <string>
#include <vector>

#include "loom/framegraph/execution_schedule.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"

namespace loom::fg {

class FrameState;

/// Forwards to the frame's command list and catches the mistakes a pass can make that the
/// executor can name with the pass: what it leaves open (a render pass, debug groups: closed and
/// reported when the pass returns), null handles, draws outside and copies, dispatches and
/// transitions inside a render pass, and timers (they belong to the executor). Such a command
/// is reported and skipped. Everything else is checked by the backend (end_frame's error).
class PassCommandList final : public rhi::CommandList {
public:
    explicit PassCommandList(FrameState& frame) : frame_(frame) {}

    /// Starts recording for a pass into `inner`.
    void begin_pass(rhi::CommandList& inner);
    /// Closes whatever the pass left open; returns what was left open as an error, if anything.
    std::optional<std::string> end_pass();
    [[nodiscard]] bool in_render_pass() const { return in_render_pass_; }

    void begin_render_pass(const rhi::RenderPassDesc& desc) override;
    void end_render_pass() override;
    void set_pipeline(rhi::PipelineHandle pipeline) override;
    void set_viewport(const rhi::Viewport& viewport) override { inner_->set_viewport(viewport); }
    void set_scissor(const rhi::Rect& rect) override { inner_->set_scissor(rect); }
    void set_bind_group(uint32_t set, const rhi::BindGroup& group) override;
    void set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) override;
    void push_constants(std::span<const std::byte> data, uint32_t offset) override { inner_->push_constants(data, offset); }
    void set_vertex_buffer(uint32_t slot, rhi::BufferHandle buffer, uint64_t offset) override {
        inner_->set_vertex_buffer(slot, buffer, offset);
    }
    void set_index_buffer(rhi::BufferHandle buffer, rhi::IndexType type, uint64_t offset) override {
        inner_->set_index_buffer(buffer, type, offset);
    }
    rhi::BufferBinding transient_uniforms(std::span<const std::byte> data) override { return inner_->transient_uniforms(data); }
    void draw(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance) override {
        if (require_render_pass("draw", true)) inner_->draw(vertex_count, instance_count, first_vertex, first_instance);
    }
    void draw_indexed(uint32_t index_count, uint32_t instance_count, uint32_t first_index, int32_t base_vertex,
                      uint32_t first_instance) override {
        if (require_render_pass("draw_indexed", true)) {
            inner_->draw_indexed(index_count, instance_count, first_index, base_vertex, first_instance);
        }
    }
    void draw_indexed_indirect(rhi::BufferHandle buffer, uint64_t offset, uint32_t draw_count, uint32_t stride) override {
        if (require_render_pass("draw_indexed_indirect", true)) inner_->draw_indexed_indirect(buffer, offset, draw_count, stride);
    }
    void dispatch(uint32_t x, uint32_t y, uint32_t z) override {
        if (require_render_pass("dispatch", false)) inner_->dispatch(x, y, z);
    }
    void copy_buffer(rhi::BufferHandle src, uint64_t src_offset, rhi::BufferHandle dst, uint64_t dst_offset,
                     uint64_t size) override {
        if (require_render_pass("copy_buffer", false)) inner_->copy_buffer(src, src_offset, dst, dst_offset, size);
    }
    void copy_texture(const rhi::TextureCopy& copy) override {
        if (require_render_pass("copy_texture", false)) inner_->copy_texture(copy);
    }
    void transition(rhi::TextureHandle texture, rhi::ResourceState state) override;
    void transition(rhi::TextureHandle texture, rhi::ResourceState state, const rhi::TextureRange& range) override;
    void transition(rhi::BufferHandle buffer, rhi::ResourceState state) override {
        if (require_render_pass("transition", false)) inner_->transition(buffer, state);
    }
    void begin_timer(std::string_view label) override;
    void end_timer() override;
    void push_debug_group(std::string_view label) override;
    void pop_debug_group() override;
    // Queues belong to the executor (Pass::set_queue): a pass that switches or syncs them is
    // reported and the command skipped.
    void set_queue(rhi::QueueType queue) override;
    rhi::QueueSignal signal_queue() override;
    void wait_queue(rhi::QueueSignal signal) override;

private:
    /// True when the command may run: inside a render pass when `inside`, else outside one.
    bool require_render_pass(std::string_view command, bool inside);

    FrameState& frame_;
    rhi::CommandList* inner_ = nullptr;
    bool in_render_pass_ = false;
    uint32_t debug_depth_ = 0;
};

/// One frame being recorded.
class FrameState {
public:
    FrameState(rhi::Device& on_device, const Plan& of_plan, const ExecutionSchedule& with_schedule)
        : device(on_device), plan(of_plan), schedule(with_schedule), pass_commands(*this) {}

    /// The handle behind a slot this frame (null for None).
    [[nodiscard]] rhi::TextureHandle resolve(const TextureSlot& slot) const;
    /// The buffer behind a slot this frame (null for None).
    [[nodiscard]] rhi::BufferHandle resolve(const BufferSlot& slot) const;
    /// What the running pass records (PlanPass::kind).
    [[nodiscard]] PassKind pass_kind() const { return plan.order[position].kind; }
    /// The spec behind a slot (plan texture, import or history); nullptr for None.
    [[nodiscard]] const ResolvedSpec* spec_of(const PortSchedule& port) const;

    /// Records an error for the running pass, prefixed with its name; the first one is kept.
    void fail(Error error);

    rhi::Device& device;
    const Plan& plan;
    const ExecutionSchedule& schedule;
    PassCommandList pass_commands;
    uint64_t frame_index = 0;
    uint32_t position = 0;                          ///< the running pass
    std::vector<rhi::TextureHandle> plan_textures;  ///< per Plan::textures
    std::vector<rhi::TextureHandle> imports;        ///< per import binding
    std::vector<ResolvedSpec> import_specs;         ///< per import binding, from its description
    std::vector<rhi::BufferHandle> plan_buffers;    ///< per Plan::buffers
    std::vector<rhi::BufferHandle> buffer_imports;  ///< per buffer import binding
    std::vector<uint64_t> buffer_import_sizes;      ///< per buffer import binding
    std::vector<rhi::TextureHandle> history_read;   ///< per history: what readers read this frame
    std::vector<bool> history_valid;                ///< per history: holds an earlier frame
    std::optional<Error> pass_error;                ///< first error of the running pass
};

}  // namespace loom::fg
