// The GL context and device setup: clip control, KHR_debug routing, capabilities, shader
// errors with the driver's info log, multisampled readback, windowed devices without display.
#include <cstdlib>

#include <epoxy/gl.h>

#include "gl_test_util.hpp"
#include "loom_test/test_support.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class GlContextTest : public GlTest {};

TEST_F(GlContextTest, ClipControlGivesLoomConventions) {
    GLint origin = 0, depth_mode = 0;
    glGetIntegerv(GL_CLIP_ORIGIN, &origin);
    glGetIntegerv(GL_CLIP_DEPTH_MODE, &depth_mode);
    EXPECT_EQ(origin, GL_UPPER_LEFT);
    EXPECT_EQ(depth_mode, GL_ZERO_TO_ONE);
}

TEST_F(GlContextTest, DebugOutputReachesTheLogger) {
    ScopedLogCapture capture;
    glEnable(0xFFFFu);  // not a capability: GL_INVALID_ENUM
    bool found = false;
    for (const std::string& message : capture.messages()) {
        if (message.find("[gl]") != std::string::npos && message.find("error") != std::string::npos) found = true;
    }
    EXPECT_TRUE(found) << "no GL error message was logged (" << capture.messages().size() << " messages)";
    glGetError();  // leave no error behind
}

TEST_F(GlContextTest, CapabilitiesComeFromTheDriver) {
    const rhi::Capabilities& caps = device().capabilities();
    EXPECT_EQ(caps.backend, rhi::Backend::OpenGL);
    EXPECT_FALSE(caps.device_name.empty());
    EXPECT_EQ(caps.api_version.rfind("4.", 0), 0u) << caps.api_version;
    EXPECT_FALSE(caps.placed_resources);
    EXPECT_GE(caps.max_texture_size, 4096u);
    EXPECT_GE(caps.max_color_attachments, 4u);
    EXPECT_GE(caps.uniform_buffer_offset_alignment, 1u);
    const auto& rgba8 = caps.format(rhi::Format::RGBA8Unorm);
    EXPECT_TRUE(rgba8.sampled && rgba8.filterable && rgba8.color_attachment && rgba8.blendable && rgba8.storage);
    EXPECT_FALSE(rgba8.depth_stencil_attachment);
    const auto& rgba8ui = caps.format(rhi::Format::RGBA8Uint);
    EXPECT_TRUE(rgba8ui.color_attachment);
    EXPECT_FALSE(rgba8ui.filterable);
    EXPECT_FALSE(rgba8ui.blendable);
    EXPECT_TRUE(caps.format(rhi::Format::Depth32F).depth_stencil_attachment);
    EXPECT_FALSE(caps.format(rhi::Format::Depth32F).color_attachment);
    EXPECT_FALSE(caps.format(rhi::Format::RGBA8Srgb).storage);  // no sRGB image formats in GLSL
    EXPECT_FALSE(caps.format(rhi::Format::Undefined).sampled);

    EXPECT_EQ(device().create_heap(rhi::HeapDesc{"heap", 1024}).error().code, ErrorCode::Unsupported);
    EXPECT_EQ(device().texture_memory_requirements(rhi::TextureDesc{}).error().code, ErrorCode::Unsupported);
    rhi::TextureDesc placed;
    placed.placement = rhi::TexturePlacement{};
    EXPECT_EQ(device().create_texture(placed).error().code, ErrorCode::Unsupported);
}

