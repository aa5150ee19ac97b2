#pragma once
// The geometry of a texture's subresources (mip levels, layers, depth slices), computed the same
// way by the shared validation layer and every backend.

#include <cstdint>

#include "loom/rhi/descriptions.hpp"

namespace loom::rhi {

/// The size of mip level `mip` (each dimension halved per level, never below 1; depth only for
/// 3D textures, 1 otherwise).
Extent3D mip_extent(const TextureDesc& desc, uint32_t mip);

/// The layers of an array or cube texture (1 for a 2D texture), or the depth slices of mip
/// `mip` of a 3D texture: what TextureRegion::layer (or origin.z on 3D) may address.
uint32_t mip_layers(const TextureDesc& desc, uint32_t mip);

/// The most mip levels the texture's size allows (a full chain down to 1x1x1).
uint32_t max_mip_levels(const TextureDesc& desc);

}  // namespace loom::rhi
