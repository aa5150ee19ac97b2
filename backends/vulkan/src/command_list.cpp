#include "command_list.hpp"

#include <algorithm>

#include "formats.hpp"
#include "vulkan_device.hpp"
#include "loom/rhi/binding_reuse.hpp"
#include "loom/rhi/subresources.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::vulkan {

using rhi::ResourceState;
using rhi::validation::in_quotes;

VulkanCommandList::VulkanCommandList(VulkanDevice& device)
    : device_(device), state_(device.pipeline_lookup(), device.resource_lookup().buffer) {}

void VulkanCommandList::begin(VkCommandBuffer cmd, bool new_frame) {
    cmd_ = cmd;
    bound_graphics_ = VK_NULL_HANDLE;
    bound_compute_ = VK_NULL_HANDLE;
    bound_layout_ = VK_NULL_HANDLE;
    group_dirty_.fill(true);
    push_dirty_ = true;
    checked_pipeline_ = nullptr;
    forget_written_sets();
    if (new_frame) {
        // The device has begun the frame on the state tracker: nothing is bound.
        error_.reset();
        stats_ = {};
        push_dirty_ = false;
        timestamp_written_ = false;
        return;
    }
    // The continuation of a frame split by a readback: command buffer state starts empty, so
    // what was bound is bound again.
    if (const Pipeline* p = device_.pipelines().find(state_.pipeline())) {
        const bool graphics = p->bind_point == VK_PIPELINE_BIND_POINT_GRAPHICS;
        vkCmdBindPipeline(cmd_, p->bind_point, p->pipeline);
        (graphics ? bound_graphics_ : bound_compute_) = p->pipeline;
    }
    for (uint32_t slot = 0; slot < rhi::kMaxVertexBuffers; ++slot) {
        const rhi::CommandListState::VertexBuffer& vb = state_.vertex_buffer(slot);
        if (const Buffer* b = device_.buffers().find(vb.buffer)) {
            VkDeviceSize offset = vb.offset;
            vkCmdBindVertexBuffers(cmd_, slot, 1, &b->buffer, &offset);
        }
    }
    const rhi::CommandListState::IndexBuffer& indices = state_.index_buffer();
    if (const Buffer* b = device_.buffers().find(indices.buffer)) {
        vkCmdBindIndexBuffer(cmd_, b->buffer, indices.offset, to_vk(indices.type));
    }
}

void VulkanCommandList::fail(ErrorCode code, std::string message) {
    if (!error_) error_ = Error{code, std::move(message)};
}

std::optional<Error> VulkanCommandList::take_error() {
    auto e = std::move(error_);
    error_.reset();
    return e;
}

void VulkanCommandList::finish() {
    accepted(state_.check_nothing_open());
    if (state_.render_pass()) end_render_pass();
    if (state_.open_timer()) end_timer();
    while (state_.debug_group_depth() > 0) pop_debug_group();
}

// ---- render passes ----------------------------------------------------------------------------

