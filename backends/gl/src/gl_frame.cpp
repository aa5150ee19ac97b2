// GlDevice: frames (recording, execution, presentation), transient uniform memory and timers.
#include <algorithm>
#include <cstring>

#include "gl_device.hpp"
#include "loom/rhi/log.hpp"

namespace loom::gl {
namespace {

/// Transient uniform memory comes in chunks of this size (bigger requests get their own).
constexpr uint64_t kTransientChunkBytes = 1u << 20;

}  // namespace

rhi::CommandList& GlDevice::begin_frame() {
    context_->make_current();
    if (Status idle = list_->state().check_begin_frame(); !idle.ok()) {
        // Recording goes on into the open frame.
        list_->fail(idle.take_error());
        return *list_;
    }
    recycle_transient_chunks(false);
    collect_timers(false);
    ++frame_index_;
    list_->begin();
    if (context_->windowed()) ensure_backbuffer();
    return *list_;
}

void GlDevice::ensure_backbuffer() {
    const rhi::Extent3D size = context_->framebuffer_size();
    const uint32_t w = std::max(1u, size.width), h = std::max(1u, size.height);
    if (GlTexture* current = textures_.find(backbuffer_)) {
        if (current->desc.width == w && current->desc.height == h) {
            current->set_all(rhi::ResourceState::Undefined);  // last frame's picture is not kept
            return;
        }
        GlTexture old = std::move(*textures_.remove(backbuffer_));
        forget_framebuffers_with(old.name);
        const std::vector<GLuint> views = view_names(old);
        if (!views.empty()) glDeleteTextures(static_cast<GLsizei>(views.size()), views.data());
        glDeleteTextures(1, &old.name);
        glDeleteFramebuffers(1, &backbuffer_fbo_);
        backbuffer_fbo_ = 0;
        cache_->invalidate();
    }
    rhi::TextureDesc desc;
    desc.name = "backbuffer";
    desc.format = rhi::Format::RGBA8Unorm;
    desc.width = w;
    desc.height = h;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc |
                 rhi::TextureUsage::CopyDst;
    auto created = create_texture_internal(desc, true);
    if (!created.ok()) {
        list_->fail(created.error().code, "begin_frame: back buffer: " + created.error().message);
        return;
    }
    backbuffer_ = *created;
    glCreateFramebuffers(1, &backbuffer_fbo_);
    glNamedFramebufferTexture(backbuffer_fbo_, GL_COLOR_ATTACHMENT0, textures_.find(backbuffer_)->name, 0);
    glNamedFramebufferReadBuffer(backbuffer_fbo_, GL_COLOR_ATTACHMENT0);
}

Status GlDevice::end_frame() {
    context_->make_current();
    LOOM_TRY(list_->state().check_recording("end_frame"));
    std::vector<GlCommand>& commands = list_->finish();
    std::optional<Error> error = std::move(list_->first_error());
    // On the application's context: its state is saved here and put back before returning.
    const GlAppStateScope scope = app_state_scope();

    counters_ = {};
    // State left by transfers or by another device's use of GL is not trusted across frames,
    // which also makes the per-frame bind counts independent of earlier frames.
    cache_->invalidate();
    for (TransientChunk& chunk : frame_chunks_) {
        if (chunk.used == 0 || chunk.staging.empty()) continue;  // mapped chunks hold their data already
        glNamedBufferSubData(chunk.name, 0, static_cast<GLsizeiptr>(chunk.used), chunk.staging.data());
        cache_->count_call();
    }
    for (GlCommand& command : commands) command(*cache_);

    if (context_->windowed() && backbuffer_fbo_) {
        // Row 0 of the back buffer is the top; row 0 of the window's framebuffer is the bottom.
        const GlTexture* bb = textures_.find(backbuffer_);
        const auto w = static_cast<GLint>(bb->desc.width), h = static_cast<GLint>(bb->desc.height);
        const rhi::Extent3D window = context_->framebuffer_size();
        cache_->enable(GL_SCISSOR_TEST, false);
        cache_->prepare_clear(1);
        // A copy of the stored values: on an sRGB-capable window framebuffer an enabled
        // GL_FRAMEBUFFER_SRGB would encode them a second time (Vulkan presents them as stored).
        glDisable(GL_FRAMEBUFFER_SRGB);
        glBlitNamedFramebuffer(backbuffer_fbo_, 0, 0, 0, w, h, 0, static_cast<GLint>(window.height),
                               static_cast<GLint>(window.width), 0, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glEnable(GL_FRAMEBUFFER_SRGB);
        cache_->count_call(3);
        context_->swap_buffers();
        if (GlTexture* t = textures_.find(backbuffer_)) t->set_all(rhi::ResourceState::Present);
    }

    for (auto& destroy_gl : deferred_deletes_) destroy_gl();
    if (!deferred_deletes_.empty()) cache_->invalidate();
    deferred_deletes_.clear();

    for (TransientChunk& chunk : frame_chunks_) {
        chunk.fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
        busy_chunks_.push_back(std::move(chunk));
    }
    frame_chunks_.clear();
    // Every frame is queued, also one without timers, so that timer_results() describes the
    // most recent finished frame rather than an older one that happened to have timers.
    pending_timers_.push_back(FrameTimers{std::move(list_->timers())});
    glFlush();

    rhi::FrameStats stats;
    stats.api_calls = counters_.api_calls;
    stats.draw_calls = counters_.draw_calls;
    stats.dispatches = counters_.dispatches;
    stats.buffer_barriers = counters_.buffer_barriers;
    stats.pipeline_binds = counters_.pipeline_binds;
    stats.texture_binds = counters_.texture_binds;
    stats.buffer_binds = counters_.buffer_binds;
    stats.render_passes = render_passes_in_frame_;
    stats.bytes_uploaded = pending_uploads_;
    last_frame_ = stats;
    pending_uploads_ = 0;
    render_passes_in_frame_ = 0;
    if (error) return std::move(*error);
    return {};
}

Status GlDevice::wait_idle() {
    context_->make_current();
    glFinish();
    recycle_transient_chunks(true);
    collect_timers(true);
    return {};
}

// ---- transient uniforms ----------------------------------------------------------------------

rhi::BufferBinding GlDevice::allocate_transient_chunk(std::span<const std::byte> data, GLuint* name) {
    // Written into a chunk of mapped memory: GL is called (and this device's context made
    // current) only for a new chunk.
    const uint64_t alignment = caps_.uniform_buffer_offset_alignment;
    const uint64_t size = std::max<uint64_t>(data.size(), 1);
    auto reusable =
        std::find_if(free_chunks_.begin(), free_chunks_.end(), [&](const TransientChunk& c) { return c.size >= size; });
    if (reusable != free_chunks_.end()) {
        frame_chunks_.push_back(std::move(*reusable));
        free_chunks_.erase(reusable);
    } else {
        context_->make_current();  // recording may interleave with calls on another device
        TransientChunk fresh;
        fresh.size = std::max(kTransientChunkBytes, checked::align_up_in_range(size, alignment));
        GlBuffer b;
        b.desc.name = "transient uniforms";
        b.desc.size = fresh.size;
        b.desc.usage = rhi::BufferUsage::Uniform;
        b.internal = true;
        glCreateBuffers(1, &b.name);
        constexpr GLbitfield kMapped = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glNamedBufferStorage(b.name, static_cast<GLsizeiptr>(fresh.size), nullptr, kMapped | GL_DYNAMIC_STORAGE_BIT);
        fresh.data = static_cast<std::byte*>(glMapNamedBufferRange(b.name, 0, static_cast<GLsizeiptr>(fresh.size), kMapped));
        if (!fresh.data) {
            fresh.staging.resize(fresh.size);
            fresh.data = fresh.staging.data();
        }
        fresh.name = b.name;
        fresh.buffer = buffers_.insert(std::move(b));
        frame_chunks_.push_back(std::move(fresh));
    }
    TransientChunk& chunk = frame_chunks_.back();
    if (!data.empty()) std::memcpy(chunk.data, data.data(), data.size());
    chunk.used = size;
    count_upload(data.size());
    if (name) *name = chunk.name;
    return rhi::BufferBinding{chunk.buffer, 0, size};
}

void GlDevice::recycle_transient_chunks(bool wait) {
    while (!busy_chunks_.empty()) {
        TransientChunk& chunk = busy_chunks_.front();
        if (chunk.fence) {
            const GLenum status = glClientWaitSync(chunk.fence, 0, wait ? GLuint64{1000000000} : 0);
            if (status == GL_TIMEOUT_EXPIRED) break;
            glDeleteSync(chunk.fence);
            chunk.fence = nullptr;
        }
        chunk.used = 0;
        free_chunks_.push_back(std::move(chunk));
        busy_chunks_.pop_front();
    }
}

// ---- timers ----------------------------------------------------------------------------------

GLuint GlDevice::acquire_query() {
    context_->make_current();
    if (!free_queries_.empty()) {
        const GLuint q = free_queries_.back();
        free_queries_.pop_back();
        return q;
    }
    GLuint q = 0;
    glCreateQueries(GL_TIME_ELAPSED, 1, &q);
    return q;
}

void GlDevice::collect_timers(bool wait) {
    while (!pending_timers_.empty()) {
        FrameTimers& frame = pending_timers_.front();
        if (!wait) {
            bool available = true;
            for (auto& [label, query] : frame.queries) {
                GLint ready = GL_FALSE;
                glGetQueryObjectiv(query, GL_QUERY_RESULT_AVAILABLE, &ready);
                if (!ready) {
                    available = false;
                    break;
                }
            }
            if (!available) return;
        }
        latest_timers_.clear();
        for (auto& [label, query] : frame.queries) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
            latest_timers_.push_back(rhi::TimerResult{label, static_cast<double>(ns) / 1.0e6});
            free_queries_.push_back(query);
        }
        pending_timers_.pop_front();
    }
}

std::vector<rhi::TimerResult> GlDevice::timer_results() {
    context_->make_current();
    collect_timers(false);
    return latest_timers_;
}

}  // namespace loom::gl
