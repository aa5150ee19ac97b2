#pragma once
// A shadow of the GL state the backend changes, so that binds and state changes that would
// not change anything are not sent to GL. Every call that does reach GL is counted.

#include <array>
#include <cstdint>
#include <unordered_map>

#include <epoxy/gl.h>

#include "loom/rhi/device.hpp"

namespace loom::gl {

/// Counters kept while a frame executes (a subset of rhi::FrameStats).
struct GlCallCounters {
    uint64_t api_calls = 0;
    uint64_t pipeline_binds = 0;
    uint64_t texture_binds = 0;
    uint64_t buffer_binds = 0;
    uint64_t draw_calls = 0;
    uint64_t dispatches = 0;
    uint64_t buffer_barriers = 0;
};

/// Fixed-function state of a graphics pipeline, in GL enums, applied at draw time.
struct GlRasterState {
    bool cull_enabled = false;
    GLenum cull_face = GL_BACK;
    GLenum front_face = GL_CCW;
    GLenum polygon_mode = GL_FILL;
    bool depth_clamp = false;
    float depth_bias_constant = 0.0f;
    float depth_bias_slope = 0.0f;
    bool depth_test = false;
    bool depth_write = false;
    GLenum depth_func = GL_LESS;
};

struct GlBlendState {
    bool enabled = false;
    GLenum src_color = GL_ONE, dst_color = GL_ZERO, color_op = GL_FUNC_ADD;
    GLenum src_alpha = GL_ONE, dst_alpha = GL_ZERO, alpha_op = GL_FUNC_ADD;
    uint8_t write_mask = 15;  ///< bit 0 R .. bit 3 A
    friend bool operator==(const GlBlendState&, const GlBlendState&) = default;
};

inline constexpr uint32_t kMaxColorAttachments = 8;
/// Texture units, uniform-buffer points and so on tracked: every (set, binding) plus the
/// push-constant buffer.
inline constexpr uint32_t kTrackedBindings = rhi::kMaxBindGroups * rhi::kMaxBindingsPerGroup + 1;

class GlAppState;

class GlStateCache {
public:
    explicit GlStateCache(GlCallCounters& counters) : counters_(&counters) { invalidate(); }

    /// On a context the application owns: the application state to save before an indexed
    /// binding is changed for the first time (null: nothing to save).
    void set_app_state(GlAppState* app) { app_ = app; }

    /// Forgets everything, so the next call of each kind reaches GL (after objects were
    /// deleted, whose names GL may hand out again).
    void invalidate();

    /// Counts a call made outside the cache (draws, clears, copies ...).
    void count_call(uint64_t n = 1) { counters_->api_calls += n; }
    void count_draw() { ++counters_->draw_calls; }
    void count_dispatch() { ++counters_->dispatches; }
    void count_buffer_barrier() { ++counters_->buffer_barriers; }