void VulkanCommandList::begin_render_pass(const rhi::RenderPassDesc& desc) {
    const std::string pass = "render pass " + in_quotes(desc.label);
    checked_pipeline_ = nullptr;
    forget_written_sets();  // the attachments change state
    if (!accepted(state_.check_begin_render_pass(desc.label))) return;
    auto shape = rhi::validation::render_pass(desc, device_.capabilities(), device_.resource_lookup().texture);
    if (!shape.ok()) return fail(shape.error().code, shape.error().message);
    // Every handle was found by the validation above.
    std::vector<Texture*> color_textures;
    for (const rhi::ColorAttachment& c : desc.colors) color_textures.push_back(*device_.textures().get(c.texture));
    Texture* depth_texture = desc.depth ? *device_.textures().get(desc.depth->texture) : nullptr;

    // Attachments move into attachment layouts; with a load op other than Load the old
    // contents are not needed, which is also the hand-over point for aliased (placed) images.
    BarrierBatch batch;
    for (std::size_t i = 0; i < desc.colors.size(); ++i) {
        const rhi::ColorAttachment& c = desc.colors[i];
        device_.transition_texture(batch, *color_textures[i], c.mip, 1, c.layer, 1, ResourceState::RenderTarget, Stream::Frame,
                                   c.load != rhi::LoadOp::Load);
    }
    if (depth_texture) {
        const rhi::DepthAttachment& d = *desc.depth;
        const rhi::FormatInfo& info = rhi::format_info(depth_texture->desc.format);
        const bool discard = (!info.has_depth() || d.depth_load != rhi::LoadOp::Load) &&
                             (!info.has_stencil() || d.stencil_load != rhi::LoadOp::Load);
        device_.transition_texture(batch, *depth_texture, d.mip, 1, d.layer, 1, ResourceState::DepthWrite, Stream::Frame, discard);
    }
    stats_.api_calls += batch.flush(cmd_);

    std::vector<VkRenderingAttachmentInfo> colors;
    for (std::size_t i = 0; i < desc.colors.size(); ++i) {
        const rhi::ColorAttachment& c = desc.colors[i];
        auto view = device_.attachment_view(*color_textures[i], c.mip, c.layer);
        if (!view.ok()) {
            fail(view.error().code, pass + ": " + view.error().message);
            return;
        }
        auto a = vk_init<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
        a.imageView = *view;
        a.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        a.loadOp = to_vk(c.load);
        a.storeOp = to_vk(c.store);
        a.clearValue.color = clear_color(color_textures[i]->desc.format, c.clear);
        colors.push_back(a);
    }
    auto depth = vk_init<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    auto stencil = vk_init<VkRenderingAttachmentInfo>(VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO);
    auto info = vk_init<VkRenderingInfo>(VK_STRUCTURE_TYPE_RENDERING_INFO);
    if (depth_texture) {
        const rhi::DepthAttachment& d = *desc.depth;
        auto view = device_.attachment_view(*depth_texture, d.mip, d.layer);
        if (!view.ok()) {
            fail(view.error().code, pass + ": " + view.error().message);
            return;
        }
        const rhi::FormatInfo& format = rhi::format_info(depth_texture->desc.format);
        depth.imageView = *view;
        depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        depth.loadOp = to_vk(d.depth_load);
        depth.storeOp = to_vk(d.depth_store);
        depth.clearValue.depthStencil = {d.clear_depth, d.clear_stencil};
        stencil = depth;
        stencil.loadOp = to_vk(d.stencil_load);
        stencil.storeOp = to_vk(d.stencil_store);
        if (format.has_depth()) info.pDepthAttachment = &depth;
        if (format.has_stencil()) info.pStencilAttachment = &stencil;
    }
    info.renderArea = {{0, 0}, {shape->width, shape->height}};
    info.layerCount = 1;
    info.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    info.pColorAttachments = colors.data();
    vkCmdBeginRendering(cmd_, &info);
    const uint32_t width = shape->width, height = shape->height;
    state_.render_pass_begun(desc.label, std::move(*shape));
    ++stats_.render_passes;
    ++stats_.api_calls;
    set_viewport({0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f});
    set_scissor({0, 0, width, height});
}

void VulkanCommandList::end_render_pass() {
    checked_pipeline_ = nullptr;
    if (!accepted(state_.end_render_pass())) return;
    vkCmdEndRendering(cmd_);
    ++stats_.api_calls;
}

// ---- state ------------------------------------------------------------------------------------

void VulkanCommandList::set_pipeline(rhi::PipelineHandle handle) {
    checked_pipeline_ = nullptr;
    if (!accepted(state_.set_pipeline(handle))) return;
    const Pipeline* p = *device_.pipelines().get(handle);  // found by the tracker
    VkPipeline& bound = p->bind_point == VK_PIPELINE_BIND_POINT_GRAPHICS ? bound_graphics_ : bound_compute_;
    if (bound == p->pipeline) return;
    vkCmdBindPipeline(cmd_, p->bind_point, p->pipeline);
    bound = p->pipeline;
    ++stats_.pipeline_binds;
    ++stats_.api_calls;
}

void VulkanCommandList::set_viewport(const rhi::Viewport& v) {
    if (state_.validating() && !accepted(rhi::validation::viewport(v))) return;
    // Outside a pass there is nothing to set: begin_render_pass resets viewport and scissor.
    if (!state_.render_pass()) return;
    // Negative height: NDC y up, row 0 at the top (docs/architecture.md, "Conventions that make
    // the two APIs agree").
    VkViewport vp{v.x, v.y + v.height, v.width, -v.height, v.min_depth, v.max_depth};
    vkCmdSetViewport(cmd_, 0, 1, &vp);
    ++stats_.api_calls;
}

