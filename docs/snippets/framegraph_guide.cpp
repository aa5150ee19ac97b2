// docs/framegraph.md: the guide's examples, compiled; plan_framegraph_examples() and
// execute_framegraph_example() run them (snippets_test.cpp).
#include <array>
#include <string>
#include <vector>

#include "snippets.hpp"

// [docs:include]
#include "loom/framegraph/framegraph.hpp"   // everything; or the single headers below
using namespace loom;
// [/docs:include]

#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::docs {
namespace {

// [docs:build]
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
// [/docs:build]

// [docs:port-sets]
const auto color = fg::TextureSpec::of(rhi::Format::RGBA16Float);

fg::PortSet deferred_render() {   // Listing 3
    return fg::PortSet("deferred-render").input("position").input("normal").input("albedo").output("color", color);
}
fg::PortSet shadow_render() {     // Listing 4
    const auto depth = fg::TextureSpec::of(rhi::Format::Depth32F);
    return fg::PortSet("shadow-render").input("shadow_map", depth).output("color", color);
}
fg::PortSet high_pass_render() {  // Listing 5
    return fg::PortSet("high-pass-render").output("high_pass", color);
}

class DeferredShadowPass : public fg::Pass {  // deferred+shadow-pass of Listing 6
public:
    DeferredShadowPass() : Pass("deferred") { add(deferred_render()).add(shadow_render()).add(high_pass_render()); }
};
// [/docs:port-sets]

Status fail_unless(bool condition, const std::string& what) {
    return condition ? Status{} : Status(Error{ErrorCode::InvalidState, "docs/framegraph.md example: " + what});
}

constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
})";
// Columns 0..7 black, 8..15 white, and so on.
constexpr const char* kStripesFrag = R"(#version 450
layout(location = 0) out vec4 color;
void main() { color = vec4(vec3(float((int(gl_FragCoord.x) / 8) % 2)), 1.0); })";
// A horizontal box blur over three texels (edges clamped).
constexpr const char* kBlurFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D source;
layout(location = 0) out vec4 color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int w = textureSize(source, 0).x;
    color = (texelFetch(source, ivec2(max(p.x - 1, 0), p.y), 0) + texelFetch(source, p, 0) +
             texelFetch(source, ivec2(min(p.x + 1, w - 1), p.y), 0)) / 3.0;
})";

Result<rhi::PipelineHandle> fullscreen_pipeline(rhi::Device& device, const char* name, const char* fragment) {
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.compile({"fullscreen.vert", rhi::ShaderStage::Vertex, kFullscreenVert, {}});
    if (!vs) return vs.take_error();
    auto fs = compiler.compile({name, rhi::ShaderStage::Fragment, fragment, {}});
    if (!fs) return fs.take_error();
    auto vertex = device.create_shader(*vs);
    if (!vertex) return vertex.take_error();
    auto pixel = device.create_shader(*fs);
    if (!pixel) return pixel.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = name;
    desc.vertex = *vertex;
    desc.fragment = *pixel;
    desc.color_formats = {rhi::Format::RGBA16Float};
    return device.create_graphics_pipeline(desc);
}

}  // namespace

