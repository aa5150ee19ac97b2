// Buffers, compute and copy passes, and subresource ranges executed through the frame graph on
// every backend: a compute pass builds geometry, indices and indirect arguments that a render
// pass draws; a mip pyramid is down-sampled (by compute and by a render pass into one mip) and
// up-sampled in place, compared with a CPU reference; shadow cascades are rendered layer by
// layer into one array and sampled as an array. The executor's transitions are the only
// synchronisation (Vulkan runs with synchronization validation: a missing barrier fails).
#include <cmath>
#include <cstring>

#include "execution_helpers.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using rhi::BufferUsage;
using rhi::Format;

const char* const kFillGeometryComp = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) writeonly buffer Vertices { vec2 v[]; } vertices;
layout(std430, set = 0, binding = 1) writeonly buffer Indices { uint i[]; } indices;
layout(std430, set = 0, binding = 2) writeonly buffer Arguments { uint a[]; } arguments;
void main() {
    // A rectangle over the left half of the frame, as two triangles, indexed backwards.
    vec2 corners[6] = vec2[6](vec2(-1.0, -1.0), vec2(0.0, -1.0), vec2(0.0, 1.0),
                              vec2(-1.0, -1.0), vec2(0.0, 1.0), vec2(-1.0, 1.0));
    for (int k = 0; k < 6; ++k) {
        vertices.v[k] = corners[k];
        indices.i[k] = uint(5 - k);
    }
    // DrawIndexedIndirectCommand: 6 indices, 1 instance, first index 0, base vertex 0, first instance 0.
    arguments.a[0] = 6u;
    arguments.a[1] = 1u;
    arguments.a[2] = 0u;
    arguments.a[3] = 0u;
    arguments.a[4] = 0u;
}
)";

const char* const kShiftComp = R"(#version 450
layout(local_size_x = 1) in;
layout(std430, set = 0, binding = 0) buffer Vertices { vec2 v[]; } vertices;
void main() {
    for (int k = 0; k < 6; ++k) vertices.v[k].x += 1.0;  // to the right half
}
)";

const char* const kPositionVert = R"(#version 450
layout(location = 0) in vec2 position;
void main() { gl_Position = vec4(position, 0.0, 1.0); }
)";

const char* const kColorFrag = R"(#version 450
layout(location = 0) out vec4 out_color;
void main() { out_color = vec4(0.25, 0.5, 0.75, 1.0); }
)";

// dst = the 2x2 box average of src (src's level 0 is the range's first mip).
const char* const kDownComp = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (p.x >= size.x || p.y >= size.y) return;
    vec4 sum = texelFetch(src, 2 * p, 0) + texelFetch(src, 2 * p + ivec2(1, 0), 0) +
               texelFetch(src, 2 * p + ivec2(0, 1), 0) + texelFetch(src, 2 * p + ivec2(1, 1), 0);
    imageStore(dst, p, sum * 0.25);
}
)";

const char* const kDownFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D src;
layout(location = 0) out vec4 out_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 sum = texelFetch(src, 2 * p, 0) + texelFetch(src, 2 * p + ivec2(1, 0), 0) +
               texelFetch(src, 2 * p + ivec2(0, 1), 0) + texelFetch(src, 2 * p + ivec2(1, 1), 0);
    out_color = sum * 0.25;
}
)";

// dst = (dst + the coarser level's texel) / 2, in place.
const char* const kUpComp = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba32f) uniform image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = imageSize(dst);
    if (p.x >= size.x || p.y >= size.y) return;
    imageStore(dst, p, (imageLoad(dst, p) + texelFetch(src, p / 2, 0)) * 0.5);
}
)";

const char* const kCascadesFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2DArray shadow;
layout(location = 0) out vec4 out_color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    out_color = vec4(texelFetch(shadow, ivec3(p, 0), 0).r, texelFetch(shadow, ivec3(p, 1), 0).r,
                     texelFetch(shadow, ivec3(p, 2), 0).r, texelFetch(shadow, ivec3(p, 3), 0).r);
}
)";

const char* const kNumbersComp = R"(#version 450
layout(local_size_x = 16) in;
layout(std430, set = 0, binding = 0) writeonly buffer Data { uint v[]; } data;
void main() { data.v[gl_LocalInvocationID.x] = gl_LocalInvocationID.x * 3u + 1u; }
)";

const char* const kCubeFrag = R"(#version 450
layout(set = 0, binding = 0) uniform samplerCube faces;
layout(location = 0) out vec4 out_color;
void main() {
    // Column x looks along +X, -X, +Y, -Y, +Z, -Z: the faces' order as layers.
    vec3 directions[6] = vec3[6](vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1));
    out_color = texture(faces, directions[int(gl_FragCoord.x)]);
}
)";

class ResourceExecution : public RenderTest {};

