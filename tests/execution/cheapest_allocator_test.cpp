// Executor::cheapest_allocator on every backend: the heap allocator only where the device
// places resources and the heap plan needs fewer bytes; interval where the shapes let whole
// textures be shared as well as bytes, and everywhere on a device without placed resources.
#include <gtest/gtest.h>

#include "execution_helpers.hpp"
#include "loom/framegraph/executor.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class CheapestAllocator : public RenderTest {};

/// a → b → c, each writing a texture of `formats[i]` that only the next reads.
std::unique_ptr<fg::FrameGraph> chain(std::array<Format, 3> formats) {
    auto graph = std::make_unique<fg::FrameGraph>();
    const char* names[] = {"a", "b", "c"};
    for (int i = 0; i < 3; ++i) {
        fg::Pass pass(names[i]);
        if (i > 0) pass.input("in", fg::TextureSpec::of(formats[i - 1]));
        pass.output("out", fg::TextureSpec::of(formats[i]));
        EXPECT_TRUE(graph->add_pass(std::move(pass)).ok());
    }
    EXPECT_TRUE(graph->connect(fg::port("a", "out"), fg::port("b", "in")).ok());
    EXPECT_TRUE(graph->connect(fg::port("b", "out"), fg::port("c", "in")).ok());
    EXPECT_TRUE(graph->mark_output(fg::port("c", "out")).ok());
    return graph;
}

TEST_P(CheapestAllocator, HeapOnlyWhereItPlacesFewerBytes) {
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {256, 256};
    options.allocator = fg::AllocatorKind::Paper;  // ignored: both are planned
    const bool placed = device().capabilities().placed_resources;

    // Three shapes: the interval allocator shares no texture (three of them), the heap
    // allocator lets a's and c's bytes alias (c starts after a's last reader).
    const auto mixed = chain({Format::RGBA16Float, Format::R8Unorm, Format::RGBA8Unorm});
    LOOM_ASSIGN_OR_FAIL(const fg::AllocatorKind for_mixed, executor.cheapest_allocator(*mixed, options));
    EXPECT_EQ(for_mixed, placed ? fg::AllocatorKind::Heap : fg::AllocatorKind::Interval);

    // One shape: interval already shares a's texture with c; the heap saves nothing more.
    const auto same = chain({Format::RGBA8Unorm, Format::RGBA8Unorm, Format::RGBA8Unorm});
    LOOM_ASSIGN_OR_FAIL(const fg::AllocatorKind for_same, executor.cheapest_allocator(*same, options));
    EXPECT_EQ(for_same, fg::AllocatorKind::Interval);

    // A graph that cannot be planned is the planner's error.
    fg::FrameGraph broken;
    ASSERT_TRUE(broken.add_pass(fg::Pass("lonely").input("in", fg::TextureSpec::of(Format::RGBA8Unorm))
                                    .output("out", fg::TextureSpec::of(Format::RGBA8Unorm))).ok());
    ASSERT_TRUE(broken.mark_output(fg::port("lonely", "out")).ok());
    const auto refused = executor.cheapest_allocator(broken, options);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::Graph) << refused.error().to_string();
}

LOOM_INSTANTIATE_RENDER_TEST(CheapestAllocator);

}  // namespace
}  // namespace loom::test
