// loom on a GL context the application owns: the application's state survives every loom call
// that touches GL (set to unusual values first, so that a missed restore or a missed baseline
// shows), application textures as graph resources, blits into application framebuffers, and
// the errors a user can make.
#include <cstring>

#include <gtest/gtest.h>

#include "embed_test_support.hpp"
#include "gl_app_context.hpp"
#include "loom/gl/gl_device.hpp"
#include "loom/gl/gl_embed.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

constexpr uint32_t kWidth = 64;
constexpr uint32_t kHeight = 48;

GLuint compile_app_program() {
    const char* vs = "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n";
    const char* fs = "#version 450 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
    GLuint program = glCreateProgram();
    for (auto [type, source] : {std::pair{GL_VERTEX_SHADER, vs}, std::pair{GL_FRAGMENT_SHADER, fs}}) {
        GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        glAttachShader(program, shader);
        glDeleteShader(shader);
    }
    glLinkProgram(program);
    return program;
}

/// The application's GL objects, bound everywhere loom also binds, with state set to values
/// that would break loom's rendering if loom did not set its own.
struct AppObjects {
    GLuint program = 0, vao = 0, fbo = 0, fbo_texture = 0, tex2d = 0, cube = 0, sampler = 0, buffer = 0, buffer2 = 0,
           pack = 0, unpack = 0;

    void create_and_bind() {
        program = compile_app_program();
        glUseProgram(program);
        glCreateVertexArrays(1, &vao);
        glBindVertexArray(vao);
        glCreateTextures(GL_TEXTURE_2D, 1, &fbo_texture);
        glTextureStorage2D(fbo_texture, 1, GL_RGBA8, 16, 16);
        glCreateFramebuffers(1, &fbo);
        glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, fbo_texture, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo);
        glCreateTextures(GL_TEXTURE_2D, 1, &tex2d);
        glTextureStorage2D(tex2d, 1, GL_RGBA8, 4, 4);
        glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &cube);
        glTextureStorage2D(cube, 1, GL_RGBA8, 4, 4);
        glCreateSamplers(1, &sampler);
        for (GLuint unit : {0u, 1u, 2u, 15u}) {
            glActiveTexture(GL_TEXTURE0 + unit);
            glBindTexture(GL_TEXTURE_2D, tex2d);
            glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
            glBindSampler(unit, sampler);
        }
        glCreateBuffers(1, &buffer);
        glNamedBufferStorage(buffer, 4096, nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &buffer2);
        glNamedBufferStorage(buffer2, 4096, nullptr, GL_DYNAMIC_STORAGE_BIT);
        for (GLuint point : {0u, 1u, 2u, rhi::kGlPushConstantBinding}) glBindBufferRange(GL_UNIFORM_BUFFER, point, buffer, 256, 512);
        for (GLuint point : {0u, 1u, 2u}) glBindBufferRange(GL_SHADER_STORAGE_BUFFER, point, buffer2, 0, 1024);
        glBindBuffer(GL_UNIFORM_BUFFER, buffer2);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
        for (GLuint unit : {0u, 1u, 2u}) glBindImageTexture(unit, tex2d, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
        // Pixel transfers: a bound pack and unpack buffer and unusual pixel store values would
        // send loom's uploads and readbacks astray.
        glCreateBuffers(1, &pack);
        glNamedBufferStorage(pack, 1 << 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
        glCreateBuffers(1, &unpack);
        glNamedBufferStorage(unpack, 1 << 16, nullptr, GL_DYNAMIC_STORAGE_BIT);
        glBindBuffer(GL_PIXEL_PACK_BUFFER, pack);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, unpack);
        glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 8);
        glPixelStorei(GL_UNPACK_SKIP_PIXELS, 1);
        glPixelStorei(GL_PACK_ALIGNMENT, 2);
        glPixelStorei(GL_PACK_ROW_LENGTH, 5);
        glPixelStorei(GL_PACK_SWAP_BYTES, GL_TRUE);
        // Fixed-function state.
        glViewport(1, 2, 30, 40);
        glDepthRange(0.25, 0.75);
        glScissor(3, 4, 50, 60);
        glEnable(GL_SCISSOR_TEST);
        glEnablei(GL_BLEND, 0);
        glBlendFuncSeparatei(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ZERO);
        glBlendEquationSeparatei(0, GL_MAX, GL_FUNC_SUBTRACT);
        glColorMaski(0, GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
        glColorMaski(1, GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_GEQUAL);
        glDepthMask(GL_FALSE);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_FRONT_AND_BACK);
        glFrontFace(GL_CW);
        glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
        glPolygonOffset(1.5f, 2.5f);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glEnable(GL_STENCIL_TEST);
        glStencilFunc(GL_NEVER, 0, 0xFF);
        glStencilMask(0x0F);
        glEnable(GL_RASTERIZER_DISCARD);
        glEnable(GL_COLOR_LOGIC_OP);
        glLogicOp(GL_CLEAR);
        glEnable(GL_SAMPLE_MASK);
        glSampleMaski(0, 0);
        glEnable(GL_PRIMITIVE_RESTART);
        glEnable(GL_CLIP_DISTANCE0);
        glBlendColor(0.1f, 0.2f, 0.3f, 0.4f);
        glProvokingVertex(GL_FIRST_VERTEX_CONVENTION);
        glActiveTexture(GL_TEXTURE5);
        // Left at GL's defaults, which differ from loom's: clip origin lower-left, depth
        // -1..1, FRAMEBUFFER_SRGB, seamless cube maps and program point size off.
    }

    void destroy() {
        glUseProgram(0);
        glDeleteProgram(program);
        glDeleteVertexArrays(1, &vao);
        glDeleteFramebuffers(1, &fbo);
        for (GLuint t : {fbo_texture, tex2d, cube}) glDeleteTextures(1, &t);
        glDeleteSamplers(1, &sampler);
        for (GLuint b : {buffer, buffer2, pack, unpack}) glDeleteBuffers(1, &b);
    }
};

