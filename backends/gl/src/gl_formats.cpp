#include "gl_formats.hpp"

#include <cstring>

namespace loom::gl {
namespace {

using rhi::Format;

constexpr std::array<GlFormat, rhi::kFormatCount> make_table() {
    std::array<GlFormat, rhi::kFormatCount> t{};
    auto set = [&t](Format f, GLenum internal, GLenum client, GLenum type) {
        t[static_cast<std::size_t>(f)] = GlFormat{internal, client, type};
    };
    set(Format::R8Unorm, GL_R8, GL_RED, GL_UNSIGNED_BYTE);
    set(Format::R8Snorm, GL_R8_SNORM, GL_RED, GL_BYTE);
    set(Format::R8Uint, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE);
    set(Format::R8Sint, GL_R8I, GL_RED_INTEGER, GL_BYTE);
    set(Format::RG8Unorm, GL_RG8, GL_RG, GL_UNSIGNED_BYTE);
    set(Format::RG8Snorm, GL_RG8_SNORM, GL_RG, GL_BYTE);
    set(Format::RG8Uint, GL_RG8UI, GL_RG_INTEGER, GL_UNSIGNED_BYTE);
    set(Format::RG8Sint, GL_RG8I, GL_RG_INTEGER, GL_BYTE);
    set(Format::RGBA8Unorm, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE);
    set(Format::RGBA8Snorm, GL_RGBA8_SNORM, GL_RGBA, GL_BYTE);
    set(Format::RGBA8Uint, GL_RGBA8UI, GL_RGBA_INTEGER, GL_UNSIGNED_BYTE);
    set(Format::RGBA8Sint, GL_RGBA8I, GL_RGBA_INTEGER, GL_BYTE);
    set(Format::RGBA8Srgb, GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE);
    // GL has no BGRA storage; the texture is RGBA and the client format swaps on transfer.
    set(Format::BGRA8Unorm, GL_RGBA8, GL_BGRA, GL_UNSIGNED_BYTE);
    set(Format::BGRA8Srgb, GL_SRGB8_ALPHA8, GL_BGRA, GL_UNSIGNED_BYTE);
    set(Format::R16Unorm, GL_R16, GL_RED, GL_UNSIGNED_SHORT);
    set(Format::RG16Unorm, GL_RG16, GL_RG, GL_UNSIGNED_SHORT);
    set(Format::RGBA16Unorm, GL_RGBA16, GL_RGBA, GL_UNSIGNED_SHORT);
    set(Format::R16Uint, GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT);
    set(Format::R16Sint, GL_R16I, GL_RED_INTEGER, GL_SHORT);
    set(Format::R16Float, GL_R16F, GL_RED, GL_HALF_FLOAT);
    set(Format::RG16Float, GL_RG16F, GL_RG, GL_HALF_FLOAT);
    set(Format::RGBA16Float, GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT);
    set(Format::R32Uint, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT);
    set(Format::R32Sint, GL_R32I, GL_RED_INTEGER, GL_INT);
    set(Format::R32Float, GL_R32F, GL_RED, GL_FLOAT);
    set(Format::RG32Float, GL_RG32F, GL_RG, GL_FLOAT);
    set(Format::RGBA32Float, GL_RGBA32F, GL_RGBA, GL_FLOAT);
    // The packed types below put R (or the first channel) in the low bits, as loom does.
    set(Format::R11G11B10Float, GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV);
    set(Format::RGB10A2Unorm, GL_RGB10_A2, GL_RGBA, GL_UNSIGNED_INT_2_10_10_10_REV);
    set(Format::RGB9E5Float, GL_RGB9_E5, GL_RGB, GL_UNSIGNED_INT_5_9_9_9_REV);
    set(Format::Depth16, GL_DEPTH_COMPONENT16, GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT);
    // Transferred as 32-bit normalised integers; see to_gl_layout.
    set(Format::Depth24, GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT);
    set(Format::Depth32F, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT);
    set(Format::Depth24Stencil8, GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8);
    set(Format::Depth32FStencil8, GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV);
    set(Format::Stencil8, GL_STENCIL_INDEX8, GL_STENCIL_INDEX, GL_UNSIGNED_BYTE);
    return t;
}

constexpr auto kTable = make_table();

uint32_t load_u32(const std::byte* p) {
    uint32_t v;
    std::memcpy(&v, p, 4);
    return v;
}
void store_u32(std::byte* p, uint32_t v) { std::memcpy(p, &v, 4); }

}  // namespace

const GlFormat* gl_format(rhi::Format format) {
    const auto index = static_cast<std::size_t>(format);
    if (index == 0 || index >= kTable.size()) return nullptr;
    return &kTable[index];
}

void to_gl_layout(rhi::Format format, std::span<std::byte> texels) {
    switch (format) {
        case Format::Depth24:
            // loom: depth in the low 24 bits. GL_UNSIGNED_INT: depth normalised to 32 bits.
            // The low byte is set to half a 24-bit step, so that a driver converting to 24
            // bits by truncation and one rounding to nearest both land on d (Mesa truncates:
            // the exact rescale (d << 8 | d >> 16) came back as d - 1 for small d).
            for (std::size_t i = 0; i + 4 <= texels.size(); i += 4) {
                const uint32_t d = load_u32(&texels[i]) & 0xFFFFFFu;
                store_u32(&texels[i], (d << 8) | 0x80u);
            }
            return;
        case Format::Depth24Stencil8:
            // loom: depth low 24 bits, stencil high 8. GL_UNSIGNED_INT_24_8: depth high, stencil low.
            for (std::size_t i = 0; i + 4 <= texels.size(); i += 4) {
                const uint32_t w = load_u32(&texels[i]);
                store_u32(&texels[i], ((w & 0xFFFFFFu) << 8) | (w >> 24));
            }
            return;
        case Format::Depth32FStencil8:
            // Same layout (float, then stencil in the low byte of the second word); the 24
            // padding bits must be zero.
            for (std::size_t i = 0; i + 8 <= texels.size(); i += 8) store_u32(&texels[i + 4], load_u32(&texels[i + 4]) & 0xFFu);
            return;
        default: return;
    }
}

void from_gl_layout(rhi::Format format, std::span<std::byte> texels) {
    switch (format) {
        case Format::Depth24:
            for (std::size_t i = 0; i + 4 <= texels.size(); i += 4) store_u32(&texels[i], load_u32(&texels[i]) >> 8);
            return;
        case Format::Depth24Stencil8:
            for (std::size_t i = 0; i + 4 <= texels.size(); i += 4) {
                const uint32_t w = load_u32(&texels[i]);
                store_u32(&texels[i], (w >> 8) | ((w & 0xFFu) << 24));
            }
            return;
        case Format::Depth32FStencil8:
            for (std::size_t i = 0; i + 8 <= texels.size(); i += 8) store_u32(&texels[i + 4], load_u32(&texels[i + 4]) & 0xFFu);
            return;
        default: return;
    }
}

GLenum attachment_point(rhi::Format format, uint32_t color_index) {
    const rhi::FormatInfo& info = rhi::format_info(format);
    if (info.has_depth() && info.has_stencil()) return GL_DEPTH_STENCIL_ATTACHMENT;
    if (info.has_depth()) return GL_DEPTH_ATTACHMENT;
    if (info.has_stencil()) return GL_STENCIL_ATTACHMENT;
    return GL_COLOR_ATTACHMENT0 + color_index;
}

// The sample counts GL reports for multisampled 2D textures of `internal_format`, as bits.
uint32_t multisample_counts(GLenum internal_format) {
    GLint count = 0;
    glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, internal_format, GL_NUM_SAMPLE_COUNTS, 1, &count);
    if (count <= 0) return 0;
    std::vector<GLint> samples(static_cast<std::size_t>(count));
    glGetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, internal_format, GL_SAMPLES, count, samples.data());
    uint32_t bits = 0;
    for (GLint n : samples) {
        if (n > 1 && n <= 64 && std::has_single_bit(static_cast<uint32_t>(n))) bits |= static_cast<uint32_t>(n);
    }
    return bits;
}