// The pipelines of the geometry graph.
struct GeometryPrograms {
    rhi::PipelineHandle fill;
    rhi::PipelineHandle shift;
    rhi::PipelineHandle draw;
};

Result<GeometryPrograms> geometry_programs(TestPrograms& programs, rhi::Device& device) {
    auto fill = programs.compute("fill_geometry.comp", kFillGeometryComp);
    if (!fill) return fill.take_error();
    auto shift = programs.compute("shift.comp", kShiftComp);
    if (!shift) return shift.take_error();
    auto vs = programs.shader(rhi::ShaderStage::Vertex, "position.vert", kPositionVert);
    if (!vs) return vs.take_error();
    auto fs = programs.shader(rhi::ShaderStage::Fragment, "color.frag", kColorFrag);
    if (!fs) return fs.take_error();
    rhi::GraphicsPipelineDesc pd;
    pd.name = "draw geometry";
    pd.vertex = *vs;
    pd.fragment = *fs;
    pd.vertex_buffers = {rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}}}};
    pd.color_formats = {Format::RGBA32Float};
    auto draw = device.create_graphics_pipeline(pd);
    if (!draw) return draw.take_error();
    programs.adopt(*draw, pd.name);
    return GeometryPrograms{*fill, *shift, *draw};
}

// A compute pass fills vertices, indices and indirect arguments, a second one moves the
// vertices in place, and a render pass draws them indirectly; the compute passes run on
// `compute_queue`.
fg::FrameGraph geometry_graph(const GeometryPrograms& programs, fg::Queue compute_queue) {
    fg::FrameGraph graph;
    auto fill_pass = fg::Pass("fill")
                         .set_kind(fg::PassKind::Compute)
                         .set_queue(compute_queue)
                         .buffer_output("vertices", fg::BufferSpec::of_size(6 * 8))
                         .buffer_output("indices", fg::BufferSpec::of_size(6 * 4))
                         .buffer_output("arguments", fg::BufferSpec::of_size(sizeof(rhi::DrawIndexedIndirectCommand)))
                         .on_execute([fill = programs.fill](fg::PassContext& ctx) {
                             ctx.commands().set_pipeline(fill);
                             ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                                  .buffer(0, ctx.buffer("vertices"))
                                                                  .buffer(1, ctx.buffer("indices"))
                                                                  .buffer(2, ctx.buffer("arguments")));
                             ctx.commands().dispatch(1);
                             return Status{};
                         });
    EXPECT_TRUE(graph.add_pass(std::move(fill_pass)).ok());
    // Read-modify-write of what the previous compute pass wrote: a storage-to-storage barrier.
    auto shift_pass = fg::Pass("shift")
                          .set_kind(fg::PassKind::Compute)
                          .set_queue(compute_queue)
                          .buffer_inout("vertices")
                          .on_execute([shift = programs.shift](fg::PassContext& ctx) {
                              ctx.commands().set_pipeline(shift);
                              ctx.commands().set_bind_group(0, rhi::BindGroup{}.buffer(0, ctx.buffer("vertices")));
                              ctx.commands().dispatch(1);
                              return Status{};
                          });
    EXPECT_TRUE(graph.add_pass(std::move(shift_pass)).ok());
    auto draw_pass = fg::Pass("draw")
                         .buffer_input("vertices", fg::BufferSpec{}.with_usage(BufferUsage::Vertex))
                         .buffer_input("indices", fg::BufferSpec{}.with_usage(BufferUsage::Index))
                         .buffer_input("arguments", fg::BufferSpec{}.with_usage(BufferUsage::Indirect))
                         .output("color", fg::TextureSpec::of(Format::RGBA32Float))
                         .on_execute([draw = programs.draw](fg::PassContext& ctx) {
                             ctx.begin_render_pass({{"color", {0.0, 0.0, 0.0, 0.0}}});
                             ctx.commands().set_pipeline(draw);
                             ctx.commands().set_vertex_buffer(0, ctx.buffer("vertices"));
                             ctx.commands().set_index_buffer(ctx.buffer("indices"), rhi::IndexType::Uint32);
                             ctx.commands().draw_indexed_indirect(ctx.buffer("arguments"), 0, 1);
                             ctx.end_render_pass();
                             return Status{};
                         });
    EXPECT_TRUE(graph.add_pass(std::move(draw_pass)).ok());
    EXPECT_TRUE(graph.connect(fg::port("fill", "vertices"), fg::port("shift", "vertices")).ok());
    EXPECT_TRUE(graph.connect(fg::port("shift", "vertices"), fg::port("draw", "vertices")).ok());
    EXPECT_TRUE(graph.connect(fg::port("fill", "indices"), fg::port("draw", "indices")).ok());
    EXPECT_TRUE(graph.connect(fg::port("fill", "arguments"), fg::port("draw", "arguments")).ok());
    EXPECT_TRUE(graph.mark_output(fg::port("draw", "color")).ok());
    return graph;
}

