#pragma once
// loom formats in GL terms: internal formats for storage, client formats/types for uploads
// and readbacks, and the conversions where GL's packed depth layouts differ from loom's.

#include <cstdint>
#include <span>
#include <vector>

#include <epoxy/gl.h>

#include "loom/rhi/device.hpp"
#include "loom/rhi/format.hpp"

namespace loom::gl {

/// How a loom format is stored and transferred in GL.
struct GlFormat {
    GLenum internal_format = 0;  ///< for glTextureStorage*
    GLenum client_format = 0;    ///< format argument of glTextureSubImage / glGetTextureSubImage
    GLenum client_type = 0;      ///< type argument of the same
};

/// The GL description of `format`, or nullptr for Undefined.
const GlFormat* gl_format(rhi::Format format);

/// Converts texels in loom's CPU layout to the layout GL transfers with client_format /
/// client_type (they differ only for packed depth-stencil formats). Same size in bytes.
void to_gl_layout(rhi::Format format, std::span<std::byte> texels);
/// The inverse of to_gl_layout, applied to readbacks.
void from_gl_layout(rhi::Format format, std::span<std::byte> texels);

/// The buffer mask for glBlitFramebuffer / the attachment point of a format.
GLenum attachment_point(rhi::Format format, uint32_t color_index);

/// Queries what the current context can do with every format (glGetInternalformativ).
std::array<rhi::FormatCapabilities, rhi::kFormatCount> query_format_capabilities();

}  // namespace loom::gl
