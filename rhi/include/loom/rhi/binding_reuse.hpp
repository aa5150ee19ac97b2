#pragma once
// Which entry of a bind group a shader binding uses, and when a backend may bind what it
// resolved for an earlier draw again with new buffer offsets
// instead of checking and resolving (GL) or writing (Vulkan) the bindings anew: per-draw uniform
// data at successive offsets of the frame's uniform memory (CommandList::set_buffer) changes
// nothing else. Both backends ask these, so that they reuse in exactly the same cases; they are
// inline because both ask them for every draw whose bindings changed.
#include <algorithm>
#include <cstdint>
#include <variant>

#include "loom/rhi/descriptions.hpp"

namespace loom::rhi {

/// The entry of `group` at `binding` that draws use: the last one given for it (null when the
/// group is null or has none). The validation layer and both backends look entries up this way.
inline const BindingEntry* bound_entry(const BindGroup* group, uint32_t binding) {
    if (!group) return nullptr;
    for (auto it = group->entries.rbegin(); it != group->entries.rend(); ++it) {
        if (it->binding == binding) return &*it;
    }
    return nullptr;
}
/// The same entry, to change (CommandListState::set_buffer replaces it).
inline BindingEntry* bound_entry(BindGroup* group, uint32_t binding) {
    return const_cast<BindingEntry*>(bound_entry(static_cast<const BindGroup*>(group), binding));
}

/// `now` is `then` but for the offset of a buffer range of explicit, non-zero size: same kind,
/// same objects, same sizes and texture ranges.
inline bool differs_only_in_buffer_offset(const BindingEntry& now, const BindingEntry& then) {
    if (now.binding != then.binding || now.resource.index() != then.resource.index()) return false;
    if (const auto* a = std::get_if<BufferBinding>(&now.resource)) {
        const auto& b = std::get<BufferBinding>(then.resource);
        // Size 0 means "to the end": its range moves with the offset, so it is resolved anew.
        return a->buffer == b.buffer && a->size == b.size && a->size != 0;
    }
    if (const auto* a = std::get_if<TextureBinding>(&now.resource)) {
        const auto& b = std::get<TextureBinding>(then.resource);
        return a->texture == b.texture && a->sampler == b.sampler && a->range.base_mip == b.range.base_mip &&
               a->range.mip_count == b.range.mip_count && a->range.base_layer == b.range.base_layer &&
               a->range.layer_count == b.range.layer_count;
    }
    const auto& a = std::get<StorageTextureBinding>(now.resource);
    const auto& b = std::get<StorageTextureBinding>(then.resource);
    return a.texture == b.texture && a.mip == b.mip && a.base_layer == b.base_layer && a.layer_count == b.layer_count;
}

/// A uniform range's new offset keeps it aligned to `alignment` and inside `buffer_size` bytes
/// (otherwise the backend checks the binding anew, which reports the error).
inline bool uniform_offset_fits(const BufferBinding& range, uint64_t buffer_size, uint64_t alignment) {
    return range.size != 0 && range.offset % std::max<uint64_t>(1, alignment) == 0 && range.offset <= buffer_size &&
           range.size <= buffer_size - range.offset;
}

}  // namespace loom::rhi
