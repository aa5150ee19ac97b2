// GlDevice: uploads and readbacks. Rows are top-first in memory on both sides: with the
// upper-left clip origin, row 0 of a GL texture is the top row, so nothing is flipped.
#include <algorithm>
#include <cstring>

#include "gl_device.hpp"

namespace loom::gl {
namespace {

std::string quote_name(const std::string& name) { return "'" + name + "'"; }

uint32_t mip_extent(uint32_t size, uint32_t mip) { return std::max(1u, size >> mip); }

bool is_layered(const GlTexture& t) { return t.target != GL_TEXTURE_2D && t.target != GL_TEXTURE_2D_MULTISAMPLE; }

/// Layers (or depth slices for 3D) of mip `mip`.
uint32_t layer_count(const GlTexture& t, uint32_t mip) {
    return t.desc.dimension == rhi::TextureDimension::Tex3D ? mip_extent(t.desc.depth_or_layers, mip) : t.desc.depth_or_layers;
}

}  // namespace

Status GlDevice::write_buffer(rhi::BufferHandle buffer, uint64_t offset, std::span<const std::byte> data) {
    context_->make_current();
    auto found = buffers_.get(buffer);
    if (!found.ok()) return found.take_error();
    GlBuffer& b = **found;
    if (offset > b.desc.size || data.size() > b.desc.size - offset) {
        return Error{ErrorCode::InvalidArgument, "write_buffer to buffer " + quote_name(b.desc.name) + ": " +
                                                     std::to_string(data.size()) + " bytes at offset " + std::to_string(offset) +
                                                     " exceed its size " + std::to_string(b.desc.size)};
    }
    if (data.empty()) return {};
    glNamedBufferSubData(b.name, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(data.size()), data.data());
    count_upload(data.size());
    return {};
}

Result<std::vector<std::byte>> GlDevice::read_buffer(rhi::BufferHandle buffer, uint64_t offset, uint64_t size) {
    context_->make_current();
    auto found = buffers_.get(buffer);
    if (!found.ok()) return found.take_error();
    GlBuffer& b = **found;
    if (offset > b.desc.size || size > b.desc.size - offset) {
        return Error{ErrorCode::InvalidArgument, "read_buffer of buffer " + quote_name(b.desc.name) + ": " + std::to_string(size) +
                                                     " bytes at offset " + std::to_string(offset) + " exceed its size " +
                                                     std::to_string(b.desc.size)};
    }
    // Shader writes become visible to buffer reads only after a barrier.
    if (b.state == rhi::ResourceState::Storage) glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::byte> out(size);
    if (size > 0) glGetNamedBufferSubData(b.name, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(size), out.data());
    return out;
}

Status GlDevice::write_texture(rhi::TextureHandle texture, const rhi::TextureRegion& region, std::span<const std::byte> data) {
    context_->make_current();
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    GlTexture& t = **found;
    const std::string what = "write_texture to texture " + quote_name(t.desc.name) + ": ";
    auto invalid = [&](const std::string& message) { return Error{ErrorCode::InvalidArgument, what + message}; };
    if (t.desc.samples > 1) return invalid("a multisampled texture cannot be uploaded to");
    if (region.mip >= t.desc.mip_levels) {
        return invalid("mip " + std::to_string(region.mip) + " out of range (" + std::to_string(t.desc.mip_levels) + " levels)");
    }
    const uint32_t mw = mip_extent(t.desc.width, region.mip), mh = mip_extent(t.desc.height, region.mip);
    const bool is3d = t.desc.dimension == rhi::TextureDimension::Tex3D;
    const uint32_t layers = layer_count(t, region.mip);
    const uint32_t w = region.extent.width ? region.extent.width : mw - std::min(mw, region.origin.x);
    const uint32_t h = region.extent.height ? region.extent.height : mh - std::min(mh, region.origin.y);
    uint32_t z = 0, d = 1;
    if (is3d) {
        if (region.layer != 0) return invalid("a 3D texture has no layers; use origin.z");
        z = region.origin.z;
        d = region.extent.depth ? region.extent.depth : layers - std::min(layers, z);
    } else {
        if (region.origin.z != 0 || region.extent.depth > 1) return invalid("origin.z / extent.depth apply to 3D textures only");
        z = region.layer;
    }
    if (uint64_t{region.origin.x} + w > mw || uint64_t{region.origin.y} + h > mh || uint64_t{z} + d > layers || w == 0 ||
        h == 0 || d == 0) {
        return invalid("region " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d) + " at (" +
                       std::to_string(region.origin.x) + "," + std::to_string(region.origin.y) + "," + std::to_string(z) +
                       ") does not fit mip " + std::to_string(region.mip) + " (" + std::to_string(mw) + "x" +
                       std::to_string(mh) + "x" + std::to_string(layers) + ")");
    }
    const uint64_t expected = uint64_t{w} * h * d * rhi::format_info(t.desc.format).bytes_per_texel;
    if (data.size() != expected) {
        return invalid(std::to_string(data.size()) + " bytes given, the region needs " + std::to_string(expected));
    }
    std::vector<std::byte> converted(data.begin(), data.end());
    to_gl_layout(t.desc.format, converted);
    // Pixel-store state and buffer bindings of the application's context must not apply.
    const GlAppStateScope scope = app_state_scope();
    const auto level = static_cast<GLint>(region.mip);
    if (t.target == GL_TEXTURE_2D) {
        glTextureSubImage2D(t.name, level, static_cast<GLint>(region.origin.x), static_cast<GLint>(region.origin.y),
                            static_cast<GLsizei>(w), static_cast<GLsizei>(h), t.format->client_format, t.format->client_type,
                            converted.data());
    } else {
        glTextureSubImage3D(t.name, level, static_cast<GLint>(region.origin.x), static_cast<GLint>(region.origin.y),
                            static_cast<GLint>(z), static_cast<GLsizei>(w), static_cast<GLsizei>(h), static_cast<GLsizei>(d),
                            t.format->client_format, t.format->client_type, converted.data());
    }
    count_upload(data.size());
    // Uploaded textures are ready to sample, as on Vulkan, where the upload ends with a
    // transition to the shader-read layout (textures that cannot be sampled stay CopyDst).
    t.state = rhi::has_any(t.desc.usage, rhi::TextureUsage::Sampled) ? rhi::ResourceState::ShaderRead
                                                                       : rhi::ResourceState::CopyDst;
    return {};
}

