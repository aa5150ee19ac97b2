#include "gl_app_state.hpp"

#include <algorithm>

namespace loom::gl {
namespace {

/// A capability loom saves, with the value loom needs while it works (kKeep: loom's state
/// cache sets it itself before every use, so no baseline is applied).
struct Capability {
    GLenum cap;
    int loom_value;  ///< 0 off, 1 on, kKeep
};
constexpr int kKeep = -1;

constexpr Capability kCapabilities[] = {
    // Set by the state cache for every draw or clear.
    {GL_CULL_FACE, kKeep},
    {GL_DEPTH_TEST, kKeep},
    {GL_DEPTH_CLAMP, kKeep},
    {GL_POLYGON_OFFSET_FILL, kKeep},
    {GL_POLYGON_OFFSET_LINE, kKeep},
    // loom's conventions (as on a context loom creates itself).
    {GL_FRAMEBUFFER_SRGB, 1},
    {GL_TEXTURE_CUBE_MAP_SEAMLESS, 1},
    {GL_PROGRAM_POINT_SIZE, 1},
    {GL_MULTISAMPLE, 1},
    // Application state that would change what loom draws.
    {GL_POLYGON_OFFSET_POINT, 0},
    {GL_STENCIL_TEST, 0},
    {GL_RASTERIZER_DISCARD, 0},
    {GL_SAMPLE_ALPHA_TO_COVERAGE, 0},
    {GL_SAMPLE_ALPHA_TO_ONE, 0},
    {GL_SAMPLE_COVERAGE, 0},
    {GL_SAMPLE_MASK, 0},
    {GL_SAMPLE_SHADING, 0},
    {GL_COLOR_LOGIC_OP, 0},
    {GL_PRIMITIVE_RESTART, 0},
    {GL_PRIMITIVE_RESTART_FIXED_INDEX, 0},
    {GL_LINE_SMOOTH, 0},
    {GL_POLYGON_SMOOTH, 0},
};

/// Pixel store parameters, GL_PACK_* and GL_UNPACK_* in the same order.
constexpr GLenum kPack[] = {GL_PACK_SWAP_BYTES,  GL_PACK_LSB_FIRST,   GL_PACK_ROW_LENGTH,  GL_PACK_IMAGE_HEIGHT,
                            GL_PACK_SKIP_ROWS,   GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_IMAGES, GL_PACK_ALIGNMENT};
constexpr GLenum kUnpack[] = {GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST,   GL_UNPACK_ROW_LENGTH,  GL_UNPACK_IMAGE_HEIGHT,
                              GL_UNPACK_SKIP_ROWS,  GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_IMAGES, GL_UNPACK_ALIGNMENT};
/// loom transfers tightly packed rows: alignment 1, everything else 0.
constexpr GLint kPixelStoreBaseline[] = {0, 0, 0, 0, 0, 0, 0, 1};

/// The texture targets loom binds (glBindTextureUnit binds a texture to its own target).
constexpr GLenum kTextureTargets[] = {GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP,
                                      GL_TEXTURE_2D_MULTISAMPLE};
constexpr GLenum kTextureBindings[] = {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_3D,
                                       GL_TEXTURE_BINDING_CUBE_MAP, GL_TEXTURE_BINDING_2D_MULTISAMPLE};

GLint get_int(GLenum pname) {
    GLint v = 0;
    glGetIntegerv(pname, &v);
    return v;
}

void set_cap(GLenum cap, bool on) {
    if (on) {
        glEnable(cap);
    } else {
        glDisable(cap);
    }
}

void bind_buffer_point(GLenum target, GLuint point, GLint buffer, GLint64 start, GLint64 size) {
    // A range of size 0 is how GL reports a glBindBufferBase binding (or none).
    if (buffer == 0 || size == 0) {
        glBindBufferBase(target, point, static_cast<GLuint>(buffer));
    } else {
        glBindBufferRange(target, point, static_cast<GLuint>(buffer), static_cast<GLintptr>(start),
                          static_cast<GLsizeiptr>(size));
    }
}

}  // namespace

GlAppState::GlAppState() {
    max_viewports_ = std::max(1, get_int(GL_MAX_VIEWPORTS));
    max_clip_distances_ = std::max(0, get_int(GL_MAX_CLIP_DISTANCES));
}

void GlAppState::enter() {
    if (depth_++ > 0) return;
    save_fixed();
    apply_baseline();
}

void GlAppState::leave() {
    if (--depth_ > 0) return;
    // Indexed bindings first: restoring them moves the active texture unit and the generic
    // buffer bindings, which the fixed state then puts back.
    restore_indexed();
    restore_fixed();
}

void GlAppState::save_fixed() {
    Fixed& f = fixed_;
    f.program = get_int(GL_CURRENT_PROGRAM);
    f.vertex_array = get_int(GL_VERTEX_ARRAY_BINDING);
    f.draw_framebuffer = get_int(GL_DRAW_FRAMEBUFFER_BINDING);
    f.read_framebuffer = get_int(GL_READ_FRAMEBUFFER_BINDING);
    f.active_texture = get_int(GL_ACTIVE_TEXTURE);
    f.uniform_buffer = get_int(GL_UNIFORM_BUFFER_BINDING);
    f.storage_buffer = get_int(GL_SHADER_STORAGE_BUFFER_BINDING);
    f.pixel_pack_buffer = get_int(GL_PIXEL_PACK_BUFFER_BINDING);
    f.pixel_unpack_buffer = get_int(GL_PIXEL_UNPACK_BUFFER_BINDING);
    f.draw_indirect_buffer = get_int(GL_DRAW_INDIRECT_BUFFER_BINDING);
    for (std::size_t i = 0; i < f.pack.size(); ++i) {
        f.pack[i] = get_int(kPack[i]);
        f.unpack[i] = get_int(kUnpack[i]);
    }
    f.clip_origin = get_int(GL_CLIP_ORIGIN);
    f.clip_depth_mode = get_int(GL_CLIP_DEPTH_MODE);
    glGetFloati_v(GL_VIEWPORT, 0, f.viewport.data());
    glGetDoublei_v(GL_DEPTH_RANGE, 0, f.depth_range.data());
    glGetIntegeri_v(GL_SCISSOR_BOX, 0, f.scissor_box.data());
    f.scissor_test.resize(static_cast<std::size_t>(max_viewports_));
    for (GLint i = 0; i < max_viewports_; ++i) {
        f.scissor_test[static_cast<std::size_t>(i)] = glIsEnabledi(GL_SCISSOR_TEST, static_cast<GLuint>(i));
    }
    f.caps.resize(std::size(kCapabilities));
    for (std::size_t i = 0; i < std::size(kCapabilities); ++i) f.caps[i] = glIsEnabled(kCapabilities[i].cap);
    f.clip_distances.resize(static_cast<std::size_t>(max_clip_distances_));
    for (GLint i = 0; i < max_clip_distances_; ++i) {
        f.clip_distances[static_cast<std::size_t>(i)] = glIsEnabled(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i));
    }
    f.cull_face_mode = get_int(GL_CULL_FACE_MODE);
    f.front_face = get_int(GL_FRONT_FACE);
    glGetIntegerv(GL_POLYGON_MODE, f.polygon_mode.data());
    glGetFloatv(GL_POLYGON_OFFSET_FACTOR, &f.polygon_offset_factor);
    glGetFloatv(GL_POLYGON_OFFSET_UNITS, &f.polygon_offset_units);
    f.depth_func = get_int(GL_DEPTH_FUNC);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &f.depth_mask);
    f.stencil_writemask = get_int(GL_STENCIL_WRITEMASK);
    f.stencil_back_writemask = get_int(GL_STENCIL_BACK_WRITEMASK);
    glGetFloatv(GL_BLEND_COLOR, f.blend_color.data());
    glGetFloatv(GL_LINE_WIDTH, &f.line_width);
    f.provoking_vertex = get_int(GL_PROVOKING_VERTEX);
}