class GlEmbed : public ::testing::Test {
protected:
    void SetUp() override {
        std::string error;
        app_ = AppGlContext::create(error);
        ASSERT_TRUE(app_) << "the application's context: " << error;
    }
    void TearDown() override {
        if (app_) app_->make_current();
        device_.reset();
        app_.reset();
    }

    void make_device(bool debug_output = true) {
        auto device = gl::create_gl_device_on_current_context({.debug_output = debug_output});
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        device_ = std::move(*device);
    }

    /// The application's RGBA8 texture, cleared to kEngineClear with its own GL calls.
    GLuint app_target() {
        GLuint texture = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGBA8, kWidth, kHeight);
        const GLfloat clear[4] = {static_cast<float>(kEngineClear[0]), static_cast<float>(kEngineClear[1]),
                                  static_cast<float>(kEngineClear[2]), static_cast<float>(kEngineClear[3])};
        glClearTexImage(texture, 0, GL_RGBA, GL_FLOAT, clear);
        return texture;
    }

    static rhi::TextureDesc target_desc() {
        rhi::TextureDesc desc;
        desc.name = "engine target";
        desc.format = rhi::Format::RGBA8Unorm;
        desc.width = kWidth;
        desc.height = kHeight;
        desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc;
        return desc;
    }

    std::unique_ptr<AppGlContext> app_;
    std::unique_ptr<rhi::Device> device_;
};

#define EXPECT_STATE_KEPT(before, what)                                                                              \
    do {                                                                                                             \
        const std::string changed = (before).diff(GlStateSnapshot::capture(16));                                     \
        EXPECT_TRUE(changed.empty()) << (what) << " changed the application's GL state:\n" << changed;                \
    } while (false)

