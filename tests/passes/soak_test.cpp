// The flagship's soak run (samples/deferred/soak.hpp, docs/soak.md): the leak check itself on
// made-up samples, and 500 frames on each backend, resized every 100 frames and rebuilt with the
// lit pass toggled every 10, whose live GPU objects must repeat exactly once warmed up.
#include <gtest/gtest.h>

#include "loom_test/render_fixture.hpp"
#include "procedural_scene.hpp"
#include "soak.hpp"

namespace loom::test {
namespace {

using deferred::SoakSample;

/// `frames` samples of a steady run with a period of 4: two shapes alternating every 2 frames.
std::vector<SoakSample> steady_samples(uint64_t frames) {
    std::vector<SoakSample> samples;
    for (uint64_t i = 0; i < frames; ++i) {
        SoakSample s;
        s.frame = i;
        s.forward = (i / 2) % 2 == 1;
        s.live.textures = s.forward ? 6 : 8;
        s.live.pipelines = s.forward ? 7 : 8;
        s.live.texture_bytes = s.forward ? 1000 : 1600;
        s.resident_bytes = 100 << 20;
        samples.push_back(s);
    }
    return samples;
}

TEST(SoakCheck, AStableRepeatingPatternIsSteady) {
    const auto verdict = deferred::check_soak(steady_samples(20), 4);
    EXPECT_TRUE(verdict.steady) << verdict.describe();
    EXPECT_EQ(verdict.warm_up_frames, 4u);
    EXPECT_EQ(verdict.compared, 12u);  // frames 8..19, each against frame - 4
    EXPECT_EQ(verdict.first_difference, "");
}

TEST(SoakCheck, OneBufferLeakedAfterTheWarmUpIsFoundAndNamed) {
    auto samples = steady_samples(20);
    // A buffer created at frame 13 and never destroyed.
    for (std::size_t i = 13; i < samples.size(); ++i) samples[i].live.buffers += 1;
    const auto verdict = deferred::check_soak(samples, 4);
    EXPECT_FALSE(verdict.steady);
    EXPECT_EQ(verdict.first_difference,
              "frame 13 has 8 textures, 1 buffers, 0 heaps, 0 samplers, 0 shaders, 8 pipelines, 1600 bytes, frame 9 had "
              "8 textures, 0 buffers, 0 heaps, 0 samplers, 0 shaders, 8 pipelines, 1600 bytes");
}

TEST(SoakCheck, GrowingBytesAloneAreALeak) {
    auto samples = steady_samples(20);
    for (std::size_t i = 10; i < samples.size(); ++i) samples[i].live.buffer_bytes = 256 * (i - 9);
    EXPECT_FALSE(deferred::check_soak(samples, 4).steady);
}

TEST(SoakCheck, ALeakDuringTheWarmUpOnlyIsNotCounted) {
    auto samples = steady_samples(20);
    samples[1].live.textures += 3;  // e.g. a first-frame upload buffer freed later
    EXPECT_TRUE(deferred::check_soak(samples, 4).steady);
}

TEST(SoakCheck, ARunOfTwoPeriodsOrLessIsTooShort) {
    const auto verdict = deferred::check_soak(steady_samples(8), 4);
    EXPECT_FALSE(verdict.steady);
    EXPECT_EQ(verdict.first_difference, "too short: 8 frames, the check needs more than 8 (two periods)");
}

TEST(SoakCheck, ThePeriodCoversBothSizesAndBothLitPasses) {
    deferred::SoakSettings settings;
    EXPECT_EQ(deferred::soak_period(settings), 200u);
    settings.resize_every = 30;
    settings.rebuild_every = 20;
    EXPECT_EQ(deferred::soak_period(settings), 120u);
}

class SoakTest : public RenderTest {};

TEST_P(SoakTest, FiveHundredFramesOfResizesAndRebuildsLeaveTheLiveObjectsUnchanged) {
    renderer::PipelineSettings settings;
    settings.capture = false;
    auto pipeline = deferred::create_procedural_pipeline(device(), deferred::procedural_scene(), settings);
    ASSERT_TRUE(pipeline.ok()) << pipeline.error().to_string();

    deferred::SoakSettings soak;
    soak.frames = 500;
    soak.size = {64, 36};
    auto samples = deferred::run_soak(device(), **pipeline, soak);
    ASSERT_TRUE(samples.ok()) << samples.error().to_string();
    ASSERT_EQ(samples->size(), 500u);

    // The run did what it says: two sizes, both lit passes, and they change what is alive.
    const SoakSample& first = (*samples)[0];
    EXPECT_EQ(first.size, (fg::Extent2D{64, 36}));
    EXPECT_FALSE(first.forward);
    EXPECT_TRUE((*samples)[10].forward);
    EXPECT_FALSE((*samples)[20].forward);
    EXPECT_EQ((*samples)[100].size, (fg::Extent2D{48, 27}));
    EXPECT_EQ((*samples)[200].size, (fg::Extent2D{64, 36}));
    EXPECT_NE((*samples)[5].live.textures, (*samples)[15].live.textures)
        << "the forward graph has no G-buffer: fewer textures than the deferred one";
    EXPECT_NE((*samples)[50].live.texture_bytes, (*samples)[150].live.texture_bytes);
    EXPECT_EQ((*pipeline)->executor().plan()->frame, (fg::Extent2D{64, 36}));  // frame 499: the first size again

    const auto verdict = deferred::check_soak(*samples, deferred::soak_period(soak));
    EXPECT_TRUE(verdict.steady) << verdict.describe();
    EXPECT_EQ(verdict.compared, 100u);
    // Start and end of the compared stretch, in the same phase: equal, object for object.
    const rhi::ResourceStats& start = (*samples)[299].live;
    const rhi::ResourceStats& end = (*samples)[499].live;
    EXPECT_EQ(start.textures, end.textures);
    EXPECT_EQ(start.buffers, end.buffers);
    EXPECT_EQ(start.samplers, end.samplers);
    EXPECT_EQ(start.shaders, end.shaders);
    EXPECT_EQ(start.pipelines, end.pipelines);
    EXPECT_EQ(start.total_bytes(), end.total_bytes());
}

LOOM_INSTANTIATE_RENDER_TEST(SoakTest);

}  // namespace
}  // namespace loom::test
