#include "execution_helpers.hpp"

#include "loom/image_io/image_io.hpp"
#include "loom/rhi/image.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

const char* const kFullscreenVert = R"(#version 450
void main() {
    // One triangle covering the screen: (-1,-1), (3,-1), (-1,3).
    vec2 p = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* const kFillFrag = R"(#version 450
layout(push_constant) uniform Fill { vec4 left; vec4 right; float split; } pc;
layout(location = 0) out vec4 out_color;
void main() { out_color = gl_FragCoord.x < pc.split ? pc.left : pc.right; }
)";

const char* const kDepthFrag = R"(#version 450
layout(push_constant) uniform Fill { vec4 left; vec4 right; float split; } pc;
void main() { gl_FragDepth = gl_FragCoord.x < pc.split ? pc.left.x : pc.right.x; }
)";

const char* const kFillDepthFrag = R"(#version 450
layout(push_constant) uniform Fill { vec4 left; vec4 right; float split; } pc;
layout(location = 0) out vec4 out_color;
void main() {
    out_color = pc.left;
    gl_FragDepth = pc.right.x;
}
)";

const char* const kFilterFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D src;
layout(push_constant) uniform Filter { vec4 mul; vec4 add; } pc;
layout(location = 0) out vec4 out_color;
void main() { out_color = texelFetch(src, ivec2(gl_FragCoord.xy), 0) * pc.mul + pc.add; }
)";

const char* const kCombineFrag = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D a;
layout(set = 0, binding = 1) uniform sampler2D b;
layout(push_constant) uniform Combine { vec4 wa; vec4 wb; } pc;
layout(location = 0) out vec4 out_color;
void main() {
    ivec2 at = ivec2(gl_FragCoord.xy);
    out_color = texelFetch(a, at, 0) * pc.wa + texelFetch(b, at, 0) * pc.wb;
}
)";

Result<rhi::ShaderHandle> compile(rhi::Device& device, rhi::ShaderStage stage, const std::string& name, const std::string& code) {
    return shader_compiler::ShaderCompiler().create_shader(device, {name, stage, code, {}});
}

}  // namespace

TestPrograms::~TestPrograms() {
    for (auto& [name, pipeline] : pipelines_) (void)device_.destroy(pipeline);
    for (rhi::ShaderHandle shader : shaders_) (void)device_.destroy(shader);
    if (vertex_) (void)device_.destroy(vertex_);
    if (sampler_) (void)device_.destroy(sampler_);
}

Result<rhi::ShaderHandle> TestPrograms::vertex_shader() {
    if (!vertex_) {
        auto shader = compile(device_, rhi::ShaderStage::Vertex, "fullscreen_test.vert", kFullscreenVert);
        if (!shader) return shader;
        vertex_ = *shader;
    }
    return vertex_;
}

Result<rhi::PipelineHandle> TestPrograms::make(const std::string& name, const std::string& fragment,
                                               std::vector<rhi::Format> colors, rhi::Format depth, bool depth_write) {
    std::string key = name;
    for (rhi::Format f : colors) (key += '/') += rhi::format_name(f);
    (key += '/') += rhi::format_name(depth);
    for (auto& [k, pipeline] : pipelines_) {
        if (k == key) return pipeline;
    }
    auto vs = vertex_shader();
    if (!vs) return vs.take_error();
    auto fs = compile(device_, rhi::ShaderStage::Fragment, name + ".frag", fragment);
    if (!fs) return fs.take_error();
    shaders_.push_back(*fs);
    rhi::GraphicsPipelineDesc desc;
    desc.name = name;
    desc.vertex = *vs;
    desc.fragment = *fs;
    desc.color_formats = std::move(colors);
    desc.depth_format = depth;
    if (depth != rhi::Format::Undefined) desc.depth = rhi::DepthState{true, depth_write, rhi::CompareOp::Always};
    auto pipeline = device_.create_graphics_pipeline(desc);
    if (!pipeline) return pipeline;
    pipelines_.emplace_back(key, *pipeline);
    return pipeline;
}

Result<rhi::ShaderHandle> TestPrograms::shader(rhi::ShaderStage stage, const std::string& name, const std::string& code) {
    auto made = compile(device_, stage, name, code);
    if (made) shaders_.push_back(*made);
    return made;
}

