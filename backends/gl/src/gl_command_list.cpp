// GlCommandList: validation, state tracking and resolution of each command at record time;
// the GL calls themselves run at end_frame() (see gl_frame.cpp).
#include <algorithm>
#include <cmath>

#include "gl_device.hpp"
#include "loom/rhi/binding_reuse.hpp"
#include "loom/rhi/subresources.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::gl {
namespace {

using rhi::ResourceState;

using rhi::validation::in_quotes;


/// Barrier bits that make shader storage writes visible to the use `next` stands for.
GLbitfield barrier_after_storage(ResourceState next) {
    switch (next) {
        case ResourceState::Undefined: return 0;
        case ResourceState::ShaderRead:
            return GL_TEXTURE_FETCH_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT |
                   GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
        case ResourceState::RenderTarget:
        case ResourceState::DepthWrite:
        case ResourceState::DepthRead:
        case ResourceState::Present: return GL_FRAMEBUFFER_BARRIER_BIT;
        case ResourceState::Storage: return GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT;
        case ResourceState::CopySrc:
        case ResourceState::CopyDst:
            return GL_TEXTURE_UPDATE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT;
        case ResourceState::VertexBuffer: return GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT;
        case ResourceState::IndexBuffer: return GL_ELEMENT_ARRAY_BARRIER_BIT;
        case ResourceState::IndirectArgument: return GL_COMMAND_BARRIER_BIT;
    }
    return GL_ALL_BARRIER_BITS;
}

/// GL's type of indices of `type` (above every vertex buffer slot: see VertexChange).
GLenum gl_index_type(rhi::IndexType type) {
    // GL_UNSIGNED_SHORT + 2 is GL_UNSIGNED_INT: arithmetic instead of a branch (per bound buffer).
    static_assert(static_cast<int>(rhi::IndexType::Uint16) == 0 && static_cast<int>(rhi::IndexType::Uint32) == 1 &&
                  GL_UNSIGNED_SHORT + 2 == GL_UNSIGNED_INT);
    return GL_UNSIGNED_SHORT + 2 * static_cast<GLenum>(type == rhi::IndexType::Uint32);
}
static_assert(GL_UNSIGNED_SHORT >= rhi::kMaxVertexBuffers && GL_UNSIGNED_INT >= rhi::kMaxVertexBuffers);

/// The GL clear call for one colour attachment, with the clear value in the attachment's kind.
void clear_color(GLuint fbo, GLint index, rhi::Format format, const std::array<double, 4>& value) {
    const rhi::ChannelKind kind = rhi::format_info(format).color_kind();
    if (kind == rhi::ChannelKind::Uint) {
        GLuint v[4];
        for (int i = 0; i < 4; ++i) v[i] = static_cast<GLuint>(std::clamp(std::nearbyint(value[static_cast<std::size_t>(i)]), 0.0, 4294967295.0));
        glClearNamedFramebufferuiv(fbo, GL_COLOR, index, v);
    } else if (kind == rhi::ChannelKind::Sint) {
        GLint v[4];
        for (int i = 0; i < 4; ++i) {
            v[i] = static_cast<GLint>(std::clamp(std::nearbyint(value[static_cast<std::size_t>(i)]), -2147483648.0, 2147483647.0));
        }
        glClearNamedFramebufferiv(fbo, GL_COLOR, index, v);
    } else {
        const GLfloat v[4] = {static_cast<float>(value[0]), static_cast<float>(value[1]), static_cast<float>(value[2]),
                              static_cast<float>(value[3])};
        glClearNamedFramebufferfv(fbo, GL_COLOR, index, v);
    }
}

}  // namespace

// ---- frame bookkeeping -----------------------------------------------------------------------

GlCommandList::GlCommandList(GlDevice& device)
    : device_(&device), state_(device.pipeline_lookup(), device.resource_lookup().buffer) {}

void GlCommandList::begin() {
    state_.begin_frame();
    commands_.clear();
    first_error_.reset();
    pass_framebuffer_ = 0;
    pass_discard_after_.clear();
    push_dirty_ = false;
    push_range_ = {};
    timers_.clear();
    draws_.clear();
    indirect_draws_.clear();
    draw_runs_.clear();
    draw_run_open_ = false;
    pipeline_states_.clear();
    vertex_states_.clear();
    binding_states_.clear();
    offset_override_ = {};
    draw_shared_valid_ = false;
    binding_state_drawn_ = vertex_state_indexed_ = false;
    draw_pipeline_ = nullptr;
    blends_.clear();
    vertex_bindings_.clear();
    vertex_changes_.clear();
    first_pending_change_ = 0;
    bindings_.clear();
    invalidate_draw_state();
    replayed_pipeline_ = replayed_vertex_ = replayed_bindings_ = UINT32_MAX;
    pipeline_draw_flags_ = 0;
}

std::vector<GlCommand>& GlCommandList::finish() {
    accepted(state_.check_nothing_open());
    if (state_.render_pass()) end_render_pass();
    if (state_.open_timer()) end_timer();
    while (state_.debug_group_depth() > 0) pop_debug_group();
    state_.end_frame();
    replayed_pipeline_ = replayed_vertex_ = replayed_bindings_ = UINT32_MAX;
    return commands_;
}

LOOM_GL_HOT uint64_t GlCommandList::device_removals() const {
    return device_->removals();
}

void GlCommandList::fail(ErrorCode code, std::string message) {
    if (!first_error_) first_error_ = Error{code, std::move(message)};
}

// ---- render passes ---------------------------------------------------------------------------

