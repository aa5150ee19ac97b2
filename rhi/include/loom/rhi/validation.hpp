#pragma once
// The shared validation layer: every rule about a description or a transfer that does not
// depend on the graphics API, checked once, in front of every backend (after sokol_gfx's
// validation layer and NVRHI's validation wrapper). Backends call these first and then only
// translate to their API, so a misuse gives the same ErrorCode and the same message on every
// backend (tests/cross_backend/misuse_table_test.cpp checks that, rule by rule).
//
// Codes: InvalidArgument for a description or call that is wrong whatever the device;
// Unsupported where it exceeds what this device can do (its Capabilities: sizes, layers,
// samples, format features, placed resources). Messages name the object in quotes and the
// field at fault: "texture 'albedo': mip_levels 9 is not in 1..8 for a 64x64x1 texture".

#include <cstdint>
#include <string>
#include <string_view>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::rhi::validation {

/// `name` in single quotes, as every message quotes the object it is about.
std::string in_quotes(std::string_view name);

/// Shape × dimension × format × usage × samples × the device's limits and format features.
Status texture_desc(const TextureDesc& desc, const Capabilities& caps);
/// Device::texture_memory_requirements: a device with placed resources and a valid `desc`.
Status texture_memory_query(const TextureDesc& desc, const Capabilities& caps);
/// A buffer has at least one byte.
Status buffer_desc(const BufferDesc& desc);
/// LOD range and anisotropy.
Status sampler_desc(const SamplerDesc& desc);
/// A heap has at least one byte, on a device with placed resources.
Status heap_desc(const HeapDesc& desc, const Capabilities& caps);

/// Device::write_buffer of `size` bytes at `offset` into `buffer` (no overflow past 2^64).
Status buffer_write(const BufferDesc& buffer, uint64_t offset, uint64_t size);
/// Device::read_buffer of `size` bytes at `offset` of `buffer`.
Status buffer_read(const BufferDesc& buffer, uint64_t offset, uint64_t size);

/// The texels one Device::write_texture call writes, the zeros of TextureRegion::extent
/// resolved to "the rest of the mip level".
struct TextureWrite {
    uint32_t mip = 0;
    /// The array layer (0 for 2D and 3D textures).
    uint32_t layer = 0;
    /// origin.z and extent.depth are depth slices of a 3D texture (0 and 1 otherwise).
    Origin3D origin{};
    Extent3D extent{};
    /// The bytes `data` must hold: the extent's texels, tightly packed, in the texture's format.
    uint64_t bytes = 0;
};
/// Device::write_texture of `data_size` bytes into `region` of `texture`.
Result<TextureWrite> texture_write(const TextureDesc& texture, const TextureRegion& region, uint64_t data_size);
/// Device::read_texture of mip `mip`, layer `layer` (depth slice on a 3D texture).
Status texture_read(const TextureDesc& texture, uint32_t mip, uint32_t layer);

}  // namespace loom::rhi::validation