TEST_P(ResourceExecution, ComputeBuiltGeometryIsDrawnIndirectly) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(const GeometryPrograms pipelines, geometry_programs(programs, device()));
    fg::FrameGraph graph = geometry_graph(pipelines, fg::Queue::Graphics);

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {32, 16};
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        // The barriers the plan's transitions make: after the storage writes, shift's
        // read-modify-write and draw's vertex, index and indirect reads (GL: one glMemoryBarrier
        // each, 4); Vulkan also orders fill's writes after the previous frame's reads (and the
        // first frame's after nothing), 3 more. Without the transitions there would be none.
        const uint64_t barriers = device().last_frame_stats().buffer_barriers;
        EXPECT_EQ(barriers, backend() == rhi::Backend::OpenGL ? 4u : 7u) << "frame " << frame;
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("draw", "color")));
        for (uint32_t y = 1; y < 16; y += 4) {
            EXPECT_EQ(image.load(7, y), (std::array<double, 4>{0, 0, 0, 0})) << "left half, row " << y << " frame " << frame;
            EXPECT_EQ(image.load(24, y), (std::array<double, 4>{0.25, 0.5, 0.75, 1})) << "right half, row " << y;
        }
    }
    // What the compute pass wrote, read back from the graph's buffer.
    LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(executor.buffer("draw", "arguments"), 0, 20));
    uint32_t words[5];
    std::memcpy(words, bytes.data(), sizeof words);
    EXPECT_EQ(std::vector<uint32_t>(words, words + 5), (std::vector<uint32_t>{6, 1, 0, 0, 0}));

    const fg::Plan& plan = *executor.plan();
    EXPECT_EQ(plan.buffers.size(), 3u);
    EXPECT_EQ(plan.resources[0].buffer_spec.usage, BufferUsage::Storage | BufferUsage::Vertex);
    const fg::ExecutionStats stats = executor.stats();
    EXPECT_EQ(stats.plan_buffers, 3u);
    EXPECT_EQ(stats.buffers, 3u) << describe(stats);
}

// The same graph with its compute passes on the async compute queue: the plan orders them with
// semaphores and moves the buffers between the queues, and on a device that runs every pass
// on one queue (GL; lavapipe has a single queue) the frame draws exactly what the one-queue
// plan draws, with validation clean.
TEST_P(ResourceExecution, AsyncComputePassesDrawWhatGraphicsQueuePassesDraw) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(const GeometryPrograms pipelines, geometry_programs(programs, device()));
    fg::PlanOptions options;
    options.frame = {32, 16};
    std::vector<rhi::Image> images;
    for (const fg::Queue queue : {fg::Queue::Graphics, fg::Queue::AsyncCompute}) {
        SCOPED_TRACE(fg::queue_name(queue));
        fg::FrameGraph graph = geometry_graph(pipelines, queue);
        fg::Executor executor(device());
        for (int frame = 0; frame < 2; ++frame) LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const fg::Plan& plan = *executor.plan();
        if (queue == fg::Queue::AsyncCompute) {
            // fill and shift (0, 1) on the async queue: fill waits for the start of the frame
            // (the previous frame's graphics work), draw (2) waits for shift.
            EXPECT_EQ(plan.queue_syncs,
                      (std::vector<fg::QueueSync>{{fg::Queue::Graphics, fg::Queue::AsyncCompute, fg::kFrameStart, 0},
                                                  {fg::Queue::AsyncCompute, fg::Queue::Graphics, 1, 2}}));
            EXPECT_EQ(plan.ownership_transfers.size(), 3u);  // vertices, indices, arguments
        } else {
            EXPECT_TRUE(plan.queue_syncs.empty());
        }
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("draw", "color")));
        EXPECT_EQ(image.load(24, 5), (std::array<double, 4>{0.25, 0.5, 0.75, 1}));
        images.push_back(std::move(image));
    }
    ASSERT_EQ(images.size(), 2u);
    EXPECT_EQ(images[0].pixels, images[1].pixels);
}

// dst = 1 - src (colour), alpha 1: a compute pass reading a sampled texture and writing a storage image.
const char* const kInvertComp = R"(#version 450
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D src;
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D dst;
void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= imageSize(dst).x || p.y >= imageSize(dst).y) return;
    imageStore(dst, p, vec4(1.0 - texelFetch(src, p, 0).rgb, 1.0));
}
)";

