#include "gl_app_context.hpp"

#include <algorithm>
#include <sstream>

#include <epoxy/egl.h>

#include "loom/rhi/shader.hpp"

namespace loom::test {

std::unique_ptr<AppGlContext> AppGlContext::create(std::string& error) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!client || std::string(client).find("EGL_MESA_platform_surfaceless") == std::string::npos) {
        error = "no EGL surfaceless platform";
        return nullptr;
    }
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor) || !eglBindAPI(EGL_OPENGL_API)) {
        error = "cannot initialise the EGL surfaceless display";
        return nullptr;
    }
    const EGLint attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_CONTEXT_FLAGS_KHR, EGL_CONTEXT_OPENGL_DEBUG_BIT_KHR,
        EGL_NONE,
    };
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT) {
        error = "eglCreateContext(OpenGL 4.5 core) failed";
        return nullptr;
    }
    std::unique_ptr<AppGlContext> out(new AppGlContext());
    out->display_ = display;
    out->context_ = context;
    out->make_current();
    return out;
}

AppGlContext::~AppGlContext() {
    release();
    // The display stays initialised: loom's own devices in this process share it.
    eglDestroyContext(static_cast<EGLDisplay>(display_), static_cast<EGLContext>(context_));
}

void AppGlContext::make_current() {
    eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, static_cast<EGLContext>(context_));
}

