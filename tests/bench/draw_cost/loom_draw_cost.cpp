// loom_draw_cost: one frame of N tiny draws through loom's RHI, on either backend, debug output
// and validation layers off; the measured frame is inside the callgrind markers. The raw
// programs beside it do the same work with the API alone.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "draw_cost_common.hpp"
#include "loom/rhi/device.hpp"

namespace {

using namespace loom;
using draw_cost::Path;

int fail(const std::string& message) {
    std::fprintf(stderr, "loom_draw_cost: %s\n", message.c_str());
    return EXIT_FAILURE;
}

struct Resources {
    rhi::TextureHandle target;
    std::array<rhi::PipelineHandle, 2> pipelines{};
    std::array<rhi::TextureHandle, 2> textures{};
    rhi::SamplerHandle sampler;
    std::array<rhi::BindGroup, 2> groups{};
    std::array<rhi::BufferHandle, 2> vertices{};
    std::array<rhi::BufferHandle, 2> indices{};
};

/// Stores a created object's handle, or passes its error on.
template <class T>
Status assign(T& out, Result<T> created) {
    if (!created.ok()) return created.take_error();
    out = *created;
    return {};
}

Result<rhi::PipelineHandle> make_pipeline(rhi::Device& device, Path path, int variant) {
    auto vs_module = draw_cost::vertex_shader(path);
    if (!vs_module.ok()) return vs_module.take_error();
    auto fs_module = draw_cost::fragment_shader(path, variant);
    if (!fs_module.ok()) return fs_module.take_error();
    auto vs = device.create_shader(*vs_module);
    if (!vs.ok()) return vs.take_error();
    auto fs = device.create_shader(*fs_module);
    if (!fs.ok()) return fs.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = "draw cost";
    desc.vertex = *vs;
    desc.fragment = *fs;
    if (path == Path::VertexBuffers) {
        desc.vertex_buffers = {rhi::VertexBufferLayout{8, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float2, 0}}}};
    }
    desc.color_formats = {rhi::Format::RGBA8Unorm};
    auto pipeline = device.create_graphics_pipeline(desc);
    (void)device.destroy(*vs);
    (void)device.destroy(*fs);
    return pipeline;
}

Status create_resources(rhi::Device& device, Path path, Resources& r) {
    rhi::TextureDesc target;
    target.name = "draw cost target";
    target.format = rhi::Format::RGBA8Unorm;
    target.width = 64;
    target.height = 64;
    target.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopySrc;
    LOOM_TRY(assign(r.target, device.create_texture(target)));
    for (int variant = 0; variant < (path == Path::Pipeline ? 2 : 1); ++variant) {
        LOOM_TRY(assign(r.pipelines[static_cast<std::size_t>(variant)], make_pipeline(device, path, variant)));
    }
    if (path == Path::BindGroup) {
        LOOM_TRY(assign(r.sampler, device.create_sampler(rhi::SamplerDesc{})));
        for (std::size_t i = 0; i < 2; ++i) {
            rhi::TextureDesc desc;
            desc.name = i == 0 ? "first image" : "second image";
            desc.format = rhi::Format::RGBA8Unorm;
            desc.width = 4;
            desc.height = 4;
            desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
            LOOM_TRY(assign(r.textures[i], device.create_texture(desc)));
            std::vector<std::byte> texels(4 * 4 * 4, std::byte{static_cast<unsigned char>(i == 0 ? 64 : 192)});
            LOOM_TRY(device.write_texture(r.textures[i], rhi::TextureRegion{}, texels));
            r.groups[i] = rhi::BindGroup{}.texture(0, r.textures[i], r.sampler);
        }
    }
    if (path == Path::VertexBuffers) {
        for (std::size_t i = 0; i < 2; ++i) {
            const float d = i == 0 ? 0.0f : 0.5f;
            const std::array<float, 6> positions = {-0.9f + d, -0.9f, -0.8f + d, -0.9f, -0.9f + d, -0.8f};
            const std::array<uint32_t, 3> triangle = {0, 1, 2};
            LOOM_TRY(assign(r.vertices[i], device.create_buffer(rhi::BufferDesc{"positions", sizeof(positions), rhi::BufferUsage::Vertex})));
            LOOM_TRY(device.write_buffer(r.vertices[i], 0, std::as_bytes(std::span(positions))));
            LOOM_TRY(assign(r.indices[i], device.create_buffer(rhi::BufferDesc{"indices", sizeof(triangle), rhi::BufferUsage::Index})));
            LOOM_TRY(device.write_buffer(r.indices[i], 0, std::as_bytes(std::span(triangle))));
        }
    }
    return {};
}

