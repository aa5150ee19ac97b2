#include "loom/rhi/binding_reuse.hpp"

#include <algorithm>
#include <variant>

namespace loom::rhi {

namespace {

bool same_range(const TextureRange& a, const TextureRange& b) {
    return a.base_mip == b.base_mip && a.mip_count == b.mip_count && a.base_layer == b.base_layer &&
           a.layer_count == b.layer_count;
}

}  // namespace

const BindingEntry* bound_entry(const BindGroup* group, uint32_t binding) {
    if (!group) return nullptr;
    for (auto it = group->entries.rbegin(); it != group->entries.rend(); ++it) {
        if (it->binding == binding) return &*it;
    }
    return nullptr;
}

bool differs_only_in_buffer_offset(const BindingEntry& now, const BindingEntry& then) {
    if (now.binding != then.binding || now.resource.index() != then.resource.index()) return false;
    if (const auto* a = std::get_if<BufferBinding>(&now.resource)) {
        const auto& b = std::get<BufferBinding>(then.resource);
        // Size 0 means "to the end": its range moves with the offset, so it is resolved anew.
        return a->buffer == b.buffer && a->size == b.size && a->size != 0;
    }
    if (const auto* a = std::get_if<TextureBinding>(&now.resource)) {
        const auto& b = std::get<TextureBinding>(then.resource);
        return a->texture == b.texture && a->sampler == b.sampler && same_range(a->range, b.range);
    }
    const auto& a = std::get<StorageTextureBinding>(now.resource);
    const auto& b = std::get<StorageTextureBinding>(then.resource);
    return a.texture == b.texture && a.mip == b.mip && a.base_layer == b.base_layer && a.layer_count == b.layer_count;
}

bool uniform_offset_fits(const BufferBinding& range, uint64_t buffer_size, uint64_t alignment) {
    return range.size != 0 && range.offset % std::max<uint64_t>(1, alignment) == 0 && range.offset <= buffer_size &&
           range.size <= buffer_size - range.offset;
}

}  // namespace loom::rhi
