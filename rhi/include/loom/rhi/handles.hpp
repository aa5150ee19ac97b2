#pragma once
// Typed handles to GPU objects (after sokol_gfx): a slot index, a generation that changes when the
// slot is reused (so a stale handle is detected), and the id of the device that made it (so a
// handle from another device is detected). A default-constructed handle is null.

#include <compare>
#include <cstddef>
#include <cstdint>
#include <functional>

namespace loom::rhi {

/// A typed handle to a GPU object: slot, generation (0 only for null) and the id of its device.
template <class Tag>
struct Handle {
    uint32_t index = 0;
    uint16_t generation = 0;  ///< 0 only for the null handle
    uint16_t device = 0;      ///< id of the owning Device

    /// True for the default-constructed (null) handle.
    [[nodiscard]] bool is_null() const { return generation == 0; }
    /// True for a non-null handle (which may still be stale).
    explicit operator bool() const { return !is_null(); }
    friend auto operator<=>(const Handle&, const Handle&) = default;
};

/// Tag of texture handles (kName names them in errors).
struct TextureTag { static constexpr const char* kName = "texture"; };
/// Tag of buffer handles.
struct BufferTag { static constexpr const char* kName = "buffer"; };
/// Tag of sampler handles.
struct SamplerTag { static constexpr const char* kName = "sampler"; };
/// Tag of shader handles.
struct ShaderTag { static constexpr const char* kName = "shader"; };
/// Tag of pipeline handles.
struct PipelineTag { static constexpr const char* kName = "pipeline"; };
/// Tag of heap handles.
struct HeapTag { static constexpr const char* kName = "heap"; };

using TextureHandle = Handle<TextureTag>;
using BufferHandle = Handle<BufferTag>;
using SamplerHandle = Handle<SamplerTag>;
using ShaderHandle = Handle<ShaderTag>;
using PipelineHandle = Handle<PipelineTag>;
/// A block of device memory in which textures can be placed at chosen offsets (aliasing).
using HeapHandle = Handle<HeapTag>;

}  // namespace loom::rhi

/// Handles hash over index, generation and device, for unordered containers.
template <class Tag>
struct std::hash<loom::rhi::Handle<Tag>> {
    std::size_t operator()(const loom::rhi::Handle<Tag>& h) const noexcept {
        return std::hash<uint64_t>{}((uint64_t{h.index} << 32) | (uint64_t{h.generation} << 16) | h.device);
    }
};
