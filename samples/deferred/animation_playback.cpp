#include "animation_playback.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "loom/renderer/gltf_scene.hpp"
#include "loom/renderer/retained_gltf_scene.hpp"
#include "loom/renderer/skin_palette.hpp"
#include "loom/scene/animation.hpp"

namespace loom::deferred {
namespace {

/// One pipeline's frame: renders, returns the device's bytes uploaded and the final picture.
struct DrawnFrame {
    uint64_t bytes = 0;
    rhi::Image picture;
};

Result<DrawnFrame> draw(rhi::Device& device, renderer::DeferredPipeline& pipeline, fg::Extent2D size) {
    LOOM_TRY(pipeline.render(size));
    DrawnFrame frame;
    frame.bytes = device.last_frame_stats().bytes_uploaded;
    auto picture = device.read_texture(pipeline.final_texture());
    if (!picture) return picture.take_error();
    frame.picture = rhi::to_rgba8(*picture);
    return frame;
}

void place_tile(rhi::Image& sheet, const rhi::Image& tile, uint32_t column, uint32_t row) {
    const std::size_t row_bytes = tile.row_bytes();
    for (uint32_t y = 0; y < tile.height; ++y) {
        std::memcpy(sheet.texel(column * tile.width, row * tile.height + y).data(), tile.texel(0, y).data(), row_bytes);
    }
}

}  // namespace

Result<AnimationRun> play_animation(rhi::Device& device, std::shared_ptr<const renderer::PreparedScene> prepared,
                                    const AnimationSettings& settings) {
    const scene::Scene& file = prepared->scene;
    if (file.animations.empty()) {
        return make_error(ErrorCode::InvalidArgument, file.source + ": the file has no animation to play");
    }
    if (settings.frames == 0) return make_error(ErrorCode::InvalidArgument, "an animation run needs at least one frame");

    AnimationRun run;
    for (const scene::Animation& animation : file.animations) run.duration = std::max(run.duration, animation.duration());

    // The retained path.
    auto retained = renderer::RetainedGltfScene::create(device, prepared);
    if (!retained) return retained.take_error();
    auto viewpoint = renderer::SceneViewpoint::choose(file, settings.camera);
    if (!viewpoint) return viewpoint.take_error();
    renderer::PipelineScene retained_content = (*retained)->pipeline_scene(*viewpoint);
    run.shapes = (*retained)->shape_count();
    run.blended = retained_content.blended.size();
    const scene::Bounds bounds = retained_content.bounds;
    auto retained_pipeline = renderer::DeferredPipeline::create(device, std::move(retained_content), settings.pipeline);
    if (!retained_pipeline) return retained_pipeline.take_error();

    // The immediate path: GltfObjects placed by a posed copy of the scene, with the same bounds.
    auto gpu = renderer::GpuScene::create(device, prepared);
    if (!gpu) return gpu.take_error();
    auto posed = std::make_shared<scene::Scene>(scene::copy_without_images(file));
    // Its joint palette is written whole every frame, as its uniforms are.
    std::shared_ptr<renderer::SkinPalette> palette;
    if (!file.skins.empty()) {
        auto made = renderer::SkinPalette::create(device, *posed);
        if (!made) return made.take_error();
        palette = std::move(*made);
    }
    renderer::PipelineScene immediate_content = renderer::gltf_pipeline_scene(*gpu, *viewpoint, posed, palette);
    immediate_content.bounds = bounds;
    immediate_content.shadow_bounds = bounds;
    run.scene_line = file.source + ": " + std::to_string(run.shapes) + " retained shape(s), " +
                     std::to_string(run.blended) + " blended item(s), " + std::to_string(file.animations.size()) +
                     " animation(s) of up to " + std::to_string(run.duration) + " s; " + viewpoint->describe();
    auto immediate_pipeline = renderer::DeferredPipeline::create(device, std::move(immediate_content), settings.pipeline);
    if (!immediate_pipeline) return immediate_pipeline.take_error();

    run.columns = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(settings.frames))));
    const uint32_t rows = (settings.frames + run.columns - 1) / run.columns;
    run.contact_sheet = rhi::Image(run.columns * settings.size.width, rows * settings.size.height, rhi::Format::RGBA8Unorm);
    // The layer's uploads: its own (records, materials, draw lists, geometry) and the joint
    // matrices posing wrote.
    auto layer_bytes = [&] {
        const renderer::SkinPalette* joints = (*retained)->skin_palette();
        return (*retained)->retained().stats().uploaded_bytes() + (joints ? joints->bytes_written() : 0);
    };
    for (uint32_t i = 0; i < settings.frames; ++i) {
        AnimationFrame frame;
        frame.time = settings.frames == 1 ? 0.0f : run.duration * static_cast<float>(i) / static_cast<float>(settings.frames - 1);
        // Each path's writes right before its own frame, so the device counts them there.
        const uint64_t layer_before = layer_bytes();
        std::vector<bool> moved(file.draw_items.size(), false);
        for (uint32_t a = 0; a < file.animations.size(); ++a) {
            auto items = (*retained)->pose(a, frame.time);
            if (!items) return items.take_error();
            for (uint32_t item : *items) moved[item] = true;
        }
        frame.moved = static_cast<uint32_t>(std::count(moved.begin(), moved.end(), true));
        auto kept = draw(device, **retained_pipeline, settings.size);
        if (!kept) return kept.take_error();
        frame.retained_bytes = kept->bytes;
        frame.layer_bytes = layer_bytes() - layer_before;

        for (uint32_t a = 0; a < file.animations.size(); ++a) (void)scene::pose(*posed, posed->animations[a], frame.time);
        if (palette) LOOM_TRY(palette->write_all(*posed));
        auto drawn = draw(device, **immediate_pipeline, settings.size);
        if (!drawn) return drawn.take_error();
        frame.immediate_bytes = drawn->bytes;
        frame.identical = kept->picture.pixels == drawn->picture.pixels;
        place_tile(run.contact_sheet, kept->picture, i % run.columns, i / run.columns);
        run.frames.push_back(frame);
    }
    LOOM_TRY(device.wait_idle());
    return run;
}