// Textures across the queues: a render pass paints, an async compute pass inverts it into a
// storage image while the graphics queue paints another texture, and a render pass combines
// the two. The same pixels as on one queue, on both backends.
TEST_P(ResourceExecution, AsyncComputeTexturesAreTransitionedAcrossTheQueues) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA32Float));
    LOOM_ASSIGN_OR_FAIL(auto combine, programs.combine(Format::RGBA32Float));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    LOOM_ASSIGN_OR_FAIL(auto invert, programs.compute("invert.comp", kInvertComp));
    const fg::TextureSpec spec = fg::TextureSpec::of(Format::RGBA32Float).with_size(16, 16);
    std::vector<rhi::Image> images;
    for (const fg::Queue queue : {fg::Queue::Graphics, fg::Queue::AsyncCompute}) {
        SCOPED_TRACE(fg::queue_name(queue));
        fg::FrameGraph graph;
        ASSERT_TRUE(graph.add_pass(fill_pass("paint", "color", spec, fill, {{0.25f, 0.5f, 0.75f, 1}, {1, 0, 0, 1}, 8.0f})).ok());
        auto invert_pass = fg::Pass("invert").set_kind(fg::PassKind::Compute).set_queue(queue).input("color").output("inverted", spec);
        invert_pass.on_execute([invert, sampler](fg::PassContext& ctx) {
            ctx.commands().set_pipeline(invert);
            ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                 .texture(0, ctx.texture("color"), sampler)
                                                 .storage_texture(1, ctx.texture("inverted")));
            ctx.commands().dispatch(2, 2);
            return Status{};
        });
        ASSERT_TRUE(graph.add_pass(std::move(invert_pass)).ok());
        ASSERT_TRUE(graph.add_pass(fill_pass("other", "color", spec, fill, {{0, 0, 0.5f, 0}, {0, 0, 0.5f, 0}, 8.0f})).ok());
        ASSERT_TRUE(graph.add_pass(combine_pass("final", "a", "b", "out", spec, combine, sampler,
                                                {{1, 1, 1, 1}, {1, 1, 1, 1}}))
                        .ok());
        ASSERT_TRUE(graph.connect(fg::port("paint", "color"), fg::port("invert", "color")).ok());
        ASSERT_TRUE(graph.connect(fg::port("invert", "inverted"), fg::port("final", "a")).ok());
        ASSERT_TRUE(graph.connect(fg::port("other", "color"), fg::port("final", "b")).ok());
        ASSERT_TRUE(graph.mark_output(fg::port("final", "out")).ok());
        fg::Executor executor(device());
        fg::PlanOptions options;
        options.frame = {16, 16};
        options.allocator = fg::AllocatorKind::Heap;
        for (int frame = 0; frame < 3; ++frame) LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const fg::Plan& plan = *executor.plan();
        if (queue == fg::Queue::AsyncCompute) {
            // invert (1) waits for paint (0); final (3) waits for invert; the inverted image
            // moves to the graphics queue, and the painted colour is held while invert may run.
            EXPECT_EQ(plan.queue_syncs, (std::vector<fg::QueueSync>{{fg::Queue::Graphics, fg::Queue::AsyncCompute, 0, 1},
                                                                    {fg::Queue::AsyncCompute, fg::Queue::Graphics, 1, 3}}));
            EXPECT_EQ(plan.resource_of("paint", "color")->occupancy, (fg::Lifetime{0, 2}));
        }
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("final", "out")));
        EXPECT_EQ(image.load(3, 5), (std::array<double, 4>{0.75, 0.5, 0.25 + 0.5, 1}));
        EXPECT_EQ(image.load(12, 5), (std::array<double, 4>{0, 1, 1 + 0.5, 1}));
        images.push_back(std::move(image));
    }
    ASSERT_EQ(images.size(), 2u);
    EXPECT_EQ(images[0].pixels, images[1].pixels);
}

// Queues belong to the executor: a pass that switches them fails the frame, named.
TEST_P(ResourceExecution, PassesCannotSwitchQueues) {
    fg::FrameGraph graph;
    auto pass = fg::Pass("sneaky").set_kind(fg::PassKind::Compute).buffer_output("data", fg::BufferSpec::of_size(64));
    pass.on_execute([](fg::PassContext& ctx) {
        ctx.commands().set_queue(rhi::QueueType::Compute);
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(pass)).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("sneaky", "data")).ok());
    fg::Executor executor(device());
    const Status status = executor.run_frame(graph, {});
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message,
              "pass 'sneaky': set_queue(compute): the executor runs each pass on the queue its plan names (Pass::set_queue)");
}