// Every loom call that runs GL work, with application state that would break loom's rendering
// (logic op CLEAR, rasterizer discard, stencil NEVER, clip distance, a bound pack buffer...):
// loom's results are right and the state is exactly the application's afterwards.
TEST_F(GlEmbed, LoomRendersRightAndRestoresTheApplicationsState) {
    const GLuint target = app_target();
    AppObjects app;
    app.create_and_bind();
    // loom's debug output (debug_output) turns synchronous output on until the device goes;
    // the application has it on already, so that the snapshots compare everything else.
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    const GlStateSnapshot before = GlStateSnapshot::capture(16);

    make_device();
    EXPECT_STATE_KEPT(before, "create_gl_device_on_current_context");
    // The debug callback is loom's now (debug_output); everything else is as it was.

    LOOM_EMBED_ASSIGN(const rhi::TextureHandle imported, gl::import_gl_texture(*device_, target, target_desc()));
    {
        LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
        OverlayGraph& overlay = *overlay_graph;
        fg::Executor executor(*device_);
        executor.import_texture(OverlayGraph::target_port(), imported, rhi::ResourceState::ShaderRead);
        fg::PlanOptions options;
        options.frame = {kWidth, kHeight};
        for (int frame = 0; frame < 2; ++frame) {
            LOOM_EMBED_OK(executor.run_frame(overlay.graph(), options));
            EXPECT_STATE_KEPT(before, "a frame of the overlay graph");
        }
    }
    // loom's readback, under the application's pack buffer and pack state.
    LOOM_EMBED_ASSIGN(const rhi::Image picture, device_->read_texture(imported));
    EXPECT_STATE_KEPT(before, "read_texture");
    EXPECT_TRUE(matches_overlay(picture, "gl_state_overlay"));

    // loom's upload, under the application's unpack buffer and unpack state.
    rhi::TextureDesc desc;
    desc.name = "upload";
    desc.width = 5;
    desc.height = 3;
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle upload, device_->create_texture(desc));
    std::vector<std::byte> texels(5 * 3 * 4);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::byte>(i * 7 + 3);
    LOOM_EMBED_OK(device_->write_texture(upload, {}, texels));
    EXPECT_STATE_KEPT(before, "write_texture");
    LOOM_EMBED_ASSIGN(const rhi::Image uploaded, device_->read_texture(upload));
    EXPECT_EQ(0, std::memcmp(uploaded.pixels.data(), texels.data(), texels.size())) << "the upload came back different";

    // Uniform buffers, push constants, blending, depth, culling and a compute pass with a
    // storage buffer and a storage image: every indexed binding kind loom uses.
    const char* vs = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.5, 1.0);
})";
    const char* fs = R"(#version 450
layout(set = 0, binding = 0) uniform Color { vec4 color; };
layout(set = 0, binding = 1) uniform sampler2D source;
layout(push_constant) uniform Tint { vec4 tint; };
layout(location = 0) out vec4 result;
void main() { result = color * tint + texelFetch(source, ivec2(0, 0), 0); })";
    const char* cs = R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0, std430) readonly buffer Values { vec4 value; };
