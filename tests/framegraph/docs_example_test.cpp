// The examples of docs/framegraph.md, compiled and checked, so the guide shows the API as it is.
#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"

namespace {

using namespace loom;

loom::Status build(fg::FrameGraph& graph) {
    const auto color = fg::TextureSpec::of(rhi::Format::RGBA16Float);  // frame-sized by default
    LOOM_TRY(graph.add_pass(fg::Pass("geometry").output("albedo", color).output("normal", color)));
    LOOM_TRY(graph.add_pass(fg::Pass("light").input("albedo").input("normal").output("hdr", color)));
    LOOM_TRY(graph.add_pass(fg::Pass("ui").inout("hdr").set_side_effect()));  // never culled
    LOOM_TRY(graph.connect(fg::port("geometry", "albedo"), fg::port("light", "albedo")));
    LOOM_TRY(graph.connect(fg::port("geometry", "normal"), fg::port("light", "normal")));
    LOOM_TRY(graph.connect(fg::port("light", "hdr"), fg::port("ui", "hdr")));
    LOOM_TRY(graph.mark_output(fg::port("ui", "hdr")));  // read after the frame
    return {};
}

const auto color = fg::TextureSpec::of(rhi::Format::RGBA16Float);

fg::Part deferred_render() {  // Listing 3
    return fg::Part("deferred-render").input("position").input("normal").input("albedo").output("color", color);
}
fg::Part shadow_render() {  // Listing 4
    return fg::Part("shadow-render").input("shadow_map", fg::TextureSpec::of(rhi::Format::Depth32F)).output("color", color);
}
fg::Part high_pass_render() {  // Listing 5
    return fg::Part("high-pass-render").output("high_pass", color);
}

class DeferredShadowPass : public fg::Pass {  // deferred+shadow-pass of Listing 6
public:
    DeferredShadowPass() : Pass("deferred") { add(deferred_render()).add(shadow_render()).add(high_pass_render()); }
};

TEST(DocsExample, BuildAndPlan) {
    fg::FrameGraph graph;
    auto built = build(graph);
    ASSERT_TRUE(built.ok()) << built.error().to_string();
    fg::PlanOptions options;
    options.frame = {1920, 1080};
    options.allocator = "paper";
    auto plan = graph.plan(options);
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    const fg::Plan& p = **plan;
    EXPECT_EQ(p.texture_of("light", "hdr"), p.texture_of("ui", "hdr"));
    EXPECT_EQ(p.order.size(), 3u);
    EXPECT_EQ(p.summary.naive_textures, 3u);
    // albedo and normal end at light, which starts hdr: no sharing possible in a chain of three.
    EXPECT_EQ(p.summary.textures, 3u);
}

TEST(DocsExample, ComposedDeferredPass) {
    fg::FrameGraph graph;
    auto id = graph.add_pass(DeferredShadowPass{});
    ASSERT_TRUE(id.ok()) << id.error().to_string();
    std::vector<std::string> names;
    for (const fg::Port& port : graph.pass(*id).ports()) names.push_back(port.name);
    EXPECT_EQ(names, (std::vector<std::string>{"position", "normal", "albedo", "color", "shadow_map", "high_pass"}));
}

}  // namespace
