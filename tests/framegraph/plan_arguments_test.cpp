// loom-plan's command-line parser (samples/plan/plan_arguments.hpp) called directly, as the
// command-line fuzz harness calls it; plan_tool_test.cpp runs the tool itself.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "plan_arguments.hpp"

namespace loom::plan {
namespace {

Result<Arguments> parse(std::vector<std::string> words) { return parse_arguments(words); }

std::string error_of(std::vector<std::string> words) {
    auto parsed = parse(std::move(words));
    EXPECT_FALSE(parsed.ok());
    if (parsed.ok()) return {};
    EXPECT_EQ(parsed.error().code, ErrorCode::InvalidArgument);
    return parsed.error().message;
}

TEST(PlanArguments, EveryOption) {
    auto args = parse({"g.json", "--allocator", "heap", "--sharing", "joinable", "--frame", "640x480", "--max-heap",
                       "1048576", "--order", "memory", "--json", "--dot", "plan.dot"});
    ASSERT_TRUE(args.ok()) << args.error().message;
    EXPECT_EQ(args->graph, "g.json");
    EXPECT_TRUE(args->options.allocator == fg::AllocatorKind::Heap);
    EXPECT_EQ(args->options.sharing, fg::SpecSharing::Joinable);
    ASSERT_TRUE(args->frame.has_value());
    EXPECT_EQ(args->frame->width, 640u);
    EXPECT_EQ(args->frame->height, 480u);
    EXPECT_EQ(args->options.max_heap_bytes, 1048576u);
    EXPECT_EQ(args->order, fg::PassOrder::Memory);
    EXPECT_TRUE(args->json);
    EXPECT_EQ(args->dot, "plan.dot");
    EXPECT_TRUE(parse({"--help"}).ok());
    // Without --order the graph file decides.
    EXPECT_EQ(parse({"g.json"})->order, std::nullopt);
    EXPECT_EQ(parse({"g.json", "--order", "declared"})->order, fg::PassOrder::Declared);
}

TEST(PlanArguments, CompareTakesEveryAllocator) {
    auto args = parse({"g.json", "--compare", "--frame", "1280x720"});
    ASSERT_TRUE(args.ok()) << args.error().message;
    EXPECT_TRUE(args->compare);
    EXPECT_EQ(error_of({"g.json", "--compare", "--allocator", "heap"}),
              "--compare plans with every allocator; leave out --allocator");
    EXPECT_EQ(error_of({"g.json", "--compare", "--dot", "p.dot"}), "--compare prints figures, not one plan: leave out --dot");
}

TEST(PlanArguments, ErrorsNameTheArgument) {
    EXPECT_EQ(error_of({"g.json", "--frame"}), "--frame needs a value");
    EXPECT_EQ(error_of({"g.json", "--frame", "0x4294967297"}),
              "--frame must be WxH (e.g. 1920x1080) with each side in 1.." + std::to_string(fg::kMaxTextureExtent) +
                  ", not '0x4294967297'");
    EXPECT_EQ(error_of({"g.json", "--max-heap", "-1"}), "--max-heap must be a byte count, not '-1'");
    EXPECT_EQ(error_of({"g.json", "--sharing", "some"}), "--sharing must be equal or joinable, not 'some'");
    EXPECT_EQ(error_of({"g.json", "--order", "fast"}), "--order must be declared or memory, not 'fast'");
    EXPECT_EQ(error_of({"g.json", "--order"}), "--order needs a value");
    EXPECT_EQ(error_of({"g.json", "--allocator", "greedy"}), "--allocator: unknown allocator 'greedy' (known: paper, interval, heap)");
    EXPECT_EQ(error_of({"g.json", "--verbose"}), "unknown option '--verbose'");
    EXPECT_EQ(error_of({"a.json", "b.json"}), "more than one graph file given ('a.json', 'b.json')");
    EXPECT_EQ(error_of({}), "no graph file given; " + std::string(kUsage));
}

TEST(PlanArguments, FrameSides) {
    EXPECT_TRUE(parse_frame("1x1").has_value());
    EXPECT_TRUE(parse_frame(std::to_string(fg::kMaxTextureExtent) + "x1").has_value());
    EXPECT_FALSE(parse_frame(std::to_string(fg::kMaxTextureExtent + 1) + "x1").has_value());
    EXPECT_FALSE(parse_frame("x").has_value());
    EXPECT_FALSE(parse_frame("1x").has_value());
    EXPECT_FALSE(parse_frame("1x1x1").has_value());
    EXPECT_FALSE(parse_frame("18446744073709551616x1").has_value());
}

}  // namespace
}  // namespace loom::plan