void VulkanCommandList::set_scissor(const rhi::Rect& r) {
    if (!state_.render_pass()) return;
    // Vulkan forbids negative offsets; clip the rectangle to the framebuffer's quadrant.
    int64_t x = r.x, y = r.y, w = r.width, h = r.height;
    if (x < 0) { w += x; x = 0; }
    if (y < 0) { h += y; y = 0; }
    VkRect2D rect{{static_cast<int32_t>(x), static_cast<int32_t>(y)},
                  {static_cast<uint32_t>(std::max<int64_t>(w, 0)), static_cast<uint32_t>(std::max<int64_t>(h, 0))}};
    vkCmdSetScissor(cmd_, 0, 1, &rect);
    ++stats_.api_calls;
}

void VulkanCommandList::set_bind_group(uint32_t set, const rhi::BindGroup& group) {
    // Handles are checked when a draw or dispatch uses them (rhi::validation::binding), as on GL:
    // a group may hold entries the pipeline does not read.
    if (accepted(state_.set_bind_group(set, group))) group_dirty_[set] = true;
}

void VulkanCommandList::set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) {
    if (accepted(state_.set_buffer(set, binding, range))) group_dirty_[set] = true;
}

void VulkanCommandList::push_constants(std::span<const std::byte> data, uint32_t offset) {
    if (accepted(state_.push_constants(data, offset))) push_dirty_ = true;
}

void VulkanCommandList::set_vertex_buffer(uint32_t slot, rhi::BufferHandle handle, uint64_t offset) {
    // A buffer found alive and fit here keeps the checked draw valid (prepare_draw).
    const Buffer* found = device_.buffers().find(handle);
    if (!accepted(state_.set_vertex_buffer(slot, handle, found ? &found->desc : nullptr, offset))) return;
    VkDeviceSize o = offset;
    // Null only unchecked (validation off): a misuse, undefined as in Vulkan itself.
    const VkBuffer vk_buffer = found ? found->buffer : VK_NULL_HANDLE;
    vkCmdBindVertexBuffers(cmd_, slot, 1, &vk_buffer, &o);
    ++stats_.buffer_binds;
    ++stats_.api_calls;
}

void VulkanCommandList::set_index_buffer(rhi::BufferHandle handle, rhi::IndexType type, uint64_t offset) {
    // A buffer found alive and fit here keeps the checked draw valid (prepare_draw).
    const Buffer* found = device_.buffers().find(handle);
    if (!accepted(state_.set_index_buffer(handle, found ? &found->desc : nullptr, type, offset))) return;
    vkCmdBindIndexBuffer(cmd_, found ? found->buffer : VK_NULL_HANDLE, offset, to_vk(type));
    ++stats_.buffer_binds;
    ++stats_.api_calls;
}

rhi::BufferBinding VulkanCommandList::transient_uniforms(std::span<const std::byte> data) {
    if (!accepted(state_.check_recording("transient_uniforms"))) return {};
    auto binding = device_.allocate_transient_uniforms(data);
    if (!binding.ok()) {
        fail(binding.error().code, "transient_uniforms: " + binding.error().message);
        return {};
    }
    stats_.bytes_uploaded += data.size();
    return *binding;
}

// ---- bindings ---------------------------------------------------------------------------------

namespace {

rhi::validation::BindingKind binding_kind(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return rhi::validation::BindingKind::StorageBuffer;
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return rhi::validation::BindingKind::SampledTexture;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return rhi::validation::BindingKind::StorageImage;
        default: return rhi::validation::BindingKind::UniformBuffer;
    }
}

}  // namespace

