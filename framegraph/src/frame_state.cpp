#include "frame_state.hpp"

#include <variant>

namespace loom::fg {

// ---- PassCommandList ---------------------------------------------------------------------------

void PassCommandList::begin_pass(rhi::CommandList& inner) {
    inner_ = &inner;
    in_render_pass_ = false;
    debug_depth_ = 0;
}

std::optional<std::string> PassCommandList::end_pass() {
    std::string left_open;
    if (in_render_pass_) {
        inner_->end_render_pass();
        in_render_pass_ = false;
        left_open = "a render pass";
    }
    if (debug_depth_ > 0) {
        for (; debug_depth_ > 0; --debug_depth_) inner_->pop_debug_group();
        left_open += std::string(left_open.empty() ? "" : " and ") + "debug groups";
    }
    if (left_open.empty()) return std::nullopt;
    return left_open;
}

void PassCommandList::begin_render_pass(const rhi::RenderPassDesc& desc) {
    if (frame_.pass_kind() != PassKind::Graphics) {
        frame_.fail(make_error(ErrorCode::InvalidState, "begin_render_pass '" + desc.label + "' in a " +
                                                            std::string(pass_kind_name(frame_.pass_kind())) +
                                                            " pass; only graphics passes open render passes"));
        return;
    }
    if (in_render_pass_) {
        frame_.fail(make_error(ErrorCode::InvalidState, "begin_render_pass '" + desc.label + "' while a render pass is open"));
        return;
    }
    inner_->begin_render_pass(desc);
    in_render_pass_ = true;
}

void PassCommandList::set_queue(rhi::QueueType queue) {
    frame_.fail(make_error(ErrorCode::InvalidState, "set_queue(" + std::string(rhi::queue_type_name(queue)) +
                                                        "): the executor runs each pass on the queue its plan names "
                                                        "(Pass::set_queue)"));
}

rhi::QueueSignal PassCommandList::signal_queue() {
    frame_.fail(make_error(ErrorCode::InvalidState,
                           "signal_queue: the executor makes the semaphores between queues from the plan"));
    return {};
}

void PassCommandList::wait_queue(rhi::QueueSignal) {
    frame_.fail(make_error(ErrorCode::InvalidState,
                           "wait_queue: the executor makes the semaphores between queues from the plan"));
}

void PassCommandList::end_render_pass() {
    if (!in_render_pass_) {
        frame_.fail(make_error(ErrorCode::InvalidState, "end_render_pass without an open render pass"));
        return;
    }
    inner_->end_render_pass();
    in_render_pass_ = false;
}

bool PassCommandList::require_render_pass(std::string_view command, bool inside) {
    if (in_render_pass_ == inside) return true;
    frame_.fail(make_error(ErrorCode::InvalidState, std::string(command) + (inside ? " outside a render pass" : " inside a render pass")));
    return false;
}

void PassCommandList::set_pipeline(rhi::PipelineHandle pipeline) {
    if (pipeline.is_null()) {
        frame_.fail(make_error(ErrorCode::InvalidHandle, "set_pipeline: null pipeline handle"));
        return;
    }
    inner_->set_pipeline(pipeline);
}

void PassCommandList::set_bind_group(uint32_t set, const rhi::BindGroup& group) {
    // A null handle here is usually an unconnected optional port (PassContext::texture is null).
    for (const rhi::BindingEntry& entry : group.entries) {
        // Built only for an error: passes bind groups for every draw.
        const auto where = [&] { return "set_bind_group: set " + std::to_string(set) + " binding " + std::to_string(entry.binding); };
        if (const auto* t = std::get_if<rhi::TextureBinding>(&entry.resource)) {
            if (t->texture.is_null() || t->sampler.is_null()) {
                frame_.fail(make_error(ErrorCode::InvalidHandle, where() + ": null " + (t->texture.is_null() ? "texture" : "sampler") +
                                                                     " (an unconnected optional port has no texture)"));
                return;
            }
        } else if (const auto* st = std::get_if<rhi::StorageTextureBinding>(&entry.resource)) {
            if (st->texture.is_null()) {
                frame_.fail(make_error(ErrorCode::InvalidHandle, where() + ": null storage texture"));
                return;
            }
        } else if (const auto* b = std::get_if<rhi::BufferBinding>(&entry.resource)) {
            if (b->buffer.is_null()) {
                frame_.fail(make_error(ErrorCode::InvalidHandle, where() + ": null buffer"));
                return;
            }
        }
    }
    inner_->set_bind_group(set, group);
}

void PassCommandList::set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) {
    if (range.buffer.is_null()) {
        frame_.fail(make_error(ErrorCode::InvalidHandle, "set_buffer: set " + std::to_string(set) + " binding " +
                                                             std::to_string(binding) + ": null buffer"));
        return;
    }
    inner_->set_buffer(set, binding, range);
}