    void use_program(GLuint program);
    // Inline, as they run for most draws: a comparison when nothing changed.
    void bind_vertex_array(GLuint vao) {
        if (!changed(vao_, vao)) return;
        glBindVertexArray(vao);
        ++counters_->api_calls;
    }
    void bind_draw_framebuffer(GLuint fbo);
    void bind_texture(uint32_t unit, GLuint texture);
    void bind_sampler(uint32_t unit, GLuint sampler);
    void bind_uniform_buffer(uint32_t point, GLuint buffer, GLintptr offset, GLsizeiptr size) {
        if (!changed(uniform_buffers_[point], BufferRange{buffer, offset, size})) return;
        if (app_) save_app_uniform_buffer(point);
        glBindBufferRange(GL_UNIFORM_BUFFER, point, buffer, offset, size);
        ++counters_->api_calls;
        ++counters_->buffer_binds;
    }
    void bind_storage_buffer(uint32_t point, GLuint buffer, GLintptr offset, GLsizeiptr size);
    void bind_image(uint32_t unit, GLuint texture, GLint level, bool layered, GLint layer, GLenum access,
                    GLenum format);
    /// What the cache knows of one vertex array's buffers.
    struct VertexBinding {
        GLuint buffer = 0;
        GLintptr offset = -1;
        GLsizei stride = -1;
        friend bool operator==(const VertexBinding&, const VertexBinding&) = default;
    };
    struct VaoState {
        std::array<VertexBinding, 16> buffers{};
        GLuint element = ~0u;
    };
    /// The cache's entry of `vao` (stays valid until invalidate()): a caller changing several
    /// of its buffers looks it up once.
    VaoState& vao_state(GLuint vao) {
        if (last_vao_state_ == nullptr || last_vao_ != vao) {
            last_vao_state_ = &vaos_[vao];
            last_vao_ = vao;
        }
        return *last_vao_state_;
    }
    void vertex_buffer(GLuint vao, uint32_t slot, GLuint buffer, GLintptr offset, GLsizei stride) {
        vertex_buffer(vao_state(vao), vao, slot, buffer, offset, stride);
    }
    /// As above, with `state` = vao_state(vao).
    void vertex_buffer(VaoState& state, GLuint vao, uint32_t slot, GLuint buffer, GLintptr offset, GLsizei stride) {
        if (slot < state.buffers.size() && !changed(state.buffers[slot], VertexBinding{buffer, offset, stride})) return;
        glVertexArrayVertexBuffer(vao, slot, buffer, offset, stride);
        ++counters_->api_calls;
        ++counters_->buffer_binds;
    }
    void element_buffer(GLuint vao, GLuint buffer) { element_buffer(vao_state(vao), vao, buffer); }
    void element_buffer(VaoState& state, GLuint vao, GLuint buffer) {
        if (!changed(state.element, buffer)) return;
        glVertexArrayElementBuffer(vao, buffer);
        ++counters_->api_calls;
        ++counters_->buffer_binds;
    }
    /// Sets SPIRV-Cross's SPIRV_Cross_BaseInstance uniform of `program` (at `location`).
    void base_instance(GLuint program, GLint location, GLint value);

    void viewport(float x, float y, float w, float h, float min_depth, float max_depth);
    void scissor(int32_t x, int32_t y, int32_t w, int32_t h);
    void enable(GLenum cap, bool on);
    void raster(const GlRasterState& state);
    void blend(uint32_t attachment, const GlBlendState& state);
    /// Enables all colour and depth writes and disables the scissor test (before clears).
    void prepare_clear(uint32_t color_attachments);

private:
    void save_app_uniform_buffer(uint32_t point);
    template <class T>
    static bool changed(T& cached, const T& wanted) {
        if (cached == wanted) return false;
        cached = wanted;
        return true;
    }

    struct BufferRange {
        GLuint buffer = 0;
        GLintptr offset = -1;
        GLsizeiptr size = -1;
        friend bool operator==(const BufferRange&, const BufferRange&) = default;
    };
    struct ImageBinding {
        GLuint texture = 0;
        GLint level = -1;
        bool layered = false;
        GLint layer = -1;
        GLenum access = 0;
        GLenum format = 0;
        friend bool operator==(const ImageBinding&, const ImageBinding&) = default;
    };
    static constexpr GLuint kUnknown = ~0u;

    GlCallCounters* counters_;
    GlAppState* app_ = nullptr;
    GLuint program_ = kUnknown;
    GLuint vao_ = kUnknown;
    GLuint framebuffer_ = kUnknown;
    std::array<GLuint, kTrackedBindings> textures_{};
    std::array<GLuint, kTrackedBindings> samplers_{};
    std::array<BufferRange, kTrackedBindings> uniform_buffers_{};
    std::array<BufferRange, kTrackedBindings> storage_buffers_{};
    std::array<ImageBinding, kTrackedBindings> images_{};
    std::unordered_map<GLuint, VaoState> vaos_;
    /// The entry of vaos_ used last (draws change the buffers of one vertex array in a row):
    /// found without hashing. Nodes of an unordered_map stay put until erased (invalidate).
    GLuint last_vao_ = 0;
    VaoState* last_vao_state_ = nullptr;
    std::unordered_map<GLuint, GLint> base_instances_;  ///< per program
    std::array<float, 6> viewport_{};
    bool viewport_known_ = false;
    std::array<int32_t, 4> scissor_{};
    bool scissor_known_ = false;
    std::unordered_map<GLenum, bool> caps_;
    GlRasterState raster_{};
    bool raster_known_ = false;
    std::array<GlBlendState, kMaxColorAttachments> blend_{};
    std::array<bool, kMaxColorAttachments> blend_known_{};
};

}  // namespace loom::gl