void GlAppState::apply_baseline() {
    const Fixed& f = fixed_;
    if (f.pixel_pack_buffer != 0) glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (f.pixel_unpack_buffer != 0) glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    for (std::size_t i = 0; i < f.pack.size(); ++i) {
        if (f.pack[i] != kPixelStoreBaseline[i]) glPixelStorei(kPack[i], kPixelStoreBaseline[i]);
        if (f.unpack[i] != kPixelStoreBaseline[i]) glPixelStorei(kUnpack[i], kPixelStoreBaseline[i]);
    }
    // loom's conventions: NDC y=+1 lands on row 0 (the top row in memory), depth 0..1.
    if (f.clip_origin != GL_UPPER_LEFT || f.clip_depth_mode != GL_ZERO_TO_ONE) glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    for (std::size_t i = 0; i < std::size(kCapabilities); ++i) {
        const Capability& c = kCapabilities[i];
        if (c.loom_value != kKeep && (f.caps[i] == GL_TRUE) != (c.loom_value == 1)) set_cap(c.cap, c.loom_value == 1);
    }
    for (GLint i = 0; i < max_clip_distances_; ++i) {
        if (f.clip_distances[static_cast<std::size_t>(i)]) glDisable(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i));
    }
    // The stencil write mask stays all ones for loom's clears (the state cache never changes it).
    if (static_cast<GLuint>(f.stencil_writemask) != ~0u || static_cast<GLuint>(f.stencil_back_writemask) != ~0u) {
        glStencilMask(~0u);
    }
    if (f.blend_color != std::array<GLfloat, 4>{}) glBlendColor(0.0f, 0.0f, 0.0f, 0.0f);
    if (f.line_width != 1.0f) glLineWidth(1.0f);
    if (f.provoking_vertex != GL_LAST_VERTEX_CONVENTION) glProvokingVertex(GL_LAST_VERTEX_CONVENTION);
}

