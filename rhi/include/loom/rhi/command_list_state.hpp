#pragma once
// The recording state of a command list, one implementation for every backend: whether a frame
// is being recorded, the open render pass, the bound pipeline, bind groups, push constants,
// vertex and index buffers, the open timer and the debug-group depth. Every command asks it
// first; it answers with the same ErrorCode and message on every backend (InvalidState for a
// command at the wrong time), and a backend only translates what it accepts to its API. The
// rules that need no state (descriptions, ranges, bindings against the pipeline) are
// rhi::validation's; this class calls them where a command's check needs both.
// tests/render/misuse_table_test.cpp breaks each rule on both backends;
// tests/rhi/command_list_state_test.cpp checks them without a device.
//
// Methods named after a command (set_pipeline, end_render_pass, begin_timer, ...) check it and,
// when it is accepted, record its effect. Where the backend can still fail after the check
// (beginning a frame or a render pass), check_* only checks, and the backend records the effect
// once it has succeeded (begin_frame, render_pass_begun). Resource states (of textures and
// buffers) are not kept here: each backend tracks them at its own granularity.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/binding_reuse.hpp"
#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/format.hpp"
#include "loom/rhi/handles.hpp"
#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::rhi {

/// What the state checks need of a pipeline the device holds (views into it: valid while it lives).
struct PipelineFacts {
    std::string_view name;
    bool compute = false;
    /// Graphics pipelines: the attachments they render to, which the render pass must have.
    std::span<const Format> color_formats;
    Format depth_format = Format::Undefined;
    uint32_t samples = 1;
    /// The vertex buffer slots the pipeline reads: 0 .. vertex_buffers - 1.
    uint32_t vertex_buffers = 0;
};
/// The facts of a pipeline by handle; an InvalidHandle error (HandlePool's message) for a null,
/// stale or foreign handle.
using PipelineLookup = std::function<Result<PipelineFacts>(PipelineHandle)>;

class CommandListState {
public:
    struct RenderPass {
        std::string label;
        validation::RenderPassShape shape;
    };
    struct VertexBuffer {
        BufferHandle buffer;
        uint64_t offset = 0;
    };
    struct IndexBuffer {
        BufferHandle buffer;
        IndexType type = IndexType::Uint32;
        uint64_t offset = 0;
        /// Indices from `offset` that fit in the buffer as it was when bound (check_index_range).
        uint64_t index_capacity = 0;
        static uint64_t capacity(uint64_t buffer_size, IndexType type, uint64_t offset) {
            return offset <= buffer_size ? (buffer_size - offset) / validation::index_bytes(type) : 0;
        }
    };

    /// Pipelines and buffers are looked up on the device whose commands are recorded.
    CommandListState(PipelineLookup pipelines, validation::BufferLookup buffers);

    /// Whether the checks of commands against the resources they use run (DeviceDesc::validation,
    /// in a build with validation::kCompiled): set_pipeline's pipeline against the pass,
    /// set_bind_group's group, the vertex and index buffers and index ranges, and check_draw's
    /// and check_dispatch's lookups. Off, those are accepted unchecked; the order of commands
    /// (frames, passes, timers, debug groups, queues) and the bounds of this class's own slots
    /// are checked either way. Backends ask it before their own per-draw checks.
    [[nodiscard]] bool validating() const { return validation::kCompiled && validate_; }
    void set_validation(bool on) { validate_ = on; }

    // ---- frames --------------------------------------------------------------------------------
    [[nodiscard]] bool recording() const { return recording_; }
    /// Device::begin_frame (or `command`, which begins a frame another way): no frame is being recorded.
    [[nodiscard]] Status check_begin_frame(std::string_view command = "begin_frame") const;
    /// A frame begins: nothing open, nothing bound.
    void begin_frame();
    /// `command` (end_frame, transient_uniforms) needs a frame being recorded.
    /// Inline: transient_uniforms and set_uniforms ask it per draw; the message is built only
    /// when no frame is being recorded.
    [[nodiscard]] Status check_recording(std::string_view command) const {
        if (recording_) [[likely]] return {};
        return not_recording(command);
    }
    /// end_frame: the first of a render pass, a timer and debug groups left open (the backend
    /// reports it as the frame's error and closes them all).
    [[nodiscard]] Status check_nothing_open() const;
    /// The frame has ended.
    void end_frame();

