#pragma once
// Mipmaps made on the CPU, once per scene, so that every backend samples the same texels (the
// RHI has no mipmap generation, and two drivers' generators need not agree).

#include <cstdint>
#include <vector>

#include "loom/rhi/image.hpp"

namespace loom::scene {

/// Levels of a full mip chain for a width x height image: floor(log2(max(width, height))) + 1.
uint32_t mip_level_count(uint32_t width, uint32_t height);

/// The full mip chain of an RGBA8Unorm or RGBA8Srgb image: level 0 is `image`, each next level
/// halves width and height (rounded down, at least 1). A texel is the mean of the 2x2 block of
/// texels below it (a level 1 texel wide or high repeats its texels; of an odd size, the last
/// column or row is left out), averaged in linear light for RGBA8Srgb colour (alpha is linear)
/// and rounded to nearest. Other formats are a programming error.
std::vector<rhi::Image> mip_chain(const rhi::Image& image);

}  // namespace loom::scene
