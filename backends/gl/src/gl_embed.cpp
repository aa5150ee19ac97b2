// Embedding: application textures as loom textures, GL names of loom textures, and showing a
// loom texture in an application framebuffer (loom/gl/gl_embed.hpp).
#include "gl_device.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::gl {
namespace {

using rhi::validation::in_quotes;

Result<GlDevice*> as_gl_device(rhi::Device& device, std::string_view what) {
    auto* gl = dynamic_cast<GlDevice*>(&device);
    if (!gl) {
        return Error{ErrorCode::InvalidArgument, std::string(what) + ": the device is a " +
                                                     std::string(rhi::backend_name(device.backend())) +
                                                     " device, not an OpenGL one"};
    }
    return gl;
}

std::string_view target_name(GLenum target) {
    switch (target) {
        case GL_TEXTURE_2D: return "GL_TEXTURE_2D";
        case GL_TEXTURE_2D_MULTISAMPLE: return "GL_TEXTURE_2D_MULTISAMPLE";
        case GL_TEXTURE_2D_ARRAY: return "GL_TEXTURE_2D_ARRAY";
        case GL_TEXTURE_3D: return "GL_TEXTURE_3D";
        case GL_TEXTURE_CUBE_MAP: return "GL_TEXTURE_CUBE_MAP";
        default: return "another target";
    }
}

std::string hex(GLint value) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X", static_cast<unsigned>(value));
    return buf;
}

}  // namespace

Result<rhi::TextureHandle> import_gl_texture(rhi::Device& device, uint32_t texture, const rhi::TextureDesc& desc,
                                             rhi::ResourceState state) {
    auto gl = as_gl_device(device, "import_gl_texture of texture " + in_quotes(desc.name));
    if (!gl.ok()) return gl.take_error();
    return (*gl)->import_texture(texture, desc, state);
}

Result<uint32_t> gl_texture_name(rhi::Device& device, rhi::TextureHandle texture) {
    auto gl = as_gl_device(device, "gl_texture_name");
    if (!gl.ok()) return gl.take_error();
    auto name = (*gl)->texture_name(texture);
    if (!name.ok()) return name.take_error();
    return uint32_t{*name};
}

Status blit_to_framebuffer(rhi::Device& device, rhi::TextureHandle texture, uint32_t framebuffer, int32_t x, int32_t y,
                           uint32_t width, uint32_t height) {
    auto gl = as_gl_device(device, "blit_to_framebuffer");
    if (!gl.ok()) return gl.take_error();
    return (*gl)->blit_to_framebuffer(texture, framebuffer, x, y, static_cast<GLsizei>(width), static_cast<GLsizei>(height));
}

