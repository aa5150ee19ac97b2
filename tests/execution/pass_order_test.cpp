// The memory order (PassOrder::Memory) executed on every backend: a graph whose declared order
// keeps two big temporaries alive at once runs in an order that needs one at a time, with the
// heap allocator aliasing what that frees, and draws exactly the pixels of the declared order.
#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class PassOrderTest : public RenderTest {};

// filter_pass with an input of another spec than its output: out = in * mul + add over the
// output's texels (the input's top-left corner).
fg::Pass shrink_pass(const std::string& name, const fg::TextureSpec& in_spec, const fg::TextureSpec& out_spec,
                     rhi::PipelineHandle pipeline, rhi::SamplerHandle sampler, FilterConstants constants) {
    fg::Pass pass(name);
    pass.input("in", in_spec).output("out", out_spec);
    pass.on_execute([pipeline, sampler, constants](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(pipeline);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("in"), sampler));
        ctx.commands().push_constants_of(constants);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    return pass;
}

std::vector<std::string> order_of(const fg::Plan& plan) {
    std::vector<std::string> names;
    for (const fg::PlanPass& pass : plan.order) names.push_back(pass.name);
    return names;
}

TEST_P(PassOrderTest, MemoryOrderDrawsTheDeclaredOrdersPixels) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto combine, programs.combine(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    // Two chains, each a frame-sized temporary (128 KiB) reduced to a 16x8 result, declared interleaved
    // (a1, b1, a2, b2): in declared order both temporaries are alive at a2.
    const fg::TextureSpec big = fg::TextureSpec::of(Format::RGBA16Float);
    const fg::TextureSpec small = fg::TextureSpec::of(Format::RGBA16Float).with_size(16, 8);
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(fill_pass("a1", "color", big, fill, {{0.25f, 0.5f, 0.0f, 1.0f}, {0.75f, 0.125f, 0.5f, 1.0f}, 8.0f})).ok());
    ASSERT_TRUE(graph.add_pass(fill_pass("b1", "color", big, fill, {{0.5f, 0.25f, 0.125f, 1.0f}, {0.0f, 1.0f, 0.25f, 1.0f}, 8.0f})).ok());
    // a2 = a1 * 2 + (0, 0, 0.25, 0); b2 = 1 - b1 (rgb)
    ASSERT_TRUE(graph.add_pass(shrink_pass("a2", big, small, filter, sampler, {{2, 2, 2, 1}, {0, 0, 0.25f, 0}})).ok());
    ASSERT_TRUE(graph.add_pass(shrink_pass("b2", big, small, filter, sampler, {{-1, -1, -1, 1}, {1, 1, 1, 0}})).ok());
    // final = (a2 + b2) / 2
    ASSERT_TRUE(graph.add_pass(combine_pass("final", "a", "b", "image", small, combine, sampler,
                                            {{0.5f, 0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f, 0.5f}})).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("a1", "color"), fg::port("a2", "in")));
    LOOM_ASSERT_OK(graph.connect(fg::port("b1", "color"), fg::port("b2", "in")));
    LOOM_ASSERT_OK(graph.connect(fg::port("a2", "out"), fg::port("final", "a")));
    LOOM_ASSERT_OK(graph.connect(fg::port("b2", "out"), fg::port("final", "b")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("final", "image")));

    std::vector<rhi::Image> pictures;
    std::vector<uint64_t> peaks;
    for (fg::AllocatorKind allocator : {fg::AllocatorKind::Heap, fg::AllocatorKind::Interval}) {
        for (fg::PassOrder order : {fg::PassOrder::Declared, fg::PassOrder::Memory}) {
            SCOPED_TRACE(std::string(fg::allocator_name(allocator)) + ", " + std::string(fg::pass_order_name(order)));
            fg::Executor executor(device());
            fg::PlanOptions options;
            options.frame = {128, 128};
            options.allocator = allocator;
            options.order = order;
            LOOM_ASSERT_OK(executor.run_frame(graph, options));
            const fg::Plan& plan = *executor.plan();
            EXPECT_EQ(order_of(plan), order == fg::PassOrder::Memory
                                          ? (std::vector<std::string>{"a1", "a2", "b1", "b2", "final"})
                                          : (std::vector<std::string>{"a1", "b1", "a2", "b2", "final"}));
            peaks.push_back(plan.summary.lower_bound_bytes);
            LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("final", "image")));
            ASSERT_EQ(image.width, 16u);
            ASSERT_EQ(image.height, 8u);
            for (uint32_t y = 0; y < 8; ++y) {
                for (uint32_t x = 0; x < 16; ++x) {
                    const std::array<double, 4> expected =
                        x < 8 ? std::array<double, 4>{0.5, 0.875, 0.5625, 1.0} : std::array<double, 4>{1.25, 0.125, 1.0, 1.0};
                    ASSERT_EQ(image.load(x, y), expected) << "pixel " << x << "," << y;
                }
            }
            pictures.push_back(std::move(image));
        }
    }
    // Byte for byte the same picture in every order and allocation; the memory order needs one
    // temporary at a time. With the interval allocator the default memory model sizes the
    // textures (64 KiB pages: 128 KiB per temporary, one page per result); the heap allocator
    // asks a device with placed resources (Vulkan) for its sizes.
    for (const rhi::Image& picture : pictures) EXPECT_TRUE(picture.pixels == pictures.front().pixels);
    EXPECT_LT(peaks[1], peaks[0]);
    EXPECT_EQ(peaks[2], 2u * 131072u + 65536u);  // declared: a1's and b1's temporaries and a2's result
    EXPECT_EQ(peaks[3], 131072u + 2u * 65536u);  // memory: b1's temporary, a2's and b2's results
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(PassOrderTest);

}  // namespace loom::test
