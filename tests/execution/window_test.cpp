// The graph's output imported from a window's back buffer (a new handle every frame), left in
// Present. Needs a display: ctest runs it under xvfb-run; without DISPLAY it skips.
#include <cstdlib>

#include "execution_helpers.hpp"
#include "loom/rhi/device.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class ExecutionWindow : public ::testing::TestWithParam<rhi::Backend> {};

TEST_P(ExecutionWindow, BackBufferImportIsPresented) {
    if (!std::getenv("DISPLAY")) GTEST_SKIP() << "no X display (ctest runs this under xvfb-run)";
    rhi::DeviceDesc desc;
    desc.backend = GetParam();
    desc.headless = false;
    desc.window.title = "loom executor window test";
    desc.window.width = 64;
    desc.window.height = 48;
    desc.window.resizable = false;
    auto created = rhi::create_device(desc);
    ASSERT_TRUE(created.ok()) << created.error().to_string();
    rhi::Device& device = **created;
    {
        TestPrograms programs(device);
        std::unique_ptr<fg::FrameGraph> graph;
        fg::Executor executor(device);
        for (int frame = 0; frame < 4; ++frame) {
            EXPECT_TRUE(device.poll_window());
            rhi::CommandList& list = device.begin_frame();
            const rhi::TextureHandle backbuffer = device.backbuffer();
            ASSERT_FALSE(backbuffer.is_null());
            LOOM_ASSIGN_OR_FAIL(const rhi::TextureDesc bd, device.texture_desc(backbuffer));
            if (!graph) {
                // The output port asks for the back buffer's format; fill → invert → back buffer.
                const fg::TextureSpec color = fg::TextureSpec::of(Format::RGBA16Float);
                LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA16Float));
                LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(bd.format));
                LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
                graph = std::make_unique<fg::FrameGraph>();
                ASSERT_TRUE(graph->add_pass(fill_pass("fill", "color", color, fill, {{1, 0, 0, 1}, {0, 1, 0, 1}, 32.0f})).ok());
                fg::Pass invert("invert");
                invert.input("in", color).output("out", fg::TextureSpec::of(bd.format));
                invert.on_execute([filter, sampler](fg::PassContext& ctx) {
                    ctx.begin_render_pass({"out"});
                    ctx.commands().set_pipeline(filter);
                    ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("in"), sampler));
                    ctx.commands().push_constants_of(FilterConstants{{-1, -1, -1, 1}, {1, 1, 1, 0}});
                    ctx.commands().draw(3);
                    ctx.end_render_pass();
                    return Status{};
                });
                ASSERT_TRUE(graph->add_pass(std::move(invert)).ok());
                LOOM_ASSERT_OK(graph->connect(fg::port("fill", "color"), fg::port("invert", "in")));
                LOOM_ASSERT_OK(graph->mark_output(fg::port("invert", "out")));
            }
            executor.import_texture(fg::port("invert", "out"), backbuffer, rhi::ResourceState::Present);
            fg::PlanOptions options;
            options.frame = {bd.width, bd.height};
            LOOM_ASSERT_OK(executor.execute(*graph, list, options));
            if (frame == 2) {
                LOOM_ASSIGN_OR_FAIL(rhi::Image image, device.read_texture(backbuffer));
                EXPECT_EQ(image.load(5, bd.height / 2), (std::array<double, 4>{0, 1, 1, 1}));
                EXPECT_EQ(image.load(bd.width - 5, bd.height / 2), (std::array<double, 4>{1, 0, 1, 1}));
            }
            LOOM_ASSERT_OK(device.end_frame());
        }
        // Rebinding a new back buffer every frame rebuilt nothing.
        EXPECT_EQ(executor.stats().realisations, 1u);
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, ExecutionWindow, ::testing::ValuesIn(backends_under_test()), BackendParamName{});

}  // namespace
}  // namespace loom::test