bool VulkanCommandList::write_set(const Pipeline& pipeline, uint32_t set, VkDescriptorSet& out, std::string_view what) {
    const PipelineLayout& layout = *pipeline.layout;
    const SetLayout& set_layout = *layout.sets[set];
    const rhi::BindGroup* group = state_.bind_group(set);
    const rhi::validation::ResourceLookup& lookup = device_.resource_lookup();
    // Every binding is checked before a descriptor set is allocated for them (unless validation
    // is off: then the bindings are taken to be what the pipeline reads, alive).
    for (const SetBinding& b : state_.validating() ? std::span(set_layout.bindings) : std::span<const SetBinding>()) {
        const rhi::validation::PipelineSlot slot{set, b.binding, binding_kind(b.type), b.name, b.kind};
        auto entry = rhi::validation::binding(what, pipeline.name, slot, group, device_.capabilities(), lookup);
        if (!entry.ok()) {
            fail(entry.error().code, entry.error().message);
            return false;
        }
    }
    auto allocated = device_.current_frame().descriptors->allocate(set_layout.layout);
    if (!allocated.ok()) {
        fail(allocated.error().code, std::string(what) + ": " + allocated.error().message);
        return false;
    }
    out = *allocated;

    // Storage for the infos that the writes point to (reserved so the pointers stay valid).
    std::vector<VkDescriptorBufferInfo>& buffer_infos = buffer_infos_;
    std::vector<VkDescriptorImageInfo>& image_infos = image_infos_;
    std::vector<VkWriteDescriptorSet>& writes = writes_;
    buffer_infos.clear();
    image_infos.clear();
    writes.clear();
    buffer_infos.reserve(set_layout.bindings.size());
    dynamic_offsets_.clear();
    WrittenSet& written = written_[set];
    written.set = VK_NULL_HANDLE;
    written.layout = &set_layout;
    written.entries.clear();
    std::size_t image_count = 0;
    for (const SetBinding& b : set_layout.bindings) image_count += b.count;
    image_infos.reserve(image_count);

    for (std::size_t n = 0; n < set_layout.bindings.size(); ++n) {
        const SetBinding& b = set_layout.bindings[n];
        const rhi::validation::PipelineSlot slot{set, b.binding, binding_kind(b.type), b.name, b.kind};
        // Found by the check above.
        const rhi::BindingEntry* entry = rhi::bound_entry(group, b.binding);
        // Built only for an error.
        auto where = [&] {
            return std::string(what) + ": pipeline " + in_quotes(pipeline.name) + " set " + std::to_string(set) +
                   " binding " + std::to_string(b.binding) + " (" + in_quotes(b.name) + ")";
        };
        written.entries.push_back(*entry);
        auto w = vk_init<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
        w.dstSet = out;
        w.dstBinding = b.binding;
        w.descriptorType = b.type;
        w.descriptorCount = b.count;
        const bool dynamic = b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
        if (dynamic || b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER || b.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            const rhi::BufferBinding* binding = &std::get<rhi::BufferBinding>(entry->resource);
            const Buffer* buffer = *device_.buffers().get(binding->buffer);  // found by the validation above
            const bool uniform = b.type != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
            // The whole rest of the buffer, for a uniform buffer at most what the device can bind.
            uint64_t range = binding->size ? binding->size : buffer->desc.size - binding->offset;
            if (!binding->size && uniform) range = std::min(range, device_.max_uniform_range());
            // A dynamic uniform buffer's offset is given when the set is bound (checked aligned
            // and inside the buffer above).
            if (dynamic) dynamic_offsets_.push_back(static_cast<uint32_t>(binding->offset));
            buffer_infos.push_back({buffer->buffer, dynamic ? 0 : binding->offset, range});
            w.descriptorCount = 1;
            w.pBufferInfo = &buffer_infos.back();
            ++stats_.buffer_binds;
        } else if (b.type == VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER) {
            const rhi::TextureBinding* binding = &std::get<rhi::TextureBinding>(entry->resource);
            // Found by the validation above.
            Texture* texture = *device_.textures().get(binding->texture);
            const Sampler* sampler = *device_.samplers().get(binding->sampler);
            const rhi::validation::BoundRange bound = rhi::validation::bound_range(slot, texture->desc, *entry);
            // Sampling needs the bound subresources in ShaderRead (depth textures: DepthRead or
            // ShaderRead); the others may be anything, e.g. the mip a pass renders to.
            ResourceState found = ResourceState::Undefined;
            const bool depth_ok = texture->depth_stencil && VulkanDevice::range_all_in(*texture, bound.range, ResourceState::DepthRead);
            if (!depth_ok && !VulkanDevice::range_all_in(*texture, bound.range, ResourceState::ShaderRead, &found)) {
                const Error e = rhi::validation::state_for_binding(what, pipeline.name, slot, texture->desc.name, found,
                                                                   texture->depth_stencil ? "DepthRead or ShaderRead" : "ShaderRead");
                fail(e.code, e.message);
                return false;
            }
            if (!texture->sampled_view) {  // Sampled usage (checked above) implies a sampled view
                fail(ErrorCode::Backend, where() + ": texture " + in_quotes(texture->desc.name) + " has no sampled view");
                return false;
            }
            if (auto owner = device_.alias_owner(*texture)) {
                fail(ErrorCode::InvalidState, where() + ": texture " + in_quotes(texture->desc.name) + " shares heap memory with " + *owner +
                                                  ", which was used after it: its contents are gone");
                return false;
            }
            VkImageView view = texture->sampled_view;
            if (!bound.whole) {
                auto made = device_.range_view(*texture, bound.range, bound.kind, false);
                if (!made.ok()) {
                    fail(made.error().code, where() + ": " + made.error().message);
                    return false;
                }
                view = *made;
            }
            const VkImageLayout layout_now = depth_ok ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                                      : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
            w.pImageInfo = image_infos.data() + image_infos.size();
            for (uint32_t i = 0; i < b.count; ++i) image_infos.push_back({sampler->sampler, view, layout_now});
            ++stats_.texture_binds;
        } else if (b.type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE) {
            const rhi::StorageTextureBinding* binding = &std::get<rhi::StorageTextureBinding>(entry->resource);
            // Found by the validation above.
            Texture* texture = *device_.textures().get(binding->texture);
            const rhi::validation::BoundRange bound = rhi::validation::bound_range(slot, texture->desc, *entry);
            ResourceState found = ResourceState::Undefined;
            if (!VulkanDevice::range_all_in(*texture, bound.range, ResourceState::Storage, &found)) {
                const Error e = rhi::validation::state_for_binding(what, pipeline.name, slot, texture->desc.name, found, "Storage");
                fail(e.code, e.message);
                return false;
            }
            // Storage views are always of one mip: never the sampled view.
            auto view = device_.range_view(*texture, bound.range, bound.kind, true);
            if (!view.ok()) {
                fail(view.error().code, where() + ": " + view.error().message);
                return false;
            }
            w.descriptorCount = 1;
            w.pImageInfo = image_infos.data() + image_infos.size();
            image_infos.push_back({VK_NULL_HANDLE, *view, VK_IMAGE_LAYOUT_GENERAL});
            ++stats_.texture_binds;
        }
        writes.push_back(w);
    }
    vkUpdateDescriptorSets(device_.context().device(), static_cast<uint32_t>(writes.size()), writes.data(), 0, nullptr);
    written.set = out;
    return true;
}