Result<rhi::PipelineHandle> TestPrograms::compute(const std::string& name, const std::string& code) {
    const std::string key = "compute/" + name;
    for (auto& [k, pipeline] : pipelines_) {
        if (k == key) return pipeline;
    }
    auto cs = shader(rhi::ShaderStage::Compute, name, code);
    if (!cs) return cs.take_error();
    auto pipeline = device_.create_compute_pipeline(rhi::ComputePipelineDesc{name, *cs});
    if (!pipeline) return pipeline;
    pipelines_.emplace_back(key, *pipeline);
    return pipeline;
}

Result<rhi::PipelineHandle> TestPrograms::fill(rhi::Format format) {
    return make("fill", kFillFrag, {format}, rhi::Format::Undefined, false);
}

Result<rhi::PipelineHandle> TestPrograms::fill_depth(rhi::Format color, rhi::Format depth) {
    return make("fill_depth", kFillDepthFrag, {color}, depth, true);
}

Result<rhi::PipelineHandle> TestPrograms::depth_only(rhi::Format depth) {
    return make("depth_only", kDepthFrag, {}, depth, true);
}

Result<rhi::PipelineHandle> TestPrograms::filter(rhi::Format format) {
    return make("filter", kFilterFrag, {format}, rhi::Format::Undefined, false);
}

Result<rhi::PipelineHandle> TestPrograms::combine(rhi::Format format) {
    return make("combine", kCombineFrag, {format}, rhi::Format::Undefined, false);
}

Result<rhi::SamplerHandle> TestPrograms::sampler() {
    if (!sampler_) {
        rhi::SamplerDesc desc;
        desc.name = "nearest";
        desc.min_filter = rhi::Filter::Nearest;
        desc.mag_filter = rhi::Filter::Nearest;
        auto sampler = device_.create_sampler(desc);
        if (!sampler) return sampler;
        sampler_ = *sampler;
    }
    return sampler_;
}

fg::Pass fill_pass(const std::string& name, const std::string& port, const fg::TextureSpec& spec,
                   rhi::PipelineHandle pipeline, FillConstants constants) {
    fg::Pass pass(name);
    pass.output(port, spec);
    pass.on_execute([port, pipeline, constants](fg::PassContext& ctx) {
        ctx.begin_render_pass({port});
        ctx.commands().set_pipeline(pipeline);
        ctx.commands().push_constants_of(constants);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    return pass;
}

fg::Pass filter_pass(const std::string& name, const std::string& in, const std::string& out, const fg::TextureSpec& spec,
                     rhi::PipelineHandle pipeline, rhi::SamplerHandle sampler, FilterConstants constants) {
    fg::Pass pass(name);
    pass.input(in, spec).output(out, spec);
    pass.on_execute([in, out, pipeline, sampler, constants](fg::PassContext& ctx) {
        ctx.begin_render_pass({out});
        ctx.commands().set_pipeline(pipeline);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture(in), sampler));
        ctx.commands().push_constants_of(constants);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    return pass;
}

fg::Pass combine_pass(const std::string& name, const std::string& a, const std::string& b, const std::string& out,
                      const fg::TextureSpec& spec, rhi::PipelineHandle pipeline, rhi::SamplerHandle sampler,
                      CombineConstants constants) {
    fg::Pass pass(name);
    pass.input(a, spec).input(b, spec).output(out, spec);
    pass.on_execute([a, b, out, pipeline, sampler, constants](fg::PassContext& ctx) {
        ctx.begin_render_pass({out});
        ctx.commands().set_pipeline(pipeline);
        ctx.commands().set_bind_group(0, rhi::BindGroup{}.texture(0, ctx.texture(a), sampler).texture(1, ctx.texture(b), sampler));
        ctx.commands().push_constants_of(constants);
        ctx.commands().draw(3);
        ctx.end_render_pass();
        return Status{};
    });
    return pass;
}

std::array<double, 4> texel(rhi::Device& device, rhi::TextureHandle texture, uint32_t x, uint32_t y) {
    auto image = device.read_texture(texture);
    EXPECT_TRUE(image.ok()) << image.error().to_string();
    if (!image || x >= image->width || y >= image->height) return {-1, -1, -1, -1};
    return image->load(x, y);
}

void save_texture(rhi::Device& device, rhi::TextureHandle texture, const std::string& name) {
    auto image = device.read_texture(texture);
    ASSERT_TRUE(image.ok()) << image.error().to_string();
    auto status = image_io::write_png(*image, output_dir() / "execution" / (name + ".png"));
    EXPECT_TRUE(status.ok()) << status.error().to_string();
}

}  // namespace loom::test