layout(set = 0, binding = 1, rgba8) uniform writeonly image2D image;
void main() { imageStore(image, ivec2(gl_GlobalInvocationID.xy), value); })";
    LOOM_EMBED_ASSIGN(const rhi::ShaderHandle vertex, compile_shader(*device_, rhi::ShaderStage::Vertex, "v.vert", vs));
    LOOM_EMBED_ASSIGN(const rhi::ShaderHandle fragment, compile_shader(*device_, rhi::ShaderStage::Fragment, "f.frag", fs));
    LOOM_EMBED_ASSIGN(const rhi::ShaderHandle compute, compile_shader(*device_, rhi::ShaderStage::Compute, "c.comp", cs));
    rhi::GraphicsPipelineDesc pd;
    pd.name = "blend";
    pd.vertex = vertex;
    pd.fragment = fragment;
    pd.color_formats = {rhi::Format::RGBA8Unorm};
    pd.depth_format = rhi::Format::Depth32F;
    pd.depth = {true, true, rhi::CompareOp::Less};
    pd.raster.cull = rhi::CullMode::Back;
    rhi::BlendState additive;
    additive.enabled = true;
    additive.src_color = additive.dst_color = additive.src_alpha = additive.dst_alpha = rhi::BlendFactor::One;
    pd.blend = {additive};
    LOOM_EMBED_ASSIGN(const rhi::PipelineHandle blend, device_->create_graphics_pipeline(pd));
    LOOM_EMBED_ASSIGN(const rhi::PipelineHandle store, device_->create_compute_pipeline({"store", compute}));
    rhi::TextureDesc color_desc;
    color_desc.name = "color";
    color_desc.width = 8;
    color_desc.height = 8;
    color_desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle color, device_->create_texture(color_desc));
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle stored, device_->create_texture(color_desc));
    rhi::TextureDesc depth_desc = color_desc;
    depth_desc.name = "depth";
    depth_desc.format = rhi::Format::Depth32F;
    depth_desc.usage = rhi::TextureUsage::DepthStencilAttachment;
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle depth, device_->create_texture(depth_desc));
    LOOM_EMBED_ASSIGN(const rhi::BufferHandle values, device_->create_buffer({"values", 16, rhi::BufferUsage::Storage}));
    const std::array<float, 4> value{0.0f, 1.0f, 0.2f, 0.6f};
    LOOM_EMBED_OK(device_->write_buffer(values, 0, std::as_bytes(std::span(value))));
    rhi::SamplerDesc nearest;
    nearest.min_filter = nearest.mag_filter = rhi::Filter::Nearest;
    LOOM_EMBED_ASSIGN(const rhi::SamplerHandle sampler, device_->create_sampler(nearest));

    rhi::CommandList& cmd = device_->begin_frame();
    rhi::RenderPassDesc pass;
    pass.label = "blend";
    pass.colors.push_back({color, 0, 0, rhi::LoadOp::Clear, rhi::StoreOp::Store, {0.2, 0.0, 0.0, 0.0}});
    pass.depth = rhi::DepthAttachment{depth};
    cmd.begin_render_pass(pass);
    cmd.set_pipeline(blend);
    const std::array<float, 4> uniform_color{0.4f, 0.1f, 0.0f, 1.0f};
    cmd.set_bind_group(0, rhi::BindGroup{}
                              .buffer(0, cmd.transient_uniforms_of(uniform_color))
                              .texture(1, imported, sampler));  // texel (0, 0) is the pattern's (0, 0, 0, 1)
    cmd.push_constants_of(std::array<float, 4>{1.0f, 2.0f, 1.0f, 0.5f});
    cmd.draw(3);
    cmd.end_render_pass();
    cmd.transition(stored, rhi::ResourceState::Storage);
    cmd.set_pipeline(store);
    cmd.set_bind_group(0, rhi::BindGroup{}.buffer(0, values).storage_texture(1, stored));
    cmd.dispatch(8, 8);
    cmd.transition(stored, rhi::ResourceState::ShaderRead);
    LOOM_EMBED_OK(device_->end_frame());
    EXPECT_STATE_KEPT(before, "a frame with uniforms, push constants, blending, depth, culling and compute");

    LOOM_EMBED_ASSIGN(const rhi::Image blended, device_->read_texture(color));
    // clear (0.2, 0, 0, 0) + (0.4, 0.1, 0, 1) * (1, 2, 1, 0.5) + (0, 0, 0, 1) = (0.6, 0.2, 0, 1.5 -> 1)
    const std::array<double, 4> want{153.0 / 255.0, 51.0 / 255.0, 0.0, 1.0};
    for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(blended.load(3, 5)[c], want[c], 0.5 / 255.0) << "channel " << c;
    LOOM_EMBED_ASSIGN(const rhi::Image compute_result, device_->read_texture(stored));
    const std::array<double, 4> want_stored{0.0, 1.0, 51.0 / 255.0, 153.0 / 255.0};
    for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(compute_result.load(7, 2)[c], want_stored[c], 0.5 / 255.0) << "channel " << c;

    for (rhi::TextureHandle t : {upload, color, stored, depth, imported}) LOOM_EMBED_OK(device_->destroy(t));
    LOOM_EMBED_OK(device_->destroy(values));
    LOOM_EMBED_OK(device_->destroy(sampler));
    LOOM_EMBED_OK(device_->destroy(blend));
    LOOM_EMBED_OK(device_->destroy(store));
    for (rhi::ShaderHandle s : {vertex, fragment, compute}) LOOM_EMBED_OK(device_->destroy(s));
    device_.reset();
    EXPECT_STATE_KEPT(before, "destroying the device");
    // The application's texture is still the application's.
    EXPECT_EQ(glIsTexture(target), GL_TRUE);
    app.destroy();
    glDeleteTextures(1, &target);
}

