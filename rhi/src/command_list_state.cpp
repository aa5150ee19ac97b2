#include "loom/rhi/command_list_state.hpp"

#include <algorithm>
#include <utility>

#include "loom/rhi/binding_reuse.hpp"

namespace loom::rhi {

using validation::in_quotes;

namespace {

Error invalid_state(std::string message) { return Error{ErrorCode::InvalidState, std::move(message)}; }

// A lookup error of a bound object, said with the command that found it ("draw: index buffer: ...").
Error stale(std::string_view command, const std::string& what, const Error& found) {
    return Error{ErrorCode::InvalidHandle, std::string(command) + ": " + what + ": " + found.message};
}

// "[RGBA8Unorm, R32Float] depth Depth32F x4"
std::string attachments_text(std::span<const Format> colors, Format depth, uint32_t samples) {
    std::string out = "[";
    for (std::size_t i = 0; i < colors.size(); ++i) out += (i ? ", " : "") + std::string(format_name(colors[i]));
    return out + "] depth " + std::string(format_name(depth)) + " x" + std::to_string(samples);
}

}  // namespace

CommandListState::CommandListState(PipelineLookup pipelines, validation::BufferLookup buffers)
    : pipelines_(std::move(pipelines)), buffers_(std::move(buffers)) {}

void CommandListState::reset() {
    pass_.reset();
    pipeline_ = {};
    pipeline_name_.clear();
    groups_ = {};
    push_data_ = {};
    push_size_ = 0;
    vertex_buffers_ = {};
    index_buffer_ = {};
    open_timer_.reset();
    debug_depth_ = 0;
    queue_ = QueueType::Graphics;
    signal_queue_.clear();
    signal_waited_.clear();
}

// ---- frames ----------------------------------------------------------------------------------------

Status CommandListState::check_begin_frame(std::string_view command) const {
    if (!recording_) return {};
    return invalid_state(std::string(command) + ": the previous frame was not ended; call end_frame first");
}

void CommandListState::begin_frame() {
    reset();
    recording_ = true;
}

Status CommandListState::not_recording(std::string_view command) {
    return invalid_state(std::string(command) + ": no frame is being recorded; call begin_frame first");
}

Status CommandListState::check_nothing_open() const {
    if (pass_) return invalid_state("end_frame: render pass " + in_quotes(pass_->label) + " was not ended");
    if (open_timer_) return invalid_state("end_frame: timer " + in_quotes(*open_timer_) + " was not ended");
    if (debug_depth_ == 1) return invalid_state("end_frame: 1 debug group was not popped");
    if (debug_depth_ > 1) {
        return invalid_state("end_frame: " + std::to_string(debug_depth_) + " debug groups were not popped");
    }
    return {};
}

void CommandListState::end_frame() {
    reset();
    recording_ = false;
}

// ---- render passes ---------------------------------------------------------------------------------

Status CommandListState::check_begin_render_pass(std::string_view label) const {
    if (queue_ != QueueType::Graphics) {
        return invalid_state("begin_render_pass " + in_quotes(label) +
                             ": the commands go to the compute queue, which runs no render passes; "
                             "set_queue(QueueType::Graphics) first");
    }
    if (!pass_) return {};
    return invalid_state("begin_render_pass " + in_quotes(label) + ": render pass " + in_quotes(pass_->label) +
                         " is still open; render passes do not nest");
}

void CommandListState::render_pass_begun(std::string_view label, validation::RenderPassShape shape) {
    pass_ = RenderPass{std::string(label), std::move(shape)};
}

Status CommandListState::end_render_pass() {
    if (!pass_) return invalid_state("end_render_pass: no render pass is open");
    pass_.reset();
    return {};
}

Status CommandListState::check_outside_render_pass(std::string_view command) const {
    if (!pass_) return {};
    return invalid_state(std::string(command) + ": render pass " + in_quotes(pass_->label) +
                         " is open; dispatches, copies, transitions and readbacks go outside render passes");
}

// ---- queues ------------------------------------------------------------------------------------

Status CommandListState::set_queue(QueueType queue) {
    const std::string command = "set_queue(" + std::string(queue_type_name(queue)) + ")";
    LOOM_TRY(check_recording(command));
    LOOM_TRY(check_outside_render_pass(command));
    // A timer or debug group cannot span two queues: each queue's commands are submitted apart.
    if (open_timer_) return invalid_state(command + ": timer " + in_quotes(*open_timer_) + " is open; end it first");
    if (debug_depth_ > 0) {
        return invalid_state(command + ": " + std::to_string(debug_depth_) + " debug group(s) open; pop them first");
    }
    queue_ = queue;
    return {};
}

Result<QueueSignal> CommandListState::signal_queue() {
    LOOM_TRY(check_recording("signal_queue"));
    LOOM_TRY(check_outside_render_pass("signal_queue"));
    signal_queue_.push_back(queue_);
    signal_waited_.push_back(false);
    return QueueSignal{static_cast<uint32_t>(signal_queue_.size() - 1), queue_};
}

Status CommandListState::wait_queue(QueueSignal signal) {
    LOOM_TRY(check_recording("wait_queue"));
    LOOM_TRY(check_outside_render_pass("wait_queue"));
    const std::string command = "wait_queue(signal " + std::to_string(signal.index) + ")";
    if (signal.index >= signal_queue_.size() || signal_queue_[signal.index] != signal.queue) {
        return Error{ErrorCode::InvalidArgument, command + ": not a signal of this frame (" +
                                                     std::to_string(signal_queue_.size()) + " made so far)"};
    }
    if (signal.queue == queue_) {
        return Error{ErrorCode::InvalidArgument, command + ": made on the " + std::string(queue_type_name(queue_)) +
                                                     " queue, which is the queue recording; wait on the other one"};
    }
    if (signal_waited_[signal.index]) {
        return Error{ErrorCode::InvalidArgument, command + ": already waited for; a signal is waited at most once"};
    }
    signal_waited_[signal.index] = true;
    return {};
}

// ---- bound state -------------------------------------------------------------------------------

Status CommandListState::set_pipeline(PipelineHandle pipeline) {
    // Unbound first: a refused pipeline leaves none (see the header).
    pipeline_ = {};
    pipeline_name_.clear();
    if (!validating()) {
        pipeline_ = pipeline;
        return {};
    }
    auto facts = pipelines_(pipeline);
    if (!facts.ok()) return Error{ErrorCode::InvalidHandle, "set_pipeline: " + facts.error().message};
    if (!facts->compute) LOOM_TRY(check_pipeline_matches_pass("set_pipeline", *facts));
    pipeline_ = pipeline;
    pipeline_name_ = facts->name;
    return {};
}

Status CommandListState::set_bind_group(uint32_t set, const BindGroup& group) {
    if (set >= kMaxBindGroups || validating()) LOOM_TRY(validation::bind_group(set, group));
    groups_[set] = group;
    return {};
}

Status CommandListState::set_buffer_slow(uint32_t set, uint32_t binding, const BufferBinding& range) {
    // The message is built only when the slot is out of range.
    if (set >= kMaxBindGroups || binding >= kMaxBindingsPerGroup) return validation::buffer_slot(set, binding);
    std::optional<BindGroup>& group = groups_[set];
    if (!group) group.emplace();
    // The last entry for a binding is the one draws use (as in a group given whole).
    if (BindingEntry* entry = bound_entry(&*group, binding)) {
        entry->resource = range;
    } else {
        group->entries.push_back({binding, range});
    }
    return {};
}

Status CommandListState::set_vertex_buffer(uint32_t slot, BufferHandle buffer, uint64_t offset) {
    LOOM_TRY(validation::vertex_buffer_slot(slot));
    auto found = buffers_(buffer);
    if (!found.ok()) return Error{ErrorCode::InvalidHandle, "set_vertex_buffer: " + found.error().message};
    LOOM_TRY(validation::vertex_buffer(slot, **found, offset));
    vertex_buffers_[slot] = {buffer, offset};
    return {};
}

Status CommandListState::set_index_buffer(BufferHandle buffer, IndexType type, uint64_t offset) {
    auto found = buffers_(buffer);
    if (!found.ok()) return Error{ErrorCode::InvalidHandle, "set_index_buffer: " + found.error().message};
    LOOM_TRY(validation::index_buffer(**found, type, offset));
    index_buffer_ = {buffer, type, offset, IndexBuffer::capacity((*found)->size, type, offset)};
    return {};
}

// ---- draws and dispatches ------------------------------------------------------------------------

// Messages are built only on a failure: draws ask these on every call.
Status CommandListState::check_pipeline_set(std::string_view command) const {
    if (!pipeline_.is_null()) return {};
    return invalid_state(std::string(command) + ": no pipeline is set; call set_pipeline first");
}

Result<PipelineFacts> CommandListState::bound_pipeline(std::string_view command, bool compute) const {
    LOOM_TRY(check_pipeline_set(command));
    auto facts = pipelines_(pipeline_);
    if (!facts.ok()) return stale(command, "pipeline " + in_quotes(pipeline_name_), facts.error());
    if (facts->compute != compute) {
        return invalid_state(std::string(command) + ": pipeline " + in_quotes(facts->name) + " is a " +
                             (facts->compute ? "compute" : "graphics") + " pipeline; " +
                             (compute ? "dispatches need a compute pipeline" : "draws need a graphics pipeline"));
    }
    return facts;
}

Status CommandListState::check_pipeline_matches_pass(std::string_view command, const PipelineFacts& p) const {
    if (!pass_) return {};
    const validation::RenderPassShape& shape = pass_->shape;
    const bool formats_match = std::equal(p.color_formats.begin(), p.color_formats.end(), shape.color_formats.begin(),
                                          shape.color_formats.end()) &&
                               p.depth_format == shape.depth_format;
    if (formats_match && p.samples == shape.samples) return {};
    return Error{ErrorCode::InvalidArgument,
                 std::string(command) + ": pipeline " + in_quotes(p.name) + " targets " +
                     attachments_text(p.color_formats, p.depth_format, p.samples) + ", render pass " +
                     in_quotes(pass_->label) + " has " +
                     attachments_text(shape.color_formats, shape.depth_format, shape.samples)};
}

Status CommandListState::check_draw(std::string_view command, bool indexed) const {
    const auto what = [&] { return std::string(command); };
    if (!pass_) return invalid_state(what() + ": no render pass is open; draws go inside a render pass");
    if (!validating()) return check_pipeline_set(command);
    auto pipeline = bound_pipeline(command, false);
    if (!pipeline.ok()) return pipeline.take_error();
    LOOM_TRY(check_pipeline_matches_pass(command, *pipeline));
    for (uint32_t slot = 0; slot < pipeline->vertex_buffers && slot < kMaxVertexBuffers; ++slot) {
        const BufferHandle buffer = vertex_buffers_[slot].buffer;
        if (buffer.is_null()) {
            return invalid_state(what() + ": pipeline " + in_quotes(pipeline->name) + " reads vertex buffer slot " +
                                 std::to_string(slot) + ", but no vertex buffer is bound there");
        }
        if (auto found = buffers_(buffer); !found.ok()) {
            return stale(command, "vertex buffer slot " + std::to_string(slot), found.error());
        }
    }
    if (indexed) {
        if (index_buffer_.buffer.is_null()) {
            return invalid_state(what() + ": no index buffer is bound; call set_index_buffer first");
        }
        auto found = buffers_(index_buffer_.buffer);
        if (!found.ok()) return stale(command, "index buffer", found.error());
    }
    return {};
}

Status CommandListState::check_index_range_slow(uint32_t first_index, uint32_t index_count) const {
    auto found = buffers_(index_buffer_.buffer);
    if (!found.ok()) return stale("draw_indexed", "index buffer", found.error());
    return validation::index_range(**found, index_buffer_.type, index_buffer_.offset, first_index, index_count);
}

Status CommandListState::check_dispatch() const {
    LOOM_TRY(check_outside_render_pass("dispatch"));
    if (!validating()) return check_pipeline_set("dispatch");
    auto pipeline = bound_pipeline("dispatch", true);
    return pipeline.ok() ? Status{} : Status(pipeline.take_error());
}

// ---- timers and debug groups ---------------------------------------------------------------------

Status CommandListState::begin_timer(std::string_view label) {
    if (open_timer_) {
        return invalid_state("begin_timer " + in_quotes(label) + ": timer " + in_quotes(*open_timer_) +
                             " is still open; timers do not nest");
    }
    open_timer_ = std::string(label);
    return {};
}

Status CommandListState::end_timer() {
    if (!open_timer_) return invalid_state("end_timer: no timer is open");
    open_timer_.reset();
    return {};
}

Status CommandListState::pop_debug_group() {
    if (debug_depth_ == 0) return invalid_state("pop_debug_group: no debug group is open");
    --debug_depth_;
    return {};
}

}  // namespace loom::rhi