    // ---- render passes ---------------------------------------------------------------------------
    /// The open render pass, or null.
    [[nodiscard]] const RenderPass* render_pass() const { return pass_ ? &*pass_ : nullptr; }
    /// begin_render_pass `label`: no render pass is open (render passes do not nest), and the
    /// commands go to the graphics queue.
    [[nodiscard]] Status check_begin_render_pass(std::string_view label) const;
    /// Render pass `label`, of `shape` (rhi::validation::render_pass), has begun.
    void render_pass_begun(std::string_view label, validation::RenderPassShape shape);
    /// end_render_pass: a render pass is open; closes it.
    Status end_render_pass();
    /// `command` goes outside render passes (dispatches, copies, transitions and readbacks);
    /// `command` may name its object too ("read_texture of texture 'x'").
    [[nodiscard]] Status check_outside_render_pass(std::string_view command) const;

    // ---- bound state ---------------------------------------------------------------------------
    /// set_pipeline: a live pipeline; a graphics one set inside a render pass renders to the
    /// pass's attachments. On an error nothing is bound, so that later draws are refused rather
    /// than drawn with the pipeline bound before.
    Status set_pipeline(PipelineHandle pipeline);
    /// The bound pipeline (null when none).
    [[nodiscard]] PipelineHandle pipeline() const { return pipeline_; }
    /// set_bind_group (rhi::validation::bind_group); keeps a copy of `group`.
    Status set_bind_group(uint32_t set, const BindGroup& group);
    /// set_buffer: `range` replaces the buffer at `binding` of the group bound to `set` (or
    /// joins it; a set with no group gets one). Inline: per-draw data comes this way, and most
    /// calls replace a buffer range the group already has.
    Status set_buffer(uint32_t set, uint32_t binding, const BufferBinding& range) {
        if (replace_buffer(set, binding, range)) [[likely]] return {};
        return set_buffer_slow(set, binding, range);
    }
    /// set_buffer's common case alone, without a Status: true when the group bound to `set`
    /// has a buffer at `binding` and `range` replaced it; false (nothing changed) otherwise,
    /// when set_buffer must be called.
    bool replace_buffer(uint32_t set, uint32_t binding, const BufferBinding& range) {
        if (set < kMaxBindGroups && groups_[set]) [[likely]] {
            if (BindingEntry* entry = bound_entry(&*groups_[set], binding)) {
                if (auto* buffer = std::get_if<BufferBinding>(&entry->resource)) [[likely]] {
                    *buffer = range;
                    return true;
                }
            }
        }
        return false;
    }
    /// The group bound to `set`, or null.
    [[nodiscard]] const BindGroup* bind_group(uint32_t set) const {
        return set < groups_.size() && groups_[set] ? &*groups_[set] : nullptr;
    }
    /// push_constants (rhi::validation::push_constants); keeps the bytes. Inline: it runs
    /// before most draws, and the check in range costs two comparisons.
    Status push_constants(std::span<const std::byte> data, uint32_t offset) {
        if (!checked::range_fits(offset, data.size(), kMaxPushConstantBytes)) {
            return validation::push_constants(offset, data.size());
        }
        std::memcpy(push_data_.data() + offset, data.data(), data.size());
        push_size_ = std::max(push_size_, offset + static_cast<uint32_t>(data.size()));
        return {};
    }
    /// All kMaxPushConstantBytes bytes of the push-constant block (zero where never written).
    [[nodiscard]] std::span<const std::byte> push_constant_data() const { return push_data_; }
    /// The bytes of the block written so far in this frame (the end of the highest write).
    [[nodiscard]] uint32_t push_constant_size() const { return push_size_; }
    /// set_vertex_buffer: a slot below kMaxVertexBuffers, a live buffer with Vertex usage, an
    /// offset inside it (rhi::validation::vertex_buffer_slot, vertex_buffer).
    Status set_vertex_buffer(uint32_t slot, BufferHandle buffer, uint64_t offset);
    /// set_vertex_buffer of a buffer the backend has looked up itself (`found`: its description,
    /// null when the handle is stale or foreign), so that it is not looked up twice. Inline, the
    /// message built only when a check fails.
    Status set_vertex_buffer(uint32_t slot, BufferHandle buffer, const BufferDesc* found, uint64_t offset) {
        if (found && replace_vertex_buffer(slot, buffer, *found, offset)) [[likely]] return {};
        if (slot < kMaxVertexBuffers && !validating()) {
            vertex_buffers_[slot] = {buffer, offset};
            return {};
        }
        return set_vertex_buffer(slot, buffer, offset);
    }
    /// set_vertex_buffer's common case alone, without a Status: true when the slot is valid and
    /// `found` (the live buffer's description) passes the checks, and the buffer is bound; false
    /// (nothing changed) otherwise, when set_vertex_buffer must be called.
    bool replace_vertex_buffer(uint32_t slot, BufferHandle buffer, const BufferDesc& found, uint64_t offset) {
        if (slot < kMaxVertexBuffers && (!validating() || validation::vertex_buffer_fits(found, offset))) [[likely]] {
            vertex_buffers_[slot] = {buffer, offset};
            return true;
        }
        return false;
    }
    /// The buffer bound to vertex buffer slot `slot` (< kMaxVertexBuffers); a null handle when none.
    [[nodiscard]] const VertexBuffer& vertex_buffer(uint32_t slot) const { return vertex_buffers_[slot]; }
    /// set_index_buffer: a live buffer with Index usage and an aligned offset inside it
    /// (rhi::validation::index_buffer).
    Status set_index_buffer(BufferHandle buffer, IndexType type, uint64_t offset);
    /// set_index_buffer of a buffer the backend has looked up itself (as set_vertex_buffer).
    Status set_index_buffer(BufferHandle buffer, const BufferDesc* found, IndexType type, uint64_t offset) {
        if (found && replace_index_buffer(buffer, *found, type, offset)) [[likely]] return {};
        if (!validating()) {
            index_buffer_ = {buffer, type, offset, found ? IndexBuffer::capacity(found->size, type, offset) : 0};
            return {};
        }
        return set_index_buffer(buffer, type, offset);
    }
    /// set_index_buffer's common case alone, as replace_vertex_buffer.
    bool replace_index_buffer(BufferHandle buffer, const BufferDesc& found, IndexType type, uint64_t offset) {
        if (!validating() || validation::index_buffer_fits(found, type, offset)) [[likely]] {
            index_buffer_ = {buffer, type, offset, IndexBuffer::capacity(found.size, type, offset)};
            return true;
        }
        return false;
    }
    /// The bound index buffer; a null handle when none.
    [[nodiscard]] const IndexBuffer& index_buffer() const { return index_buffer_; }