// The application's texture, bound to a graph port, receives the graph's result; the
// application reads it with its own GL calls (rows top-first: loom's convention).
TEST_F(GlEmbed, ImportedTextureIsTheGraphOutput) {
    make_device();
    const GLuint target = app_target();
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle imported, gl::import_gl_texture(*device_, target, target_desc()));
    LOOM_EMBED_ASSIGN(const uint32_t name, gl::gl_texture_name(*device_, imported));
    EXPECT_EQ(name, target);
    const rhi::ResourceStats stats_before = device_->resource_stats();
    {
        LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
        OverlayGraph& overlay = *overlay_graph;
        fg::Executor executor(*device_);
        executor.import_texture(OverlayGraph::target_port(), imported, rhi::ResourceState::ShaderRead);
        fg::PlanOptions options;
        options.frame = {kWidth, kHeight};
        LOOM_EMBED_OK(executor.run_frame(overlay.graph(), options));
        // Only the pattern's texture is loom's; the target is the application's.
        EXPECT_EQ(executor.stats().textures, 1u);
        EXPECT_EQ(device_->resource_stats().textures, stats_before.textures + 1);
    }
    rhi::Image picture(kWidth, kHeight, rhi::Format::RGBA8Unorm);
    glGetTextureImage(target, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(picture.pixels.size()), picture.pixels.data());
    EXPECT_TRUE(matches_overlay(picture, "gl_imported_target"));

    LOOM_EMBED_OK(device_->destroy(imported));
    EXPECT_EQ(glIsTexture(target), GL_TRUE) << "destroying the import deleted the application's texture";
    EXPECT_EQ(device_->resource_stats().textures, stats_before.textures);
    glDeleteTextures(1, &target);
}

// blit_to_framebuffer shows loom's picture the right way up in the application's framebuffer
// (GL counts rows from the bottom), in the rectangle asked for.
TEST_F(GlEmbed, BlitToApplicationFramebufferKeepsTopRowOnTop) {
    make_device();
    const GLuint target = app_target();
    LOOM_EMBED_ASSIGN(const rhi::TextureHandle imported, gl::import_gl_texture(*device_, target, target_desc()));
    {
        LOOM_EMBED_ASSIGN(auto overlay_graph, OverlayGraph::create(*device_, rhi::Format::RGBA8Unorm));
        OverlayGraph& overlay = *overlay_graph;
        fg::Executor executor(*device_);
        executor.import_texture(OverlayGraph::target_port(), imported, rhi::ResourceState::ShaderRead);
        fg::PlanOptions options;
        options.frame = {kWidth, kHeight};
        LOOM_EMBED_OK(executor.run_frame(overlay.graph(), options));
    }
    // The application's framebuffer: 80x60, black, the picture at (10, 5) in GL coordinates.
    GLuint screen = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &screen);
    glTextureStorage2D(screen, 1, GL_RGBA8, 80, 60);
    const GLfloat black[4] = {0, 0, 0, 1};
    glClearTexImage(screen, 0, GL_RGBA, GL_FLOAT, black);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, screen, 0);
    const GlStateSnapshot before = GlStateSnapshot::capture(16);
    LOOM_EMBED_OK(gl::blit_to_framebuffer(*device_, imported, fbo, 10, 5, kWidth, kHeight));
    EXPECT_STATE_KEPT(before, "blit_to_framebuffer");

    std::vector<uint8_t> rows(80 * 60 * 4);
    glGetTextureImage(screen, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rows.size()), rows.data());
    uint64_t wrong = 0;
    for (uint32_t gl_row = 0; gl_row < 60; ++gl_row) {
        for (uint32_t x = 0; x < 80; ++x) {
            const uint8_t* texel = rows.data() + (gl_row * 80 + x) * 4;
            Rgba8 want{0, 0, 0, 255};
            const bool inside = x >= 10 && x < 10 + kWidth && gl_row >= 5 && gl_row < 5 + kHeight;
            // GL row 5 + kHeight - 1 (the highest) shows loom's row 0.
            if (inside) want = expected_overlay(x - 10, 5 + kHeight - 1 - gl_row, kWidth, kHeight);
            if (Rgba8{texel[0], texel[1], texel[2], texel[3]} != want) ++wrong;
        }
    }
    EXPECT_EQ(wrong, 0u) << "texels of the application's framebuffer differ from the flipped overlay";
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &screen);
    LOOM_EMBED_OK(device_->destroy(imported));
    glDeleteTextures(1, &target);
}