void VulkanCommandList::forget_written_sets() {
    for (WrittenSet& w : written_) w.set = VK_NULL_HANDLE;
}

bool VulkanCommandList::reuse_written_set(const SetLayout& layout, uint32_t set) {
    const WrittenSet& written = written_[set];
    if (written.set == VK_NULL_HANDLE || written.layout != &layout || layout.dynamic_count == 0) return false;
    const rhi::BindGroup* group = state_.bind_group(set);
    if (!group) return false;
    dynamic_offsets_.clear();
    const uint64_t alignment = device_.capabilities().uniform_buffer_offset_alignment;
    for (std::size_t i = 0; i < layout.bindings.size(); ++i) {
        const SetBinding& b = layout.bindings[i];
        const rhi::BindingEntry* entry = rhi::bound_entry(group, b.binding);
        const rhi::BindingEntry& then = written.entries[i];
        if (!entry || !rhi::differs_only_in_buffer_offset(*entry, then)) return false;
        const auto* range = std::get_if<rhi::BufferBinding>(&entry->resource);
        if (!range) continue;
        if (b.type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC) {
            if (range->offset != std::get<rhi::BufferBinding>(then.resource).offset) return false;
            continue;
        }
        // The range was fixed when the set was written; the buffer is alive (nothing was
        // destroyed since the set was written).
        if (state_.validating()) {
            const Buffer* buffer = device_.buffers().find(range->buffer);
            if (!buffer || !rhi::uniform_offset_fits(*range, buffer->desc.size, alignment)) return false;
        }
        dynamic_offsets_.push_back(static_cast<uint32_t>(range->offset));
    }
    return true;
}

bool VulkanCommandList::flush_bindings(const Pipeline& pipeline, std::string_view what) {
    const PipelineLayout& layout = *pipeline.layout;
    const bool layout_changed = bound_layout_ != layout.layout;
    for (uint32_t s = 0; s < layout.set_count; ++s) {
        if (layout.sets[s]->bindings.empty()) continue;
        if (!group_dirty_[s] && !layout_changed) continue;
        VkDescriptorSet set = written_[s].set;
        if (!reuse_written_set(*layout.sets[s], s)) {
            if (!write_set(pipeline, s, set, what)) return false;
        }
        vkCmdBindDescriptorSets(cmd_, pipeline.bind_point, layout.layout, s, 1, &set,
                                static_cast<uint32_t>(dynamic_offsets_.size()), dynamic_offsets_.data());
        ++stats_.api_calls;
        group_dirty_[s] = false;
    }
    if (layout.push_constant_size > 0 && (push_dirty_ || layout_changed)) {
        vkCmdPushConstants(cmd_, layout.layout, layout.push_constant_stages, 0, layout.push_constant_size,
                           state_.push_constant_data().data());
        ++stats_.api_calls;
        // Push constants travel in the command buffer; GL uploads them to a buffer. Both
        // count them as uploaded bytes.
        stats_.bytes_uploaded += layout.push_constant_size;
        push_dirty_ = false;
    }
    bound_layout_ = layout.layout;
    return true;
}

