// Plans a chain of four passes with loom::framegraph alone (no GPU) and checks the plan: results
// two passes apart share a texture (a.out with c.out, b.out with the output d.out).
#include <cstdio>

#include "loom/framegraph/framegraph.hpp"

int main() {
    using namespace loom;
    fg::FrameGraph graph;
    const auto color = fg::TextureSpec::of(rhi::Format::RGBA16Float);
    auto built = [&]() -> Status {
        LOOM_TRY(graph.add_pass(fg::Pass("a").output("out", color)));
        LOOM_TRY(graph.add_pass(fg::Pass("b").input("in").output("out", color)));
        LOOM_TRY(graph.add_pass(fg::Pass("c").input("in").output("out", color)));
        LOOM_TRY(graph.add_pass(fg::Pass("d").input("in").output("out", color)));
        LOOM_TRY(graph.connect(fg::port("a", "out"), fg::port("b", "in")));
        LOOM_TRY(graph.connect(fg::port("b", "out"), fg::port("c", "in")));
        LOOM_TRY(graph.connect(fg::port("c", "out"), fg::port("d", "in")));
        LOOM_TRY(graph.mark_output(fg::port("d", "out")));
        return {};
    }();
    if (!built) {
        std::fprintf(stderr, "plan_graph: %s\n", built.error().to_string().c_str());
        return 1;
    }
    fg::PlanOptions options;
    options.frame = {640, 480};
    auto plan = graph.plan(options);
    if (!plan) {
        std::fprintf(stderr, "plan_graph: %s\n", plan.error().to_string().c_str());
        return 1;
    }
    const fg::Plan& p = **plan;
    // a.out dies at b, so c.out can take its texture; b.out dies at c, so d.out takes its.
    const bool shared = p.texture_of("a", "out") == p.texture_of("c", "out") &&
                        p.texture_of("b", "out") == p.texture_of("d", "out") &&
                        p.texture_of("a", "out") != p.texture_of("b", "out");
    std::printf("plan_graph: %zu passes, %u textures (naive %u), %s\n", p.order.size(), p.summary.textures,
                p.summary.naive_textures, shared ? "a.out+c.out and b.out+d.out share" : "unexpected sharing");
    return p.order.size() == 4 && p.summary.textures == 2 && p.summary.naive_textures == 4 && shared ? 0 : 1;
}