// What the executor creates is what the plan says: every buffer with the plan's size and usage
// and, where the device places resources, at the plan's heap offset, beside the textures.
TEST_P(ResourceExecution, CreatedBuffersAndTexturesAreThePlans) {
    fg::FrameGraph graph;
    // The passes record nothing: the plan's realisation and transitions are what is checked.
    ASSERT_TRUE(graph.add_pass(fg::Pass("depth").output("depth", fg::TextureSpec::of(Format::Depth32F))).ok());
    ASSERT_TRUE(graph.add_pass(fg::Pass("cull")
                                   .set_kind(fg::PassKind::Compute)
                                   .input("depth")
                                   .buffer_output("lights", fg::BufferSpec::sized(fg::BufferSize::per_tile(16, 16, 1024)))
                                   .buffer_output("counts", fg::BufferSpec::sized(fg::BufferSize::per_pixel(4))))
                    .ok());
    ASSERT_TRUE(graph.add_pass(fg::Pass("args")
                                   .set_kind(fg::PassKind::Compute)
                                   .buffer_input("counts")
                                   .buffer_output("arguments", fg::BufferSpec::of_size(20).with_usage(BufferUsage::Indirect)))
                    .ok());
    ASSERT_TRUE(graph.add_pass(fg::Pass("shade")
                                   .input("depth")
                                   .buffer_input("lights", fg::BufferSpec{}.with_usage(BufferUsage::Uniform))
                                   .buffer_input("arguments", fg::BufferSpec{}.with_usage(BufferUsage::Indirect))
                                   .output("color", fg::TextureSpec::of(Format::RGBA16Float)))
                    .ok());
    ASSERT_TRUE(graph.connect(fg::port("depth", "depth"), fg::port("cull", "depth")).ok());
    ASSERT_TRUE(graph.connect(fg::port("depth", "depth"), fg::port("shade", "depth")).ok());
    ASSERT_TRUE(graph.connect(fg::port("cull", "lights"), fg::port("shade", "lights")).ok());
    ASSERT_TRUE(graph.connect(fg::port("cull", "counts"), fg::port("args", "counts")).ok());
    ASSERT_TRUE(graph.connect(fg::port("args", "arguments"), fg::port("shade", "arguments")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("shade", "color")).ok());

    for (fg::AllocatorKind allocator : {fg::AllocatorKind::Interval, fg::AllocatorKind::Heap}) {
        SCOPED_TRACE(fg::allocator_name(allocator));
        fg::Executor executor(device());
        fg::PlanOptions options;
        options.frame = {96, 64};
        options.allocator = allocator;
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const fg::Plan& plan = *executor.plan();
        ASSERT_EQ(plan.buffers.size(), 3u);
        const bool placed = plan.allocator == "heap" && device().capabilities().placed_resources;
        for (uint32_t b = 0; b < plan.buffers.size(); ++b) {
            LOOM_ASSIGN_OR_FAIL(rhi::BufferDesc desc, device().buffer_desc(executor.plan_buffer(b)));
            EXPECT_EQ(desc.size, plan.buffers[b].spec.size) << plan.buffers[b].name;
            EXPECT_EQ(desc.usage, plan.buffers[b].spec.usage) << plan.buffers[b].name;
            ASSERT_EQ(desc.placement.has_value(), placed) << plan.buffers[b].name;
            if (placed) {
                EXPECT_EQ(desc.placement->offset, plan.buffers[b].placement->offset) << plan.buffers[b].name;
            }
        }
        for (uint32_t t = 0; t < plan.textures.size(); ++t) {
            LOOM_ASSIGN_OR_FAIL(rhi::TextureDesc desc, device().texture_desc(executor.plan_texture(t)));
            ASSERT_EQ(desc.placement.has_value(), placed) << plan.textures[t].name;
            if (placed) {
                EXPECT_EQ(desc.placement->offset, plan.textures[t].placement->offset) << plan.textures[t].name;
            }
        }
        // 6 x 4 tiles of 1 KiB, 96 x 64 pixels of 4 bytes, 20 bytes.
        EXPECT_EQ(plan.resources[1].buffer_spec.size, 6u * 4u * 1024u);
        EXPECT_EQ(plan.resources[1].buffer_spec.usage, BufferUsage::Storage | BufferUsage::Uniform);
        EXPECT_EQ(plan.resources[2].buffer_spec.size, 96u * 64u * 4u);
        const fg::ExecutionStats stats = executor.stats();
        EXPECT_EQ(stats.buffers, 3u) << describe(stats);
        EXPECT_EQ(stats.placed_buffers, placed ? 3u : 0u) << describe(stats);
        if (placed) {
            uint64_t heap_bytes = 0;
            for (uint64_t h : plan.heaps) heap_bytes += h;
            EXPECT_EQ(stats.heap_bytes, heap_bytes);
            EXPECT_EQ(plan.summary.bytes, heap_bytes);
        }
    }
}