uint64_t VulkanCommandList::device_removals() const {
    return device_.textures().removals() + device_.buffers().removals() + device_.samplers().removals() +
           device_.pipelines().removals();
}

void VulkanCommandList::notice_removals() {
    const uint64_t removals = device_removals();
    if (removals == checked_removals_) return;
    // Something was destroyed: every check and every written descriptor set is made again.
    checked_pipeline_ = nullptr;
    group_dirty_.fill(true);
    forget_written_sets();
    checked_removals_ = removals;
}

const Pipeline* VulkanCommandList::prepare_draw(std::string_view what, bool indexed) {
    notice_removals();
    // Nothing the tracker checks for a draw changed since the last one: its answer holds.
    const Pipeline* p = checked_pipeline_;
    if (!p || (indexed && !checked_indexed_)) {
        checked_pipeline_ = nullptr;
        if (!accepted(state_.check_draw(what, indexed))) return nullptr;
        p = *device_.pipelines().get(state_.pipeline());  // found by the tracker
        checked_pipeline_ = p;
        checked_indexed_ = indexed;
    }
    return flush_bindings(*p, what) ? p : nullptr;
}

void VulkanCommandList::draw(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance) {
    if (!prepare_draw("draw", false)) return;
    vkCmdDraw(cmd_, vertex_count, instance_count, first_vertex, first_instance);
    ++stats_.draw_calls;
    ++stats_.api_calls;
}

void VulkanCommandList::draw_indexed(uint32_t index_count, uint32_t instance_count, uint32_t first_index, int32_t base_vertex,
                                     uint32_t first_instance) {
    if (!prepare_draw("draw_indexed", true)) return;
    // The GPU would read past the buffer (undefined without robustness features): refuse.
    if (!accepted(state_.check_index_range(first_index, index_count))) return;
    vkCmdDrawIndexed(cmd_, index_count, instance_count, first_index, base_vertex, first_instance);
    ++stats_.draw_calls;
    ++stats_.api_calls;
}

void VulkanCommandList::draw_indexed_indirect(rhi::BufferHandle handle, uint64_t offset, uint32_t draw_count,
                                              uint32_t stride) {
    const char* what = "draw_indexed_indirect";
    auto buffer = device_.buffers().get(handle);
    if (!buffer.ok()) return fail(ErrorCode::InvalidHandle, std::string(what) + ": argument buffer: " + buffer.error().message);
    const Buffer& b = **buffer;
    if (state_.validating() && !accepted(rhi::validation::indirect_draws(b.desc, offset, draw_count, stride))) return;
    if (!prepare_draw(what, true)) return;
    if (draw_count == 0) return;
    if (device_.context().multi_draw_indirect()) {
        vkCmdDrawIndexedIndirect(cmd_, b.buffer, offset, draw_count, stride);
        ++stats_.api_calls;
    } else {
        // Without the multiDrawIndirect feature a command reads one draw.
        for (uint32_t i = 0; i < draw_count; ++i) vkCmdDrawIndexedIndirect(cmd_, b.buffer, offset + uint64_t{i} * stride, 1, stride);
        stats_.api_calls += draw_count;
    }
    ++stats_.draw_calls;
}

void VulkanCommandList::dispatch(uint32_t x, uint32_t y, uint32_t z) {
    if (!accepted(state_.check_dispatch())) return;
    notice_removals();
    if (!flush_bindings(**device_.pipelines().get(state_.pipeline()), "dispatch")) return;  // found by the tracker
    vkCmdDispatch(cmd_, x, y, z);
    ++stats_.dispatches;
    ++stats_.api_calls;
}

// ---- copies and transitions -------------------------------------------------------------------