void AppGlContext::release() {
    eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

namespace {

struct Recorder {
    GlStateSnapshot& out;
    void add(std::string name, std::vector<double> values) { out.values.emplace_back(std::move(name), std::move(values)); }
    void integer(const char* name, GLenum pname, int count = 1) {
        std::vector<GLint> v(static_cast<std::size_t>(std::max(count, 4)));
        glGetIntegerv(pname, v.data());
        add(name, std::vector<double>(v.begin(), v.begin() + count));
    }
    void floats(const char* name, GLenum pname, int count) {
        std::vector<GLfloat> v(static_cast<std::size_t>(count));
        glGetFloatv(pname, v.data());
        add(name, std::vector<double>(v.begin(), v.end()));
    }
    void enabled(const char* name, GLenum cap) { add(name, {static_cast<double>(glIsEnabled(cap))}); }
    void indexed(const std::string& name, GLenum pname, GLuint index) {
        GLint64 v = 0;
        glGetInteger64i_v(pname, index, &v);
        add(name + "[" + std::to_string(index) + "]", {static_cast<double>(v)});
    }
};

}  // namespace

GlStateSnapshot GlStateSnapshot::capture(unsigned units) {
    GlStateSnapshot snapshot;
    Recorder r{snapshot};
    r.integer("GL_CURRENT_PROGRAM", GL_CURRENT_PROGRAM);
    r.integer("GL_VERTEX_ARRAY_BINDING", GL_VERTEX_ARRAY_BINDING);
    r.integer("GL_DRAW_FRAMEBUFFER_BINDING", GL_DRAW_FRAMEBUFFER_BINDING);
    r.integer("GL_READ_FRAMEBUFFER_BINDING", GL_READ_FRAMEBUFFER_BINDING);
    r.integer("GL_ACTIVE_TEXTURE", GL_ACTIVE_TEXTURE);
    r.integer("GL_UNIFORM_BUFFER_BINDING", GL_UNIFORM_BUFFER_BINDING);
    r.integer("GL_SHADER_STORAGE_BUFFER_BINDING", GL_SHADER_STORAGE_BUFFER_BINDING);
    r.integer("GL_PIXEL_PACK_BUFFER_BINDING", GL_PIXEL_PACK_BUFFER_BINDING);
    r.integer("GL_PIXEL_UNPACK_BUFFER_BINDING", GL_PIXEL_UNPACK_BUFFER_BINDING);
    r.integer("GL_ARRAY_BUFFER_BINDING", GL_ARRAY_BUFFER_BINDING);
    for (GLenum p : {GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST, GL_PACK_ROW_LENGTH, GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_ROWS,
                     GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_IMAGES, GL_PACK_ALIGNMENT, GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST,
                     GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS,
                     GL_UNPACK_SKIP_IMAGES, GL_UNPACK_ALIGNMENT}) {
        r.integer(("pixel store " + std::to_string(p)).c_str(), p);
    }
    r.integer("GL_CLIP_ORIGIN", GL_CLIP_ORIGIN);
    r.integer("GL_CLIP_DEPTH_MODE", GL_CLIP_DEPTH_MODE);
    r.integer("GL_VIEWPORT", GL_VIEWPORT, 4);
    r.floats("GL_DEPTH_RANGE", GL_DEPTH_RANGE, 2);
    r.integer("GL_SCISSOR_BOX", GL_SCISSOR_BOX, 4);
    const std::pair<const char*, GLenum> caps[] = {
        {"GL_SCISSOR_TEST", GL_SCISSOR_TEST}, {"GL_CULL_FACE", GL_CULL_FACE}, {"GL_DEPTH_TEST", GL_DEPTH_TEST},
        {"GL_DEPTH_CLAMP", GL_DEPTH_CLAMP}, {"GL_POLYGON_OFFSET_FILL", GL_POLYGON_OFFSET_FILL},
        {"GL_POLYGON_OFFSET_LINE", GL_POLYGON_OFFSET_LINE}, {"GL_POLYGON_OFFSET_POINT", GL_POLYGON_OFFSET_POINT},
        {"GL_FRAMEBUFFER_SRGB", GL_FRAMEBUFFER_SRGB}, {"GL_TEXTURE_CUBE_MAP_SEAMLESS", GL_TEXTURE_CUBE_MAP_SEAMLESS},
        {"GL_PROGRAM_POINT_SIZE", GL_PROGRAM_POINT_SIZE}, {"GL_MULTISAMPLE", GL_MULTISAMPLE},
        {"GL_STENCIL_TEST", GL_STENCIL_TEST}, {"GL_RASTERIZER_DISCARD", GL_RASTERIZER_DISCARD},
        {"GL_SAMPLE_ALPHA_TO_COVERAGE", GL_SAMPLE_ALPHA_TO_COVERAGE}, {"GL_SAMPLE_ALPHA_TO_ONE", GL_SAMPLE_ALPHA_TO_ONE},
        {"GL_SAMPLE_COVERAGE", GL_SAMPLE_COVERAGE}, {"GL_SAMPLE_MASK", GL_SAMPLE_MASK}, {"GL_SAMPLE_SHADING", GL_SAMPLE_SHADING},
        {"GL_COLOR_LOGIC_OP", GL_COLOR_LOGIC_OP}, {"GL_PRIMITIVE_RESTART", GL_PRIMITIVE_RESTART},
        {"GL_PRIMITIVE_RESTART_FIXED_INDEX", GL_PRIMITIVE_RESTART_FIXED_INDEX}, {"GL_LINE_SMOOTH", GL_LINE_SMOOTH},
        {"GL_POLYGON_SMOOTH", GL_POLYGON_SMOOTH}, {"GL_CLIP_DISTANCE0", GL_CLIP_DISTANCE0}, {"GL_CLIP_DISTANCE3", GL_CLIP_DISTANCE3},
        {"GL_DEBUG_OUTPUT", GL_DEBUG_OUTPUT}, {"GL_DEBUG_OUTPUT_SYNCHRONOUS", GL_DEBUG_OUTPUT_SYNCHRONOUS},
        {"GL_DITHER", GL_DITHER},
    };
    for (const auto& [name, cap] : caps) r.enabled(name, cap);
    r.integer("GL_CULL_FACE_MODE", GL_CULL_FACE_MODE);
    r.integer("GL_FRONT_FACE", GL_FRONT_FACE);
    r.integer("GL_POLYGON_MODE", GL_POLYGON_MODE, 1);
    r.floats("GL_POLYGON_OFFSET_FACTOR", GL_POLYGON_OFFSET_FACTOR, 1);
    r.floats("GL_POLYGON_OFFSET_UNITS", GL_POLYGON_OFFSET_UNITS, 1);
    r.integer("GL_DEPTH_FUNC", GL_DEPTH_FUNC);
    r.integer("GL_DEPTH_WRITEMASK", GL_DEPTH_WRITEMASK);
    r.integer("GL_STENCIL_WRITEMASK", GL_STENCIL_WRITEMASK);
    r.integer("GL_STENCIL_BACK_WRITEMASK", GL_STENCIL_BACK_WRITEMASK);
    r.integer("GL_STENCIL_FUNC", GL_STENCIL_FUNC);
    r.floats("GL_BLEND_COLOR", GL_BLEND_COLOR, 4);
    r.floats("GL_LINE_WIDTH", GL_LINE_WIDTH, 1);
    r.integer("GL_PROVOKING_VERTEX", GL_PROVOKING_VERTEX);
    for (GLuint i = 0; i < 8; ++i) {
        r.add("GL_BLEND[" + std::to_string(i) + "]", {static_cast<double>(glIsEnabledi(GL_BLEND, i))});
        for (GLenum p : {GL_BLEND_SRC_RGB, GL_BLEND_DST_RGB, GL_BLEND_SRC_ALPHA, GL_BLEND_DST_ALPHA, GL_BLEND_EQUATION_RGB,
                         GL_BLEND_EQUATION_ALPHA}) {
            r.indexed("blend " + std::to_string(p), p, i);
        }
        GLboolean mask[4] = {};
        glGetBooleani_v(GL_COLOR_WRITEMASK, i, mask);
        r.add("GL_COLOR_WRITEMASK[" + std::to_string(i) + "]", {double(mask[0]), double(mask[1]), double(mask[2]), double(mask[3])});
    }
    GLint active = 0;
    glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
    std::vector<GLuint> points;
    for (GLuint i = 0; i < units; ++i) points.push_back(i);
    points.push_back(rhi::kGlPushConstantBinding);
    for (GLuint unit : points) {
        const std::string u = "[" + std::to_string(unit) + "]";
        glActiveTexture(GL_TEXTURE0 + unit);
        for (GLenum p : {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_3D, GL_TEXTURE_BINDING_CUBE_MAP,
                         GL_TEXTURE_BINDING_2D_MULTISAMPLE, GL_SAMPLER_BINDING}) {
            GLint v = 0;
            glGetIntegerv(p, &v);
            r.add("texture unit binding " + std::to_string(p) + u, {static_cast<double>(v)});
        }
        for (GLenum p : {GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE}) r.indexed("ubo " + std::to_string(p), p, unit);
        GLint max_ssbo = 0, max_images = 0;
        glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &max_ssbo);
        glGetIntegerv(GL_MAX_IMAGE_UNITS, &max_images);
        if (unit < static_cast<GLuint>(max_ssbo)) {
            for (GLenum p : {GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START, GL_SHADER_STORAGE_BUFFER_SIZE}) {
                r.indexed("ssbo " + std::to_string(p), p, unit);
            }
        }
        if (unit < static_cast<GLuint>(max_images)) {
            for (GLenum p : {GL_IMAGE_BINDING_NAME, GL_IMAGE_BINDING_LEVEL, GL_IMAGE_BINDING_LAYERED, GL_IMAGE_BINDING_LAYER,
                             GL_IMAGE_BINDING_ACCESS, GL_IMAGE_BINDING_FORMAT}) {
                r.indexed("image " + std::to_string(p), p, unit);
            }
        }
    }
    glActiveTexture(static_cast<GLenum>(active));
    return snapshot;
}

std::string GlStateSnapshot::diff(const GlStateSnapshot& after) const {
    std::ostringstream out;
    auto print = [&](const std::vector<double>& v) {
        for (std::size_t i = 0; i < v.size(); ++i) out << (i ? " " : "") << v[i];
    };
    for (std::size_t i = 0; i < values.size() && i < after.values.size(); ++i) {
        if (values[i] == after.values[i]) continue;
        out << values[i].first << ": ";
        print(values[i].second);
        out << " -> ";
        print(after.values[i].second);
        out << "\n";
    }
    return out.str();
}

}  // namespace loom::test
