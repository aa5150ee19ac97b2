// GlDevice: uploads and readbacks. Rows are top-first in memory on both sides: with the
// upper-left clip origin, row 0 of a GL texture is the top row, so nothing is flipped.
#include <algorithm>
#include <cstring>

#include "gl_device.hpp"
#include "loom/rhi/subresources.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::gl {
namespace {

bool is_layered(const GlTexture& t) { return t.target != GL_TEXTURE_2D && t.target != GL_TEXTURE_2D_MULTISAMPLE; }

}  // namespace

Status GlDevice::write_buffer(rhi::BufferHandle buffer, uint64_t offset, std::span<const std::byte> data) {
    context_->make_current();
    auto found = buffers_.get(buffer);
    if (!found.ok()) return found.take_error();
    GlBuffer& b = **found;
    LOOM_TRY(rhi::validation::buffer_write(b.desc, offset, data.size()));
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
    LOOM_TRY(rhi::validation::buffer_read(b.desc, offset, size));
    // Refused as on Vulkan, whose readbacks submit the frame recorded so far and cannot cut a render pass in two.
    LOOM_TRY(
        list_->state().check_outside_render_pass("read_buffer of buffer " + rhi::validation::in_quotes(b.desc.name)));
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
    auto write = rhi::validation::texture_write(t.desc, region, data.size());
    if (!write.ok()) return write.take_error();
    // Arrays and cubes address layers as the z of glTextureSubImage3D, 3D textures depth slices.
    const bool is3d = t.desc.dimension == rhi::TextureDimension::Tex3D;
    const uint32_t w = write->extent.width, h = write->extent.height;
    const uint32_t z = is3d ? write->origin.z : write->layer, d = write->extent.depth;
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
    // Only the subresource written, as on Vulkan.
    t.states[t.subresource(region.mip, t.layers() == 1 ? 0 : region.layer)] =
        rhi::has_any(t.desc.usage, rhi::TextureUsage::Sampled) ? rhi::ResourceState::ShaderRead : rhi::ResourceState::CopyDst;
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
    LOOM_TRY(rhi::validation::texture_read(t.desc, mip, layer));
    // Refused as on Vulkan, whose readbacks submit the frame recorded so far and cannot cut a render pass in two.
    LOOM_TRY(
        list_->state().check_outside_render_pass("read_texture of texture " + rhi::validation::in_quotes(t.desc.name)));
    const rhi::Extent3D size = rhi::mip_extent(t.desc, mip);
    const uint32_t w = size.width, h = size.height;
    rhi::Image image(w, h, t.desc.format);
    if (t.states[t.subresource(mip, t.layers() == 1 ? 0 : layer)] == rhi::ResourceState::Storage) {
        glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);
    }
    if (t.desc.samples > 1) {
        // Resolve into a single-sampled texture first; GL cannot read multisampled texels back.
        // (Only colour: the validation layer refuses multisampled depth/stencil readback.)
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