void GlCommandList::begin_render_pass(const rhi::RenderPassDesc& desc) {
    const std::string what = "begin_render_pass " + in_quotes(desc.label) + ": ";
    if (!accepted(state_.check_begin_render_pass(desc.label))) return;
    auto shape = rhi::validation::render_pass(desc, device_->capabilities(), device_->resource_lookup().texture);
    if (!shape.ok()) return fail(shape.take_error());
    // Every handle was found by the validation above.
    std::vector<std::pair<const GlTexture*, std::array<uint32_t, 2>>> colors;
    std::vector<GlTexture*> color_textures;
    for (const rhi::ColorAttachment& a : desc.colors) {
        GlTexture* t = *device_->textures().get(a.texture);
        colors.push_back({t, {a.mip, a.layer}});
        color_textures.push_back(t);
    }
    GlTexture* depth = desc.depth ? *device_->textures().get(desc.depth->texture) : nullptr;
    const GLuint fbo = device_->framebuffer_for(colors, depth, desc.depth ? std::array<uint32_t, 2>{desc.depth->mip, desc.depth->layer}
                                                                          : std::array<uint32_t, 2>{0, 0});
    if (fbo == 0) {
        fail(ErrorCode::Unsupported, what + "this combination of attachments is not a complete framebuffer on this device");
        return;
    }
    // The pass moves its attachments (one mip and layer each) into the attachment states itself;
    // storage writes to them become visible to the framebuffer first.
    bool after_storage = false;
    auto attach = [&](GlTexture& t, uint32_t mip, uint32_t layer, ResourceState state) {
        ResourceState& s = t.states[t.subresource(mip, t.layers() == 1 ? 0 : layer)];
        after_storage = after_storage || s == ResourceState::Storage;
        s = state;
    };
    for (std::size_t i = 0; i < desc.colors.size(); ++i) {
        attach(*color_textures[i], desc.colors[i].mip, desc.colors[i].layer, ResourceState::RenderTarget);
    }
    if (depth) attach(*depth, desc.depth->mip, desc.depth->layer, ResourceState::DepthWrite);
    if (after_storage) {
        record([](GlStateCache& cache) {
            glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
            cache.count_call();
        });
    }

    struct ColorClear {
        GLint index;
        rhi::Format format;
        std::array<double, 4> value;
    };
    std::vector<ColorClear> color_clears;
    std::vector<GLenum> discard_before;
    std::vector<GLenum> discard_after;
    for (std::size_t i = 0; i < desc.colors.size(); ++i) {
        const rhi::ColorAttachment& a = desc.colors[i];
        const auto index = static_cast<GLint>(i);
        if (a.load == rhi::LoadOp::Clear) color_clears.push_back({index, shape->color_formats[i], a.clear});
        if (a.load == rhi::LoadOp::DontCare) discard_before.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
        if (a.store == rhi::StoreOp::DontCare) discard_after.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    bool clear_depth = false, clear_stencil = false;
    float depth_value = 1.0f;
    GLint stencil_value = 0;
    if (desc.depth) {
        const rhi::FormatInfo& info = rhi::format_info(shape->depth_format);
        const rhi::DepthAttachment& d = *desc.depth;
        if (info.has_depth()) {
            clear_depth = d.depth_load == rhi::LoadOp::Clear;
            if (d.depth_load == rhi::LoadOp::DontCare) discard_before.push_back(GL_DEPTH_ATTACHMENT);
            if (d.depth_store == rhi::StoreOp::DontCare) discard_after.push_back(GL_DEPTH_ATTACHMENT);
        }
        if (info.has_stencil()) {
            clear_stencil = d.stencil_load == rhi::LoadOp::Clear;
            if (d.stencil_load == rhi::LoadOp::DontCare) discard_before.push_back(GL_STENCIL_ATTACHMENT);
            if (d.stencil_store == rhi::StoreOp::DontCare) discard_after.push_back(GL_STENCIL_ATTACHMENT);
        }
        depth_value = d.clear_depth;
        stencil_value = static_cast<GLint>(std::min<uint32_t>(d.clear_stencil, 255));
    }
    const uint32_t width = shape->width, height = shape->height;
    const auto color_count = static_cast<uint32_t>(desc.colors.size());
    record([=](GlStateCache& cache) {
        cache.bind_draw_framebuffer(fbo);
        if (!discard_before.empty()) {
            glInvalidateNamedFramebufferData(fbo, static_cast<GLsizei>(discard_before.size()), discard_before.data());
            cache.count_call();
        }
        if (!color_clears.empty() || clear_depth || clear_stencil) cache.prepare_clear(color_count);
        for (const ColorClear& c : color_clears) {
            clear_color(fbo, c.index, c.format, c.value);
            cache.count_call();
        }
        if (clear_depth && clear_stencil) {
            glClearNamedFramebufferfi(fbo, GL_DEPTH_STENCIL, 0, depth_value, stencil_value);
            cache.count_call();
        } else if (clear_depth) {
            glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &depth_value);
            cache.count_call();
        } else if (clear_stencil) {
            glClearNamedFramebufferiv(fbo, GL_STENCIL, 0, &stencil_value);
            cache.count_call();
        }
        cache.viewport(0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f);
        cache.scissor(0, 0, static_cast<int32_t>(width), static_cast<int32_t>(height));
    });
    state_.render_pass_begun(desc.label, std::move(*shape));
    pass_framebuffer_ = fbo;
    pass_discard_after_ = std::move(discard_after);
    device_->count_render_pass();
}

void GlCommandList::end_render_pass() {
    invalidate_draw_state();  // draws need another render pass, which resolves them anew
    if (!accepted(state_.end_render_pass())) return;
    if (!pass_discard_after_.empty()) {
        record([fbo = pass_framebuffer_, discard = std::move(pass_discard_after_)](GlStateCache& cache) {
            glInvalidateNamedFramebufferData(fbo, static_cast<GLsizei>(discard.size()), discard.data());
            cache.count_call();
        });
    }
    pass_discard_after_.clear();
}

// ---- state -----------------------------------------------------------------------------------

void GlCommandList::set_pipeline(rhi::PipelineHandle pipeline) {
    // The tracker checks the pipeline against the open pass; GL binds it at the next draw.
    if (pipeline != state_.pipeline()) invalidate_draw_state();
    if (!accepted(state_.set_pipeline(pipeline))) invalidate_draw_state();
}

void GlCommandList::set_viewport(const rhi::Viewport& v) {
    if (state_.validating() && !accepted(rhi::validation::viewport(v))) return;
    // With the upper-left origin, GL window y runs down from row 0, exactly like loom's
    // top-left viewport rectangles: no flip.
    record([v](GlStateCache& cache) { cache.viewport(v.x, v.y, v.width, v.height, v.min_depth, v.max_depth); });
}

void GlCommandList::set_scissor(const rhi::Rect& r) {
    record([r](GlStateCache& cache) {
        cache.scissor(r.x, r.y, static_cast<int32_t>(r.width), static_cast<int32_t>(r.height));
    });
}

LOOM_GL_HOT bool GlCommandList::takes_new_offset(std::size_t i, const rhi::BufferBinding& range) {
    auto* then = std::get_if<rhi::BufferBinding>(&resolved_entries_[i].resource);
    // Size 0 means "to the end": its range moves with the offset, so it is resolved anew.
    if (!then || then->buffer != range.buffer || then->size != range.size || range.size == 0) return false;
    if (range.offset == then->offset) return true;
    // A new offset of a uniform range in the same (living) buffer: checked here as the full
    // check would.
    if (draw_pipeline_->bindings[i].kind != BindingKind::UniformBuffer) return false;
    if (state_.validating()) {
        const GlBuffer* buffer = device_->buffers().find(range.buffer);
        if (!buffer ||
            !rhi::uniform_offset_fits(range, buffer->desc.size, device_->capabilities().uniform_buffer_offset_alignment)) {
            return false;
        }
    }
    then->offset = range.offset;
    return true;
}

LOOM_GL_HOT void GlCommandList::next_binding_state() {
    const BindingState last = binding_states_.back();
    BindingState next;
    next.first_binding = static_cast<uint32_t>(bindings_.size());
    next.binding_count = last.binding_count;
    for (uint32_t i = 0; i < last.binding_count; ++i) bindings_.push_back(bindings_[last.first_binding + i]);
    if (offset_override_.binding != kNoOverride) {
        bindings_[next.first_binding + (offset_override_.binding - last.first_binding)].offset = offset_override_.offset;
        offset_override_ = {};
    }
    binding_states_.push_back(next);
    binding_state_drawn_ = false;
    draw_shared_valid_ = false;
}