void GlAppState::restore_fixed() {
    const Fixed& f = fixed_;
    glUseProgram(static_cast<GLuint>(f.program));
    glBindVertexArray(static_cast<GLuint>(f.vertex_array));
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(f.draw_framebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(f.read_framebuffer));
    glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(f.uniform_buffer));
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(f.storage_buffer));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, static_cast<GLuint>(f.pixel_pack_buffer));
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, static_cast<GLuint>(f.pixel_unpack_buffer));
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, static_cast<GLuint>(f.draw_indirect_buffer));
    for (std::size_t i = 0; i < f.pack.size(); ++i) {
        glPixelStorei(kPack[i], f.pack[i]);
        glPixelStorei(kUnpack[i], f.unpack[i]);
    }
    glClipControl(static_cast<GLenum>(f.clip_origin), static_cast<GLenum>(f.clip_depth_mode));
    glViewportIndexedf(0, f.viewport[0], f.viewport[1], f.viewport[2], f.viewport[3]);
    glDepthRangeIndexed(0, f.depth_range[0], f.depth_range[1]);
    glScissorIndexed(0, f.scissor_box[0], f.scissor_box[1], f.scissor_box[2], f.scissor_box[3]);
    for (GLint i = 0; i < max_viewports_; ++i) {
        if (f.scissor_test[static_cast<std::size_t>(i)]) {
            glEnablei(GL_SCISSOR_TEST, static_cast<GLuint>(i));
        } else {
            glDisablei(GL_SCISSOR_TEST, static_cast<GLuint>(i));
        }
    }
    for (std::size_t i = 0; i < std::size(kCapabilities); ++i) set_cap(kCapabilities[i].cap, f.caps[i] == GL_TRUE);
    for (GLint i = 0; i < max_clip_distances_; ++i) {
        set_cap(GL_CLIP_DISTANCE0 + static_cast<GLenum>(i), f.clip_distances[static_cast<std::size_t>(i)] == GL_TRUE);
    }
    glCullFace(static_cast<GLenum>(f.cull_face_mode));
    glFrontFace(static_cast<GLenum>(f.front_face));
    glPolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(f.polygon_mode[0]));
    glPolygonOffset(f.polygon_offset_factor, f.polygon_offset_units);
    glDepthFunc(static_cast<GLenum>(f.depth_func));
    glDepthMask(f.depth_mask);
    glStencilMaskSeparate(GL_FRONT, static_cast<GLuint>(f.stencil_writemask));
    glStencilMaskSeparate(GL_BACK, static_cast<GLuint>(f.stencil_back_writemask));
    glBlendColor(f.blend_color[0], f.blend_color[1], f.blend_color[2], f.blend_color[3]);
    glLineWidth(f.line_width);
    glProvokingVertex(static_cast<GLenum>(f.provoking_vertex));
    glActiveTexture(static_cast<GLenum>(f.active_texture));
}

