#include "loom/rhi/subresources.hpp"

#include <algorithm>
#include <bit>

namespace loom::rhi {

namespace {
uint32_t halved(uint32_t size, uint32_t mip) { return mip >= 32 ? 1u : std::max(1u, size >> mip); }
}  // namespace

Extent3D mip_extent(const TextureDesc& desc, uint32_t mip) {
    const bool is3d = desc.dimension == TextureDimension::Tex3D;
    return {halved(desc.width, mip), halved(desc.height, mip), is3d ? halved(desc.depth_or_layers, mip) : 1u};
}

uint32_t mip_layers(const TextureDesc& desc, uint32_t mip) {
    return desc.dimension == TextureDimension::Tex3D ? halved(desc.depth_or_layers, mip) : desc.depth_or_layers;
}

uint32_t max_mip_levels(const TextureDesc& desc) {
    const uint32_t depth = desc.dimension == TextureDimension::Tex3D ? desc.depth_or_layers : 1u;
    return static_cast<uint32_t>(std::bit_width(std::max({desc.width, desc.height, depth, 1u})));
}

}  // namespace loom::rhi
