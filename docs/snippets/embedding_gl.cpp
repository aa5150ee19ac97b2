// docs/embedding.md, OpenGL: loom on the application's context, compiled; gl_engine_frame()
// runs it on a context the test made current (snippets_test.cpp).
#include "embedding_graph.hpp"
#include "snippets.hpp"

// [docs:gl-includes]
#include "loom/framegraph/framegraph.hpp"
#include "loom/gl/gl_embed.hpp"
// [/docs:gl-includes]

#include <epoxy/gl.h>

namespace loom::docs {

Result<rhi::Image> gl_engine_frame(uint32_t engine_texture, uint32_t width, uint32_t height, uint32_t window_framebuffer) {
    // [docs:gl-device]
    // The application's OpenGL 4.5 context is current on this thread.
    auto device = gl::create_gl_device_on_current_context({.debug_output = true});
    if (!device) return device.take_error();  // Unsupported: no context current, or older than 4.5
    // [/docs:gl-device]

    // [docs:gl-import]
    rhi::TextureDesc desc;  // what the application's texture is: checked against it
    desc.name = "engine color";
    desc.format = rhi::Format::RGBA8Unorm;  // glTextureStorage2D(texture, 1, GL_RGBA8, width, height)
    desc.width = width;
    desc.height = height;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled;
    auto target = gl::import_gl_texture(**device, engine_texture, desc);
    if (!target) return target.take_error();  // InvalidArgument naming what differs
    // [/docs:gl-import]

    auto embedded = EmbeddingGraph::create(**device, rhi::Format::RGBA8Unorm);
    if (!embedded) return embedded.take_error();
    fg::FrameGraph& graph = (*embedded)->graph;
    {
        // [docs:gl-frame]
        fg::Executor executor(**device);
        executor.import_texture(fg::port("ui", "target"), *target, rhi::ResourceState::ShaderRead);
        fg::PlanOptions options;
        options.frame = {width, height};
        LOOM_TRY(executor.run_frame(graph, options));  // GL work runs here, on the application's context
        // The application's GL state is what it was before run_frame.
        // [/docs:gl-frame]
    }
    // [docs:gl-show]
    // Into the application's framebuffer (0 for the window's), the right way up: loom's row 0 is
    // the top row, GL counts window rows from the bottom.
    LOOM_TRY(gl::blit_to_framebuffer(**device, *target, window_framebuffer, 0, 0, width, height));
    // [/docs:gl-show]

    rhi::Image picture(width, height, rhi::Format::RGBA8Unorm);
    // [docs:gl-name]
    // The GL name behind a loom texture, for the application's own GL calls.
    auto name = gl::gl_texture_name(**device, *target);
    if (!name) return name.take_error();
    glGetTextureImage(*name, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(picture.pixels.size()), picture.pixels.data());
    // [/docs:gl-name]

    // [docs:gl-release]
    LOOM_TRY((*device)->destroy(*target));  // forgets the wrapper; the GL texture stays the application's
    embedded->reset();
    device->reset();  // with the application's context still current
    // [/docs:gl-release]
    return picture;
}

}  // namespace loom::docs
