#include "loom/framegraph/memory_model.hpp"

#include <algorithm>

namespace loom::fg {

uint64_t DefaultMemoryModel::texture_bytes(const rhi::TextureDesc& desc) {
    const uint64_t texel = rhi::format_info(desc.format).bytes_per_texel;
    const uint64_t per_texel = texel * desc.depth_or_layers * desc.samples;
    uint64_t total = 0;
    for (uint32_t mip = 0; mip < desc.mip_levels; ++mip) {
        const uint64_t width = std::max<uint64_t>(1, desc.width >> mip);
        const uint64_t height = std::max<uint64_t>(1, desc.height >> mip);
        total += width * height * per_texel;
    }
    return total;
}

Result<rhi::MemoryRequirements> DefaultMemoryModel::requirements(const rhi::TextureDesc& desc) {
    const uint64_t alignment = std::max<uint64_t>(alignment_, 1);
    return rhi::MemoryRequirements{align_up(texture_bytes(desc), alignment), alignment};
}

}  // namespace loom::fg
