#include "embed_test_support.hpp"

#include <sstream>

#include "loom/rhi/shader_compiler.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

constexpr const char* kFullscreenVert = R"(#version 450
void main() {
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kPatternFrag = R"(#version 450
layout(location = 0) out vec4 color;
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    color = vec4(float(p.x % 16) / 15.0, float(p.y % 16) / 15.0, float((p.x / 16 + p.y / 16) % 2), 1.0);
}
)";

constexpr const char* kOverlayFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D pattern;
layout(location = 0) out vec4 color;
void main() {
    color = texelFetch(pattern, ivec2(gl_FragCoord.xy), 0);
}
)";

const fg::TextureSpec kRgba8 = fg::TextureSpec::of(rhi::Format::RGBA8Unorm);

}  // namespace

Rgba8 expected_pattern(uint32_t x, uint32_t y) {
    return {static_cast<uint8_t>(17 * (x % 16)), static_cast<uint8_t>(17 * (y % 16)),
            static_cast<uint8_t>(((x / 16 + y / 16) % 2) * 255), 255};
}

Rgba8 expected_overlay(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
    if (x < width / 2 && y < height / 2) return expected_pattern(x, y);
    return kEngineClearBytes;
}

::testing::AssertionResult matches_overlay(const rhi::Image& image, const std::string& name) {
    if (image.format != rhi::Format::RGBA8Unorm) {
        return ::testing::AssertionFailure() << name << ": image is " << rhi::format_name(image.format) << ", not RGBA8Unorm";
    }
    uint64_t wrong = 0;
    std::ostringstream first;
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto texel = image.texel(x, y);
            const Rgba8 want = expected_overlay(x, y, image.width, image.height);
            Rgba8 got{};
            for (std::size_t c = 0; c < 4; ++c) got[c] = static_cast<uint8_t>(texel[c]);
            if (got == want) continue;
            if (wrong++ == 0) {
                first << "(" << x << ", " << y << ") is (" << int(got[0]) << ", " << int(got[1]) << ", " << int(got[2]) << ", "
                      << int(got[3]) << "), expected (" << int(want[0]) << ", " << int(want[1]) << ", " << int(want[2])
                      << ", " << int(want[3]) << ")";
            }
        }
    }
    if (wrong == 0) return ::testing::AssertionSuccess();
    const auto path = output_dir() / "embed" / (name + ".png");
    std::filesystem::create_directories(path.parent_path());
    (void)rhi::write_png(image, path);
    return ::testing::AssertionFailure() << name << ": " << wrong << " of " << image.width * image.height
                                         << " texels differ, first " << first.str() << "; picture: " << path.string();
}

Result<rhi::ShaderHandle> compile_shader(rhi::Device& device, rhi::ShaderStage stage, const std::string& name,
                                         const std::string& source) {
    rhi::ShaderCompiler compiler;
    auto module = compiler.compile({name, stage, source, {}});
    if (!module.ok()) return module.take_error();
    return device.create_shader(*module);
}

OverlayGraph::OverlayGraph(rhi::Device& device) : device_(device) {
    auto make = [&]() -> Status {
        auto vs = compile_shader(device_, rhi::ShaderStage::Vertex, "fullscreen.vert", kFullscreenVert);
        if (!vs.ok()) return vs.take_error();
        vertex_ = *vs;
        auto pattern_fs = compile_shader(device_, rhi::ShaderStage::Fragment, "pattern.frag", kPatternFrag);
        if (!pattern_fs.ok()) return pattern_fs.take_error();
        pattern_fragment_ = *pattern_fs;
        auto overlay_fs = compile_shader(device_, rhi::ShaderStage::Fragment, "overlay.frag", kOverlayFrag);
        if (!overlay_fs.ok()) return overlay_fs.take_error();
        overlay_fragment_ = *overlay_fs;
        rhi::GraphicsPipelineDesc desc;
        desc.name = "pattern";
        desc.vertex = vertex_;
        desc.fragment = pattern_fragment_;
        desc.color_formats = {rhi::Format::RGBA8Unorm};
        auto pattern = device_.create_graphics_pipeline(desc);
        if (!pattern.ok()) return pattern.take_error();
        pattern_ = *pattern;
        desc.name = "overlay";
        desc.fragment = overlay_fragment_;
        auto overlay = device_.create_graphics_pipeline(desc);
        if (!overlay.ok()) return overlay.take_error();
        overlay_ = *overlay;

        rhi::SamplerDesc sampler_desc;
        sampler_desc.name = "nearest";
        sampler_desc.min_filter = sampler_desc.mag_filter = rhi::Filter::Nearest;
        auto sampler = device_.create_sampler(sampler_desc);
        if (!sampler.ok()) return sampler.take_error();
        sampler_ = *sampler;

        const rhi::PipelineHandle pattern_pipeline = pattern_, overlay_pipeline = overlay_;
        const rhi::SamplerHandle nearest = sampler_;
        LOOM_TRY(graph_.add_pass(fg::Pass("pattern").output("color", kRgba8).on_execute([pattern_pipeline](fg::PassContext& ctx) {
            ctx.begin_render_pass({{"color"}});
            ctx.commands().set_pipeline(pattern_pipeline);
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        })));
        fg::Pass overlay_pass("overlay");
        overlay_pass.input("pattern", kRgba8).declare("target", fg::PortKind::InOut, kRgba8, /*optional=*/true);
        overlay_pass.on_execute([overlay_pipeline, nearest](fg::PassContext& ctx) {
            const fg::Extent2D size = ctx.extent("target");
            ctx.begin_render_pass({{"target"}});
            ctx.commands().set_pipeline(overlay_pipeline);
            const rhi::Viewport quadrant{0.0f, 0.0f, static_cast<float>(size.width / 2), static_cast<float>(size.height / 2)};
            ctx.commands().set_viewport(quadrant);
            ctx.commands().set_scissor({0, 0, size.width / 2, size.height / 2});
            ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture("pattern"), nearest));
            ctx.commands().draw(3);
            ctx.end_render_pass();
            return Status{};
        });
        LOOM_TRY(graph_.add_pass(std::move(overlay_pass)));
        LOOM_TRY(graph_.connect(fg::port("pattern", "color"), fg::port("overlay", "pattern")));
        LOOM_TRY(graph_.mark_output(target_port()));
        return {};
    };
    status_ = make();
}

OverlayGraph::~OverlayGraph() {
    if (sampler_) (void)device_.destroy(sampler_);
    if (overlay_) (void)device_.destroy(overlay_);
    if (pattern_) (void)device_.destroy(pattern_);
    for (rhi::ShaderHandle s : {overlay_fragment_, pattern_fragment_, vertex_}) {
        if (s) (void)device_.destroy(s);
    }
}

}  // namespace loom::test
