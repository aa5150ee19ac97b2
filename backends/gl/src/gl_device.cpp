// GlDevice: creation, capabilities, the window, and the public factory.
#include "gl_device.hpp"
#include "loom/rhi/validation.hpp"

#include <algorithm>
#include <bit>

#include "gl_debug.hpp"
#include "loom/rhi/log.hpp"

namespace loom::gl {

Result<std::unique_ptr<rhi::Device>> create_gl_device(const rhi::DeviceDesc& desc) {
    auto device = GlDevice::create(desc);
    if (!device.ok()) return device.take_error();
    return std::unique_ptr<rhi::Device>(std::move(*device));
}

Result<std::unique_ptr<rhi::Device>> create_gl_device_on_current_context(const CurrentContextDesc& desc) {
    auto device = GlDevice::create_on_current_context(desc);
    if (!device.ok()) return device.take_error();
    return std::unique_ptr<rhi::Device>(std::move(*device));
}

std::optional<GlCacheStats> gl_cache_stats(const rhi::Device& device) {
    if (const auto* gl = dynamic_cast<const GlDevice*>(&device)) return gl->cache_stats();
    return std::nullopt;
}

Result<std::unique_ptr<GlDevice>> GlDevice::create(const rhi::DeviceDesc& desc) {
    auto context = desc.headless ? GlContext::create_headless(desc.debug)
                                 : GlContext::create_windowed(desc.window, desc.debug);
    if (!context.ok()) return context.take_error();
    std::unique_ptr<GlDevice> device(new GlDevice());
    device->context_ = std::move(*context);
    LOOM_TRY(device->init(desc.debug, desc.validation));
    return device;
}

Result<std::unique_ptr<GlDevice>> GlDevice::create_on_current_context(const CurrentContextDesc& desc) {
    auto context = GlContext::adopt_current();
    if (!context.ok()) return context.take_error();
    std::unique_ptr<GlDevice> device(new GlDevice());
    device->context_ = std::move(*context);
    LOOM_TRY(device->init(desc.debug_output, desc.validation));
    return device;
}

Status GlDevice::init(bool debug, bool validation) {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 5)) {
        return Error{ErrorCode::Unsupported, "OpenGL 4.5 is required, the context is " + std::to_string(major) + "." +
                                                 std::to_string(minor)};
    }
    if (context_->adopted()) {
        // The application's context: loom's conventions are set around each of its calls and
        // the application's state is put back after (gl_app_state.hpp), so nothing is set here.
        app_state_ = std::make_unique<GlAppState>();
        if (debug) saved_debug_output_ = take_over_debug_output();
    } else {
        if (debug) install_debug_output();
        // loom's conventions: NDC y=+1 lands on row 0 (the top row in memory), depth 0..1.
        glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
        // Tightly packed rows for every upload and readback.
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        // Writes to sRGB attachments encode, as they do on Vulkan.
        glEnable(GL_FRAMEBUFFER_SRGB);
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
        glEnable(GL_PROGRAM_POINT_SIZE);
    }
    cache_ = std::make_unique<GlStateCache>(counters_);
    cache_->set_app_state(app_state_.get());
    {
        const GlAppStateScope scope = app_state_scope();
        init_capabilities();
    }
    list_ = std::make_unique<GlCommandList>(*this);
    list_->set_validation(validation);
    log_info("gl", "device: " + caps_.device_name + " | " + caps_.api_version +
                       (context_->adopted() ? " (the application's context)" : "") + " | " +
                       rhi::validation::checks_in_log("debug output", debug, validation));
    return {};
}

void GlDevice::init_capabilities() {
    auto integer = [](GLenum pname) {
        GLint v = 0;
        glGetIntegerv(pname, &v);
        return static_cast<uint32_t>(std::max(v, 0));
    };
    caps_.backend = rhi::Backend::OpenGL;
    caps_.device_name = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    caps_.api_version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    caps_.formats = query_format_capabilities();
    caps_.placed_resources = false;
    caps_.draw_indirect = true;  // glMultiDrawElementsIndirect: core since GL 4.3
    caps_.polygon_mode_line = true;  // glPolygonMode: core
    caps_.depth_clamp = true;        // GL_DEPTH_CLAMP: core since GL 3.2
    GLint timer_bits = 0;
    glGetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &timer_bits);
    caps_.timestamps = timer_bits > 0;
    if (caps_.timestamps) discard_first_timer_query();
    caps_.max_texture_size = integer(GL_MAX_TEXTURE_SIZE);
    caps_.max_color_attachments = std::min({integer(GL_MAX_COLOR_ATTACHMENTS), integer(GL_MAX_DRAW_BUFFERS),
                                            kMaxColorAttachments});
    caps_.uniform_buffer_offset_alignment = std::max<uint32_t>(1, integer(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT));
    if (std::has_single_bit(caps_.uniform_buffer_offset_alignment)) {
        uniform_alignment_mask_ = caps_.uniform_buffer_offset_alignment - 1;
    }
    caps_.storage_buffer_offset_alignment = std::max<uint32_t>(1, integer(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT));
    limits_.max_image_units = integer(GL_MAX_IMAGE_UNITS);
    limits_.max_storage_buffer_bindings = integer(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS);
    caps_.max_texture_size_3d = integer(GL_MAX_3D_TEXTURE_SIZE);
    caps_.max_texture_size_cube = integer(GL_MAX_CUBE_MAP_TEXTURE_SIZE);
    caps_.max_texture_layers = integer(GL_MAX_ARRAY_TEXTURE_LAYERS);
    caps_.max_samples = std::max<uint32_t>(1, integer(GL_MAX_SAMPLES));
}