void VulkanCommandList::copy_buffer(rhi::BufferHandle src_handle, uint64_t src_offset, rhi::BufferHandle dst_handle,
                                    uint64_t dst_offset, uint64_t size) {
    if (!accepted(state_.check_outside_render_pass("copy_buffer"))) return;
    auto src = device_.buffers().get(src_handle);
    auto dst = device_.buffers().get(dst_handle);
    if (!src.ok()) return fail(ErrorCode::InvalidHandle, "copy_buffer source: " + src.error().message);
    if (!dst.ok()) return fail(ErrorCode::InvalidHandle, "copy_buffer destination: " + dst.error().message);
    Buffer& s = **src;
    Buffer& d = **dst;
    if (!accepted(rhi::validation::buffer_copy(s.desc, src_offset, d.desc, dst_offset, size, &s == &d))) return;
    if (size == 0) return;
    device_.take_over_bytes(s);
    if (&s != &d) device_.take_over_bytes(d);
    BarrierBatch batch;
    if (&s == &d) {
        // One buffer read and written: a global dependency covers both roles.
        batch.before_transfer();
    } else {
        batch.buffer(s.buffer, s.state, ResourceState::CopySrc);
        batch.buffer(d.buffer, d.state, ResourceState::CopyDst);
    }
    stats_.api_calls += batch.flush(cmd_);
    VkBufferCopy region{src_offset, dst_offset, size};
    vkCmdCopyBuffer(cmd_, s.buffer, d.buffer, 1, &region);
    // Copies leave buffers in the states they had (as on GL, where buffer states only
    // matter around storage access).
    if (&s == &d) {
        batch.after_transfer();
    } else {
        batch.buffer(s.buffer, ResourceState::CopySrc, s.state);
        batch.buffer(d.buffer, ResourceState::CopyDst, d.state);
    }
    stats_.api_calls += 1 + batch.flush(cmd_);
}

