#include "frame_state.hpp"

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
    if (in_render_pass_) {
        // Let the backend report it (with both labels); keep our count in step.
        inner_->begin_render_pass(desc);
        return;
    }
    inner_->begin_render_pass(desc);
    in_render_pass_ = true;
}

void PassCommandList::end_render_pass() {
    inner_->end_render_pass();
    in_render_pass_ = false;
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