// Bind groups, push constants and vertex and index buffers are kept by the tracker and
// resolved to GL names at each draw or dispatch.
void GlCommandList::set_bind_group(uint32_t set, const rhi::BindGroup& group) {
    invalidate_binding_state();
    accepted(state_.set_bind_group(set, group));
}

LOOM_GL_HOT bool GlCommandList::rebinds_offset(uint32_t set, uint32_t binding, const rhi::BufferBinding& range,
                                               bool transient) {
    if (!binding_state_valid_ || !pipeline_state_valid_) return false;
    const std::vector<PipelineBinding>& bindings = draw_pipeline_->bindings;
    // Per-draw data rebinds the same binding draw after draw: try the last one found first.
    std::size_t i = last_rebound_;
    if (i >= bindings.size() || bindings[i].set != set || bindings[i].binding != binding) {
        i = 0;
        while (i < bindings.size() && (bindings[i].set != set || bindings[i].binding != binding)) ++i;
        if (i == bindings.size()) return true;  // the pipeline does not read it: its draws are unchanged
        last_rebound_ = i;
    }
    if (transient) {
        // The device's own transient memory: alive, aligned and inside by construction.
        auto* then = std::get_if<rhi::BufferBinding>(&resolved_entries_[i].resource);
        if (!then || then->buffer != range.buffer || then->size != range.size ||
            bindings[i].kind != BindingKind::UniformBuffer) {
            return false;
        }
        then->offset = range.offset;
    } else if (!takes_new_offset(i, range)) {
        return false;
    }
    const auto resolved = static_cast<uint32_t>(binding_states_.back().first_binding + i);
    const auto offset = static_cast<GLintptr>(range.offset);
    if (offset_override_.binding == resolved) {
        offset_override_.offset = offset;  // the next draws rebind it at the new offset
    } else if (!binding_state_drawn_) {
        bindings_[resolved].offset = offset;
    } else if (offset_override_.binding == kNoOverride) {
        // Drawn with the old offset: the next draws carry the new one instead of a copy of
        // the whole binding state (one uniform range per draw is the common case).
        offset_override_ = {resolved, offset};
        draw_shared_valid_ = false;
    } else {
        next_binding_state();  // a second range changes: copy the state (with the override)
        bindings_[binding_states_.back().first_binding + i].offset = offset;
    }
    return true;
}

void GlCommandList::set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) {
    // Per-draw uniform data: while the bindings resolved for the draws before still hold, a new
    // offset in the same buffer changes one offset of them, checked here, and the next draw
    // stays on the short path.
    if (!accepted(state_.set_buffer(set, binding, range)) ||
        !(draw_state_removals_ == device_removals() && rebinds_offset(set, binding, range, false))) {
        invalidate_binding_state();
    }
}

void GlCommandList::set_uniforms(uint32_t set, uint32_t binding, std::span<const std::byte> data) {
    if (!accepted(state_.check_recording("set_uniforms"))) return;
    const rhi::BufferBinding range = device_->allocate_transient(data);
    const bool replaced = state_.replace_buffer(set, binding, range) || accepted(state_.set_buffer(set, binding, range));
    if (!replaced || !rebinds_offset(set, binding, range, true)) invalidate_binding_state();
}

void GlCommandList::push_constants(std::span<const std::byte> data, uint32_t offset) {
    if (accepted(state_.push_constants(data, offset))) push_dirty_ = true;
}

// A vertex or index buffer is recorded as a VertexChange that the next draw applies on top of
// the vertex state it draws with: a state resolved after the change (a new pipeline, a refused
// or non-draw command between) drops the changes pending, as it holds them already. Found alive
// and fit when bound, the buffer keeps the checked draw valid. The common case is inline and
// makes no call, so that it needs no stack frame; the rest is out of line.
void GlCommandList::set_vertex_buffer(uint32_t slot, rhi::BufferHandle buffer, uint64_t offset) {
    const GlBuffer* found = device_->buffers().find(buffer);
    if (found && vertex_changes_.has_room() && state_.replace_vertex_buffer(slot, buffer, found->desc, offset)) [[likely]] {
        vertex_changes_.push_back_in_room({slot, found->name, static_cast<GLintptr>(offset)});
        return;
    }
    set_vertex_buffer_slow(slot, buffer, found, offset);
}

void GlCommandList::set_vertex_buffer_slow(uint32_t slot, rhi::BufferHandle buffer, const GlBuffer* found,
                                           uint64_t offset) {
    if (!accepted(state_.set_vertex_buffer(slot, buffer, found ? &found->desc : nullptr, offset))) {
        invalidate_vertex_state();
        return;
    }
    vertex_changes_.push_back({slot, found ? found->name : 0, static_cast<GLintptr>(offset)});  // null only unchecked
}

void GlCommandList::set_index_buffer(rhi::BufferHandle buffer, rhi::IndexType type, uint64_t offset) {
    const GlBuffer* found = device_->buffers().find(buffer);
    if (found && vertex_changes_.has_room() && state_.replace_index_buffer(buffer, found->desc, type, offset)) [[likely]] {
        vertex_changes_.push_back_in_room({gl_index_type(type), found->name, static_cast<GLintptr>(offset)});
        return;
    }
    set_index_buffer_slow(buffer, found, type, offset);
}

void GlCommandList::set_index_buffer_slow(rhi::BufferHandle buffer, const GlBuffer* found, rhi::IndexType type,
                                          uint64_t offset) {
    if (!accepted(state_.set_index_buffer(buffer, found ? &found->desc : nullptr, type, offset))) {
        invalidate_vertex_state();
        return;
    }
    vertex_changes_.push_back({gl_index_type(type), found ? found->name : 0, static_cast<GLintptr>(offset)});
}

rhi::BufferBinding GlCommandList::transient_uniforms(std::span<const std::byte> data) {
    if (!accepted(state_.check_recording("transient_uniforms"))) return {};
    return device_->allocate_transient(data);
}

// ---- bindings --------------------------------------------------------------------------------

