#pragma once
// The application's GL state around loom's work on a context the application owns (a device
// made by create_gl_device_on_current_context). loom runs with its own baseline (upper-left
// clip origin, depth 0..1, tightly packed pixel transfers, sRGB writes encoded, ...) and puts
// back every value it changed, so that the application finds its state as it left it.
//
// Fixed state is saved when loom's work starts (GlAppStateScope) and restored when it ends.
// Indexed bindings (texture and sampler units, uniform and storage buffer points, image units,
// per-draw-buffer blending and colour masks) are many; they are saved by the state cache right
// before loom changes one of them for the first time, and only those are restored.
// docs/embedding.md lists the state, item by item; tests/embed checks it.

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include <epoxy/gl.h>

#include "gl_state_cache.hpp"

namespace loom::gl {

/// Saves and restores the application's GL state (see the top of this file).
class GlAppState {
public:
    GlAppState();

    /// Saves the fixed state and sets loom's baseline. Nests: only the outermost call saves.
    void enter();
    /// Restores everything saved since the outermost enter().
    void leave();
    [[nodiscard]] bool active() const { return depth_ > 0; }

    // Called by the state cache before it changes one indexed binding.
    void save_texture_unit(uint32_t unit);
    void save_sampler_unit(uint32_t unit);
    void save_uniform_buffer(uint32_t point);
    void save_storage_buffer(uint32_t point);
    void save_image_unit(uint32_t unit);
    void save_draw_buffer(uint32_t index);

private:
    struct TextureUnit {
        std::array<GLint, 5> textures{};  ///< per target in kTextureTargets
        GLint sampler = 0;
        bool textures_saved = false;
        bool sampler_saved = false;
    };
    struct BufferPoint {
        GLint buffer = 0;
        GLint64 start = 0;
        GLint64 size = 0;
    };
    struct ImageUnit {
        GLint texture = 0, level = 0, layered = 0, layer = 0, access = 0, format = 0;
    };
    struct DrawBuffer {
        GLboolean blend = GL_FALSE;
        GLint src_rgb = 0, dst_rgb = 0, src_alpha = 0, dst_alpha = 0, equation_rgb = 0, equation_alpha = 0;
        std::array<GLboolean, 4> color_mask{};
    };

    /// State saved when the scope is entered.
    struct Fixed {
        GLint program = 0, vertex_array = 0, draw_framebuffer = 0, read_framebuffer = 0, active_texture = GL_TEXTURE0;
        GLint uniform_buffer = 0, storage_buffer = 0, pixel_pack_buffer = 0, pixel_unpack_buffer = 0;
        GLint draw_indirect_buffer = 0;  ///< bound by draw_indexed_indirect
        std::array<GLint, 8> pack{};    ///< per name in kPixelStore, GL_PACK_*
        std::array<GLint, 8> unpack{};  ///< the same, GL_UNPACK_*
        GLint clip_origin = GL_LOWER_LEFT, clip_depth_mode = GL_NEGATIVE_ONE_TO_ONE;
        std::array<GLfloat, 4> viewport{};
        std::array<GLdouble, 2> depth_range{};
        std::array<GLint, 4> scissor_box{};
        std::vector<GLboolean> scissor_test;  ///< per viewport
        std::vector<GLboolean> caps;          ///< per capability in kCapabilities
        std::vector<GLboolean> clip_distances;
        GLint cull_face_mode = GL_BACK, front_face = GL_CCW;
        std::array<GLint, 2> polygon_mode{};
        GLfloat polygon_offset_factor = 0.0f, polygon_offset_units = 0.0f;
        GLint depth_func = GL_LESS;
        GLboolean depth_mask = GL_TRUE;
        GLint stencil_writemask = 0, stencil_back_writemask = 0;
        std::array<GLfloat, 4> blend_color{};
        GLfloat line_width = 1.0f;
        GLint provoking_vertex = GL_LAST_VERTEX_CONVENTION;
    };

    void save_fixed();
    void apply_baseline();
    void restore_fixed();
    void restore_indexed();

    int depth_ = 0;
    GLint max_viewports_ = 1;
    GLint max_clip_distances_ = 8;
    Fixed fixed_;
    std::map<uint32_t, TextureUnit> texture_units_;
    std::map<uint32_t, BufferPoint> uniform_buffers_;
    std::map<uint32_t, BufferPoint> storage_buffers_;
    std::map<uint32_t, ImageUnit> image_units_;
    std::map<uint32_t, DrawBuffer> draw_buffers_;
};

/// Enters the application-state scope of `state` (when not null) for its lifetime. The state
/// cache forgets what it knew on both ends: the application may have changed anything before,
/// and the restored state is the application's after.
class GlAppStateScope {
public:
    GlAppStateScope(GlAppState* state, GlStateCache& cache) : state_(state), cache_(&cache) {
        if (!state_) return;
        cache_->invalidate();
        state_->enter();
    }
    ~GlAppStateScope() {
        if (!state_) return;
        state_->leave();
        cache_->invalidate();
    }
    GlAppStateScope(const GlAppStateScope&) = delete;
    GlAppStateScope& operator=(const GlAppStateScope&) = delete;

private:
    GlAppState* state_;
    GlStateCache* cache_;
};

}  // namespace loom::gl