// An application buffer imported for a buffer port takes the plan buffer's place (beside an
// imported texture, whose import numbering is separate); a copy pass copies it into a plan buffer.
TEST_P(ResourceExecution, ImportedBuffersStandInForPlanBuffers) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto numbers, programs.compute("numbers.comp", kNumbersComp));
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA8Unorm));
    fg::FrameGraph graph;
    auto fill_numbers = fg::Pass("fill").set_kind(fg::PassKind::Compute).buffer_output("data", fg::BufferSpec::of_size(64));
    fill_numbers.on_execute([numbers](fg::PassContext& ctx) {
        ctx.commands().set_pipeline(numbers);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.buffer(0, ctx.buffer("data")));
        ctx.commands().dispatch(1);
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(fill_numbers)).ok());
    auto save = fg::Pass("save").set_kind(fg::PassKind::Copy).buffer_input("data").buffer_output("copy", fg::BufferSpec::of_size(64));
    save.on_execute([](fg::PassContext& ctx) -> Status {
        if (ctx.buffer_size("data") != 64 || ctx.buffer_size("copy") != 64) {
            return make_error(ErrorCode::InvalidState, "unexpected buffer sizes");
        }
        ctx.commands().copy_buffer(ctx.buffer("data"), 0, ctx.buffer("copy"), 0, 64);
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(save)).ok());
    ASSERT_TRUE(graph.add_pass(fill_pass("paint", "color", fg::TextureSpec::of(Format::RGBA8Unorm), fill,
                                         {{0, 1, 0, 1}, {0, 1, 0, 1}, 0.0f}))
                    .ok());
    ASSERT_TRUE(graph.connect(fg::port("fill", "data"), fg::port("save", "data")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("save", "copy")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("paint", "color")).ok());

    LOOM_ASSIGN_OR_FAIL(auto app_buffer, device().create_buffer({"app numbers", 64, BufferUsage::Storage | BufferUsage::CopySrc}));
    rhi::TextureDesc td;
    td.name = "app colour";
    td.width = 4;
    td.height = 4;
    td.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc;
    LOOM_ASSIGN_OR_FAIL(auto app_texture, device().create_texture(td));

    {
        fg::Executor executor(device());
        executor.import_buffer(fg::port("fill", "data"), app_buffer, rhi::ResourceState::CopySrc);
        executor.import_texture(fg::port("paint", "color"), app_texture);
        fg::PlanOptions options;
        options.frame = {4, 4};
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        EXPECT_EQ(executor.buffer("fill", "data"), app_buffer);
        std::vector<uint32_t> expected(16);
        for (uint32_t i = 0; i < 16; ++i) expected[i] = i * 3 + 1;
        for (rhi::BufferHandle b : {app_buffer, executor.buffer("save", "copy")}) {
            LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(b, 0, 64));
            std::vector<uint32_t> words(16);
            std::memcpy(words.data(), bytes.data(), 64);
            EXPECT_EQ(words, expected);
        }
        EXPECT_EQ(texel(device(), app_texture, 1, 1), (std::array<double, 4>{0, 1, 0, 1}));
        EXPECT_EQ(executor.stats().buffers, 1u) << describe(executor.stats());  // the copy only

        // A buffer smaller than the port's is refused, naming the port.
        LOOM_ASSIGN_OR_FAIL(auto small, device().create_buffer({"small", 32, BufferUsage::Storage}));
        executor.import_buffer(fg::port("fill", "data"), small);
        Status status = executor.run_frame(graph, options);
        ASSERT_FALSE(status.ok());
        EXPECT_EQ(status.error().message, "buffer import fill.data: buffer 'small' is 32 bytes storage but the port's buffer is "
                                          "buffer 64 bytes storage|copy_src");
        (void)device().wait_idle();
        ASSERT_TRUE(executor.release().ok());
        ASSERT_TRUE(device().destroy(small).ok());
    }
    ASSERT_TRUE(device().destroy(app_buffer).ok());
    ASSERT_TRUE(device().destroy(app_texture).ok());
}

TEST_P(ResourceExecution, ComputePassesCannotOpenRenderPasses) {
    fg::FrameGraph graph;
    auto bad = fg::Pass("bad").set_kind(fg::PassKind::Compute).output("color").on_execute([](fg::PassContext& ctx) {
        ctx.commands().begin_render_pass(rhi::RenderPassDesc{});
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(bad)).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("bad", "color")).ok());
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {8, 8};
    Status status = executor.run_frame(graph, options);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().message,
              "pass 'bad': begin_render_pass '' in a compute pass; only graphics passes open render passes");
}

// The CPU reference of the pyramid test: a 16-texel-wide pattern (columns < 5 red, the rest
// half green), down-sampled by 2x2 averages to 8 and 4 texels, then up-sampled in place.
using Row = std::vector<std::array<double, 4>>;

Row down(const Row& fine) {
    Row coarse(fine.size() / 2);
    for (std::size_t x = 0; x < coarse.size(); ++x) {
        for (int c = 0; c < 4; ++c) coarse[x][c] = (fine[2 * x][c] + fine[2 * x + 1][c]) * 0.5;  // rows are equal
    }
    return coarse;
}

void up(Row& fine, const Row& coarse) {
    for (std::size_t x = 0; x < fine.size(); ++x) {
        for (int c = 0; c < 4; ++c) fine[x][c] = (fine[x][c] + coarse[x / 2][c]) * 0.5;
    }
}