// Mesa 22.3's llvmpipe answers the first GL_TIME_ELAPSED query of a context that contains
// rendering work with the time since boot (the start timestamp is never written); an empty
// query does not count. One discarded query around a clear of a 1x1 target, before the first
// frame, keeps that value out of the user's timings. Later queries are right.
void GlDevice::discard_first_timer_query() {
    GLuint texture = 0, framebuffer = 0, query = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 1, 1);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glCreateQueries(GL_TIME_ELAPSED, 1, &query);
    glBeginQuery(GL_TIME_ELAPSED, query);
    const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, black);
    glEndQuery(GL_TIME_ELAPSED);
    GLuint64 discarded = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &discarded);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &texture);
    free_queries_.push_back(query);
}

GlDevice::~GlDevice() {
    context_->make_current();
    glFinish();
    list_.reset();
    for (auto& destroy_gl : deferred_deletes_) destroy_gl();
    deferred_deletes_.clear();
    for (auto& [key, fbo] : framebuffers_) glDeleteFramebuffers(1, &fbo);
    framebuffers_.clear();
    if (backbuffer_fbo_) glDeleteFramebuffers(1, &backbuffer_fbo_);
    for (auto& [key, entry] : vertex_arrays_) glDeleteVertexArrays(1, &entry.vao);
    vertex_arrays_.clear();
    auto drop_chunk = [](TransientChunk& c) {
        if (c.fence) glDeleteSync(c.fence);
    };
    for (auto& c : free_chunks_) drop_chunk(c);
    for (auto& c : frame_chunks_) drop_chunk(c);
    for (auto& c : busy_chunks_) drop_chunk(c);
    for (auto& frame : pending_timers_) {
        for (auto& [label, query] : frame.queries) free_queries_.push_back(query);
    }
    if (!free_queries_.empty()) glDeleteQueries(static_cast<GLsizei>(free_queries_.size()), free_queries_.data());
    // Whatever the user did not destroy goes with the device (imports stay the application's).
    textures_.clear([](rhi::TextureHandle, GlTexture& t) {
        const std::vector<GLuint> views = view_names(t);
        if (!views.empty()) glDeleteTextures(static_cast<GLsizei>(views.size()), views.data());
        if (!t.imported) glDeleteTextures(1, &t.name);
    });
    buffers_.clear([](rhi::BufferHandle, GlBuffer& b) { glDeleteBuffers(1, &b.name); });
    samplers_.clear([](rhi::SamplerHandle, GlSampler& s) { glDeleteSamplers(1, &s.name); });
    pipelines_.clear([](rhi::PipelineHandle, GlPipeline& p) { glDeleteProgram(p.program); });
    shaders_.clear([](rhi::ShaderHandle, GlShader& s) { glDeleteShader(s.name_gl); });
    if (saved_debug_output_) restore_debug_output(*saved_debug_output_);
    glFinish();
}

Result<rhi::HeapHandle> GlDevice::create_heap(const rhi::HeapDesc& desc) {
    LOOM_TRY(rhi::validation::heap_desc(desc, caps_));  // refuses: no placed resources
    return Error{ErrorCode::Unsupported, "heap " + rhi::validation::in_quotes(desc.name) + ": not created"};
}

Result<rhi::MemoryRequirements> GlDevice::texture_memory_requirements(const rhi::TextureDesc& desc) {
    LOOM_TRY(rhi::validation::texture_memory_query(desc, caps_));  // refuses: no placed resources
    return Error{ErrorCode::Unsupported, "texture " + rhi::validation::in_quotes(desc.name) + ": no memory requirements"};
}

Result<rhi::MemoryRequirements> GlDevice::buffer_memory_requirements(const rhi::BufferDesc& desc) {
    LOOM_TRY(rhi::validation::buffer_memory_query(desc));
    // GL places nothing, but planners size transient buffers the same way on every backend:
    // the size rounded up to 256 bytes (the largest uniform/storage offset alignment GL drivers
    // report) at an alignment of 256.
    constexpr uint64_t kAlignment = 256;
    if (desc.size > UINT64_MAX - (kAlignment - 1)) {
        return Error{ErrorCode::InvalidArgument, "buffer " + rhi::validation::in_quotes(desc.name) + ": size " + std::to_string(desc.size) +
                                                     " cannot be rounded up to " + std::to_string(kAlignment) + " bytes"};
    }
    return rhi::MemoryRequirements{(desc.size + kAlignment - 1) / kAlignment * kAlignment, kAlignment};
}

Status GlDevice::destroy(rhi::HeapHandle heap) {
    (void)heap;
    return Error{ErrorCode::InvalidHandle, "heap handle: the OpenGL backend creates no heaps"};
}

bool GlDevice::poll_window() { return context_->poll_events(); }

rhi::Extent3D GlDevice::window_size() const { return context_->framebuffer_size(); }

const rhi::WindowInput& GlDevice::window_input() const {
    const rhi::WindowInput* input = context_->input();
    return input ? *input : Device::window_input();
}

rhi::TextureHandle GlDevice::backbuffer() {
    return (context_->windowed() && list_->recording()) ? backbuffer_ : rhi::TextureHandle{};
}

}  // namespace loom::gl
