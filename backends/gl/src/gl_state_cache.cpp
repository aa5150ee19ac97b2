#include "gl_state_cache.hpp"

#include "gl_app_state.hpp"

namespace loom::gl {

void GlStateCache::invalidate() {
    program_ = kUnknown;
    vao_ = kUnknown;
    framebuffer_ = kUnknown;
    textures_.fill(kUnknown);
    samplers_.fill(kUnknown);
    uniform_buffers_.fill(BufferRange{kUnknown, -1, -1});
    storage_buffers_.fill(BufferRange{kUnknown, -1, -1});
    images_.fill(ImageBinding{kUnknown, -1, false, -1, 0, 0});
    vaos_.clear();
    last_vao_state_ = nullptr;
    base_instances_.clear();
    viewport_known_ = false;
    scissor_known_ = false;
    caps_.clear();
    raster_known_ = false;
    blend_known_.fill(false);
}

void GlStateCache::use_program(GLuint program) {
    if (!changed(program_, program)) return;
    glUseProgram(program);
    ++counters_->api_calls;
    ++counters_->pipeline_binds;
}

void GlStateCache::bind_draw_framebuffer(GLuint fbo) {
    if (!changed(framebuffer_, fbo)) return;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    ++counters_->api_calls;
}

void GlStateCache::bind_texture(uint32_t unit, GLuint texture) {
    if (!changed(textures_[unit], texture)) return;
    if (app_) app_->save_texture_unit(unit);
    glBindTextureUnit(unit, texture);
    ++counters_->api_calls;
    ++counters_->texture_binds;
}

void GlStateCache::bind_sampler(uint32_t unit, GLuint sampler) {
    if (!changed(samplers_[unit], sampler)) return;
    if (app_) app_->save_sampler_unit(unit);
    glBindSampler(unit, sampler);
    ++counters_->api_calls;
}

void GlStateCache::save_app_uniform_buffer(uint32_t point) { app_->save_uniform_buffer(point); }

void GlStateCache::bind_storage_buffer(uint32_t point, GLuint buffer, GLintptr offset, GLsizeiptr size) {
    if (!changed(storage_buffers_[point], BufferRange{buffer, offset, size})) return;
    if (app_) app_->save_storage_buffer(point);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, point, buffer, offset, size);
    ++counters_->api_calls;
    ++counters_->buffer_binds;
}

void GlStateCache::bind_image(uint32_t unit, GLuint texture, GLint level, bool layered, GLint layer, GLenum access,
                              GLenum format) {
    if (!changed(images_[unit], ImageBinding{texture, level, layered, layer, access, format})) return;
    if (app_) app_->save_image_unit(unit);
    glBindImageTexture(unit, texture, level, layered ? GL_TRUE : GL_FALSE, layer, access, format);
    ++counters_->api_calls;
    ++counters_->texture_binds;
}

void GlStateCache::base_instance(GLuint program, GLint location, GLint value) {
    auto it = base_instances_.find(program);
    if (it != base_instances_.end() && it->second == value) return;
    base_instances_[program] = value;
    glProgramUniform1i(program, location, value);
    ++counters_->api_calls;
}

void GlStateCache::viewport(float x, float y, float w, float h, float min_depth, float max_depth) {
    const std::array<float, 6> wanted{x, y, w, h, min_depth, max_depth};
    if (viewport_known_ && viewport_ == wanted) return;
    if (!viewport_known_ || viewport_[0] != x || viewport_[1] != y || viewport_[2] != w || viewport_[3] != h) {
        glViewportIndexedf(0, x, y, w, h);
        ++counters_->api_calls;
    }
    if (!viewport_known_ || viewport_[4] != min_depth || viewport_[5] != max_depth) {
        glDepthRangeIndexed(0, min_depth, max_depth);
        ++counters_->api_calls;
    }
    viewport_ = wanted;
    viewport_known_ = true;
}

void GlStateCache::scissor(int32_t x, int32_t y, int32_t w, int32_t h) {
    const std::array<int32_t, 4> wanted{x, y, w, h};
    if (scissor_known_ && scissor_ == wanted) return;
    glScissorIndexed(0, x, y, w, h);
    ++counters_->api_calls;
    scissor_ = wanted;
    scissor_known_ = true;
}

void GlStateCache::enable(GLenum cap, bool on) {
    auto it = caps_.find(cap);
    if (it != caps_.end() && it->second == on) return;
    caps_[cap] = on;
    if (on) {
        glEnable(cap);
    } else {
        glDisable(cap);
    }
    ++counters_->api_calls;
}