    // ---- draws and dispatches ------------------------------------------------------------------
    /// A draw (`command`: draw, draw_indexed, draw_indexed_indirect): inside a render pass, with
    /// a live graphics pipeline that renders to the pass's attachments, a live vertex buffer in
    /// every slot it reads and, when `indexed`, a live index buffer. Bind groups against the
    /// pipeline are the backend's to check next (rhi::validation::binding).
    [[nodiscard]] Status check_draw(std::string_view command, bool indexed) const;
    /// check_index_range with the buffer looked up: the message of a range that does not fit.
    [[nodiscard]] Status check_index_range_slow(uint32_t first_index, uint32_t index_count) const;
    /// draw_indexed (after check_draw): the indices lie inside the bound index buffer
    /// (rhi::validation::index_range). Per draw, so the buffer is not looked up again while the
    /// range fits the size it had when bound: the caller has checked the draw with check_draw
    /// since anything was last destroyed, which found that buffer alive.
    [[nodiscard]] Status check_index_range(uint32_t first_index, uint32_t index_count) const {
        if (index_range_fits(first_index, index_count)) [[likely]] return {};
        return check_index_range_slow(first_index, index_count);
    }
    /// check_index_range's answer alone, without a Status (false: call check_index_range).
    [[nodiscard]] bool index_range_fits(uint32_t first_index, uint32_t index_count) const {
        // validation::index_range_fits with the division done when the buffer was bound.
        return !validating() || uint64_t{first_index} + index_count <= index_buffer_.index_capacity;
    }
    /// dispatch: outside render passes, with a live compute pipeline.
    [[nodiscard]] Status check_dispatch() const;

