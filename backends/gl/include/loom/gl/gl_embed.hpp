#pragma once
// Embedding the OpenGL backend in an application that owns the GL context (an engine with its
// own window, context and textures). docs/embedding.md is the guide.
//
//   // the application's OpenGL 4.5 context is current on this thread
//   auto device = loom::gl::create_gl_device_on_current_context({.debug_output = true});
//   auto target = loom::gl::import_gl_texture(**device, engine_color_texture, desc);
//   executor.import_texture(fg::port("compose", "out"), *target, rhi::ResourceState::ShaderRead);
//   executor.run_frame(graph, options);   // GL work runs inside end_frame, on the app's context
//   // the application's GL state is as it was before run_frame
//
// Rules: the application's context is current on the calling thread whenever it calls into
// the device (or into an Executor that uses it), and when the device is destroyed; the device
// is used from that one thread. No transform feedback, conditional rendering or GL_TIME_ELAPSED
// query may be active while loom works. Every piece of GL state loom changes is put back before
// the call returns (see docs/embedding.md for the list); loom's conventions (row 0 on top,
// depth 0..1) hold inside loom only: an application that draws with GL's own convention sees
// loom's pictures upside down, which blit_to_framebuffer corrects when it shows them.

#include <cstdint>
#include <memory>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::gl {

/// How a device runs on the application's context.
struct CurrentContextDesc {
    /// Route KHR_debug messages to loom::log (errors as LogLevel::Error), by installing loom's
    /// debug callback and enabling synchronous debug output. The application's callback and
    /// both enables are put back when the device is destroyed. Off: loom leaves debug output
    /// alone.
    bool debug_output = false;
    /// loom's checks of recorded commands (rhi::DeviceDesc::validation).
    bool validation = true;
};

/// Creates an OpenGL device on the context current on the calling thread (an OpenGL 4.5 core
/// or compatibility context the application made). loom creates no context or window, never
/// makes another context current and never destroys this one. Unsupported when no context is
/// current or it is older than 4.5; the message says which.
Result<std::unique_ptr<rhi::Device>> create_gl_device_on_current_context(const CurrentContextDesc& desc = {});

/// Wraps the application's GL texture `texture` (a texture name of the current context) as a
/// loom texture, so that passes can sample it or render into it (e.g. bound to a graph port
/// with fg::Executor::import_texture). `desc` describes it: dimension, format (the texture's
/// internal format must be the one loom uses for it), size, mips, layers, samples and usage.
/// `state` is the state it is in for loom's tracking. Destroying the handle (Device::destroy)
/// forgets the wrapper and leaves the GL texture to the application, which must destroy the
/// handle before it deletes the texture. Imported textures are not counted in
/// Device::resource_stats(). Errors: InvalidArgument (not a GL device, not a texture, a
/// description that does not match the texture; the message names the texture and says what
/// differs), Unsupported (a format or usage the device cannot do).
Result<rhi::TextureHandle> import_gl_texture(rhi::Device& device, uint32_t texture, const rhi::TextureDesc& desc,
                                             rhi::ResourceState state = rhi::ResourceState::ShaderRead);

/// The GL texture name behind a loom texture of a GL device (one loom created or an import),
/// e.g. to sample loom's result in the application's own shaders. InvalidArgument for another
/// kind of device; InvalidHandle for a stale handle.
Result<uint32_t> gl_texture_name(rhi::Device& device, rhi::TextureHandle texture);

/// Copies mip 0 of the 2D colour texture `texture` into the application's framebuffer object
/// `framebuffer` (0: the default framebuffer), stretched over the rectangle whose lower-left
/// corner is (x, y) in GL window coordinates and whose size is width x height, rows flipped so
/// that loom's top row lands at the top of the rectangle. Runs at once (outside a frame), with
/// the application's state restored. InvalidState while a frame is being recorded (its
/// commands have not run yet); InvalidArgument for an unsuitable texture or framebuffer.
Status blit_to_framebuffer(rhi::Device& device, rhi::TextureHandle texture, uint32_t framebuffer, int32_t x, int32_t y,
                           uint32_t width, uint32_t height);

}  // namespace loom::gl
