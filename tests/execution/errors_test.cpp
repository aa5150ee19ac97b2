// Errors a user can cause while executing come back as Status naming the pass (or port), the
// frame stays balanced, and the next frame runs normally.
#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

using rhi::Format;

const fg::TextureSpec kColor = fg::TextureSpec::of(Format::RGBA16Float);

class ExecutionErrors : public RenderTest {
protected:
    void SetUp() override {
        RenderTest::SetUp();
        programs_ = std::make_unique<TestPrograms>(device());
        LOOM_ASSIGN_OR_FAIL(fill_, programs_->fill(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(filter_, programs_->filter(Format::RGBA16Float));
        LOOM_ASSIGN_OR_FAIL(sampler_, programs_->sampler());
    }
    void TearDown() override {
        programs_.reset();
        RenderTest::TearDown();
    }

    /// Runs a graph of one pass whose output `port` of `pass` is `spec` at a 16x8 frame and
    /// expects a realisation error: Unsupported, a message containing `expected`, the port as
    /// the error's subject, and no texture left behind.
    void expect_refused_at_realisation(const std::string& pass, const std::string& port, const fg::TextureSpec& spec,
                                       const std::string& expected) {
        fg::FrameGraph graph;
        fg::Pass only(pass);
        only.output(port, spec);
        only.on_execute([](fg::PassContext&) { return Status{}; });
        ASSERT_TRUE(graph.add_pass(std::move(only)).ok());
        LOOM_ASSERT_OK(graph.mark_output(fg::port(pass, port)));
        const rhi::ResourceStats before = device().resource_stats();
        {
            fg::Executor executor(device());
            fg::PlanOptions options;
            options.frame = {16, 8};
            Status status = executor.run_frame(graph, options);
            ASSERT_FALSE(status.ok());
            EXPECT_EQ(status.error().code, ErrorCode::Unsupported);
            EXPECT_NE(status.error().message.find(expected), std::string::npos) << status.error().message;
            EXPECT_EQ(status.error().subjects, (std::vector<std::string>{pass + "." + port}));
        }
        EXPECT_EQ(device().resource_stats().textures, before.textures);
    }

    // first → broken → last; `broken` runs `behaviour` and then draws its output normally
    // unless the behaviour says it failed.
    fg::FrameGraph graph_with(std::function<Status(fg::PassContext&)> behaviour) {
        fg::FrameGraph graph;
        EXPECT_TRUE(graph.add_pass(fill_pass("first", "color", kColor, fill_, {{1, 0, 0, 1}, {1, 0, 0, 1}, 0.0f})).ok());
        fg::Pass broken("broken");
        broken.input("in", kColor).output("out", kColor);
        broken.on_execute([this, behaviour](fg::PassContext& ctx) { return behaviour(ctx); });
        EXPECT_TRUE(graph.add_pass(std::move(broken)).ok());
        fg::Pass last("last");
        last.input("in", kColor).output("out", kColor).on_execute([this](fg::PassContext& ctx) {
            ++last_runs_;
            ctx.begin_render_pass({"out"});
            ctx.commands().set_pipeline(filter_);
            ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("in"), sampler_));
            ctx.commands().push_constants_of(FilterConstants{});
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        });
        EXPECT_TRUE(graph.add_pass(std::move(last)).ok());
        EXPECT_TRUE(graph.connect(fg::port("first", "color"), fg::port("broken", "in")).ok());
        EXPECT_TRUE(graph.connect(fg::port("broken", "out"), fg::port("last", "in")).ok());
        EXPECT_TRUE(graph.mark_output(fg::port("last", "out")).ok());
        return graph;
    }

    // A well-behaved "broken" pass: out = in.
    Status draw_copy(fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(filter_);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("in"), sampler_));
        ctx.commands().push_constants_of(FilterConstants{});
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return {};
    }

    // Runs one failing frame; the error must name the pass and contain `needle`; "last" must not
    // have run; then a good frame must work with the same executor.
    void expect_pass_error(std::function<Status(fg::PassContext&)> behaviour, ErrorCode code, const std::string& needle) {
        bool fail = true;
        fg::FrameGraph graph = graph_with([&](fg::PassContext& ctx) { return fail ? behaviour(ctx) : draw_copy(ctx); });
        fg::Executor executor(device());
        fg::PlanOptions options;
        options.frame = {16, 8};
        last_runs_ = 0;
        Status status = executor.run_frame(graph, options);
        ASSERT_FALSE(status.ok()) << needle;
        EXPECT_EQ(status.error().code, code) << status.error().to_string();
        EXPECT_NE(status.error().message.find("pass 'broken'"), std::string::npos) << status.error().message;
        EXPECT_NE(status.error().message.find(needle), std::string::npos) << status.error().message;
        EXPECT_EQ(last_runs_, 0) << "a pass after the failing one was recorded";
        fail = false;
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        EXPECT_EQ(last_runs_, 1);
        EXPECT_EQ(texel(device(), executor.texture("last", "out"), 3, 3), (std::array<double, 4>{1, 0, 0, 1}));
    }

    std::unique_ptr<TestPrograms> programs_;
    rhi::PipelineHandle fill_, filter_;
    rhi::SamplerHandle sampler_;
    int last_runs_ = 0;
};

TEST_P(ExecutionErrors, ErrorReturnedByAPass) {
    expect_pass_error([](fg::PassContext&) { return Status(make_error(ErrorCode::ShaderCompile, "bloom.frag:3: oops")); },
                      ErrorCode::ShaderCompile, "bloom.frag:3: oops");
}

TEST_P(ExecutionErrors, RenderPassLeftOpen) {
    expect_pass_error([](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        return Status{};
    }, ErrorCode::InvalidState, "render pass still open");
}