void VulkanCommandList::copy_texture(const rhi::TextureCopy& copy) {
    forget_written_sets();
    if (!accepted(state_.check_outside_render_pass("copy_texture"))) return;
    auto src = device_.textures().get(copy.src);
    auto dst = device_.textures().get(copy.dst);
    if (!src.ok()) return fail(ErrorCode::InvalidHandle, "copy_texture source: " + src.error().message);
    if (!dst.ok()) return fail(ErrorCode::InvalidHandle, "copy_texture destination: " + dst.error().message);
    Texture& s = **src;
    Texture& d = **dst;
    auto range = rhi::validation::texture_copy(s.desc, d.desc, &s == &d, copy);
    if (!range.ok()) return fail(range.error().code, range.error().message);
    const rhi::Extent3D extent = range->extent;
    // Like the GL backend, a copy leaves the source in CopySrc and the destination in CopyDst.
    BarrierBatch batch;
    device_.transition_texture(batch, s, range->src_mip, 1, range->src_layer, 1, ResourceState::CopySrc, Stream::Frame);
    device_.transition_texture(batch, d, range->dst_mip, 1, range->dst_layer, 1, ResourceState::CopyDst, Stream::Frame);
    stats_.api_calls += batch.flush(cmd_);
    VkImageCopy region{};
    const rhi::Origin3D& so = range->src_origin;
    const rhi::Origin3D& dso = range->dst_origin;
    region.srcSubresource = {s.aspect, range->src_mip, range->src_layer, 1};
    region.srcOffset = {static_cast<int32_t>(so.x), static_cast<int32_t>(so.y), static_cast<int32_t>(so.z)};
    region.dstSubresource = {d.aspect, range->dst_mip, range->dst_layer, 1};
    region.dstOffset = {static_cast<int32_t>(dso.x), static_cast<int32_t>(dso.y), static_cast<int32_t>(dso.z)};
    region.extent = {extent.width, extent.height, extent.depth};
    vkCmdCopyImage(cmd_, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    ++stats_.api_calls;
}

void VulkanCommandList::transition(rhi::TextureHandle handle, ResourceState state) {
    transition(handle, state, rhi::TextureRange{});
}

void VulkanCommandList::transition(rhi::TextureHandle handle, ResourceState state, const rhi::TextureRange& range) {
    forget_written_sets();
    if (!accepted(state_.check_outside_render_pass("transition"))) return;
    auto texture = device_.textures().get(handle);
    if (!texture.ok()) return fail(ErrorCode::InvalidHandle, "transition: " + texture.error().message);
    Texture& t = **texture;
    auto resolved = rhi::validation::texture_range_transition(t.desc, state, range, device_.capabilities());
    if (!resolved.ok()) return fail(resolved.error().code, resolved.error().message);
    if ((state == ResourceState::ShaderRead || state == ResourceState::DepthRead) && !t.sampled_view) {
        // Images loom did not make (the application's, the swapchain's) may lack SAMPLED usage.
        return fail(ErrorCode::Unsupported, "transition: texture " + in_quotes(t.desc.name) + " to " +
                                                std::string(rhi::resource_state_name(state)) +
                                                ": the image has no SAMPLED usage");
    }
    const rhi::TextureRange& r = *resolved;
    if (state == ResourceState::Undefined) {
        // Nothing to do on the GPU: the next transition discards the contents.
        for (uint32_t m = r.base_mip; m < r.base_mip + r.mip_count; ++m) {
            for (uint32_t l = r.base_layer; l < r.base_layer + r.layer_count; ++l) t.states[t.subresource(m, l)] = ResourceState::Undefined;
        }
        return;
    }
    BarrierBatch batch;
    device_.transition_texture(batch, t, r.base_mip, r.mip_count, r.base_layer, r.layer_count, state, Stream::Frame);
    stats_.api_calls += batch.flush(cmd_);
}

void VulkanCommandList::transition(rhi::BufferHandle handle, ResourceState state) {
    if (!accepted(state_.check_outside_render_pass("transition"))) return;
    auto buffer = device_.buffers().get(handle);
    if (!buffer.ok()) return fail(ErrorCode::InvalidHandle, "transition: " + buffer.error().message);
    Buffer& b = **buffer;
    if (!accepted(rhi::validation::buffer_transition(b.desc, state))) return;
    // A placed buffer whose bytes another alias used since starts over from Undefined: the
    // barrier then orders it after everything before (the aliasing hand-over).
    device_.take_over_bytes(b);
    BarrierBatch batch;
    batch.buffer(b.buffer, b.state, state);
    b.state = state;
    stats_.buffer_barriers += batch.buffer_barriers().size();
    stats_.api_calls += batch.flush(cmd_);
}

// ---- timers and debug groups ----------------------------------------------------------------

void VulkanCommandList::begin_timer(std::string_view label) {
    if (!accepted(state_.begin_timer(label))) return;
    FrameSlot& frame = device_.current_frame();
    if (!frame.timestamps) return;  // no timestamp support: timers report nothing
    if (frame.timer_labels.size() >= kMaxTimersPerFrame) {
        // The frame's query pool is full: the timer is open, without timestamps.
        return fail(ErrorCode::InvalidState, "begin_timer " + in_quotes(label) + ": more than " +
                                                 std::to_string(kMaxTimersPerFrame) + " timers in one frame");
    }
    const uint32_t index = static_cast<uint32_t>(frame.timer_labels.size());
    frame.timer_labels.emplace_back(label);
    vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, frame.timestamps, 2 * index);
    ++stats_.api_calls;
    timestamp_written_ = true;
}

void VulkanCommandList::end_timer() {
    if (!accepted(state_.end_timer()) || !timestamp_written_) return;
    FrameSlot& frame = device_.current_frame();
    const uint32_t index = static_cast<uint32_t>(frame.timer_labels.size() - 1);
    vkCmdWriteTimestamp2(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, frame.timestamps, 2 * index + 1);
    ++stats_.api_calls;
    timestamp_written_ = false;
}

void VulkanCommandList::push_debug_group(std::string_view label) {
    state_.push_debug_group();
    device_.context().begin_label(cmd_, label);
    ++stats_.api_calls;
}

void VulkanCommandList::pop_debug_group() {
    if (!accepted(state_.pop_debug_group())) return;
    device_.context().end_label(cmd_);
    ++stats_.api_calls;
}

// ---- queues ------------------------------------------------------------------------------------
// The state tracker checks; the device turns the calls into batches and semaphores
// (device_queues.cpp).

void VulkanCommandList::set_queue(rhi::QueueType queue) {
    if (!accepted(state_.set_queue(queue))) return;
    accepted(device_.switch_queue(queue));
}

rhi::QueueSignal VulkanCommandList::signal_queue() {
    auto signal = state_.signal_queue();
    if (!signal.ok()) {
        accepted(signal.take_error());
        return {};
    }
    accepted(device_.signal_queue(signal->index));
    return *signal;
}

void VulkanCommandList::wait_queue(rhi::QueueSignal signal) {
    if (!accepted(state_.wait_queue(signal))) return;
    accepted(device_.wait_queue(signal.index));
}

}  // namespace loom::vulkan