std::array<rhi::FormatCapabilities, rhi::kFormatCount> query_format_capabilities() {
    std::array<rhi::FormatCapabilities, rhi::kFormatCount> caps{};
    auto query = [](GLenum internal, GLenum pname) {
        GLint value = GL_NONE;
        glGetInternalformativ(GL_TEXTURE_2D, internal, pname, 1, &value);
        return value;
    };
    // GL_FULL_SUPPORT only: a "caveat" may mean a software fallback or a partial feature.
    auto full = [&](GLenum internal, GLenum pname) { return query(internal, pname) == GL_FULL_SUPPORT; };
    for (rhi::Format format : rhi::all_formats()) {
        const GlFormat* gl = gl_format(format);
        rhi::FormatCapabilities& c = caps[static_cast<std::size_t>(format)];
        if (!gl || query(gl->internal_format, GL_INTERNALFORMAT_SUPPORTED) != GL_TRUE) continue;
        const rhi::FormatInfo& info = rhi::format_info(format);
        const GLenum f = gl->internal_format;
        c.sampled = full(f, GL_FRAGMENT_TEXTURE);
        c.filterable = c.sampled && !info.is_integer() && full(f, GL_FILTER);
        if (info.is_color()) {
            c.color_attachment = full(f, GL_FRAMEBUFFER_RENDERABLE);
            c.blendable = c.color_attachment && !info.is_integer() && full(f, GL_FRAMEBUFFER_BLEND);
            // Image load/store in both directions; BGRA has no image format qualifier in GLSL.
            c.storage = !info.features.bgra && full(f, GL_SHADER_IMAGE_LOAD) && full(f, GL_SHADER_IMAGE_STORE);
        } else {
            c.depth_stencil_attachment = full(f, GL_FRAMEBUFFER_RENDERABLE);
        }
        if (c.color_attachment || c.depth_stencil_attachment) c.sample_counts |= multisample_counts(f);
    }
    return caps;
}

}  // namespace loom::gl