bool GlCommandList::resolve_bindings(const GlPipeline& p, std::string_view command) {
    // Every binding is checked before any state, as on Vulkan (unless validation is off: then
    // the bindings are taken to be what the pipeline reads, alive).
    const rhi::validation::ResourceLookup& lookup = device_->resource_lookup();
    resolved_entries_.clear();
    for (const PipelineBinding& b : state_.validating() ? std::span(p.bindings) : std::span<const PipelineBinding>()) {
        const rhi::validation::PipelineSlot slot{b.set, b.binding, b.kind, b.name, b.texture_kind};
        auto entry =
            rhi::validation::binding(command, p.name, slot, state_.bind_group(b.set), device_->capabilities(), lookup);
        if (!entry.ok()) {
            fail(entry.take_error());
            return false;
        }
    }
    for (const PipelineBinding& b : p.bindings) {
        const rhi::validation::PipelineSlot slot{b.set, b.binding, b.kind, b.name, b.texture_kind};
        // Found by the check above.
        const rhi::BindingEntry* entry = rhi::bound_entry(state_.bind_group(b.set), b.binding);
        resolved_entries_.push_back(*entry);
        // The handles were found by the validation above.
        ResolvedBinding r;
        r.kind = b.kind;
        r.point = rhi::gl_binding_point(b.set, b.binding);
        switch (b.kind) {
            case BindingKind::UniformBuffer:
            case BindingKind::StorageBuffer: {
                const auto& range = std::get<rhi::BufferBinding>(entry->resource);
                const GlBuffer& buf = **device_->buffers().get(range.buffer);
                r.object = buf.name;
                r.offset = static_cast<GLintptr>(range.offset);
                r.size = static_cast<GLsizeiptr>(range.size ? range.size : buf.desc.size - range.offset);
                break;
            }
            case BindingKind::SampledTexture: {
                const auto& tb = std::get<rhi::TextureBinding>(entry->resource);
                GlTexture& t = **device_->textures().get(tb.texture);
                const bool depth = rhi::format_info(t.desc.format).is_depth_stencil();
                const rhi::validation::BoundRange bound = rhi::validation::bound_range(slot, t.desc, *entry);
                // Parity with Vulkan, where sampling needs the shader-read layout: the bound
                // subresources in ShaderRead (depth: all in DepthRead or all in ShaderRead).
                auto all_in = [&](ResourceState wanted) {
                    bool all = true;
                    t.for_each_in(bound.range, [&](std::size_t i) { all = all && t.states[i] == wanted; });
                    return all;
                };
                if (!all_in(ResourceState::ShaderRead) && !(depth && all_in(ResourceState::DepthRead))) {
                    ResourceState found = ResourceState::ShaderRead;
                    t.for_each_in(bound.range, [&](std::size_t i) {
                        if (found == ResourceState::ShaderRead && t.states[i] != ResourceState::ShaderRead) found = t.states[i];
                    });
                    Error e = rhi::validation::state_for_binding(command, p.name, slot, t.desc.name, found,
                                                                 depth ? "DepthRead or ShaderRead" : "ShaderRead");
                    fail(e.code, e.message);
                    return false;
                }
                r.object = t.name;
                if (!bound.whole) {
                    // A range, or the texture seen as another dimension: a view of it.
                    auto view = device_->texture_view(t, bound.range, bound.kind);
                    if (!view.ok()) {
                        Error e = view.take_error();
                        e.message = std::string(command) + ": pipeline " + in_quotes(p.name) + " binding " + in_quotes(b.name) + ": " + e.message;
                        fail(std::move(e));
                        return false;
                    }
                    r.object = *view;
                }
                r.sampler = (*device_->samplers().get(tb.sampler))->name;
                break;
            }
            case BindingKind::StorageImage: {
                const auto& sb = std::get<rhi::StorageTextureBinding>(entry->resource);
                GlTexture& t = **device_->textures().get(sb.texture);
                const rhi::validation::BoundRange bound = rhi::validation::bound_range(slot, t.desc, *entry);
                ResourceState found = ResourceState::Storage;
                t.for_each_in(bound.range, [&](std::size_t i) {
                    if (found == ResourceState::Storage && t.states[i] != ResourceState::Storage) found = t.states[i];
                });
                if (found != ResourceState::Storage) {
                    Error e = rhi::validation::state_for_binding(command, p.name, slot, t.desc.name, found, "Storage");
                    fail(e.code, e.message);
                    return false;
                }
                r.object = t.name;
                r.level = static_cast<GLint>(sb.mip);
                r.access = b.image_access;
                r.format = t.format->internal_format;
                if (bound.kind == rhi::TextureKind::Tex2D) {
                    // One layer of an array or cube (or a 2D texture): bound unlayered.
                    r.layered = false;
                    r.layer = static_cast<GLint>(bound.range.base_layer);
                } else if (bound.whole || t.layers() == 1) {
                    // Every layer (or slice of a 3D texture) as the texture has them.
                    r.layered = true;
                } else {
                    // Some layers, or a 2D texture or cube seen as an array: a view of the level.
                    auto view = device_->texture_view(t, rhi::TextureRange{sb.mip, 1, bound.range.base_layer, bound.range.layer_count},
                                                      bound.kind);
                    if (!view.ok()) {
                        Error e = view.take_error();
                        e.message = std::string(command) + ": pipeline " + in_quotes(p.name) + " binding " + in_quotes(b.name) + ": " + e.message;
                        fail(std::move(e));
                        return false;
                    }
                    r.object = *view;
                    r.level = 0;
                    r.layered = true;
                }
                break;
            }
        }
        bindings_.push_back(r);
    }
    return true;
}

GlCommandList::PushRange GlCommandList::push_constant_range(const GlPipeline& p) {
    if (p.push_constant_size == 0) return {};
    if (!push_constants_current(p)) copy_push_constants(p);
    return push_range_;
}

LOOM_GL_HOT void GlCommandList::copy_push_constants(const GlPipeline& p) {
    const uint32_t size = std::max(p.push_constant_size, state_.push_constant_size());
    const rhi::BufferBinding copy = device_->allocate_transient(state_.push_constant_data().first(size), &push_range_.object);
    push_range_.offset = static_cast<GLintptr>(copy.offset);
    push_range_.size = static_cast<GLsizeiptr>(copy.size);
    push_dirty_ = false;
}

// ---- draws and dispatches --------------------------------------------------------------------

LOOM_GL_HOT void GlCommandList::apply_bindings(GlStateCache& cache, uint32_t first, uint32_t count) const {
    for (uint32_t i = first; i < first + count; ++i) {
        const ResolvedBinding& b = bindings_[i];
        switch (b.kind) {
            case BindingKind::UniformBuffer: cache.bind_uniform_buffer(b.point, b.object, b.offset, b.size); break;
            case BindingKind::StorageBuffer: cache.bind_storage_buffer(b.point, b.object, b.offset, b.size); break;
            case BindingKind::SampledTexture:
                cache.bind_texture(b.point, b.object);
                cache.bind_sampler(b.point, b.sampler);
                break;
            case BindingKind::StorageImage:
                cache.bind_image(b.point, b.object, b.level, b.layered, b.layer, b.access, b.format);
                break;
        }
    }
}

LOOM_GL_HOT bool GlCommandList::draw_state_current(bool indexed, bool indirect) {
    // Draws with nothing bound, begun, recorded or destroyed between them share the state
    // checked and resolved for the first: a later draw costs its arguments only, or the part
    // that changed (a bind group, the vertex buffers).
    if (draw_state_removals_ != device_removals() || indirect ||
        (indexed && vertex_state_valid_ && !vertex_state_indexed_)) {
        invalidate_draw_state();  // objects may be gone, or checks that only these draws need
        return false;
    }
    return pipeline_state_valid_ && vertex_state_valid_ && binding_state_valid_;
}

