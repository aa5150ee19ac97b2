#include "loom/renderer/gpu_scene.hpp"

#include <span>
#include <string>

#include "loom/scene/mip_chain.hpp"

namespace loom::renderer {

std::shared_ptr<const PreparedScene> prepare_scene(scene::Scene scene) {
    auto prepared = std::make_shared<PreparedScene>();
    prepared->geometry = scene::pack_geometry(scene);
    prepared->mips.reserve(scene.images.size());
    for (const scene::TextureImage& image : scene.images) prepared->mips.push_back(scene::mip_chain(image.image));
    prepared->scene = std::move(scene);
    return prepared;
}

Result<std::shared_ptr<GpuScene>> GpuScene::create(rhi::Device& device, std::shared_ptr<const PreparedScene> prepared,
                                                   GpuSceneContent content) {
    std::shared_ptr<GpuScene> gpu(new GpuScene(device, std::move(prepared)));
    LOOM_TRY(gpu->upload(content));
    return gpu;
}

GpuScene::~GpuScene() {
    // Errors here would mean stale handles of our own; nothing a caller could act on.
    if (vertices_) (void)device_->destroy(vertices_);
    if (indices_) (void)device_->destroy(indices_);
    if (skin_) (void)device_->destroy(skin_);
    for (rhi::TextureHandle texture : images_) (void)device_->destroy(texture);
    for (rhi::SamplerHandle sampler : samplers_) (void)device_->destroy(sampler);
    if (fallback_.texture) (void)device_->destroy(fallback_.texture);
    if (fallback_.sampler) (void)device_->destroy(fallback_.sampler);
}

Result<rhi::TextureHandle> GpuScene::upload_image(const std::vector<rhi::Image>& levels, const std::string& name) {
    rhi::TextureDesc desc;
    desc.name = name;
    desc.format = levels.front().format;
    desc.width = levels.front().width;
    desc.height = levels.front().height;
    desc.mip_levels = static_cast<uint32_t>(levels.size());
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
    auto texture = device_->create_texture(desc);
    if (!texture) return texture.take_error();
    for (uint32_t mip = 0; mip < levels.size(); ++mip) {
        rhi::TextureRegion region;
        region.mip = mip;
        if (Status written = device_->write_texture(*texture, region, levels[mip].pixels); !written) {
            (void)device_->destroy(*texture);
            return written.take_error();
        }
        texture_bytes_ += levels[mip].pixels.size();
    }
    return *texture;
}

Status GpuScene::upload(GpuSceneContent content) {
    const scene::PackedGeometry& geometry = prepared_->geometry;
    const std::string& source = prepared_->scene.source;
    if (content == GpuSceneContent::All && !geometry.vertices.empty() && !geometry.indices.empty()) {
        rhi::BufferDesc vertices{source + " vertices", std::span(geometry.vertices).size_bytes(), rhi::BufferUsage::Vertex};
        auto vertex_buffer = device_->create_buffer(vertices);
        if (!vertex_buffer) return vertex_buffer.take_error();
        vertices_ = *vertex_buffer;
        LOOM_TRY(device_->write_buffer(vertices_, 0, std::as_bytes(std::span(geometry.vertices))));
        rhi::BufferDesc indices{source + " indices", std::span(geometry.indices).size_bytes(), rhi::BufferUsage::Index};
        auto index_buffer = device_->create_buffer(indices);
        if (!index_buffer) return index_buffer.take_error();
        indices_ = *index_buffer;
        LOOM_TRY(device_->write_buffer(indices_, 0, std::as_bytes(std::span(geometry.indices))));
        if (!geometry.skin.empty()) {
            rhi::BufferDesc skin{source + " skin influences", std::span(geometry.skin).size_bytes(), rhi::BufferUsage::Vertex};
            auto skin_buffer = device_->create_buffer(skin);
            if (!skin_buffer) return skin_buffer.take_error();
            skin_ = *skin_buffer;
            LOOM_TRY(device_->write_buffer(skin_, 0, std::as_bytes(std::span(geometry.skin))));
        }
        if (!prepared_->scene.skins.empty()) {
            auto palette = SkinPalette::create(*device_, prepared_->scene);
            if (!palette) return palette.take_error();
            palette_ = std::move(*palette);
        }
    }

    const scene::Scene& scene = prepared_->scene;
    for (std::size_t i = 0; i < scene.images.size(); ++i) {
        auto texture = upload_image(prepared_->mips[i], scene.images[i].name);
        if (!texture) return texture.take_error();
        images_.push_back(*texture);
    }
    for (const scene::Texture& texture : scene.textures) {
        auto sampler = device_->create_sampler(texture.sampler);
        if (!sampler) return sampler.take_error();
        samplers_.push_back(*sampler);
        textures_.push_back(rhi::TextureBinding{images_[texture.image], *sampler});
    }

    rhi::Image white(1, 1, rhi::Format::RGBA8Unorm);
    white.store(0, 0, {1.0, 1.0, 1.0, 1.0});
    auto fallback = upload_image({white}, source + " fallback (white)");
    if (!fallback) return fallback.take_error();
    fallback_.texture = *fallback;
    rhi::SamplerDesc sampler_desc;
    sampler_desc.name = source + " fallback";
    auto sampler = device_->create_sampler(sampler_desc);
    if (!sampler) return sampler.take_error();
    fallback_.sampler = *sampler;
    return {};
}

}  // namespace loom::renderer
