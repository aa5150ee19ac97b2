// Runs the guides' snippets: the first graph of docs/getting-started.md and the examples of
// docs/framegraph.md and docs/backends.md on every backend, the OpenGL embedding of
// docs/embedding.md on a context of the test's own. Pixels are checked where the snippet draws.
#include <gtest/gtest.h>

#include "loom_test/render_fixture.hpp"
#include "snippets.hpp"
#if defined(LOOM_DOCS_HAS_GL)
#include <epoxy/gl.h>

#include "gl_app_context.hpp"
#endif

namespace loom::test {
namespace {

class DocsSnippets : public RenderTest {};

TEST_P(DocsSnippets, FirstGraphOfTheGettingStartedGuide) {
    auto image = docs::render_first_graph(device());
    ASSERT_TRUE(image.ok()) << image.error().to_string();
    ASSERT_EQ(image->width, 256u);
    ASSERT_EQ(image->height, 64u);
    // gradient: red = x / 255; invert: 1 - rgb.
    for (uint32_t x = 0; x < 256; x += 17) {
        const auto texel = image->texel(x, 31);
        EXPECT_EQ(static_cast<int>(texel[0]), 255 - static_cast<int>(x)) << "column " << x;
        EXPECT_EQ(static_cast<int>(texel[1]), 255);
        EXPECT_EQ(static_cast<int>(texel[2]), 255);
        EXPECT_EQ(static_cast<int>(texel[3]), 255);
    }
}

TEST_P(DocsSnippets, FrameGraphGuideExamples) {
    const Status planned = docs::plan_framegraph_examples();
    ASSERT_TRUE(planned.ok()) << planned.error().to_string();
    auto image = docs::execute_framegraph_example(device());
    ASSERT_TRUE(image.ok()) << image.error().to_string();
    // Stripes 8 texels wide, blurred over three: 1/3 and 2/3 at the edges of a white stripe.
    EXPECT_NEAR(image->load(7, 100)[0], 1.0 / 3.0, 1e-3);
    EXPECT_NEAR(image->load(8, 100)[0], 2.0 / 3.0, 1e-3);
    EXPECT_NEAR(image->load(12, 100)[0], 1.0, 1e-3);
    EXPECT_NEAR(image->load(3, 100)[0], 0.0, 1e-3);
}

// Planning only: no device.
TEST(DocsSnippetsPlans, BuffersPassKindsAndRangesPlanAsTheirJsonTwins) {
    const Status planned = docs::plan_buffer_examples(LOOM_PLAN_GRAPHS_DIR);
    EXPECT_TRUE(planned.ok()) << planned.error().to_string();
}

TEST_P(DocsSnippets, BackendsGuideDescribesTheDevice) {
    auto text = docs::describe_device(device());
    ASSERT_TRUE(text.ok()) << text.error().to_string();
    EXPECT_NE(text->find(device().capabilities().device_name), std::string::npos) << *text;
    EXPECT_NE(text->find("1 render pass(es)"), std::string::npos) << *text;
    EXPECT_NE(text->find(backend() == rhi::Backend::Vulkan ? "placed resources: yes" : "placed resources: no"),
              std::string::npos)
        << *text;
}

LOOM_INSTANTIATE_RENDER_TEST(DocsSnippets);

#if defined(LOOM_DOCS_HAS_GL)
TEST(DocsEmbeddingGl, EngineFrame) {
    std::string error;
    auto app = AppGlContext::create(error);
    ASSERT_TRUE(app) << error;
    GLuint texture = 0, screen = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_RGBA8, 32, 16);
    const GLfloat blue[4] = {0, 0, 1, 1};
    glClearTexImage(texture, 0, GL_RGBA, GL_FLOAT, blue);
    glCreateTextures(GL_TEXTURE_2D, 1, &screen);
    glTextureStorage2D(screen, 1, GL_RGBA8, 32, 16);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, screen, 0);
    auto picture = docs::gl_engine_frame(texture, 32, 16, fbo);
    ASSERT_TRUE(picture.ok()) << picture.error().to_string();
    auto at = [&](uint32_t x, uint32_t y) {
        const auto t = picture->texel(x, y);
        return std::array<int, 4>{int(t[0]), int(t[1]), int(t[2]), int(t[3])};
    };
    EXPECT_EQ(at(3, 2), (std::array<int, 4>{255, 0, 0, 255})) << "loom's quadrant (top left)";
    EXPECT_EQ(at(20, 2), (std::array<int, 4>{0, 0, 255, 255})) << "the engine's clear";
    EXPECT_EQ(at(3, 12), (std::array<int, 4>{0, 0, 255, 255})) << "the engine's clear";
    // The blit shows loom's top rows at the top of the framebuffer: GL's highest rows.
    std::vector<uint8_t> rows(32 * 16 * 4);
    glGetTextureImage(screen, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(rows.size()), rows.data());
    EXPECT_EQ(rows[(15 * 32 + 3) * 4 + 0], 255) << "GL row 15 (the top) shows red";
    EXPECT_EQ(rows[(0 * 32 + 3) * 4 + 2], 255) << "GL row 0 (the bottom) shows the engine's blue";
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &screen);
    glDeleteTextures(1, &texture);
}
#endif

}  // namespace
}  // namespace loom::test