bool GlCommandList::prepare_draw_state(const char* command, bool indexed, bool indirect) {
    // Only the bindings changed (nothing recorded, destroyed, or bound but bind groups since
    // they were resolved): they may be the same but for uniform offsets.
    const bool reuse_allowed = pipeline_state_valid_ && !binding_states_.empty();
    // The render pass, the pipeline against it, the vertex and index buffers it reads. Binding
    // vertex or index buffers (each found alive and fit when bound) keeps a checked draw valid,
    // but for the index buffer of the first indexed draw after non-indexed ones.
    if (!pipeline_state_valid_ || (indexed && !draw_checked_indexed_)) {
        if (!accepted(state_.check_draw(command, indexed))) return false;
        draw_checked_indexed_ = indexed;
    }
    if (!pipeline_state_valid_) {
        // The tracker found the pipeline alive.
        const GlPipeline* p = *device_->pipelines().get(state_.pipeline());
        if (indirect && p->base_instance_location >= 0) {
            // GL offsets gl_InstanceIndex by a uniform set per draw: one call cannot give each
            // command its own first instance (per-instance attributes are offset by GL itself).
            fail(ErrorCode::Unsupported, std::string(command) + ": pipeline " + in_quotes(p->name) +
                                             " reads gl_InstanceIndex, which GL's indirect draws cannot offset by each "
                                             "command's first instance; use a per-instance vertex attribute");
            return false;
        }
        PipelineState d;
        d.program = p->program;
        d.topology = p->topology;
        d.raster = p->raster;
        d.base_instance_location = p->base_instance_location;
        d.first_blend = static_cast<uint32_t>(blends_.size());
        d.blend_count = static_cast<uint32_t>(p->blend.size());
        blends_.insert(blends_.end(), p->blend.begin(), p->blend.end());
        pipeline_states_.push_back(d);
        draw_pipeline_ = p;
        pipeline_draw_flags_ = static_cast<uint8_t>((p->push_constant_size != 0 ? kDrawPush : 0) |
                                                    (p->base_instance_location >= 0 ? kDrawBaseInstance : 0));
        // Vertex buffers go on the pipeline's vertex array; bindings follow its layout.
        vertex_state_valid_ = binding_state_valid_ = false;
    }
    const GlPipeline& p = *draw_pipeline_;
    if (!vertex_state_valid_) {
        const rhi::CommandListState::IndexBuffer& bound_indices = state_.index_buffer();
        if (indirect && bound_indices.offset != 0) {
            // GL's indirect draws count first_index from the start of the element buffer.
            fail(ErrorCode::InvalidArgument, std::string(command) + ": the index buffer must be bound at offset 0");
            return false;
        }
        VertexState v;
        v.vao = p.vao;
        v.first_vertex_binding = static_cast<uint32_t>(vertex_bindings_.size());
        v.vertex_binding_count = static_cast<uint32_t>(p.strides.size());
        for (uint32_t slot = 0; slot < p.strides.size(); ++slot) {
            const rhi::CommandListState::VertexBuffer& vb = state_.vertex_buffer(slot);
            vertex_bindings_.push_back({slot, (*device_->buffers().get(vb.buffer))->name, static_cast<GLintptr>(vb.offset),
                                        static_cast<GLsizei>(p.strides[slot])});
        }
        if (indexed) {
            v.index_buffer = (*device_->buffers().get(bound_indices.buffer))->name;
            v.index_type = gl_index_type(bound_indices.type);
            v.index_offset = bound_indices.offset;
        }
        vertex_states_.push_back(v);
        vertex_state_indexed_ = v.index_buffer != 0;
        vertex_changes_.shrink_to(first_pending_change_);  // the tracker's buffers are in the new state
    }
    if (!binding_state_valid_ && reuse_bindings(p, reuse_allowed)) {
        binding_state_valid_ = true;
    }
    if (!binding_state_valid_) {
        BindingState b;
        b.first_binding = static_cast<uint32_t>(bindings_.size());
        offset_override_ = {};  // the bound groups hold every offset the new state resolves
        if (!resolve_bindings(p, command)) {
            bindings_.shrink_to(b.first_binding);
            binding_states_.push_back(b);  // keeps the indices of the others in step; never drawn
            binding_state_drawn_ = false;
            return false;
        }
        b.binding_count = static_cast<uint32_t>(bindings_.size()) - b.first_binding;
        binding_states_.push_back(b);
        binding_state_drawn_ = false;
    }
    pipeline_state_valid_ = vertex_state_valid_ = binding_state_valid_ = true;
    draw_state_removals_ = device_removals();
    return true;
}

void GlCommandList::replay_shared_states(GlStateCache& cache, const Draw& draw) {
    if (draw.pipeline_state != replayed_pipeline_) {
        const PipelineState& p = pipeline_states_[draw.pipeline_state];
        cache.use_program(p.program);
        cache.raster(p.raster);
        for (uint32_t i = 0; i < p.blend_count; ++i) cache.blend(i, blends_[p.first_blend + i]);
        cache.enable(GL_SCISSOR_TEST, true);
        replayed_topology_ = p.topology;
        replayed_pipeline_ = draw.pipeline_state;
    }
    if (draw.vertex_state != replayed_vertex_) {
        const VertexState& v = vertex_states_[draw.vertex_state];
        cache.bind_vertex_array(v.vao);
        for (uint32_t i = v.first_vertex_binding; i < v.first_vertex_binding + v.vertex_binding_count; ++i) {
            const VertexBinding& b = vertex_bindings_[i];
            cache.vertex_buffer(v.vao, b.slot, b.buffer, b.offset, b.stride);
        }
        if (v.index_buffer != 0) cache.element_buffer(v.vao, v.index_buffer);
        replayed_index_type_ = v.index_type;
        replayed_index_offset_ = v.index_offset;
        replayed_vertex_ = draw.vertex_state;
    }
    if (draw.binding_state != replayed_bindings_) {
        const BindingState& b = binding_states_[draw.binding_state];
        apply_bindings(cache, b.first_binding, b.binding_count);
        replayed_bindings_ = draw.binding_state;
    }
}

void GlCommandList::replay_run(GlStateCache& cache, DrawRun run) {
    // Pointers held in registers: the GL calls between could change any memory, as far as the
    // compiler knows, so fields of *this would be read again per draw.
    const Draw* draw = &draws_[run.first];
    for (const Draw* end = draw + run.count; draw != end; ++draw) replay_draw(cache, *draw);
}

LOOM_GL_HOT void GlCommandList::replay_vertex_changes(GlStateCache& cache, const Draw& draw) {
    const VertexState& v = vertex_states_[draw.vertex_state];
    GlStateCache::VaoState& vao = cache.vao_state(v.vao);
    const VertexBinding* slots = &vertex_bindings_[v.first_vertex_binding];
    const VertexChange* c = &vertex_changes_[draw.first_vertex_change];
    for (const VertexChange* end = c + draw.vertex_change_count; c != end; ++c) {
        if (c->slot < v.vertex_binding_count) {
            cache.vertex_buffer(vao, v.vao, c->slot, c->buffer, c->offset, slots[c->slot].stride);
        } else if (c->slot >= rhi::kMaxVertexBuffers) {  // else a slot the pipeline does not read
            cache.element_buffer(vao, v.vao, c->buffer);
            replayed_index_type_ = c->slot;
            replayed_index_offset_ = static_cast<uint64_t>(c->offset);
        }
    }
}