TEST_F(GlContextTest, GlCompileAndLinkFailuresNameTheShader) {
    rhi::ShaderModule broken;
    broken.name = "broken.frag";
    broken.stage = rhi::ShaderStage::Fragment;
    broken.gl_source = "#version 450\nvoid main() { undeclared = 1; }\n";
    auto shader = device().create_shader(broken);
    ASSERT_FALSE(shader.ok());
    EXPECT_EQ(shader.error().code, ErrorCode::ShaderCompile);
    EXPECT_NE(shader.error().message.find("broken.frag"), std::string::npos) << shader.error().message;
    EXPECT_NE(shader.error().message.find("undeclared"), std::string::npos) << shader.error().message;

    // The vertex shader writes no `v_uv`, which the fragment shader reads: a link error.
    rhi::ShaderModule vs;
    vs.name = "plain.vert";
    vs.stage = rhi::ShaderStage::Vertex;
    vs.gl_source = "#version 450\nvoid main() { gl_Position = vec4(0.0); }\n";
    rhi::ShaderModule fs;
    fs.name = "reads_uv.frag";
    fs.stage = rhi::ShaderStage::Fragment;
    fs.gl_source = "#version 450\nlayout(location = 0) in vec2 v_uv;\nout vec4 c;\nvoid main() { c = vec4(v_uv, 0, 1); }\n";
    // Make the mismatch a hard link error: the fragment input's type differs from the output.
    vs.gl_source = "#version 450\nlayout(location = 0) out vec3 v_uv;\nvoid main() { v_uv = vec3(0); gl_Position = vec4(0.0); }\n";
    LOOM_ASSIGN_OR_FAIL(auto v, device().create_shader(vs));
    LOOM_ASSIGN_OR_FAIL(auto f, device().create_shader(fs));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "mismatched stages";
    pd.vertex = v;
    pd.fragment = f;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    auto pipeline = device().create_graphics_pipeline(pd);
    ASSERT_FALSE(pipeline.ok());
    EXPECT_EQ(pipeline.error().code, ErrorCode::ShaderLink);
    EXPECT_NE(pipeline.error().message.find("mismatched stages"), std::string::npos) << pipeline.error().message;
}

TEST_F(GlContextTest, ResourceBytesFollowTheTexelFormula) {
    // GL does not reveal allocation sizes: bytes are texels times bytes per texel, summed over
    // mips (3D mips halve their depth too), times samples.
    rhi::TextureDesc mipped;
    mipped.name = "mipped";
    mipped.width = 16;
    mipped.height = 8;
    mipped.mip_levels = 3;
    LOOM_ASSIGN_OR_FAIL(auto t1, device().create_texture(mipped));
    EXPECT_EQ(device().resource_stats().texture_bytes, (16u * 8 + 8 * 4 + 4 * 2) * 4);
    rhi::TextureDesc volume;
    volume.name = "volume";
    volume.dimension = rhi::TextureDimension::Tex3D;
    volume.format = rhi::Format::R32Float;
    volume.width = volume.height = volume.depth_or_layers = 4;
    volume.mip_levels = 2;
    volume.usage = rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto t2, device().create_texture(volume));
    EXPECT_EQ(device().resource_stats().texture_bytes, (16u * 8 + 8 * 4 + 4 * 2) * 4 + (64u + 8) * 4);
    LOOM_ASSIGN_OR_FAIL(auto b, device().create_buffer(rhi::BufferDesc{"b", 100, rhi::BufferUsage::Vertex}));
    EXPECT_EQ(device().resource_stats().buffer_bytes, 100u);
    LOOM_ASSERT_OK(device().destroy(t1));
    LOOM_ASSERT_OK(device().destroy(t2));
    LOOM_ASSERT_OK(device().destroy(b));
    EXPECT_EQ(device().resource_stats().total_bytes(), 0u);
}

TEST_F(GlContextTest, MultisampledTargetIsResolvedOnReadback) {
    rhi::TextureDesc desc;
    desc.name = "msaa";
    desc.width = desc.height = 8;
    desc.samples = 4;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopySrc;
    LOOM_ASSIGN_OR_FAIL(auto msaa, device().create_texture(desc));
    EXPECT_EQ(device().resource_stats().texture_bytes, 8u * 8 * 4 * 4);
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) {
        list.begin_render_pass(clear_pass("msaa clear", msaa, {0.2, 0.4, 0.6, 1.0}));
        list.end_render_pass();
    }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(msaa));
    EXPECT_EQ(rgba8_at(image, 3, 5), (std::array<int, 4>{51, 102, 153, 255}));
}

