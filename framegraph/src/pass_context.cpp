#include "loom/framegraph/pass_context.hpp"

#include <algorithm>

#include "frame_state.hpp"
#include "loom/framegraph/execution_schedule.hpp"

namespace loom::fg {

PassContext::PassContext(FrameState& frame, uint32_t position) : frame_(frame), position_(position) {}

rhi::Device& PassContext::device() const { return frame_.device; }
rhi::CommandList& PassContext::commands() const { return frame_.pass_commands; }
const std::string& PassContext::pass_name() const { return frame_.plan.order[position_].name; }
const Plan& PassContext::plan() const { return frame_.plan; }
const PlanPass& PassContext::plan_pass() const { return frame_.plan.order[position_]; }
uint64_t PassContext::frame_index() const { return frame_.frame_index; }
Extent2D PassContext::frame_size() const { return frame_.plan.frame; }

const PortSchedule* PassContext::find(std::string_view port, bool record_error) {
    for (const PortSchedule& p : frame_.schedule.passes[position_].ports) {
        if (p.name == port) return &p;
    }
    if (record_error) {
        std::string names;
        for (const PortSchedule& p : frame_.schedule.passes[position_].ports) names += (names.empty() ? "" : ", ") + p.name;
        fail(make_error(ErrorCode::InvalidArgument,
                        "no port '" + std::string(port) + "' (ports: " + (names.empty() ? "none" : names) + ")"));
    }
    return nullptr;
}

bool PassContext::has_texture(std::string_view port) const {
    for (const PortSchedule& p : frame_.schedule.passes[position_].ports) {
        if (p.name == port) return !frame_.resolve(p.texture).is_null();
    }
    return false;
}

const PortSchedule* PassContext::find_typed(std::string_view port, ResourceType type) {
    const PortSchedule* p = find(port, true);
    if (!p) return nullptr;
    const std::size_t index = static_cast<std::size_t>(p - frame_.schedule.passes[position_].ports.data());
    if (plan_pass().ports[index].type != type) {
        const bool buffer = type == ResourceType::Buffer;
        fail(make_error(ErrorCode::InvalidArgument, "port '" + std::string(port) + "' is a " +
                                                        (buffer ? "texture port (use texture())" : "buffer port (use buffer())")));
        return nullptr;
    }
    return p;
}

rhi::TextureHandle PassContext::texture(std::string_view port) {
    const PortSchedule* p = find_typed(port, ResourceType::Texture);
    return p ? frame_.resolve(p->texture) : rhi::TextureHandle{};
}

bool PassContext::has_buffer(std::string_view port) const {
    for (const PortSchedule& p : frame_.schedule.passes[position_].ports) {
        if (p.name == port) return !frame_.resolve(p.buffer).is_null();
    }
    return false;
}

rhi::BufferHandle PassContext::buffer(std::string_view port) {
    const PortSchedule* p = find_typed(port, ResourceType::Buffer);
    return p ? frame_.resolve(p->buffer) : rhi::BufferHandle{};
}

uint64_t PassContext::buffer_size(std::string_view port) {
    const PortSchedule* p = find(port, true);
    if (!p) return 0;
    switch (p->buffer.kind) {
        case BufferSlot::Kind::None: return 0;
        case BufferSlot::Kind::Plan: return frame_.plan.buffers[p->buffer.index].spec.size;
        case BufferSlot::Kind::Import:
            return p->buffer.index < frame_.buffer_import_sizes.size() ? frame_.buffer_import_sizes[p->buffer.index] : 0;
    }
    return 0;
}

const ResolvedSpec* PassContext::spec(std::string_view port) {
    const PortSchedule* p = find(port, true);
    return p ? frame_.spec_of(*p) : nullptr;
}

Extent2D PassContext::extent(std::string_view port) {
    const ResolvedSpec* s = spec(port);
    return s ? s->extent : Extent2D{};
}

rhi::TextureRange PassContext::range(std::string_view port) {
    const PortSchedule* p = find(port, true);
    return p ? p->range : rhi::TextureRange{};
}

Extent2D PassContext::range_extent(std::string_view port) {
    const PortSchedule* p = find(port, true);
    const ResolvedSpec* s = p ? frame_.spec_of(*p) : nullptr;
    if (!s) return {};
    const uint32_t mip = p->range.base_mip < 32 ? p->range.base_mip : 31;
    return {std::max(1u, s->extent.width >> mip), std::max(1u, s->extent.height >> mip)};
}

bool PassContext::history_valid(std::string_view port) {
    const PortSchedule* p = find(port, true);
    if (!p) return false;
    if (p->texture.kind != TextureSlot::Kind::History) {
        fail(make_error(ErrorCode::InvalidArgument, "port '" + std::string(port) + "' is not a history port"));
        return false;
    }
    return frame_.history_valid[p->texture.index];
}

rhi::ColorAttachment PassContext::color_attachment(const ColorPort& port) {
    rhi::ColorAttachment attachment;
    const PortSchedule* p = find(port.port, true);
    if (!p) return attachment;
    attachment.texture = frame_.resolve(p->texture);
    if (attachment.texture.is_null()) {
        fail(make_error(ErrorCode::InvalidArgument, "port '" + port.port + "' has no texture to render to (unconnected)"));
        return attachment;
    }
    attachment.mip = port.mip.value_or(p->range.base_mip);
    attachment.layer = port.layer.value_or(p->range.base_layer);
    attachment.load = p->load;
    if (attachment.load == rhi::LoadOp::Clear && port.writes_every_texel) attachment.load = rhi::LoadOp::DontCare;
    attachment.store = p->store;
    attachment.clear = port.clear;
    return attachment;
}

rhi::DepthAttachment PassContext::depth_attachment(const DepthPort& port) {
    rhi::DepthAttachment attachment;
    const PortSchedule* p = find(port.port, true);
    if (!p) return attachment;
    attachment.texture = frame_.resolve(p->texture);
    if (attachment.texture.is_null()) {
        fail(make_error(ErrorCode::InvalidArgument, "port '" + port.port + "' has no texture to render to (unconnected)"));
        return attachment;
    }
    attachment.mip = port.mip.value_or(p->range.base_mip);
    attachment.layer = port.layer.value_or(p->range.base_layer);
    rhi::LoadOp load = p->load;
    if (load == rhi::LoadOp::Clear && port.writes_every_texel) load = rhi::LoadOp::DontCare;
    attachment.depth_load = load;
    attachment.depth_store = p->store;
    attachment.stencil_load = load;
    attachment.stencil_store = p->store;
    attachment.clear_depth = port.clear_depth;
    attachment.clear_stencil = port.clear_stencil;
    return attachment;
}

rhi::RenderPassDesc PassContext::render_pass(std::span<const ColorPort> colors, const std::optional<DepthPort>& depth) {
    rhi::RenderPassDesc desc;
    desc.label = pass_name();
    for (const ColorPort& c : colors) desc.colors.push_back(color_attachment(c));
    if (depth) desc.depth = depth_attachment(*depth);
    return desc;
}

void PassContext::begin_render_pass(std::span<const ColorPort> colors, const std::optional<DepthPort>& depth) {
    if (colors.empty() && !depth) {
        fail(make_error(ErrorCode::InvalidArgument, "begin_render_pass without attachments"));
        return;
    }
    rhi::RenderPassDesc desc = render_pass(colors, depth);
    if (frame_.pass_error) return;  // the frame fails anyway; don't record a broken pass
    frame_.pass_commands.begin_render_pass(desc);
}

void PassContext::end_render_pass() {
    if (!frame_.pass_commands.in_render_pass()) {
        fail(make_error(ErrorCode::InvalidState, "end_render_pass without an open render pass"));
        return;
    }
    frame_.pass_commands.end_render_pass();
}

void PassContext::fail(Error error) { frame_.fail(std::move(error)); }

Status PassContext::status() const {
    if (frame_.pass_error) return *frame_.pass_error;
    return {};
}

}  // namespace loom::fg