Result<rhi::TextureHandle> GlDevice::import_texture(GLuint name, const rhi::TextureDesc& desc, rhi::ResourceState state) {
    context_->make_current();
    const std::string what = "import_gl_texture of GL texture " + std::to_string(name) + " as " + in_quotes(desc.name) + ": ";
    auto mismatch = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    if (name == 0 || glIsTexture(name) != GL_TRUE) return mismatch("not a texture of the current context");
    LOOM_TRY(rhi::validation::texture_desc(desc, caps_));

    const GLenum target = texture_target(desc);
    GLint actual_target = 0;
    glGetTextureParameteriv(name, GL_TEXTURE_TARGET, &actual_target);
    if (static_cast<GLenum>(actual_target) != target) {
        return mismatch("the texture is a " + std::string(target_name(static_cast<GLenum>(actual_target))) +
                        ", the description needs a " + std::string(target_name(target)));
    }
    const GlFormat* format = gl_format(desc.format);
    auto level = [&](GLint mip, GLenum pname) {
        GLint v = 0;
        glGetTextureLevelParameteriv(name, mip, pname, &v);
        return v;
    };
    const GLint internal_format = level(0, GL_TEXTURE_INTERNAL_FORMAT);
    if (static_cast<GLenum>(internal_format) != format->internal_format) {
        return mismatch("its internal format is " + hex(internal_format) + ", loom stores " +
                        std::string(rhi::format_name(desc.format)) + " as " + hex(static_cast<GLint>(format->internal_format)));
    }
    const uint32_t width = static_cast<uint32_t>(level(0, GL_TEXTURE_WIDTH));
    const uint32_t height = static_cast<uint32_t>(level(0, GL_TEXTURE_HEIGHT));
    const uint32_t depth = static_cast<uint32_t>(level(0, GL_TEXTURE_DEPTH));
    const uint32_t want_depth = desc.dimension == rhi::TextureDimension::Cube ? 1 : desc.depth_or_layers;
    if (width != desc.width || height != desc.height || depth != want_depth) {
        return mismatch("the texture is " + std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(depth) +
                        ", the description says " + std::to_string(desc.width) + "x" + std::to_string(desc.height) + "x" +
                        std::to_string(want_depth));
    }
    if (desc.samples > 1) {
        const auto samples = static_cast<uint32_t>(level(0, GL_TEXTURE_SAMPLES));
        if (samples != desc.samples) {
            return mismatch("the texture has " + std::to_string(samples) + " samples, the description " +
                            std::to_string(desc.samples));
        }
    }
    GLint immutable = GL_FALSE;
    glGetTextureParameteriv(name, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    uint32_t levels = 0;
    if (immutable) {
        GLint immutable_levels = 0;
        glGetTextureParameteriv(name, GL_TEXTURE_IMMUTABLE_LEVELS, &immutable_levels);
        levels = static_cast<uint32_t>(immutable_levels);
    } else {
        while (levels < desc.mip_levels && level(static_cast<GLint>(levels), GL_TEXTURE_WIDTH) > 0) ++levels;
    }
    if (levels < desc.mip_levels) {
        return mismatch("the texture has " + std::to_string(levels) + " mip level(s), the description " +
                        std::to_string(desc.mip_levels));
    }

    GlTexture t;
    t.desc = desc;
    t.name = name;
    t.target = target;
    t.format = format;
    t.set_all(state);
    t.imported = true;
    t.immutable = immutable != GL_FALSE;
    return textures_.insert(std::move(t));
}

Result<GLuint> GlDevice::texture_name(rhi::TextureHandle texture) {
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    return (*found)->name;
}

Status GlDevice::blit_to_framebuffer(rhi::TextureHandle texture, GLuint framebuffer, GLint x, GLint y, GLsizei width,
                                     GLsizei height) {
    context_->make_current();
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    const GlTexture& t = **found;
    const std::string what = "blit_to_framebuffer of texture " + in_quotes(t.desc.name) + ": ";
    if (list_->recording()) {
        return Error{ErrorCode::InvalidState, what + "a frame is being recorded; its commands run at end_frame, blit after it"};
    }
    if (t.target != GL_TEXTURE_2D || !rhi::format_info(t.desc.format).is_color()) {
        return Error{ErrorCode::InvalidArgument, what + "needs a single-sampled 2D colour texture"};
    }
    if (width <= 0 || height <= 0) return Error{ErrorCode::InvalidArgument, what + "the destination rectangle is empty"};
    if (framebuffer != 0 && glIsFramebuffer(framebuffer) != GL_TRUE) {
        return Error{ErrorCode::InvalidArgument, what + "GL name " + std::to_string(framebuffer) + " is not a framebuffer"};
    }
    const GlAppStateScope scope = app_state_scope();
    GLuint source = 0;
    glCreateFramebuffers(1, &source);
    glNamedFramebufferTexture(source, GL_COLOR_ATTACHMENT0, t.name, 0);
    glNamedFramebufferReadBuffer(source, GL_COLOR_ATTACHMENT0);
    cache_->enable(GL_SCISSOR_TEST, false);
    // Row 0 of the texture is loom's top row; GL window coordinates count rows from the bottom.
    const auto w = static_cast<GLint>(t.desc.width), h = static_cast<GLint>(t.desc.height);
    // The stored values, not encoded again for an sRGB-capable framebuffer.
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(source, framebuffer, 0, 0, w, h, x, y + height, x + width, y, GL_COLOR_BUFFER_BIT,
                           width == w && height == h ? GL_NEAREST : GL_LINEAR);
    glEnable(GL_FRAMEBUFFER_SRGB);  // loom's convention (the application's value comes back with the scope)
    glDeleteFramebuffers(1, &source);
    return {};
}

}  // namespace loom::gl