LOOM_GL_HOT void GlCommandList::replay_draw(GlStateCache& cache, const Draw& draw) {
    // The shared states change between runs of draws (out of line); per draw come the buffers
    // bound since the last draw, per-draw uniform ranges, and the call.
    if (draw.flags & kDrawNewState) [[unlikely]] replay_shared_states(cache, draw);
    if (draw.vertex_change_count != 0) replay_vertex_changes(cache, draw);
    if (draw.flags & (kDrawOverride | kDrawPush | kDrawBaseInstance)) {
        if (draw.flags & kDrawOverride) {
            const ResolvedBinding& b = bindings_[draw.override_binding];
            cache.bind_uniform_buffer(b.point, b.object, draw.override_offset, b.size);
        }
        if (draw.flags & kDrawPush) {
            cache.bind_uniform_buffer(rhi::kGlPushConstantBinding, draw.push.object, draw.push.offset, draw.push.size);
        }
        if (draw.flags & kDrawBaseInstance) {
            const PipelineState& p = pipeline_states_[draw.pipeline_state];
            cache.base_instance(p.program, p.base_instance_location, static_cast<GLint>(draw.first_instance));
        }
    }
    if (draw.flags & kDrawIndirect) [[unlikely]] {
        const IndirectDraw& args = indirect_draws_[draw.first];
        // The argument buffer binding is not shadowed by the cache; it is bound for each
        // multi-draw (one call for many draws).
        glBindBuffer(GL_DRAW_INDIRECT_BUFFER, args.buffer);
        glMultiDrawElementsIndirect(replayed_topology_, replayed_index_type_, reinterpret_cast<const void*>(args.offset),
                                    args.count, args.stride);
        cache.count_call(2);
        cache.count_draw();
        return;
    }
    // One instance from instance 0 (and vertex 0) is GL's plain call, which costs the driver
    // less than the instanced forms.
    const bool plain = ((draw.instance_count ^ 1u) | static_cast<uint32_t>(draw.base_vertex) | draw.first_instance) == 0;
    if (draw.flags & kDrawIndexed) {
        // Inside the buffer (checked at record time).
        const uint64_t index_bytes = replayed_index_type_ == GL_UNSIGNED_SHORT ? 2 : 4;
        const auto* offset = reinterpret_cast<const void*>(
            static_cast<uintptr_t>(replayed_index_offset_ + uint64_t{draw.first} * index_bytes));
        if (plain) {
            glDrawElements(replayed_topology_, static_cast<GLsizei>(draw.count), replayed_index_type_, offset);
        } else {
            glDrawElementsInstancedBaseVertexBaseInstance(replayed_topology_, static_cast<GLsizei>(draw.count),
                                                          replayed_index_type_, offset,
                                                          static_cast<GLsizei>(draw.instance_count), draw.base_vertex,
                                                          draw.first_instance);
        }
    } else if (plain) {
        glDrawArrays(replayed_topology_, static_cast<GLint>(draw.first), static_cast<GLsizei>(draw.count));
    } else {
        glDrawArraysInstancedBaseInstance(replayed_topology_, static_cast<GLint>(draw.first), static_cast<GLsizei>(draw.count),
                                          static_cast<GLsizei>(draw.instance_count), draw.first_instance);
    }
    cache.count_call();
    cache.count_draw();
}

void GlCommandList::draw_common(bool indexed, uint32_t count, uint32_t instance_count, uint32_t first, int32_t base_vertex,
                                uint32_t first_instance, const std::optional<IndirectDraw>& indirect) {
    // Most draws find the state checked and resolved for the previous one still current.
    const char* command = indirect ? "draw_indexed_indirect" : indexed ? "draw_indexed" : "draw";
    const bool is_indirect = indirect.has_value();
    if (!draw_state_current(indexed, is_indirect) && !prepare_draw_state(command, indexed, is_indirect)) {
        // A refused draw leaves state resolved in part: the next one starts again.
        invalidate_draw_state();
        return;
    }
    // Now, before any early return: the inline paths of the draws after this one take push_range_
    // as the draw pipeline's block while the push constants are unchanged.
    push_constant_range(*draw_pipeline_);
    // Indirect draws' index ranges are in GPU memory: the GPU checks them.
    if (indexed && !indirect && !accepted(state_.check_index_range(first, count))) return;
    // Checked like any other draw (as Vulkan records it), then nothing to draw.
    if (indirect ? indirect->count == 0 : (count == 0 || instance_count == 0)) return;
    uint32_t indirect_index = UINT32_MAX;
    if (indirect) {
        indirect_index = static_cast<uint32_t>(indirect_draws_.size());
        indirect_draws_.push_back(*indirect);
    }
    draws_.make_room();
    draw_shared_ = {.pipeline_state = static_cast<uint32_t>(pipeline_states_.size() - 1),
                    .vertex_state = static_cast<uint32_t>(vertex_states_.size() - 1),
                    .binding_state = static_cast<uint32_t>(binding_states_.size() - 1),
                    .override_binding = offset_override_.binding,
                    .flags = static_cast<uint8_t>(pipeline_draw_flags_ |
                                                  (offset_override_.binding != kNoOverride ? kDrawOverride : 0))};
    draw_shared_valid_ = true;
    const auto flags = static_cast<uint8_t>(kDrawNewState | (indexed ? kDrawIndexed : 0) | (indirect ? kDrawIndirect : 0));
    append_draw(flags, count, instance_count, indirect ? indirect_index : first, base_vertex, first_instance);
    if (draw_run_open_) {
        ++draw_runs_.back().count;
    } else {
        open_draw_run();
    }
}

LOOM_GL_HOT void GlCommandList::append_draw(uint8_t flags, uint32_t count, uint32_t instance_count, uint32_t first,
                                            int32_t base_vertex, uint32_t first_instance) {
    const auto first_change = static_cast<uint32_t>(first_pending_change_);
    first_pending_change_ = vertex_changes_.size();
    // Written once, in place (the pipeline was found alive for this state: nothing destroyed since).
    const DrawShared& shared = draw_shared_;
    draws_.push_back_in_room(Draw{.pipeline_state = shared.pipeline_state,
                                  .vertex_state = shared.vertex_state,
                                  .binding_state = shared.binding_state,
                                  .count = count,
                                  .instance_count = instance_count,
                                  .first = first,
                                  .base_vertex = base_vertex,
                                  .first_instance = first_instance,
                                  .first_vertex_change = first_change,
                                  .vertex_change_count = static_cast<uint32_t>(first_pending_change_ - first_change),
                                  .override_binding = shared.override_binding,
                                  .flags = static_cast<uint8_t>(shared.flags | flags),
                                  .override_offset = offset_override_.offset,
                                  .push = push_range_});
    binding_state_drawn_ = true;
}

void GlCommandList::open_draw_run() {
    const auto run = static_cast<uint32_t>(draw_runs_.size());
    draw_runs_.push_back({static_cast<uint32_t>(draws_.size() - 1), 1});
    draw_run_open_ = true;
    // Small enough for std::function to hold without allocating.
    commands_.push_back([this, run](GlStateCache& cache) { replay_run(cache, draw_runs_[run]); });
}

