#pragma once
// Typed handles to GPU objects (after sokol_gfx): a slot index, a generation that changes when the
// slot is reused (so a stale handle is detected), and the id of the device that made it (so a
// handle from another device is detected). A default-constructed handle is null.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace loom::rhi {

template <class Tag>
struct Handle {
    uint32_t index = 0;
    uint16_t generation = 0;  ///< 0 only for the null handle
    uint16_t device = 0;      ///< id of the owning Device

    [[nodiscard]] bool is_null() const { return generation == 0; }
    explicit operator bool() const { return !is_null(); }
    friend auto operator<=>(const Handle&, const Handle&) = default;
};

struct TextureTag { static constexpr const char* kName = "texture"; };
struct BufferTag { static constexpr const char* kName = "buffer"; };
struct SamplerTag { static constexpr const char* kName = "sampler"; };
struct ShaderTag { static constexpr const char* kName = "shader"; };
struct PipelineTag { static constexpr const char* kName = "pipeline"; };
struct HeapTag { static constexpr const char* kName = "heap"; };

using TextureHandle = Handle<TextureTag>;
using BufferHandle = Handle<BufferTag>;
using SamplerHandle = Handle<SamplerTag>;
using ShaderHandle = Handle<ShaderTag>;
using PipelineHandle = Handle<PipelineTag>;
/// A block of device memory in which textures can be placed at chosen offsets (aliasing).
using HeapHandle = Handle<HeapTag>;

}  // namespace loom::rhi

template <class Tag>
struct std::hash<loom::rhi::Handle<Tag>> {
    std::size_t operator()(const loom::rhi::Handle<Tag>& h) const noexcept {
        return std::hash<uint64_t>{}((uint64_t{h.index} << 32) | (uint64_t{h.generation} << 16) | h.device);
    }
};
