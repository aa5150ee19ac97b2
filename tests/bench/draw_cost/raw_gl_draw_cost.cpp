// raw_gl_draw_cost: the work of loom_draw_cost --backend gl written directly against OpenGL 4.5
// (EGL surfaceless, libepoxy), the way a competent GL programmer would: per-draw data in a
// persistently mapped ring bound with glBindBufferRange, one GL call per changed state.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "draw_cost_common.hpp"

namespace {

using namespace loom;
using draw_cost::Path;

[[noreturn]] void die(const std::string& message) {
    std::fprintf(stderr, "raw_gl_draw_cost: %s\n", message.c_str());
    std::exit(EXIT_FAILURE);
}

void create_context() {
    EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) die("no surfaceless EGL display");
    if (!eglBindAPI(EGL_OPENGL_API)) die("eglBindAPI failed");
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        die("no OpenGL 4.5 core context");
    }
}

GLuint compile_stage(GLenum stage, const rhi::ShaderModule& module) {
    const GLuint shader = glCreateShader(stage);
    const char* source = module.gl_source.c_str();
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) die("cannot compile " + module.name);
    return shader;
}

GLuint make_program(Path path, int variant) {
    auto vs = draw_cost::vertex_shader(path);
    auto fs = draw_cost::fragment_shader(path, variant);
    if (!vs.ok() || !fs.ok()) die("shader compilation failed");
    const GLuint program = glCreateProgram();
    const GLuint v = compile_stage(GL_VERTEX_SHADER, *vs), f = compile_stage(GL_FRAGMENT_SHADER, *fs);
    glAttachShader(program, v);
    glAttachShader(program, f);
    glLinkProgram(program);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) die("cannot link the program");
    glDeleteShader(v);
    glDeleteShader(f);
    return program;
}

struct Objects {
    GLuint framebuffer = 0, target = 0, vao = 0, ring = 0, sampler = 0;
    std::byte* ring_memory = nullptr;
    GLint ring_alignment = 256;
    std::array<GLuint, 2> programs{}, textures{}, vertices{}, indices{};
};

Objects create_objects(Path path, uint32_t draws) {
    Objects o;
    glCreateTextures(GL_TEXTURE_2D, 1, &o.target);
    glTextureStorage2D(o.target, 1, GL_RGBA8, 64, 64);
    glCreateFramebuffers(1, &o.framebuffer);
    glNamedFramebufferTexture(o.framebuffer, GL_COLOR_ATTACHMENT0, o.target, 0);
    glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
    glCreateVertexArrays(1, &o.vao);
    for (int variant = 0; variant < (path == Path::Pipeline ? 2 : 1); ++variant) {
        o.programs[static_cast<std::size_t>(variant)] = make_program(path, variant);
    }
    if (path == Path::PushConstants || path == Path::TransientUniforms) {
        // Each draw's constants at the next multiple of the offset alignment after the last.
        GLint alignment = 256;
        glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
        const auto constants = static_cast<GLint>(sizeof(draw_cost::DrawConstants));
        o.ring_alignment = (constants + alignment - 1) / alignment * alignment;
        const GLsizeiptr size = static_cast<GLsizeiptr>(draws) * o.ring_alignment;
        const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glCreateBuffers(1, &o.ring);
        glNamedBufferStorage(o.ring, size, nullptr, flags);
        o.ring_memory = static_cast<std::byte*>(glMapNamedBufferRange(o.ring, 0, size, flags));
    }
    if (path == Path::BindGroup) {
        glCreateSamplers(1, &o.sampler);
        glBindSampler(rhi::gl_binding_point(0, 0), o.sampler);
        glCreateTextures(GL_TEXTURE_2D, 2, o.textures.data());
        for (std::size_t i = 0; i < 2; ++i) {
            glTextureStorage2D(o.textures[i], 1, GL_RGBA8, 4, 4);
            std::array<unsigned char, 64> texels{};
            texels.fill(static_cast<unsigned char>(i == 0 ? 64 : 192));
            glTextureSubImage2D(o.textures[i], 0, 0, 0, 4, 4, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
        }
    }
    if (path == Path::VertexBuffers) {
        glCreateBuffers(2, o.vertices.data());
        glCreateBuffers(2, o.indices.data());
        for (std::size_t i = 0; i < 2; ++i) {
            const float d = i == 0 ? 0.0f : 0.5f;
            const std::array<float, 6> positions = {-0.9f + d, -0.9f, -0.8f + d, -0.9f, -0.9f + d, -0.8f};
            const std::array<uint32_t, 3> triangle = {0, 1, 2};
            glNamedBufferStorage(o.vertices[i], sizeof(positions), positions.data(), 0);
            glNamedBufferStorage(o.indices[i], sizeof(triangle), triangle.data(), 0);
        }
        glEnableVertexArrayAttrib(o.vao, 0);
        glVertexArrayAttribFormat(o.vao, 0, 2, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(o.vao, 0, 0);
    }
    return o;
}

void frame(const Objects& o, Path path, uint32_t draws) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, o.framebuffer);
    glViewport(0, 0, 64, 64);
    const GLfloat clear[4] = {0, 0, 0, 0};
    glClearNamedFramebufferfv(o.framebuffer, GL_COLOR, 0, clear);
    glUseProgram(o.programs[0]);
    glBindVertexArray(o.vao);
    const GLuint point = path == Path::PushConstants ? rhi::kGlPushConstantBinding : rhi::gl_binding_point(0, 0);
    switch (path) {
        case Path::PushConstants:
        case Path::TransientUniforms:
            for (uint32_t i = 0; i < draws; ++i) {
                const draw_cost::DrawConstants c = draw_cost::draw_constants(i);
                const auto offset = static_cast<GLintptr>(i) * o.ring_alignment;
                std::memcpy(o.ring_memory + offset, &c, sizeof c);
                glBindBufferRange(GL_UNIFORM_BUFFER, point, o.ring, offset, sizeof c);
                glDrawArrays(GL_TRIANGLES, 0, 3);
            }
            break;
        case Path::BindGroup:
            for (uint32_t i = 0; i < draws; ++i) {
                glBindTextureUnit(point, o.textures[i & 1]);
                glDrawArrays(GL_TRIANGLES, 0, 3);
            }
            break;
        case Path::VertexBuffers:
            for (uint32_t i = 0; i < draws; ++i) {
                glVertexArrayVertexBuffer(o.vao, 0, o.vertices[i & 1], 0, 8);
                glVertexArrayElementBuffer(o.vao, o.indices[i & 1]);
                glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, nullptr);
            }
            break;
        case Path::Pipeline:
            for (uint32_t i = 0; i < draws; ++i) {
                glUseProgram(o.programs[i & 1]);
                glDrawArrays(GL_TRIANGLES, 0, 3);
            }
            break;
    }
    glFinish();
}

}  // namespace

int main(int argc, char** argv) {
    auto options = draw_cost::parse_options(argc, argv, false);
    if (!options.ok()) die(options.error().message);
    create_context();
    const Objects objects = create_objects(options->path, options->draws);
    for (uint32_t i = 0; i < options->warmup_frames; ++i) frame(objects, options->path, options->draws);
    if (glGetError() != GL_NO_ERROR) die("a GL error in the warm-up frames");
    draw_cost::begin_measurement();
    frame(objects, options->path, options->draws);
    draw_cost::end_measurement();
    draw_cost::report("raw-gl", *options);
    return EXIT_SUCCESS;
}