TEST_P(ExecutionErrors, UnknownPortName) {
    expect_pass_error([](fg::PassContext& ctx) {
        (void)ctx.texture("colour");
        return Status{};
    }, ErrorCode::InvalidArgument, "no port 'colour' (ports: in, out)");
}

TEST_P(ExecutionErrors, RenderingToAnInputWithoutTextureOrToNothing) {
    expect_pass_error([](fg::PassContext& ctx) {
        ctx.begin_render_pass({});
        return Status{};
    }, ErrorCode::InvalidArgument, "begin_render_pass without attachments");
}

TEST_P(ExecutionErrors, TimersBelongToTheExecutor) {
    expect_pass_error([this](fg::PassContext& ctx) {
        ctx.commands().begin_timer("mine");
        ctx.commands().end_timer();
        return draw_copy(ctx);
    }, ErrorCode::InvalidState, "begin_timer 'mine'");
}

TEST_P(ExecutionErrors, NullHandlesAndCommandsInTheWrongPlace) {
    expect_pass_error([](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline({});
        ctx.end_render_pass();
        return Status{};
    }, ErrorCode::InvalidHandle, "set_pipeline: null pipeline handle");
    expect_pass_error([this](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(filter_);
        // What an unconnected optional port gives: a null texture.
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, rhi::TextureHandle{}, sampler_));
        ctx.end_render_pass();
        return Status{};
    }, ErrorCode::InvalidHandle, "set_bind_group: set 0 binding 0: null texture");
    expect_pass_error([this](fg::PassContext& ctx) {
        ctx.commands().set_pipeline(filter_);
        ctx.commands().draw(3);
        return Status{};
    }, ErrorCode::InvalidState, "draw outside a render pass");
    expect_pass_error([](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().transition(ctx.texture("in"), rhi::ResourceState::ShaderRead);
        ctx.end_render_pass();
        return Status{};
    }, ErrorCode::InvalidState, "transition inside a render pass");
}

TEST_P(ExecutionErrors, BackendErrorInsideThePassNamesItsRenderPass) {
    // A pipeline made for other attachment formats: the backend records the mismatch and
    // end_frame reports it, naming the render pass, which the executor labels with the pass.
    LOOM_ASSIGN_OR_FAIL(rhi::PipelineHandle rgba8, programs_->fill(Format::RGBA8Unorm));
    bool fail = true;
    fg::FrameGraph graph = graph_with([&](fg::PassContext& ctx) {
        if (!fail) return draw_copy(ctx);
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(rgba8);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    Status status = executor.run_frame(graph, options);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message.rfind("frame 0: ", 0), 0u) << status.error().message;
    EXPECT_NE(status.error().message.find("'broken'"), std::string::npos) << status.error().message;
    fail = false;
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
}

TEST_P(ExecutionErrors, TexturesBeyondTheDevicesLimitNameTheirPorts) {
    // Within loom's limit (65536 per side) but past the device's (16384 on llvmpipe and
    // lavapipe): an error naming the ports, before any texture is created, and nothing leaks.
    const uint32_t device_max = device().capabilities().max_texture_size;
    ASSERT_GT(device_max, 0u);
    if (device_max >= fg::kMaxTextureExtent) GTEST_SKIP() << "this device reaches loom's own limit";
    expect_refused_at_realisation("wide", "strip", fg::TextureSpec::of(Format::R8Unorm).with_size(device_max + 1, 2),
                                  "R8Unorm " + std::to_string(device_max + 1) + "x2, for wide.strip) is larger than "
                                  "this device's limit of " + std::to_string(device_max) + " texels per side");
}

TEST_P(ExecutionErrors, SampleCountsBeyondTheDevicesLimitNameTheirPorts) {
    // Within loom's limit (64 samples) but past the device's (4 on llvmpipe and lavapipe).
    const uint32_t device_max = device().capabilities().max_samples;
    ASSERT_GE(device_max, 1u);
    ASSERT_GT(device().capabilities().max_texture_layers, 0u);
    if (device_max >= fg::kMaxTextureSamples) GTEST_SKIP() << "this device reaches loom's own limit";
    expect_refused_at_realisation("msaa", "color", fg::TextureSpec::of(Format::RGBA8Unorm).with_samples(device_max * 2),
                                  "for msaa.color) has more samples than this device's limit of " +
                                      std::to_string(device_max));
}

TEST_P(ExecutionErrors, PlanningErrorsNameThePort) {
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(fg::Pass("lonely").input("in", kColor).output("out", kColor)).ok());
    LOOM_ASSERT_OK(graph.mark_output(fg::port("lonely", "out")));
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    Status status = executor.run_frame(graph, options);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::Graph);
    EXPECT_NE(status.error().message.find("lonely.in"), std::string::npos) << status.error().message;
    EXPECT_EQ(executor.stats().device.textures, device().resource_stats().textures);
    EXPECT_EQ(executor.stats().textures, 0u);
}

TEST_P(ExecutionErrors, TextureTheDeviceCannotCreateNamesIt) {
    // A size beyond the device's limit: the backend refuses the texture, the executor names it.
    fg::FrameGraph graph;
    const uint32_t too_big = device().capabilities().max_texture_size * 2;
    ASSERT_TRUE(graph.add_pass(fill_pass("huge", "color", fg::TextureSpec::of(Format::RGBA8Unorm).with_size(too_big, 4), fill_, {})).ok());
    LOOM_ASSERT_OK(graph.mark_output(fg::port("huge", "color")));
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 8};
    Status status;
    {
        ScopedLogCapture capture;  // backends may log the refusal too
        status = executor.run_frame(graph, options);
    }
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().message.find("huge.color"), std::string::npos) << status.error().message;
    EXPECT_EQ(executor.stats().textures, 0u);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ExecutionErrors);

}  // namespace loom::test