// A draw whose state is current (draw_shared_valid_: nothing bound but per-draw data since the
// draw before; nothing destroyed), inside an open run, with room for its record is appended
// inline: the common case makes no call and needs no stack frame. Changed push constants are
// copied first, out of line (a tail call); anything else takes draw_common. push_range_ holds
// the draw pipeline's block unless push_dirty_: draw_common copied it when the state was made.
void GlCommandList::draw(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance) {
    if (draw_shared_valid_ && draws_.has_room() && draw_state_removals_ == device_removals() && vertex_count != 0 &&
        instance_count != 0) [[likely]] {
        if (push_dirty_ && draw_pipeline_->push_constant_size != 0) [[unlikely]] {
            draw_copying_push_constants(vertex_count, instance_count, first_vertex, first_instance);
            return;
        }
        append_draw(0, vertex_count, instance_count, first_vertex, 0, first_instance);
        ++draw_runs_.back().count;  // open: draw_shared_valid_ holds
        return;
    }
    draw_slow(vertex_count, instance_count, first_vertex, first_instance);
}

void GlCommandList::draw_copying_push_constants(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex,
                                                uint32_t first_instance) {
    copy_push_constants(*draw_pipeline_);
    append_draw(0, vertex_count, instance_count, first_vertex, 0, first_instance);
    ++draw_runs_.back().count;  // open: draw_shared_valid_ holds
}

void GlCommandList::draw_slow(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance) {
    draw_common(false, vertex_count, instance_count, first_vertex, 0, first_instance);
}

void GlCommandList::draw_indexed(uint32_t index_count, uint32_t instance_count, uint32_t first_index, int32_t base_vertex,
                                 uint32_t first_instance) {
    if (draw_shared_valid_ && vertex_state_indexed_ && draws_.has_room() &&
        draw_state_removals_ == device_removals() && index_count != 0 &&
        instance_count != 0 && state_.index_range_fits(first_index, index_count)) [[likely]] {
        if (push_dirty_ && draw_pipeline_->push_constant_size != 0) [[unlikely]] {
            draw_indexed_copying_push_constants(index_count, instance_count, first_index, base_vertex, first_instance);
            return;
        }
        append_draw(kDrawIndexed, index_count, instance_count, first_index, base_vertex, first_instance);
        ++draw_runs_.back().count;  // open: draw_shared_valid_ holds
        return;
    }
    draw_indexed_slow(index_count, instance_count, first_index, base_vertex, first_instance);
}

void GlCommandList::draw_indexed_copying_push_constants(uint32_t index_count, uint32_t instance_count,
                                                        uint32_t first_index, int32_t base_vertex,
                                                        uint32_t first_instance) {
    copy_push_constants(*draw_pipeline_);
    append_draw(kDrawIndexed, index_count, instance_count, first_index, base_vertex, first_instance);
    ++draw_runs_.back().count;  // open: draw_shared_valid_ holds
}

void GlCommandList::draw_indexed_slow(uint32_t index_count, uint32_t instance_count, uint32_t first_index,
                                      int32_t base_vertex, uint32_t first_instance) {
    draw_common(true, index_count, instance_count, first_index, base_vertex, first_instance);
}

void GlCommandList::draw_indexed_indirect(rhi::BufferHandle buffer, uint64_t offset, uint32_t draw_count,
                                          uint32_t stride) {
    const char* command = "draw_indexed_indirect";
    auto found = device_->buffers().get(buffer);
    if (!found.ok()) return fail(ErrorCode::InvalidHandle, std::string(command) + ": argument buffer: " + found.error().message);
    const GlBuffer& b = **found;
    if (state_.validating() && !accepted(rhi::validation::indirect_draws(b.desc, offset, draw_count, stride))) return;
    draw_common(true, 0, 0, 0, 0, 0,
                IndirectDraw{b.name, static_cast<uintptr_t>(offset), static_cast<GLsizei>(draw_count), static_cast<GLsizei>(stride)});
}

bool GlCommandList::reuse_bindings(const GlPipeline& p, bool allowed) {
    if (!allowed || resolved_entries_.size() != p.bindings.size()) return false;
    for (std::size_t i = 0; i < p.bindings.size(); ++i) {
        const PipelineBinding& b = p.bindings[i];
        const rhi::BindingEntry* entry = rhi::bound_entry(state_.bind_group(b.set), b.binding);
        if (!entry) return false;
        const auto* range = std::get_if<rhi::BufferBinding>(&entry->resource);
        // Anything else is resolved anew (resolve_bindings starts these entries over).
        if (range ? !takes_new_offset(i, *range) : !rhi::differs_only_in_buffer_offset(*entry, resolved_entries_[i])) {
            return false;
        }
    }
    // The same bindings with the new offsets.
    next_binding_state();
    const BindingState& next = binding_states_.back();
    for (uint32_t i = 0; i < next.binding_count; ++i) {
        if (const auto* range = std::get_if<rhi::BufferBinding>(&resolved_entries_[i].resource)) {
            bindings_[next.first_binding + i].offset = static_cast<GLintptr>(range->offset);
        }
    }
    return true;
}

void GlCommandList::dispatch(uint32_t groups_x, uint32_t groups_y, uint32_t groups_z) {
    if (!accepted(state_.check_dispatch())) return;
    const GlPipeline* p = *device_->pipelines().get(state_.pipeline());  // found by the tracker
    const auto first = static_cast<uint32_t>(bindings_.size());
    if (!resolve_bindings(*p, "dispatch")) {
        bindings_.shrink_to(first);
        return;
    }
    if (const PushRange push = push_constant_range(*p); push.object != 0) {
        ResolvedBinding r;
        r.kind = BindingKind::UniformBuffer;
        r.point = rhi::kGlPushConstantBinding;
        r.object = push.object;
        r.offset = push.offset;
        r.size = push.size;
        bindings_.push_back(r);
    }
    const auto count = static_cast<uint32_t>(bindings_.size()) - first;
    if (groups_x == 0 || groups_y == 0 || groups_z == 0) return;
    const GLuint program = p->program;
    record([=, this](GlStateCache& cache) {
        cache.use_program(program);
        apply_bindings(cache, first, count);
        glDispatchCompute(groups_x, groups_y, groups_z);
        cache.count_call();
        cache.count_dispatch();
    });
}

// ---- copies and transitions ------------------------------------------------------------------