std::string animation_csv(const AnimationRun& run) {
    std::ostringstream out;
    out << "frame,time,moved,retained_bytes,layer_bytes,immediate_bytes,identical\n";
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
        const AnimationFrame& f = run.frames[i];
        out << i << "," << f.time << "," << f.moved << "," << f.retained_bytes << "," << f.layer_bytes << ","
            << f.immediate_bytes << "," << (f.identical ? 1 : 0) << "\n";
    }
    return out.str();
}

std::string animation_summary(const AnimationRun& run) {
    std::ostringstream out;
    out << "animation: " << run.scene_line << "\n";
    const std::size_t identical =
        static_cast<std::size_t>(std::count_if(run.frames.begin(), run.frames.end(), [](const auto& f) { return f.identical; }));
    out << "frames: " << run.frames.size() << " over " << run.duration << " s; the retained and immediate pictures are identical in "
        << identical << " of " << run.frames.size() << "\n";
    if (run.frames.size() < 2) return out.str();
    // The first frame uploads the scene (and first-use memory); the frames after it show the
    // steady cost of playing.
    uint64_t retained = 0, layer = 0, immediate = 0, moved = 0;
    for (std::size_t i = 1; i < run.frames.size(); ++i) {
        retained += run.frames[i].retained_bytes;
        layer += run.frames[i].layer_bytes;
        immediate += run.frames[i].immediate_bytes;
        moved += run.frames[i].moved;
    }
    const double n = static_cast<double>(run.frames.size() - 1);
    out << "bytes uploaded per frame after the first (mean): retained " << static_cast<double>(retained) / n
        << " (of which the layer's " << static_cast<double>(layer) / n << " for " << static_cast<double>(moved) / n
        << " moved item(s)), immediate " << static_cast<double>(immediate) / n;
    if (retained != 0) out << "; immediate / retained = " << static_cast<double>(immediate) / static_cast<double>(retained);
    out << "\n";
    return out.str();
}

}  // namespace loom::deferred
