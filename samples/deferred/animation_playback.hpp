#pragma once
// The flagship's animation run (loom-deferred --animate N): a glTF file's animations played for
// N frames, sampled evenly from the start to the end of the longest, and drawn two ways side by
// side on one device, each through its own pipeline:
//
//   retained   the scene in the retained object layer (renderer::RetainedGltfScene): posing
//              sets the world matrices of the items that moved and writes the joint matrices of
//              the skins that moved (64 bytes per joint), and the next frame uploads their
//              records (128 bytes each) and nothing else of the scene;
//   immediate  GltfObjects reading the posed scene at every draw: every draw writes its object's
//              uniform block (384 bytes) into per-frame memory, and every skin's joint matrices
//              are written every frame.
//
// Per frame it records the bytes each path uploaded (what the device counted: the passes' own
// per-frame uniforms included, the same in both) and the retained layer's own uploads, and
// checks that the two final pictures are identical. The retained path's pictures make the
// contact sheet.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "loom/renderer/deferred_pipeline.hpp"
#include "loom/renderer/gpu_scene.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"

namespace loom::deferred {

struct AnimationSettings {
    uint32_t frames = 8;
    fg::Extent2D size{480, 270};
    /// The file's camera; none: its first, or one framing the scene.
    std::optional<uint32_t> camera;
    renderer::PipelineSettings pipeline;
};

/// One frame of the run.
struct AnimationFrame {
    float time = 0.0f;            ///< seconds
    uint32_t moved = 0;           ///< draw items the pose moved (since the frame before)
    uint64_t retained_bytes = 0;  ///< the device's bytes uploaded in the retained path's frame
    uint64_t layer_bytes = 0;     ///< of which the retained layer's (records, materials, draw lists, geometry, joints)
    uint64_t immediate_bytes = 0; ///< the device's bytes uploaded in the immediate path's frame
    bool identical = false;       ///< the two final pictures are bit-identical
};

struct AnimationRun {
    std::vector<AnimationFrame> frames;
    /// The retained path's final pictures, left to right and top to bottom (RGBA8).
    rhi::Image contact_sheet;
    uint32_t columns = 0;
    float duration = 0.0f;   ///< of the longest animation
    uint64_t shapes = 0;     ///< draw items in the retained layer
    uint64_t blended = 0;    ///< blended draw items (GltfObjects in both paths)
    std::string scene_line;  ///< what was drawn, from where
};

/// Plays `prepared`'s animations (see the top of this file). Errors: a scene without animations
/// (InvalidArgument, naming the file), frames == 0, the pipelines' and the device's.
Result<AnimationRun> play_animation(rhi::Device& device, std::shared_ptr<const renderer::PreparedScene> prepared,
                                    const AnimationSettings& settings);

/// The run as CSV: frame, time, moved, retained_bytes, layer_bytes, immediate_bytes, identical.
std::string animation_csv(const AnimationRun& run);
/// A few lines: the scene, the frames, bytes per frame after the first of each path and their
/// ratio, and how many frames were identical.
std::string animation_summary(const AnimationRun& run);

}  // namespace loom::deferred