Status plan_framegraph_examples() {
    {
        // [docs:plan]
        fg::FrameGraph graph;
        if (auto built = build(graph); !built) { /* built.error().message names the pass and port */ }
        fg::PlanOptions options;
        options.frame = {1920, 1080};
        options.allocator = fg::AllocatorKind::Paper;
        auto plan = graph.plan(options);  // Result<std::shared_ptr<const fg::Plan>>
        // plan->get()->texture_of("light", "hdr") == plan->get()->texture_of("ui", "hdr")
        // [/docs:plan]
        if (!plan) return plan.take_error();
        const fg::Plan& p = **plan;
        LOOM_TRY(fail_unless(p.texture_of("light", "hdr") == p.texture_of("ui", "hdr"),
                             "the inout shares the texture of its source"));
        LOOM_TRY(fail_unless(p.order.size() == 3, "three passes are scheduled"));
        LOOM_TRY(fail_unless(p.summary.naive_textures == 3, "three outputs, naively three textures"));
        // albedo and normal end at light, which starts hdr: no sharing possible in a chain of three.
        LOOM_TRY(fail_unless(p.summary.textures == 3, "three textures"));
    }
    {
        fg::FrameGraph graph;
        // [docs:add-port-sets]
        auto id = graph.add_pass(DeferredShadowPass{});  // ports: position, normal, albedo, color, shadow_map, high_pass
        // [/docs:add-port-sets]
        if (!id) return id.take_error();
        std::vector<std::string> names;
        for (const fg::Port& port : graph.pass(*id).ports()) names.push_back(port.name);
        LOOM_TRY(fail_unless(names == std::vector<std::string>{"position", "normal", "albedo", "color", "shadow_map",
                                                               "high_pass"},
                             "the composed pass has the port sets' ports in order"));
    }
    {
        using namespace fg;
        fg::PlanOptions options;
        // [docs:typed]
        FrameGraph graph;
        graph.reserve(3, 8);   // passes, and ports in all: no array grows while declaring
        const PassId geometry = *graph.add_pass(Pass("geometry").output("albedo", TextureSpec::of(rhi::Format::RGBA8Unorm)));
        // read() declares an input reading what a port writes and connects it when the pass is added:
        // one step, no port name to invent (the input is called read0, read1, ... in its pass).
        const PassId blur = *graph.add_pass(Pass("blur").read(port_of(geometry, 0)).output("out"));
        const PassId composite = *graph.add_pass(Pass("composite").input("color").input("blurred").output("final"));
        LOOM_TRY(graph.connect(port_of(geometry, 0), port_of(composite, 0)));   // by PortAddress
        LOOM_TRY(graph.connect(port_of(blur, 1), port_of(composite, 1)));
        LOOM_TRY(graph.mark_output(port_of(composite, 2)));
        LOOM_TRY(graph.set_side_effect(blur));                                  // by PassId
        auto plan = graph.plan(options);
        // Next frame: graph.redeclare() keeps the memory (and the plan, if the same graph comes again).
        // [/docs:typed]
        if (!plan) return plan.take_error();
        LOOM_TRY(fail_unless((*plan)->order.size() == 3, "the typed graph schedules its three passes"));
        LOOM_TRY(fail_unless((*plan)->texture_of("geometry", "albedo") == (*plan)->texture_of("composite", "color"),
                             "the connection by handles joins the two ports"));
        options.order = PassOrder::Declared;
        LOOM_TRY(graph.plan(options));
        // [docs:set-texture-spec]
        // A setting changed: albedo in 16-bit float from now on. Nothing is declared again, and
        // in the declared order the next plan() is made from the previous plan.
        LOOM_TRY(graph.set_texture_spec(port_of(geometry, 0), TextureSpec::of(rhi::Format::RGBA16Float)));
        auto respecified = graph.plan(options);
        // [/docs:set-texture-spec]
        if (!respecified) return respecified.take_error();
        LOOM_TRY(fail_unless((*respecified)->resources[0].spec.format == rhi::Format::RGBA16Float,
                             "the respecified albedo is 16-bit float"));
        LOOM_TRY(fail_unless(graph.plans_resized() == 1, "the respecified graph is planned from the previous plan"));
    }
    return {};
}

Result<rhi::Image> execute_framegraph_example(rhi::Device& device) {
    auto stripes_pipeline = fullscreen_pipeline(device, "stripes.frag", kStripesFrag);
    if (!stripes_pipeline) return stripes_pipeline.take_error();
    auto blur = fullscreen_pipeline(device, "blur.frag", kBlurFrag);
    if (!blur) return blur.take_error();
    const rhi::PipelineHandle blur_pipeline = *blur;
    auto nearest = device.create_sampler({});
    if (!nearest) return nearest.take_error();
    const rhi::SamplerHandle sampler = *nearest;
    fg::FrameGraph graph;
    LOOM_TRY(graph.add_pass(fg::Pass("stripes").output("out", color).on_execute([&](fg::PassContext& ctx) {
        ctx.begin_render_pass({"out"});
        ctx.commands().set_pipeline(*stripes_pipeline);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    })));
    // [docs:execute]
    // A pass records its work in execute(): subclass Pass, or hand a callback to on_execute().
    LOOM_TRY(graph.add_pass(fg::Pass("blur").input("in", color).output("out", color)
                                .on_execute([&](fg::PassContext& ctx) {
                                    ctx.begin_render_pass({"out"});   // the plan's load/store actions
                                    ctx.commands().set_pipeline(blur_pipeline);
                                    ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("in"), sampler));
                                    ctx.commands().draw(3);
                                    ctx.end_render_pass();
                                    return Status{};
                                })));
    LOOM_TRY(graph.connect(fg::port("stripes", "out"), fg::port("blur", "in")));
    LOOM_TRY(graph.mark_output(fg::port("blur", "out")));

    fg::Executor executor(device);
    fg::PlanOptions options;
    options.frame = {1280, 720};
    LOOM_TRY(executor.run_frame(graph, options));   // begin_frame, every pass, end_frame
    auto image = device.read_texture(executor.texture("blur", "out"));
    // [/docs:execute]
    return image;
}

}  // namespace loom::docs
