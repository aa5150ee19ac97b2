#pragma once
// The OpenGL 4.5 core backend of the RHI. Headless devices render into framebuffer objects on
// an EGL surfaceless context; windowed devices open a GLFW window and blit their back buffer
// into it at end_frame(). Conventions (y-up NDC, depth 0..1, row 0 on top, counter-clockwise
// front faces) come from glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE).

#include <cstddef>
#include <memory>
#include <optional>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::gl {

/// Creates an OpenGL 4.5 device (desc.backend is ignored). Unsupported when no 4.5 core
/// context can be made (no EGL display, no window system for a windowed device); the message
/// says which step failed.
Result<std::unique_ptr<rhi::Device>> create_gl_device(const rhi::DeviceDesc& desc);

/// Sizes of the GL backend's object caches, for tests and diagnostics.
struct GlCacheStats {
    std::size_t framebuffers = 0;   ///< framebuffer objects cached by attachment set
    std::size_t vertex_arrays = 0;  ///< vertex array objects cached by vertex layout
};

/// The cache sizes of a device made by create_gl_device(); nullopt for any other device.
std::optional<GlCacheStats> gl_cache_stats(const rhi::Device& device);

}  // namespace loom::gl