TEST_P(ResourceExecution, MipPyramidIsBuiltAndUpsampledInPlace) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto down_compute, programs.compute("down.comp", kDownComp));
    LOOM_ASSIGN_OR_FAIL(auto up_compute, programs.compute("up.comp", kUpComp));
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA32Float));
    LOOM_ASSIGN_OR_FAIL(auto down_render, programs.make("down", kDownFrag, {Format::RGBA32Float}));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());

    const fg::TextureSpec spec = fg::TextureSpec::of(Format::RGBA32Float).with_size(16, 16).with_mips(3);
    fg::FrameGraph graph;
    const FillConstants pattern{{1, 0, 0, 1}, {0, 0.5f, 0, 1}, 5.0f};
    auto base = fg::Pass("base").output("pyramid", spec, fg::mip(0)).on_execute([fill, pattern](fg::PassContext& ctx) {
        ctx.begin_render_pass({"pyramid"});
        ctx.commands().set_pipeline(fill);
        ctx.commands().push_constants_of(pattern);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(base)).ok());
    // A compute pass reading `from` and writing (or blending into) mip `to`.
    auto compute_step = [&](const std::string& name, uint32_t from, uint32_t to, rhi::PipelineHandle pipeline) {
        return fg::Pass(name)
            .set_kind(fg::PassKind::Compute)
            .input("src", {}, fg::mip(from))
            .inout("pyramid", {}, fg::mip(to))
            .on_execute([pipeline, sampler](fg::PassContext& ctx) {
                const fg::Extent2D size = ctx.range_extent("pyramid");
                ctx.commands().set_pipeline(pipeline);
                ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                     .texture(0, ctx.texture("src"), sampler, ctx.range("src"))
                                                     .storage_texture(1, ctx.texture("pyramid"), ctx.range("pyramid").base_mip));
                ctx.commands().dispatch((size.width + 7) / 8, (size.height + 7) / 8);
                return Status{};
            });
    };
    ASSERT_TRUE(graph.add_pass(compute_step("down1", 0, 1, down_compute)).ok());
    // Mip 2 by a render pass into that mip (the attachment defaults to the port's range).
    auto down2 = fg::Pass("down2").input("src", {}, fg::mip(1)).inout("pyramid", {}, fg::mip(2)).on_execute([down_render, sampler](fg::PassContext& ctx) {
        ctx.begin_render_pass({"pyramid"});
        ctx.commands().set_pipeline(down_render);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("src"), sampler, ctx.range("src")));
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    ASSERT_TRUE(graph.add_pass(std::move(down2)).ok());
    ASSERT_TRUE(graph.add_pass(compute_step("up1", 2, 1, up_compute)).ok());
    ASSERT_TRUE(graph.add_pass(compute_step("up0", 1, 0, up_compute)).ok());
    const char* chain[] = {"base", "down1", "down2", "up1", "up0"};
    for (int i = 1; i < 5; ++i) {
        ASSERT_TRUE(graph.connect(fg::port(chain[i - 1], "pyramid"), fg::port(chain[i], "src")).ok());
        ASSERT_TRUE(graph.connect(fg::port(chain[i - 1], "pyramid"), fg::port(chain[i], "pyramid")).ok());
    }
    ASSERT_TRUE(graph.mark_output(fg::port("up0", "pyramid")).ok());

    Row mip0(16);
    for (uint32_t x = 0; x < 16; ++x) mip0[x] = x < 5 ? std::array<double, 4>{1, 0, 0, 1} : std::array<double, 4>{0, 0.5, 0, 1};
    Row mip1 = down(mip0);
    const Row mip2 = down(mip1);
    up(mip1, mip2);
    up(mip0, mip1);
    const Row expected[] = {mip0, mip1, mip2};

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 16};
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        const rhi::TextureHandle pyramid = executor.texture("up0", "pyramid");
        for (uint32_t level = 0; level < 3; ++level) {
            LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(pyramid, level));
            ASSERT_EQ(image.width, 16u >> level);
            for (uint32_t y = 0; y < image.height; ++y) {
                for (uint32_t x = 0; x < image.width; ++x) {
                    ASSERT_EQ(image.load(x, y), expected[level][x]) << "mip " << level << " at " << x << "," << y << " frame " << frame;
                }
            }
        }
    }
    EXPECT_EQ(executor.plan()->textures.size(), 1u);
}