void PassCommandList::transition(rhi::TextureHandle texture, rhi::ResourceState state) {
    if (!require_render_pass("transition", false)) return;
    if (texture.is_null()) {
        frame_.fail(make_error(ErrorCode::InvalidHandle, "transition: null texture"));
        return;
    }
    inner_->transition(texture, state);
}

void PassCommandList::transition(rhi::TextureHandle texture, rhi::ResourceState state, const rhi::TextureRange& range) {
    if (!require_render_pass("transition", false)) return;
    if (texture.is_null()) {
        frame_.fail(make_error(ErrorCode::InvalidHandle, "transition: null texture"));
        return;
    }
    inner_->transition(texture, state, range);
}

void PassCommandList::begin_timer(std::string_view label) {
    frame_.fail(make_error(ErrorCode::InvalidState, "begin_timer '" + std::string(label) +
                                                        "': the executor times every pass itself and RHI timers do not nest"));
}

void PassCommandList::end_timer() {
    frame_.fail(make_error(ErrorCode::InvalidState, "end_timer: the executor times every pass itself"));
}

void PassCommandList::push_debug_group(std::string_view label) {
    inner_->push_debug_group(label);
    ++debug_depth_;
}

void PassCommandList::pop_debug_group() {
    if (debug_depth_ == 0) {
        frame_.fail(make_error(ErrorCode::InvalidState, "pop_debug_group without a matching push_debug_group in the pass"));
        return;
    }
    inner_->pop_debug_group();
    --debug_depth_;
}

// ---- FrameState --------------------------------------------------------------------------------

rhi::TextureHandle FrameState::resolve(const TextureSlot& slot) const {
    switch (slot.kind) {
        case TextureSlot::Kind::None: return {};
        case TextureSlot::Kind::Plan: return slot.index < plan_textures.size() ? plan_textures[slot.index] : rhi::TextureHandle{};
        case TextureSlot::Kind::Import: return slot.index < imports.size() ? imports[slot.index] : rhi::TextureHandle{};
        case TextureSlot::Kind::History: return slot.index < history_read.size() ? history_read[slot.index] : rhi::TextureHandle{};
    }
    return {};
}

rhi::BufferHandle FrameState::resolve(const BufferSlot& slot) const {
    switch (slot.kind) {
        case BufferSlot::Kind::None: return {};
        case BufferSlot::Kind::Plan: return slot.index < plan_buffers.size() ? plan_buffers[slot.index] : rhi::BufferHandle{};
        case BufferSlot::Kind::Import:
            return slot.index < buffer_imports.size() ? buffer_imports[slot.index] : rhi::BufferHandle{};
    }
    return {};
}

const ResolvedSpec* FrameState::spec_of(const PortSchedule& port) const {
    switch (port.texture.kind) {
        case TextureSlot::Kind::None: return nullptr;
        case TextureSlot::Kind::Plan: return &plan.textures[port.texture.index].spec;
        case TextureSlot::Kind::Import:
            return port.texture.index < import_specs.size() ? &import_specs[port.texture.index] : nullptr;
        case TextureSlot::Kind::History: return &schedule.histories[port.texture.index].spec;
    }
    return nullptr;
}

void FrameState::fail(Error error) {
    if (pass_error) return;
    error.message = "pass '" + plan.order[position].name + "': " + error.message;
    pass_error = std::move(error);
}

}  // namespace loom::fg