void GlAppState::restore_indexed() {
    for (auto& [unit, saved] : texture_units_) {
        glActiveTexture(GL_TEXTURE0 + unit);
        if (saved.textures_saved) {
            for (std::size_t t = 0; t < std::size(kTextureTargets); ++t) {
                glBindTexture(kTextureTargets[t], static_cast<GLuint>(saved.textures[t]));
            }
        }
        if (saved.sampler_saved) glBindSampler(unit, static_cast<GLuint>(saved.sampler));
    }
    for (auto& [point, saved] : uniform_buffers_) bind_buffer_point(GL_UNIFORM_BUFFER, point, saved.buffer, saved.start, saved.size);
    for (auto& [point, saved] : storage_buffers_) {
        bind_buffer_point(GL_SHADER_STORAGE_BUFFER, point, saved.buffer, saved.start, saved.size);
    }
    for (auto& [unit, saved] : image_units_) {
        glBindImageTexture(unit, static_cast<GLuint>(saved.texture), saved.level, static_cast<GLboolean>(saved.layered),
                           saved.layer, static_cast<GLenum>(saved.access), static_cast<GLenum>(saved.format));
    }
    for (auto& [index, saved] : draw_buffers_) {
        if (saved.blend) {
            glEnablei(GL_BLEND, index);
        } else {
            glDisablei(GL_BLEND, index);
        }
        glBlendFuncSeparatei(index, static_cast<GLenum>(saved.src_rgb), static_cast<GLenum>(saved.dst_rgb),
                             static_cast<GLenum>(saved.src_alpha), static_cast<GLenum>(saved.dst_alpha));
        glBlendEquationSeparatei(index, static_cast<GLenum>(saved.equation_rgb), static_cast<GLenum>(saved.equation_alpha));
        glColorMaski(index, saved.color_mask[0], saved.color_mask[1], saved.color_mask[2], saved.color_mask[3]);
    }
    texture_units_.clear();
    uniform_buffers_.clear();
    storage_buffers_.clear();
    image_units_.clear();
    draw_buffers_.clear();
}

void GlAppState::save_texture_unit(uint32_t unit) {
    if (depth_ == 0) return;
    TextureUnit& saved = texture_units_[unit];
    if (saved.textures_saved) return;
    glActiveTexture(GL_TEXTURE0 + unit);
    for (std::size_t t = 0; t < std::size(kTextureBindings); ++t) saved.textures[t] = get_int(kTextureBindings[t]);
    saved.textures_saved = true;
}

void GlAppState::save_sampler_unit(uint32_t unit) {
    if (depth_ == 0) return;
    TextureUnit& saved = texture_units_[unit];
    if (saved.sampler_saved) return;
    glActiveTexture(GL_TEXTURE0 + unit);
    saved.sampler = get_int(GL_SAMPLER_BINDING);
    saved.sampler_saved = true;
}

void GlAppState::save_uniform_buffer(uint32_t point) {
    if (depth_ == 0 || uniform_buffers_.contains(point)) return;
    BufferPoint saved;
    glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, point, &saved.buffer);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_START, point, &saved.start);
    glGetInteger64i_v(GL_UNIFORM_BUFFER_SIZE, point, &saved.size);
    uniform_buffers_[point] = saved;
}

void GlAppState::save_storage_buffer(uint32_t point) {
    if (depth_ == 0 || storage_buffers_.contains(point)) return;
    BufferPoint saved;
    glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, point, &saved.buffer);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, point, &saved.start);
    glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, point, &saved.size);
    storage_buffers_[point] = saved;
}

void GlAppState::save_image_unit(uint32_t unit) {
    if (depth_ == 0 || image_units_.contains(unit)) return;
    ImageUnit saved;
    glGetIntegeri_v(GL_IMAGE_BINDING_NAME, unit, &saved.texture);
    glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, unit, &saved.level);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, unit, &saved.layered);
    glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, unit, &saved.layer);
    glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, unit, &saved.access);
    glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, unit, &saved.format);
    image_units_[unit] = saved;
}

void GlAppState::save_draw_buffer(uint32_t index) {
    if (depth_ == 0 || draw_buffers_.contains(index)) return;
    DrawBuffer saved;
    saved.blend = glIsEnabledi(GL_BLEND, index);
    glGetIntegeri_v(GL_BLEND_SRC_RGB, index, &saved.src_rgb);
    glGetIntegeri_v(GL_BLEND_DST_RGB, index, &saved.dst_rgb);
    glGetIntegeri_v(GL_BLEND_SRC_ALPHA, index, &saved.src_alpha);
    glGetIntegeri_v(GL_BLEND_DST_ALPHA, index, &saved.dst_alpha);
    glGetIntegeri_v(GL_BLEND_EQUATION_RGB, index, &saved.equation_rgb);
    glGetIntegeri_v(GL_BLEND_EQUATION_ALPHA, index, &saved.equation_alpha);
    glGetBooleani_v(GL_COLOR_WRITEMASK, index, saved.color_mask.data());
    draw_buffers_[index] = saved;
}

}  // namespace loom::gl