TEST_F(GlContextTest, DestroyWhileRecordingIsDeferredUntilTheFrameRan) {
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "target", rhi::Format::RGBA8Unorm, 8, 8));
    LOOM_ASSIGN_OR_FAIL(auto pipeline, make_solid_pipeline(device(), rhi::Format::RGBA8Unorm));
    const std::vector<float> vertices = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
    LOOM_ASSIGN_OR_FAIL(auto vb, make_buffer_of(device(), "vertices", rhi::BufferUsage::Vertex, vertices));
    rhi::CommandList& list = device().begin_frame();
    list.begin_render_pass(clear_pass("draw", target, {0, 0, 0, 1}));
    list.set_pipeline(pipeline);
    list.set_vertex_buffer(0, vb);
    list.push_constants_of(std::array<float, 4>{0, 1, 0, 1});
    list.draw(3);
    list.end_render_pass();
    // The handles go stale at once; the GL objects live until the recorded draw has run.
    LOOM_ASSERT_OK(device().destroy(vb));
    LOOM_ASSERT_OK(device().destroy(pipeline));
    EXPECT_EQ(device().resource_stats().buffers, 0u);
    LOOM_ASSERT_OK(device().end_frame());
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(target));
    EXPECT_EQ(rgba8_at(image, 4, 4), (std::array<int, 4>{0, 255, 0, 255}));
}

TEST_F(GlContextTest, RecordingInterleavedWithAnotherDeviceUsesTheRightContext) {
    LOOM_ASSIGN_OR_FAIL(auto other, gl::create_gl_device(rhi::DeviceDesc{}));
    LOOM_ASSIGN_OR_FAIL(auto mine, make_target(device(), "mine", rhi::Format::RGBA8Unorm, 4, 4));
    LOOM_ASSIGN_OR_FAIL(auto theirs, make_target(*other, "theirs", rhi::Format::RGBA8Unorm, 4, 4));
    rhi::CommandList& list = device().begin_frame();
    // The other device makes its context current in the middle of this recording ...
    LOOM_ASSERT_OK(run_frame(*other, [&](rhi::CommandList& l) {
        l.begin_render_pass(clear_pass("theirs", theirs, {0, 0, 1, 1}));
        l.end_render_pass();
    }));
    // ... and recording here goes on in this device's context (framebuffers, transient memory).
    list.begin_render_pass(clear_pass("mine", mine, {1, 0, 0, 1}));
    list.end_render_pass();
    (void)list.transient_uniforms_of(std::array<float, 4>{});
    LOOM_ASSERT_OK(device().end_frame());
    LOOM_ASSIGN_OR_FAIL(rhi::Image a, device().read_texture(mine));
    LOOM_ASSIGN_OR_FAIL(rhi::Image b, other->read_texture(theirs));
    EXPECT_EQ(rgba8_at(a, 1, 1), (std::array<int, 4>{255, 0, 0, 255}));
    EXPECT_EQ(rgba8_at(b, 1, 1), (std::array<int, 4>{0, 0, 255, 255}));
    EXPECT_EQ(gl::gl_cache_stats(*other)->framebuffers, 1u);
    EXPECT_EQ(caches().framebuffers, 1u);
    LOOM_ASSERT_OK(other->destroy(theirs));
    LOOM_ASSERT_OK(device().destroy(mine));
}

TEST(GlWindowTest, WindowedDeviceWithoutDisplayIsUnsupported) {
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((display && *display) || (wayland && *wayland)) GTEST_SKIP() << "a display is available";
    rhi::DeviceDesc desc;
    desc.headless = false;
    ScopedLogCapture capture;  // GLFW may report the missing display on its own
    auto device = gl::create_gl_device(desc);
    ASSERT_FALSE(device.ok());
    EXPECT_EQ(device.error().code, ErrorCode::Unsupported);
    EXPECT_NE(device.error().message.find("window"), std::string::npos) << device.error().message;
}

}  // namespace
}  // namespace loom::test