void record_draws(rhi::CommandList& list, Path path, const Resources& r, uint32_t draws) {
    switch (path) {
        case Path::PushConstants:
            for (uint32_t i = 0; i < draws; ++i) {
                list.push_constants_of(draw_cost::draw_constants(i));
                list.draw(3);
            }
            break;
        case Path::TransientUniforms:
            for (uint32_t i = 0; i < draws; ++i) {
                // Per-draw data at set 0, binding 0 without building a BindGroup.
                list.set_uniforms_of(0, 0, draw_cost::draw_constants(i));
                list.draw(3);
            }
            break;
        case Path::BindGroup:
            for (uint32_t i = 0; i < draws; ++i) {
                list.set_bind_group(0, r.groups[i & 1]);
                list.draw(3);
            }
            break;
        case Path::VertexBuffers:
            for (uint32_t i = 0; i < draws; ++i) {
                list.set_vertex_buffer(0, r.vertices[i & 1]);
                list.set_index_buffer(r.indices[i & 1], rhi::IndexType::Uint32);
                list.draw_indexed(3);
            }
            break;
        case Path::Pipeline:
            for (uint32_t i = 0; i < draws; ++i) {
                list.set_pipeline(r.pipelines[i & 1]);
                list.draw(3);
            }
            break;
    }
}

Status frame(rhi::Device& device, Path path, const Resources& r, uint32_t draws) {
    rhi::CommandList& list = device.begin_frame();
    if (path == Path::BindGroup) {
        for (rhi::TextureHandle t : r.textures) list.transition(t, rhi::ResourceState::ShaderRead);
    }
    rhi::RenderPassDesc pass;
    pass.label = "draws";
    rhi::ColorAttachment color;
    color.texture = r.target;
    pass.colors.push_back(color);
    list.begin_render_pass(pass);
    list.set_pipeline(r.pipelines[0]);
    record_draws(list, path, r, draws);
    list.end_render_pass();
    LOOM_TRY(device.end_frame());
    return device.wait_idle();
}

}  // namespace

int main(int argc, char** argv) {
    auto options = draw_cost::parse_options(argc, argv, true);
    if (!options.ok()) return fail(options.error().message);
    const auto backend = rhi::parse_backend(options->backend);
    if (!backend) return fail("--backend: unknown backend '" + options->backend + "' (gl, vulkan)");
    rhi::DeviceDesc desc;
    desc.backend = *backend;
    desc.debug = false;
    desc.validation = options->validation;
    auto device = rhi::create_device(desc);
    if (!device.ok()) return fail(device.error().to_string());
    Resources resources;
    if (auto status = create_resources(**device, options->path, resources); !status.ok()) return fail(status.error().to_string());
    for (uint32_t i = 0; i < options->warmup_frames; ++i) {
        if (auto status = frame(**device, options->path, resources, options->draws); !status.ok()) return fail(status.error().to_string());
    }
    draw_cost::begin_measurement();
    const Status status = frame(**device, options->path, resources, options->draws);
    draw_cost::end_measurement();
    if (!status.ok()) return fail(status.error().to_string());
    draw_cost::report(std::string("loom-") + options->backend, *options);
    return EXIT_SUCCESS;
}