Result<rhi::Image> GlDevice::read_texture(rhi::TextureHandle texture, uint32_t mip, uint32_t layer) {
    context_->make_current();
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    const GlAppStateScope scope = app_state_scope();
    return read_texture_gl(**found, mip, layer);
}

Result<rhi::Image> GlDevice::read_texture_gl(GlTexture& t, uint32_t mip, uint32_t layer) {
    const std::string what = "read_texture of texture " + quote_name(t.desc.name) + ": ";
    if (mip >= t.desc.mip_levels) {
        return Error{ErrorCode::InvalidArgument, what + "mip " + std::to_string(mip) + " out of range (" +
                                                     std::to_string(t.desc.mip_levels) + " levels)"};
    }
    if (layer >= layer_count(t, mip)) {
        return Error{ErrorCode::InvalidArgument, what + "layer " + std::to_string(layer) + " out of range (" +
                                                     std::to_string(layer_count(t, mip)) + ")"};
    }
    const uint32_t w = mip_extent(t.desc.width, mip), h = mip_extent(t.desc.height, mip);
    rhi::Image image(w, h, t.desc.format);
    if (t.state == rhi::ResourceState::Storage) glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    if (t.desc.samples > 1) {
        // Resolve into a single-sampled texture first; GL cannot read multisampled texels back.
        if (!rhi::format_info(t.desc.format).is_color()) {
            return Error{ErrorCode::Unsupported, what + "multisampled depth/stencil textures cannot be read back"};
        }
        GLuint resolved = 0, src_fbo = 0, dst_fbo = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &resolved);
        glTextureStorage2D(resolved, 1, t.format->internal_format, static_cast<GLsizei>(w), static_cast<GLsizei>(h));
        glCreateFramebuffers(1, &src_fbo);
        glCreateFramebuffers(1, &dst_fbo);
        glNamedFramebufferTexture(src_fbo, GL_COLOR_ATTACHMENT0, t.name, 0);
        glNamedFramebufferTexture(dst_fbo, GL_COLOR_ATTACHMENT0, resolved, 0);
        glNamedFramebufferReadBuffer(src_fbo, GL_COLOR_ATTACHMENT0);
        glNamedFramebufferDrawBuffer(dst_fbo, GL_COLOR_ATTACHMENT0);
        cache_->enable(GL_SCISSOR_TEST, false);
        // Resolving must not re-encode sRGB values: copy them as stored.
        glDisable(GL_FRAMEBUFFER_SRGB);
        glBlitNamedFramebuffer(src_fbo, dst_fbo, 0, 0, static_cast<GLint>(w), static_cast<GLint>(h), 0, 0,
                               static_cast<GLint>(w), static_cast<GLint>(h), GL_COLOR_BUFFER_BIT, GL_NEAREST);
        glEnable(GL_FRAMEBUFFER_SRGB);
        glGetTextureImage(resolved, 0, t.format->client_format, t.format->client_type,
                          static_cast<GLsizei>(image.pixels.size()), image.pixels.data());
        glDeleteFramebuffers(1, &src_fbo);
        glDeleteFramebuffers(1, &dst_fbo);
        glDeleteTextures(1, &resolved);
        cache_->invalidate();
    } else {
        glGetTextureSubImage(t.name, static_cast<GLint>(mip), 0, 0, is_layered(t) ? static_cast<GLint>(layer) : 0,
                             static_cast<GLsizei>(w), static_cast<GLsizei>(h), 1, t.format->client_format,
                             t.format->client_type, static_cast<GLsizei>(image.pixels.size()), image.pixels.data());
    }
    from_gl_layout(t.desc.format, image.pixels);
    return image;
}

}  // namespace loom::gl