TEST_P(ResourceExecution, CascadesRenderedLayerByLayerAreSampledAsAnArray) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto depth, programs.depth_only(Format::Depth32F));
    LOOM_ASSIGN_OR_FAIL(auto show, programs.make("cascades", kCascadesFrag, {Format::RGBA32Float}));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    const fg::TextureSpec spec = fg::TextureSpec::of(Format::Depth32F).with_size(16, 16).with_layers(4);

    fg::FrameGraph graph;
    for (uint32_t i = 0; i < 4; ++i) {
        const std::string name = "cascade" + std::to_string(i);
        // Layer i: depth (i + 1) / 8 left of column 8, 1/2 + i/8 right of it.
        const FillConstants depths{{(i + 1) / 8.0f, 0, 0, 0}, {0.5f + i / 8.0f, 0, 0, 0}, 8.0f};
        fg::Pass pass(name);
        if (i == 0) {
            pass.output("shadow", spec, fg::layer(0));
        } else {
            pass.inout("shadow", {}, fg::layer(i));
        }
        pass.on_execute([depth, depths](fg::PassContext& ctx) {
            ctx.begin_depth_pass("shadow");
            ctx.commands().set_pipeline(depth);
            ctx.commands().push_constants_of(depths);
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        });
        ASSERT_TRUE(graph.add_pass(std::move(pass)).ok());
        if (i > 0) {
            ASSERT_TRUE(graph.connect(fg::port("cascade" + std::to_string(i - 1), "shadow"), fg::port(name, "shadow")).ok());
        }
    }
    auto light = fg::Pass("light")
                     .input("shadow")
                     .output("color", fg::TextureSpec::of(Format::RGBA32Float))
                     .on_execute([show, sampler](fg::PassContext& ctx) {
                         ctx.begin_render_pass({"color"});
                         ctx.commands().set_pipeline(show);
                         ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("shadow"), sampler));
                         ctx.commands().draw(3);
                         ctx.end_render_pass();
                         return Status{};
                     });
    ASSERT_TRUE(graph.add_pass(std::move(light)).ok());
    ASSERT_TRUE(graph.connect(fg::port("cascade3", "shadow"), fg::port("light", "shadow")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("light", "color")).ok());

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {16, 16};
    for (int frame = 0; frame < 2; ++frame) {
        LOOM_ASSERT_OK(executor.run_frame(graph, options));
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("light", "color")));
        EXPECT_EQ(image.load(3, 5), (std::array<double, 4>{0.125, 0.25, 0.375, 0.5})) << "frame " << frame;
        EXPECT_EQ(image.load(12, 9), (std::array<double, 4>{0.5, 0.625, 0.75, 0.875})) << "frame " << frame;
    }
}

TEST_P(ResourceExecution, CubeMapWrittenFaceByFaceIsSampledAsACube) {
    TestPrograms programs(device());
    LOOM_ASSIGN_OR_FAIL(auto fill, programs.fill(Format::RGBA32Float));
    LOOM_ASSIGN_OR_FAIL(auto look, programs.make("cube", kCubeFrag, {Format::RGBA32Float}));
    LOOM_ASSIGN_OR_FAIL(auto sampler, programs.sampler());
    const fg::TextureSpec spec = fg::TextureSpec::of(Format::RGBA32Float).with_size(8, 8).with_cube();
    auto face_color = [](uint32_t face) { return Color{(face + 1) / 8.0f, face / 16.0f, 1.0f - face / 8.0f, 1.0f}; };

    fg::FrameGraph graph;
    for (uint32_t face = 0; face < 6; ++face) {
        const std::string name = "face" + std::to_string(face);
        fg::Pass pass(name);
        if (face == 0) {
            pass.output("cube", spec, fg::layer(0));
        } else {
            pass.inout("cube", {}, fg::layer(face));
        }
        const FillConstants constants{face_color(face), face_color(face), 0.0f};
        pass.on_execute([fill, constants](fg::PassContext& ctx) {
            ctx.begin_render_pass({"cube"});
            ctx.commands().set_pipeline(fill);
            ctx.commands().push_constants_of(constants);
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        });
        ASSERT_TRUE(graph.add_pass(std::move(pass)).ok());
        if (face > 0) {
            ASSERT_TRUE(graph.connect(fg::port("face" + std::to_string(face - 1), "cube"), fg::port(name, "cube")).ok());
        }
    }
    auto look_pass = fg::Pass("look")
                         .input("cube")
                         .output("color", fg::TextureSpec::of(Format::RGBA32Float))
                         .on_execute([look, sampler](fg::PassContext& ctx) {
                             ctx.begin_render_pass({"color"});
                             ctx.commands().set_pipeline(look);
                             ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("cube"), sampler));
                             ctx.commands().draw(3);
                             ctx.end_render_pass();
                             return Status{};
                         });
    ASSERT_TRUE(graph.add_pass(std::move(look_pass)).ok());
    ASSERT_TRUE(graph.connect(fg::port("face5", "cube"), fg::port("look", "cube")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("look", "color")).ok());

    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {6, 1};
    LOOM_ASSERT_OK(executor.run_frame(graph, options));
    EXPECT_TRUE(executor.plan()->resources[0].spec.cube);
    EXPECT_EQ(executor.plan()->resources[0].spec.layers, 6u);
    LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(executor.texture("look", "color")));
    for (uint32_t face = 0; face < 6; ++face) {
        const Color c = face_color(face);
        EXPECT_EQ(image.load(face, 0), (std::array<double, 4>{c[0], c[1], c[2], c[3]})) << "face " << face;
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ResourceExecution);

}  // namespace loom::test