    // ---- timers and debug groups ---------------------------------------------------------------
    /// begin_timer `label`: no timer is open (timers do not nest).
    Status begin_timer(std::string_view label);
    /// end_timer: a timer is open; closes it.
    Status end_timer();
    /// The label of the open timer, if one is open.
    [[nodiscard]] const std::optional<std::string>& open_timer() const { return open_timer_; }
    void push_debug_group() { ++debug_depth_; }
    /// pop_debug_group: a debug group is open; closes the innermost.
    Status pop_debug_group();
    /// Debug groups pushed and not popped in this frame.
    [[nodiscard]] uint32_t debug_group_depth() const { return debug_depth_; }

    // ---- queues --------------------------------------------------------------------------------
    /// The queue the commands now go to (each frame starts on Graphics).
    [[nodiscard]] QueueType queue() const { return queue_; }
    /// set_queue: outside render passes, no timer or debug group open; records the queue.
    Status set_queue(QueueType queue);
    /// signal_queue: outside render passes; the new signal of the current queue.
    Result<QueueSignal> signal_queue();
    /// wait_queue: outside render passes, a signal of this frame made on the other queue and
    /// not waited for before; records the wait.
    Status wait_queue(QueueSignal signal);
    /// Signals made in this frame.
    [[nodiscard]] uint32_t signal_count() const { return static_cast<uint32_t>(signal_waited_.size()); }

private:
    /// set_buffer where the set has no group yet, or no buffer range at `binding`.
    Status set_buffer_slow(uint32_t set, uint32_t binding, const BufferBinding& range);
    /// Forgets everything bound and open (frames begin and end with nothing).
    void reset();
    /// check_recording's error.
    [[nodiscard]] static Status not_recording(std::string_view command);
    /// A pipeline is set (all that is checked of it with validation off).
    [[nodiscard]] Status check_pipeline_set(std::string_view command) const;
    /// The bound pipeline's facts for `command`: set, alive and of the right kind.
    [[nodiscard]] Result<PipelineFacts> bound_pipeline(std::string_view command, bool compute) const;
    /// A graphics pipeline renders to the open pass's attachment formats and sample count.
    [[nodiscard]] Status check_pipeline_matches_pass(std::string_view command, const PipelineFacts& pipeline) const;

    PipelineLookup pipelines_;
    validation::BufferLookup buffers_;

    bool validate_ = true;
    bool recording_ = false;
    std::optional<RenderPass> pass_;
    PipelineHandle pipeline_;
    std::string pipeline_name_;  ///< to name the pipeline in errors once it has been destroyed
    std::array<std::optional<BindGroup>, kMaxBindGroups> groups_{};
    std::array<std::byte, kMaxPushConstantBytes> push_data_{};
    uint32_t push_size_ = 0;
    std::array<VertexBuffer, kMaxVertexBuffers> vertex_buffers_{};
    IndexBuffer index_buffer_;
    std::optional<std::string> open_timer_;
    uint32_t debug_depth_ = 0;
    QueueType queue_ = QueueType::Graphics;
    std::vector<QueueType> signal_queue_;  ///< per signal of the frame, its queue
    std::vector<bool> signal_waited_;      ///< per signal of the frame, whether a wait used it
};

}  // namespace loom::rhi
