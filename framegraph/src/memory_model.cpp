#include "loom/framegraph/memory_model.hpp"

#include <algorithm>
#include <limits>

#include "loom/rhi/checked_math.hpp"

namespace loom::fg {

std::optional<uint64_t> DefaultMemoryModel::checked_texture_bytes(const rhi::TextureDesc& desc) {
    const uint64_t texel = rhi::format_info(desc.format).bytes_per_texel;
    auto per_texel = checked::product({texel, desc.depth_or_layers, desc.samples});
    if (!per_texel) return std::nullopt;
    uint64_t total = 0;
    for (uint32_t mip = 0; mip < desc.mip_levels && mip < 32; ++mip) {
        const uint64_t width = std::max<uint64_t>(1, desc.width >> mip);
        const uint64_t height = std::max<uint64_t>(1, desc.height >> mip);
        auto level = checked::product({width, height, *per_texel});
        if (!level) return std::nullopt;
        auto sum = checked::add(total, *level);
        if (!sum) return std::nullopt;
        total = *sum;
    }
    // Levels past the 32nd are 1x1 (and shifting a 32-bit size by 32 or more is undefined).
    if (desc.mip_levels > 32) {
        auto rest = checked::product({desc.mip_levels - 32u, *per_texel});
        if (!rest) return std::nullopt;
        auto sum = checked::add(total, *rest);
        if (!sum) return std::nullopt;
        total = *sum;
    }
    return total;
}

Result<rhi::MemoryRequirements> MemoryModel::buffer_requirements(const rhi::BufferDesc& desc) {
    auto bytes = checked::align_up(desc.size, kDefaultBufferAlignment);
    if (!bytes) {
        return make_error(ErrorCode::InvalidArgument,
                          "buffer '" + desc.name + "' of " + std::to_string(desc.size) + " bytes is too large to align");
    }
    return rhi::MemoryRequirements{*bytes, kDefaultBufferAlignment};
}

uint64_t DefaultMemoryModel::texture_bytes(const rhi::TextureDesc& desc) {
    return checked_texture_bytes(desc).value_or(std::numeric_limits<uint64_t>::max());
}

Result<rhi::MemoryRequirements> DefaultMemoryModel::requirements(const rhi::TextureDesc& desc) {
    const uint64_t alignment = std::max<uint64_t>(alignment_, 1);
    auto bytes = checked_texture_bytes(desc);
    if (bytes) bytes = checked::align_up(*bytes, alignment);
    if (!bytes) {
        return make_error(ErrorCode::InvalidArgument,
                          "texture '" + desc.name + "' (" + std::to_string(desc.width) + "x" +
                              std::to_string(desc.height) + ", " + std::to_string(desc.depth_or_layers) + " layers, " +
                              std::to_string(desc.mip_levels) + " mips, " + std::to_string(desc.samples) +
                              " samples) needs more than 2^64 bytes");
    }
    return rhi::MemoryRequirements{*bytes, alignment};
}

}  // namespace loom::fg