void GlStateCache::raster(const GlRasterState& s) {
    const bool all = !raster_known_;
    GlRasterState& c = raster_;
    enable(GL_CULL_FACE, s.cull_enabled);
    if (s.cull_enabled && (all || c.cull_face != s.cull_face)) {
        glCullFace(s.cull_face);
        ++counters_->api_calls;
        c.cull_face = s.cull_face;
    }
    if (all || c.front_face != s.front_face) {
        glFrontFace(s.front_face);
        ++counters_->api_calls;
        c.front_face = s.front_face;
    }
    if (all || c.polygon_mode != s.polygon_mode) {
        glPolygonMode(GL_FRONT_AND_BACK, s.polygon_mode);
        ++counters_->api_calls;
        c.polygon_mode = s.polygon_mode;
    }
    enable(GL_DEPTH_CLAMP, s.depth_clamp);
    const bool bias = s.depth_bias_constant != 0.0f || s.depth_bias_slope != 0.0f;
    enable(GL_POLYGON_OFFSET_FILL, bias);
    enable(GL_POLYGON_OFFSET_LINE, bias);
    if (bias && (all || c.depth_bias_constant != s.depth_bias_constant || c.depth_bias_slope != s.depth_bias_slope)) {
        glPolygonOffset(s.depth_bias_slope, s.depth_bias_constant);
        ++counters_->api_calls;
        c.depth_bias_constant = s.depth_bias_constant;
        c.depth_bias_slope = s.depth_bias_slope;
    }
    enable(GL_DEPTH_TEST, s.depth_test);
    if (s.depth_test && (all || c.depth_func != s.depth_func)) {
        glDepthFunc(s.depth_func);
        ++counters_->api_calls;
        c.depth_func = s.depth_func;
    }
    if (all || c.depth_write != s.depth_write) {
        glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
        ++counters_->api_calls;
        c.depth_write = s.depth_write;
    }
    if (all) {
        // Fields not sent above (cull face while culling is off ...) are unknown until sent.
        c = s;
        if (!s.cull_enabled) c.cull_face = 0;
        if (!s.depth_test) c.depth_func = 0;
        if (!bias) c.depth_bias_constant = c.depth_bias_slope = -1.0f;
    }
    raster_known_ = true;
}

void GlStateCache::blend(uint32_t i, const GlBlendState& s) {
    GlBlendState& c = blend_[i];
    const bool all = !blend_known_[i];
    if (app_) app_->save_draw_buffer(i);
    if (all || c.enabled != s.enabled) {
        if (s.enabled) {
            glEnablei(GL_BLEND, i);
        } else {
            glDisablei(GL_BLEND, i);
        }
        ++counters_->api_calls;
    }
    if (s.enabled && (all || c.src_color != s.src_color || c.dst_color != s.dst_color || c.src_alpha != s.src_alpha ||
                      c.dst_alpha != s.dst_alpha || !c.enabled)) {
        glBlendFuncSeparatei(i, s.src_color, s.dst_color, s.src_alpha, s.dst_alpha);
        ++counters_->api_calls;
    }
    if (s.enabled && (all || c.color_op != s.color_op || c.alpha_op != s.alpha_op || !c.enabled)) {
        glBlendEquationSeparatei(i, s.color_op, s.alpha_op);
        ++counters_->api_calls;
    }
    if (all || c.write_mask != s.write_mask) {
        glColorMaski(i, (s.write_mask & 1) != 0, (s.write_mask & 2) != 0, (s.write_mask & 4) != 0,
                     (s.write_mask & 8) != 0);
        ++counters_->api_calls;
    }
    if (s.enabled) {
        c = s;
    } else {
        // Blend factors are not sent while blending is off; they are unknown after that.
        c.enabled = false;
        c.write_mask = s.write_mask;
    }
    blend_known_[i] = true;
}

void GlStateCache::prepare_clear(uint32_t color_attachments) {
    enable(GL_SCISSOR_TEST, false);
    for (uint32_t i = 0; i < color_attachments && i < kMaxColorAttachments; ++i) {
        if (blend_known_[i] && blend_[i].write_mask == 15) continue;
        if (app_) app_->save_draw_buffer(i);
        glColorMaski(i, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        ++counters_->api_calls;
        // A slot whose state is unknown stays unknown: the next blend() sends all of it.
        if (blend_known_[i]) blend_[i].write_mask = 15;
    }
    if (!raster_known_ || !raster_.depth_write) {
        glDepthMask(GL_TRUE);
        ++counters_->api_calls;
        if (raster_known_) raster_.depth_write = true;
    }
    // The stencil write mask is never changed from its initial all-ones.
}

}  // namespace loom::gl
