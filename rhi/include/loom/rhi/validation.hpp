#pragma once
// The shared validation layer: every rule about a description or a transfer that does not
// depend on the graphics API, checked once, in front of every backend (after sokol_gfx's
// validation layer and NVRHI's validation wrapper). Backends call these first and then only
// translate to their API, so a misuse gives the same ErrorCode and the same message on every
// backend (tests/render/misuse_table_test.cpp checks that, rule by rule). The rules about when
// a command may be recorded (a render pass open, a pipeline bound) are rhi::CommandListState's
// (loom/rhi/command_list_state.hpp).
//
// Codes: InvalidArgument for a description or call that is wrong whatever the device;
// Unsupported where it exceeds what this device can do (its Capabilities: sizes, layers,
// samples, format features, placed resources). Messages name the object in quotes and the
// field at fault: "texture 'albedo': mip_levels 9 is not in 1..8 for a 64x64x1 texture".

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

// CMake option LOOM_RHI_VALIDATION (ON by default) defines it for loom::rhi and its users.
#ifndef LOOM_RHI_VALIDATION
#define LOOM_RHI_VALIDATION 1
#endif

namespace loom::rhi::validation {

/// Whether this build checks recorded commands (CMake option LOOM_RHI_VALIDATION). Where it
/// is false the checks are compiled out and every device skips them, whatever
/// DeviceDesc::validation says (see CommandListState::validating for what they are).
inline constexpr bool kCompiled = LOOM_RHI_VALIDATION != 0;

/// `name` in single quotes, as every message quotes the object it is about.
std::string in_quotes(std::string_view name);

/// What a device's log line says of its checks: `api_debug` (the API's own, DeviceDesc::debug:
/// "debug output", "the Khronos validation layer") on or off, with a reminder of its cost when
/// on, and loom's validation (DeviceDesc::validation, and whether this build compiled it out).
std::string checks_in_log(std::string_view api_debug, bool debug, bool validation);

/// Shape × dimension × format × usage × samples × the device's limits and format features.
Status texture_desc(const TextureDesc& desc, const Capabilities& caps);
/// Device::texture_memory_requirements: a device with placed resources and a valid `desc`.
Status texture_memory_query(const TextureDesc& desc, const Capabilities& caps);
/// A buffer has at least one byte; a placement only on a device with placed resources
/// (Unsupported otherwise). Where it lands in its heap is buffer_placement's to check.
Status buffer_desc(const BufferDesc& desc, const Capabilities& caps);
/// Device::buffer_memory_requirements: a buffer of at least one byte (the placement is ignored;
/// devices without placed resources answer too).
Status buffer_memory_query(const BufferDesc& desc);
/// A placed buffer (`desc.placement` set) that needs `requirements` (Device::
/// buffer_memory_requirements) inside heap `heap`: its offset a multiple of the alignment and
/// its bytes inside the heap.
Status buffer_placement(const BufferDesc& desc, const HeapDesc& heap, const MemoryRequirements& requirements);
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

// ---- pipelines -----------------------------------------------------------------------------

/// What the validation layer needs of a shader the device holds.
struct ShaderFacts {
    std::string_view name;
    ShaderStage stage = ShaderStage::Vertex;
    const ShaderReflection* reflection = nullptr;
};
/// The facts of a shader by handle, on the device being validated; an InvalidHandle error
/// (HandlePool's message) for a null, stale or foreign handle.
using ShaderLookup = std::function<Result<ShaderFacts>(ShaderHandle)>;

/// Device::create_graphics_pipeline: live vertex and fragment shaders of those stages; at least
/// one attachment format; colour formats that are colour formats the device renders to (at most
/// its colour attachments), a depth format it renders depth to; at most one blend state per
/// colour format, enabled only where the format blends; a depth test or write only with a depth
/// format; a sample count every format has; at most kMaxVertexBuffers vertex buffers, no
/// attribute location twice, every vertex input fed; line polygons and depth clamping only where
/// the device has them.
Status graphics_pipeline(const GraphicsPipelineDesc& desc, const Capabilities& caps, const ShaderLookup& lookup);
/// Device::create_compute_pipeline: a live compute shader.
Status compute_pipeline(const ComputePipelineDesc& desc, const ShaderLookup& lookup);

// ---- commands ------------------------------------------------------------------------------
// What a CommandList checks of a command's arguments before it records it (the first error of
// a frame comes back from end_frame). Whether the command may come now (inside or outside a
// render pass, with a pipeline bound) is rhi::CommandListState's to say.

/// The description of a texture by handle, on the device being validated; an InvalidHandle
/// error (HandlePool's message) for a null, stale or foreign handle.
using TextureLookup = std::function<Result<const TextureDesc*>(TextureHandle)>;
/// The same for buffers.
using BufferLookup = std::function<Result<const BufferDesc*>(BufferHandle)>;

/// The size, sample count and formats of a render pass's attachments (what a graphics pipeline
/// drawing in it must target).
struct RenderPassShape {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t samples = 1;
    std::vector<Format> color_formats;
    Format depth_format = Format::Undefined;
};
/// CommandList::begin_render_pass: at least one attachment, at most the device's colour
/// attachments; each one a live texture of the right kind of format, with the attachment usage,
/// an existing mip and layer, not 3D; all of one size and sample count.
Result<RenderPassShape> render_pass(const RenderPassDesc& desc, const Capabilities& caps, const TextureLookup& lookup);

/// The texels one CommandList::copy_texture call copies, the zeros of the source region's
/// extent resolved to "the rest of the source mip level".
struct TextureCopyRange {
    uint32_t src_mip = 0, src_layer = 0;
    Origin3D src_origin{};
    uint32_t dst_mip = 0, dst_layer = 0;
    Origin3D dst_origin{};
    /// extent.depth counts depth slices of 3D textures (1 otherwise).
    Extent3D extent{};
};
/// CommandList::copy_texture between textures described by `src` and `dst` (`same_texture`
/// when they are one texture): copy-compatible formats (equal, or colour formats of the same
/// texel size), equal sample counts, both 3D or neither, existing subresources, a region that
/// fits both, and not one subresource copied onto itself.
Result<TextureCopyRange> texture_copy(const TextureDesc& src, const TextureDesc& dst, bool same_texture, const TextureCopy& copy);

/// A TextureRange of `texture`, checked and resolved: counts of kRemainingSubresources become
/// "to the last one"; a range that is empty or leaves the texture's mip levels or layers (a
/// Tex3D texture has one layer, its depth slices are not layers) is an InvalidArgument error
/// starting with `what` ("transition: texture 'x'").
Result<TextureRange> texture_range(std::string_view what, const TextureDesc& texture, const TextureRange& range);
/// set_buffer's set and binding are inside loom's limits.
Status buffer_slot(uint32_t set, uint32_t binding);

/// The layers a TextureRange addresses in `texture`: its array layers, 6 for a cube, 1 for 2D and 3D.
uint32_t range_layers(const TextureDesc& texture);

/// CommandList::copy_buffer: both ranges inside their buffers, and not overlapping when the
/// buffers are one (`same_buffer`).
Status buffer_copy(const BufferDesc& src, uint64_t src_offset, const BufferDesc& dst, uint64_t dst_offset, uint64_t size,
                   bool same_buffer);

/// What a pipeline reads at one (set, binding), from its shaders' reflection.
enum class BindingKind : uint8_t { UniformBuffer, StorageBuffer, SampledTexture, StorageImage };

/// One (set, binding) a pipeline reads, for draw-time checks of the bound groups.
struct PipelineSlot {
    uint32_t set = 0;
    uint32_t binding = 0;
    BindingKind kind = BindingKind::UniformBuffer;
    std::string_view name;  ///< the GLSL name
    /// Textures and storage images: what the shader declares (sampler2D, image2DArray, ...).
    TextureKind texture_kind = TextureKind::Tex2D;
};

/// The subresources a texture or storage-image binding reads, resolved (counts concrete), and
/// what the shader sees them as. Backends make their views from it.
struct BoundRange {
    TextureRange range;
    TextureKind kind = TextureKind::Tex2D;
    /// The texture's whole range, seen as its own dimension: bind the texture itself, no view.
    bool whole = true;
};

/// The BoundRange of a texture binding's entry (after rhi::validation::binding accepted it):
/// TextureBinding::range, or a StorageTextureBinding's mip and layers, for `slot`'s declaration.
BoundRange bound_range(const PipelineSlot& slot, const TextureDesc& texture, const BindingEntry& entry);

/// Buffers, textures and samplers by handle on the device being validated; InvalidHandle
/// errors (HandlePool's messages) for null, stale or foreign handles.
struct ResourceLookup {
    BufferLookup buffer;
    TextureLookup texture;
    std::function<Result<bool>(SamplerHandle)> sampler;  ///< true when alive
};

/// The ResourceLookup over a backend's handle pools (rhi::HandlePool of objects with a `desc`),
/// which must outlive it.
template <class BufferPool, class TexturePool, class SamplerPool>
ResourceLookup lookup_in(BufferPool& buffers, TexturePool& textures, SamplerPool& samplers) {
    ResourceLookup lookup;
    lookup.buffer = [&buffers](BufferHandle h) -> Result<const BufferDesc*> {
        auto found = buffers.get(h);
        if (!found.ok()) return found.take_error();
        return &(*found)->desc;
    };
    lookup.texture = [&textures](TextureHandle h) -> Result<const TextureDesc*> {
        auto found = textures.get(h);
        if (!found.ok()) return found.take_error();
        return &(*found)->desc;
    };
    lookup.sampler = [&samplers](SamplerHandle h) -> Result<bool> {
        auto found = samplers.get(h);
        if (!found.ok()) return found.take_error();
        return true;
    };
    return lookup;
}

/// A draw or dispatch (`command`) with pipeline `pipeline`: the entry `group` (null when no
/// group is set for slot.set) has at slot.binding must be there, of the slot's kind, refer to
/// live resources with the usage the kind needs, a buffer range inside the buffer with its
/// offset aligned as `caps` says, a texture's range (a storage image's mip and layers) inside
/// the texture and of a shape the shader's declaration can see (one layer for a sampler2D or
/// image2D of an array, all six faces of a cube for a samplerCube, a Tex3D texture for a
/// sampler3D). Returns the entry. The
/// resource states sampling and storage access need are the command lists' to check
/// (state_for_binding gives their message).
Result<const BindingEntry*> binding(std::string_view command, std::string_view pipeline, const PipelineSlot& slot, const BindGroup* group,
                                    const Capabilities& caps, const ResourceLookup& lookup);
/// The InvalidState error for texture `texture` bound at `slot` while in `state`, where the
/// slot's kind needs `needed` ("ShaderRead", "DepthRead or ShaderRead", "Storage").
Error state_for_binding(std::string_view command, std::string_view pipeline, const PipelineSlot& slot, std::string_view texture,
                        ResourceState state, std::string_view needed);

/// CommandList::transition of a texture to `state`: a state textures have, for the texture's kind
/// of format (RenderTarget and Present a colour format, DepthWrite and DepthRead a depth/stencil
/// one), with the usage it needs (RenderTarget: ColorAttachment, DepthWrite:
/// DepthStencilAttachment, Storage: Storage); ShaderRead and DepthRead where this device samples
/// the format (Unsupported otherwise).
Status texture_transition(const TextureDesc& texture, ResourceState state, const Capabilities& caps);
/// CommandList::transition of the subresources `range` of a texture to `state`: texture_transition,
/// and the range inside the texture (texture_range). Returns the range resolved.
Result<TextureRange> texture_range_transition(const TextureDesc& texture, ResourceState state, const TextureRange& range,
                                              const Capabilities& caps);
/// CommandList::transition of a buffer to `state`: a state buffers have (not RenderTarget,
/// DepthWrite, DepthRead or Present).
Status buffer_transition(const BufferDesc& buffer, ResourceState state);

/// CommandList::set_viewport: a positive size, depths within 0..1, nothing NaN.
Status viewport(const Viewport& viewport);
/// CommandList::push_constants: the bytes fit kMaxPushConstantBytes.
Status push_constants(uint64_t offset, uint64_t size);
/// CommandList::set_bind_group: set and bindings within kMaxBindGroups / kMaxBindingsPerGroup.
Status bind_group(uint32_t set, const BindGroup& group);
/// Bytes of one index of `type`.
inline uint64_t index_bytes(IndexType type) { return type == IndexType::Uint16 ? 2 : 4; }

// The three checks below run at every bind of vertex and index buffers: inline, with their
// errors (and messages) made out of line by the *_refused functions.
Status vertex_buffer_slot_refused(uint32_t slot);
Status vertex_buffer_refused(uint32_t slot, const BufferDesc& buffer, uint64_t offset);
Status index_buffer_refused(const BufferDesc& buffer, IndexType type, uint64_t offset);
/// CommandList::set_vertex_buffer: the slot is below kMaxVertexBuffers.
inline Status vertex_buffer_slot(uint32_t slot) {
    if (slot < kMaxVertexBuffers) [[likely]] return {};
    return vertex_buffer_slot_refused(slot);
}
/// CommandList::set_vertex_buffer with `buffer` (after vertex_buffer_slot): Vertex usage and
/// the offset inside it.
inline bool vertex_buffer_fits(const BufferDesc& buffer, uint64_t offset) {
    return has_all(buffer.usage, BufferUsage::Vertex) && offset < buffer.size;
}
/// vertex_buffer_fits, with the error when it does not.
inline Status vertex_buffer(uint32_t slot, const BufferDesc& buffer, uint64_t offset) {
    if (vertex_buffer_fits(buffer, offset)) [[likely]] return {};
    return vertex_buffer_refused(slot, buffer, offset);
}
/// CommandList::set_index_buffer: Index usage; the offset inside the buffer and a multiple of
/// the index size.
inline bool index_buffer_fits(const BufferDesc& buffer, IndexType type, uint64_t offset) {
    return has_all(buffer.usage, BufferUsage::Index) && offset < buffer.size && offset % index_bytes(type) == 0;
}
/// index_buffer_fits, with the error when it does not.
inline Status index_buffer(const BufferDesc& buffer, IndexType type, uint64_t offset) {
    if (index_buffer_fits(buffer, type, offset)) [[likely]] return {};
    return index_buffer_refused(buffer, type, offset);
}
/// Whether `index_count` indices from `first_index` lie inside `buffer_size` bytes of an index
/// buffer bound at `offset`: index_range's rule, which the state tracker also asks per draw
/// with the size it kept when the buffer was bound.
inline bool index_range_fits(uint64_t buffer_size, IndexType type, uint64_t offset, uint32_t first_index,
                             uint32_t index_count) {
    // (first_index + index_count) * 4 < 2^35: exact in 64 bits, no overflow check needed.
    return offset <= buffer_size && (uint64_t{first_index} + index_count) * index_bytes(type) <= buffer_size - offset;
}
/// CommandList::draw_indexed: `index_count` indices from `first_index` lie inside the index
/// buffer bound at `offset`.
Status index_range(const BufferDesc& buffer, IndexType type, uint64_t offset, uint32_t first_index, uint32_t index_count);
/// CommandList::draw_indexed_indirect: Indirect usage; offset and stride multiples of 4, the
/// stride at least one DrawIndexedIndirectCommand; every command inside the buffer.
Status indirect_draws(const BufferDesc& buffer, uint64_t offset, uint32_t draw_count, uint32_t stride);

}  // namespace loom::rhi::validation
