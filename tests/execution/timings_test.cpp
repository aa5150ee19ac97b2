// Every pass is timed every frame: CPU recording time always, GPU time where the device has
// timestamps. (Presence only: no assertion on how long anything takes.)
#include <algorithm>

#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class TimingsTest : public RenderTest {};

TEST_P(TimingsTest, EveryPassHasTimings) {
    TestPrograms programs(device());
    const fg::TextureSpec spec = fg::TextureSpec::of(Format::RGBA16Float);
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(Format::RGBA16Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(fill_pass("fill", "color", spec, fill, {{1, 0, 0, 1}, {0, 1, 0, 1}, 4.0f})).ok());
    ASSERT_TRUE(graph.add_pass(filter_pass("blur_h", "in", "out", spec, filter, sampler, {})).ok());
    ASSERT_TRUE(graph.add_pass(filter_pass("blur_v", "in", "out", spec, filter, sampler, {})).ok());
    ASSERT_TRUE(graph.add_pass(fill_pass("unused", "color", spec, fill, {})).ok());  // culled: not timed
    LOOM_ASSERT_OK(graph.connect(fg::port("fill", "color"), fg::port("blur_h", "in")));
    LOOM_ASSERT_OK(graph.connect(fg::port("blur_h", "out"), fg::port("blur_v", "in")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("blur_v", "out")));

    fg::Executor executor(device());
    EXPECT_TRUE(executor.timings().empty()) << "timings before the first frame";
    fg::PlanOptions options;
    options.frame = {32, 32};
    for (int frame = 0; frame < 3; ++frame) LOOM_ASSERT_OK(executor.run_frame(graph, options));
    LOOM_ASSERT_OK(device().wait_idle());

    const std::vector<fg::PassTiming> timings = executor.timings();
    ASSERT_EQ(timings.size(), 3u);
    const std::vector<std::string> names{"fill", "blur_h", "blur_v"};
    for (std::size_t i = 0; i < timings.size(); ++i) {
        SCOPED_TRACE(names[i]);
        EXPECT_EQ(timings[i].pass, names[i]);
        EXPECT_GT(timings[i].cpu_ms, 0.0);
        if (device().capabilities().timestamps) {
            ASSERT_TRUE(timings[i].gpu_ms.has_value());
            EXPECT_GE(*timings[i].gpu_ms, 0.0);
        } else {
            EXPECT_FALSE(timings[i].gpu_ms.has_value());
        }
    }
    // The printable table names every pass and ends with the total.
    const std::string table = fg::describe_timings(timings);
    for (const std::string& name : names) EXPECT_NE(table.find("\n" + name + " "), std::string::npos) << table;
    EXPECT_EQ(table.rfind("pass", 0), 0u) << table;
    EXPECT_NE(table.find("\ntotal "), std::string::npos) << table;
    EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 5) << table;
    // The device's own timer list has one entry per pass, labelled with the pass name.
    const std::vector<rhi::TimerResult> raw = device().timer_results();
    if (device().capabilities().timestamps) {
        ASSERT_EQ(raw.size(), 3u);
        for (std::size_t i = 0; i < raw.size(); ++i) EXPECT_EQ(raw[i].label, names[i]);
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(TimingsTest);

}  // namespace loom::test