void GlCommandList::copy_buffer(rhi::BufferHandle src, uint64_t src_offset, rhi::BufferHandle dst, uint64_t dst_offset,
                                uint64_t size) {
    if (!accepted(state_.check_outside_render_pass("copy_buffer"))) return;
    auto s = device_->buffers().get(src);
    if (!s.ok()) {
        fail(ErrorCode::InvalidHandle, "copy_buffer source: " + s.error().message);
        return;
    }
    auto d = device_->buffers().get(dst);
    if (!d.ok()) {
        fail(ErrorCode::InvalidHandle, "copy_buffer destination: " + d.error().message);
        return;
    }
    const GlBuffer& sb = **s;
    const GlBuffer& db = **d;
    if (!accepted(rhi::validation::buffer_copy(sb.desc, src_offset, db.desc, dst_offset, size, &sb == &db))) return;
    if (size == 0) return;
    const GLuint from = sb.name, to = db.name;
    record([=](GlStateCache& cache) {
        glCopyNamedBufferSubData(from, to, static_cast<GLintptr>(src_offset), static_cast<GLintptr>(dst_offset),
                                 static_cast<GLsizeiptr>(size));
        cache.count_call();
    });
}

void GlCommandList::copy_texture(const rhi::TextureCopy& copy) {
    if (!accepted(state_.check_outside_render_pass("copy_texture"))) return;
    auto s = device_->textures().get(copy.src);
    if (!s.ok()) {
        fail(ErrorCode::InvalidHandle, "copy_texture source: " + s.error().message);
        return;
    }
    auto d = device_->textures().get(copy.dst);
    if (!d.ok()) {
        fail(ErrorCode::InvalidHandle, "copy_texture destination: " + d.error().message);
        return;
    }
    GlTexture& st = **s;
    GlTexture& dt = **d;
    auto range = rhi::validation::texture_copy(st.desc, dt.desc, &st == &dt, copy);
    if (!range.ok()) return fail(range.take_error());
    // Layers of arrays and cubes are the z of glCopyImageSubData, as are depth slices of 3D textures.
    const bool is3d = st.desc.dimension == rhi::TextureDimension::Tex3D;
    const rhi::Origin3D so = range->src_origin, dso = range->dst_origin;
    const uint32_t sz = is3d ? so.z : range->src_layer, dz = is3d ? dso.z : range->dst_layer;
    const uint32_t w = range->extent.width, h = range->extent.height, depth = range->extent.depth;
    const uint32_t src_mip = range->src_mip, dst_mip = range->dst_mip;
    ResourceState& src_state = st.states[st.subresource(src_mip, st.layers() == 1 ? 0 : range->src_layer)];
    ResourceState& dst_state = dt.states[dt.subresource(dst_mip, dt.layers() == 1 ? 0 : range->dst_layer)];
    if (src_state == ResourceState::Storage || dst_state == ResourceState::Storage) {
        const GLbitfield bits = barrier_after_storage(ResourceState::CopySrc);
        record([bits](GlStateCache& cache) {
            glMemoryBarrier(bits);
            cache.count_call();
        });
    }
    src_state = ResourceState::CopySrc;
    dst_state = ResourceState::CopyDst;
    const GLuint from = st.name, to = dt.name;
    const GLenum from_target = st.target, to_target = dt.target;
    record([=](GlStateCache& cache) {
        glCopyImageSubData(from, from_target, static_cast<GLint>(src_mip), static_cast<GLint>(so.x), static_cast<GLint>(so.y),
                           static_cast<GLint>(sz), to, to_target, static_cast<GLint>(dst_mip), static_cast<GLint>(dso.x),
                           static_cast<GLint>(dso.y), static_cast<GLint>(dz),
                           static_cast<GLsizei>(w), static_cast<GLsizei>(h), static_cast<GLsizei>(depth));
        cache.count_call();
    });
}

void GlCommandList::transition(rhi::TextureHandle texture, ResourceState state) { transition(texture, state, rhi::TextureRange{}); }

void GlCommandList::transition(rhi::TextureHandle texture, ResourceState state, const rhi::TextureRange& range) {
    if (!accepted(state_.check_outside_render_pass("transition"))) return;
    auto found = device_->textures().get(texture);
    if (!found.ok()) return fail(ErrorCode::InvalidHandle, "transition: " + found.error().message);
    GlTexture& t = **found;
    auto resolved = rhi::validation::texture_range_transition(t.desc, state, range, device_->capabilities());
    if (!resolved.ok()) return fail(resolved.take_error());
    // Storage writes are the only accesses GL does not order by itself: a barrier when any
    // subresource moved was written as storage (e.g. mip k after a down-sampling dispatch).
    bool after_storage = false;
    t.for_each_in(*resolved, [&](std::size_t i) {
        after_storage = after_storage || t.states[i] == ResourceState::Storage;
        t.states[i] = state;
    });
    if (after_storage) {
        const GLbitfield bits = barrier_after_storage(state);
        if (bits != 0) {
            record([bits](GlStateCache& cache) {
                glMemoryBarrier(bits);
                cache.count_call();
            });
        }
    }
}

void GlCommandList::transition(rhi::BufferHandle buffer, ResourceState state) {
    if (!accepted(state_.check_outside_render_pass("transition"))) return;
    auto found = device_->buffers().get(buffer);
    if (!found.ok()) return fail(ErrorCode::InvalidHandle, "transition: " + found.error().message);
    GlBuffer& b = **found;
    if (!accepted(rhi::validation::buffer_transition(b.desc, state))) return;
    if (b.state == ResourceState::Storage) {
        const GLbitfield bits = barrier_after_storage(state);
        if (bits != 0) {
            record([bits](GlStateCache& cache) {
                glMemoryBarrier(bits);
                cache.count_call();
                cache.count_buffer_barrier();
            });
        }
    }
    b.state = state;
}

// ---- timers and debug groups -----------------------------------------------------------------

void GlCommandList::begin_timer(std::string_view label) {
    if (!accepted(state_.begin_timer(label))) return;
    const GLuint query = device_->acquire_query();
    timers_.emplace_back(std::string(label), query);
    record([query](GlStateCache& cache) {
        glBeginQuery(GL_TIME_ELAPSED, query);
        cache.count_call();
    });
}

void GlCommandList::end_timer() {
    if (!accepted(state_.end_timer())) return;
    record([](GlStateCache& cache) {
        glEndQuery(GL_TIME_ELAPSED);
        cache.count_call();
    });
}

void GlCommandList::push_debug_group(std::string_view label) {
    state_.push_debug_group();
    std::string text(label);
    record([text](GlStateCache& cache) {
        glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(text.size()), text.data());
        cache.count_call();
    });
}

void GlCommandList::pop_debug_group() {
    if (!accepted(state_.pop_debug_group())) return;
    record([](GlStateCache& cache) {
        glPopDebugGroup();
        cache.count_call();
    });
}

// ---- queues ------------------------------------------------------------------------------------
// GL has one queue: a context executes its commands in order, so the compute queue's commands
// simply run where they were recorded and signals and waits order nothing that is not ordered
// already. The state tracker still checks their use, as on every backend.

void GlCommandList::set_queue(rhi::QueueType queue) { accepted(state_.set_queue(queue)); }

rhi::QueueSignal GlCommandList::signal_queue() {
    auto signal = state_.signal_queue();
    if (!signal.ok()) {
        accepted(signal.take_error());
        return {};
    }
    return *signal;
}

void GlCommandList::wait_queue(rhi::QueueSignal signal) { accepted(state_.wait_queue(signal)); }

}  // namespace loom::gl
