#include "gltf_render.hpp"

#include "loom/renderer/gltf_scene.hpp"

namespace loom::test {

renderer::PipelineSettings gltf_test_settings(bool forward) {
    renderer::PipelineSettings settings;
    settings.forward = forward;
    settings.shadow_map_size = 512;
    return settings;
}

Result<GltfFrame> render_gltf(rhi::Device& device, scene::Scene scene, bool forward, uint32_t width, uint32_t height) {
    auto prepared = renderer::prepare_scene(std::move(scene));
    auto viewpoint = renderer::SceneViewpoint::choose(prepared->scene);
    if (!viewpoint) return viewpoint.take_error();
    auto gpu = renderer::GpuScene::create(device, prepared);
    if (!gpu) return gpu.take_error();
    auto pipeline = renderer::DeferredPipeline::create(device, renderer::gltf_pipeline_scene(*gpu, *viewpoint),
                                                       gltf_test_settings(forward));
    if (!pipeline) return pipeline.take_error();
    return render_frame(device, **pipeline, width, height);
}

Result<GltfFrame> render_frame(rhi::Device& device, renderer::DeferredPipeline& pipeline, uint32_t width,
                               uint32_t height) {
    LOOM_TRY(pipeline.render({width, height}));
    LOOM_TRY(device.wait_idle());
    GltfFrame frame;
    frame.plan = *pipeline.executor().plan();
    frame.stats = pipeline.executor().stats();
    for (const renderer::Intermediate& intermediate : pipeline.intermediates()) {
        auto image = device.read_texture(intermediate.texture);
        if (!image) return image.take_error();
        frame.images.emplace(intermediate.name, std::move(*image));
    }
    auto final_image = device.read_texture(pipeline.final_texture());
    if (!final_image) return final_image.take_error();
    frame.images.emplace("final", std::move(*final_image));
    if (pipeline.transparent()) frame.blend_order = pipeline.transparent()->draw_order();
    frame.view = pipeline.view({width, height});
    return frame;
}

}  // namespace loom::test