// The application's debug callback is put back when the device goes.
TEST_F(GlEmbed, DebugOutputIsHandedBack) {
    const GLDEBUGPROC app_callback = [](GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*, const void*) {};
    int user = 0;
    glDebugMessageCallback(app_callback, &user);
    glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    make_device(/*debug_output=*/true);
    void* current = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &current);
    EXPECT_NE(current, reinterpret_cast<void*>(app_callback)) << "loom's callback is not installed";
    EXPECT_EQ(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS), GL_TRUE);
    device_.reset();
    void* user_back = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &current);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user_back);
    EXPECT_EQ(current, reinterpret_cast<void*>(app_callback));
    EXPECT_EQ(user_back, static_cast<void*>(&user));
    EXPECT_EQ(glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS), GL_FALSE);
    glDebugMessageCallback(nullptr, nullptr);
}

TEST_F(GlEmbed, ErrorsNameTheTextureAndWhatDiffers) {
    make_device();
    const GLuint target = app_target();
    auto expect_error = [&](const Result<rhi::TextureHandle>& result, ErrorCode code, const std::string& needle) {
        ASSERT_FALSE(result.ok()) << "expected an error containing '" << needle << "'";
        EXPECT_EQ(result.error().code, code) << result.error().to_string();
        EXPECT_NE(result.error().message.find(needle), std::string::npos) << result.error().to_string();
        EXPECT_NE(result.error().message.find("engine target"), std::string::npos) << result.error().to_string();
    };
    expect_error(gl::import_gl_texture(*device_, 0, target_desc()), ErrorCode::InvalidArgument, "not a texture");
    expect_error(gl::import_gl_texture(*device_, 987654, target_desc()), ErrorCode::InvalidArgument, "not a texture");
    rhi::TextureDesc wrong_size = target_desc();
    wrong_size.width = kWidth + 1;
    expect_error(gl::import_gl_texture(*device_, target, wrong_size), ErrorCode::InvalidArgument, "64x48x1");
    rhi::TextureDesc wrong_format = target_desc();
    wrong_format.format = rhi::Format::RGBA16Float;
    expect_error(gl::import_gl_texture(*device_, target, wrong_format), ErrorCode::InvalidArgument, "internal format");
    rhi::TextureDesc wrong_kind = target_desc();
    wrong_kind.dimension = rhi::TextureDimension::Tex2DArray;
    wrong_kind.depth_or_layers = 2;
    expect_error(gl::import_gl_texture(*device_, target, wrong_kind), ErrorCode::InvalidArgument, "GL_TEXTURE_2D_ARRAY");
    rhi::TextureDesc too_many_mips = target_desc();
    too_many_mips.mip_levels = 3;
    expect_error(gl::import_gl_texture(*device_, target, too_many_mips), ErrorCode::InvalidArgument, "mip level");

    LOOM_EMBED_ASSIGN(const rhi::TextureHandle imported, gl::import_gl_texture(*device_, target, target_desc()));
    (void)device_->begin_frame();
    const Status during_frame = gl::blit_to_framebuffer(*device_, imported, 0, 0, 0, kWidth, kHeight);
    EXPECT_FALSE(during_frame.ok());
    if (!during_frame.ok()) {
        EXPECT_EQ(during_frame.error().code, ErrorCode::InvalidState);
    }
    LOOM_EMBED_OK(device_->end_frame());
    LOOM_EMBED_OK(device_->destroy(imported));
    const auto stale = gl::gl_texture_name(*device_, imported);
    ASSERT_FALSE(stale.ok());
    EXPECT_EQ(stale.error().code, ErrorCode::InvalidHandle);
    glDeleteTextures(1, &target);

    // Without a current context there is nothing to run on.
    app_->release();
    const auto no_context = gl::create_gl_device_on_current_context();
    ASSERT_FALSE(no_context.ok());
    EXPECT_EQ(no_context.error().code, ErrorCode::Unsupported);
    EXPECT_NE(no_context.error().message.find("no OpenGL context is current"), std::string::npos);
    app_->make_current();
}

}  // namespace
}  // namespace loom::test
