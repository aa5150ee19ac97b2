#include "flagship_support.hpp"

namespace loom::test {

Result<std::map<std::string, rhi::Image>> read_back(rhi::Device& device, const renderer::DeferredPipeline& pipeline) {
    std::map<std::string, rhi::Image> images;
    for (const renderer::Intermediate& intermediate : pipeline.intermediates()) {
        auto image = device.read_texture(intermediate.texture);
        if (!image) return image.take_error();
        images.emplace(intermediate.name, std::move(*image));
    }
    auto final_image = device.read_texture(pipeline.final_texture());
    if (!final_image) return final_image.take_error();
    images.emplace("final", std::move(*final_image));
    return images;
}

Result<FlagshipFrame> render_flagship(rhi::Device& device, uint32_t width, uint32_t height,
                                      const renderer::PipelineSettings& settings, uint32_t frames) {
    auto pipeline = deferred::create_procedural_pipeline(device, deferred::procedural_scene(), settings);
    if (!pipeline) return pipeline.take_error();
    for (uint32_t i = 0; i < frames; ++i) LOOM_TRY((*pipeline)->render({width, height}));
    LOOM_TRY(device.wait_idle());
    FlagshipFrame frame;
    frame.plan = *(*pipeline)->executor().plan();
    frame.stats = (*pipeline)->executor().stats();
    auto images = read_back(device, **pipeline);
    if (!images) return images.take_error();
    frame.images = std::move(*images);
    return frame;
}

}  // namespace loom::test
