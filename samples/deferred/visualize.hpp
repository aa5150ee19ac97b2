#pragma once
// Turning the pipeline's textures into pictures a person can read (the paper's Figures 3-7):
// G-buffer maps scaled into colours, HDR colour tone-mapped, depth normalised.

#include <map>
#include <string>

#include "loom/passes/view.hpp"
#include "loom/rhi/image.hpp"

namespace loom::deferred {

/// How to show the HDR colour maps: the composite pass's exposure and curve, without bloom.
struct DisplaySettings {
    float exposure = 1.0f;
    scene::Bounds scene_bounds;  ///< positions are shown relative to these
};

/// An RGBA8 picture of the texture read back as `name` ("pass.port"); `all` holds every
/// read-back texture by name (the normal map masks the background of the position map).
rhi::Image visualize(const std::string& name, const rhi::Image& image, const std::map<std::string, rhi::Image>& all,
                     const DisplaySettings& settings);

/// The material map of Figure 3 (the paper's specular map): metallic in red and roughness in
/// green (the alpha channels of the position and normal maps), the emission map's luminance / 16
/// in blue.
rhi::Image material_map(const rhi::Image& position, const rhi::Image& normal, const rhi::Image& emission);

/// Figure 3 as one picture: position, normal / albedo, material, at half size in a 2x2 grid.
rhi::Image mosaic(const rhi::Image& top_left, const rhi::Image& top_right, const rhi::Image& bottom_left,
                  const rhi::Image& bottom_right);

}  // namespace loom::deferred
