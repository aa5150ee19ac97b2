// Storage ports: compute passes write and modify a storage image, a render pass samples it.
// The executor's transitions (→ Storage before each storage pass, → ShaderRead before the
// sampling pass) are what makes the writes visible: Vulkan barriers, GL glMemoryBarrier.
#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::Format;

const char* const kGenerateComp = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D data;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(data, p, vec4(float(p.x), 0.5, 1.0, 1.0));
}
)";

const char* const kIncrementComp = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0, rgba32f) uniform image2D data;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    imageStore(data, p, imageLoad(data, p) + vec4(10.0, 0.0, 0.0, 0.0));
}
)";

class ComputeExecution : public RenderTest {};

fg::Pass compute_pass(const std::string& name, rhi::PipelineHandle pipeline, const std::string& port) {
    return fg::Pass(name).on_execute([pipeline, port](fg::PassContext& ctx) {
        const fg::Extent2D size = ctx.extent(port);
        ctx.commands().set_pipeline(pipeline);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.storage_texture(0, ctx.texture(port)));
        ctx.commands().dispatch((size.width + 7) / 8, (size.height + 7) / 8);
        return Status{};
    });
}

TEST_P(ComputeExecution, StoragePassesThenSampled) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto generate, programs.compute("generate.comp", kGenerateComp));
    LOOM_ASSIGN_OR_FAIL(auto increment, programs.compute("increment.comp", kIncrementComp));
    LOOM_ASSIGN_OR_FAIL(auto filter, programs.filter(Format::RGBA32Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    const fg::TextureSpec storage = fg::TextureSpec::of(Format::RGBA32Float).with_usage(rhi::TextureUsage::Storage);
    const fg::TextureSpec color = fg::TextureSpec::of(Format::RGBA32Float);

    fg::FrameGraph graph;
    fg::Pass gen = compute_pass("generate", generate, "data");
    gen.output("data", storage);
    ASSERT_TRUE(graph.add_pass(std::move(gen)).ok());
    fg::Pass inc = compute_pass("increment", increment, "data");
    inc.inout("data", storage);
    ASSERT_TRUE(graph.add_pass(std::move(inc)).ok());
    fg::Pass inc2 = compute_pass("increment_again", increment, "data");
    inc2.inout("data", storage);
    ASSERT_TRUE(graph.add_pass(std::move(inc2)).ok());
    ASSERT_TRUE(graph.add_pass(filter_pass("show", "in", "out", color, filter, sampler, {})).ok());
    LOOM_ASSERT_OK(graph.connect(fg::port("generate", "data"), fg::port("increment", "data")));
    LOOM_ASSERT_OK(graph.connect(fg::port("increment", "data"), fg::port("increment_again", "data")));
    LOOM_ASSERT_OK(graph.connect(fg::port("increment_again", "data"), fg::port("show", "in")));
    LOOM_ASSERT_OK(graph.mark_output(fg::port("show", "out")));

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {20, 12};  // not a multiple of the workgroup size
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("show", "out")));
        for (uint32_t y = 0; y < 12; ++y) {
            for (uint32_t x = 0; x < 20; ++x) {
                ASSERT_EQ(image.load(x, y), (std::array<double, 4>{x + 20.0, 0.5, 1.0, 1.0})) << x << "," << y << " frame " << frame;
            }
        }
    }
    // The schedule puts the storage image into Storage before each compute pass and into
    // ShaderRead before the render pass that samples it.
    const fg::ExecutionSchedule& schedule = *executor.schedule();
    const fg::TextureSlot data = schedule.passes[0].ports[0].texture;
    for (uint32_t p = 0; p < 3; ++p) {
        EXPECT_EQ(schedule.passes[p].before, (std::vector<fg::Transition>{{data, rhi::ResourceState::Storage}})) << p;
    }
    EXPECT_EQ(schedule.passes[3].before, (std::vector<fg::Transition>{{data, rhi::ResourceState::ShaderRead}}));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ComputeExecution);

}  // namespace loom::test
