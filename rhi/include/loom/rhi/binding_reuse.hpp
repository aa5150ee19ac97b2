#pragma once
// Which entry of a bind group a shader binding uses, and when a backend may bind what it
// resolved for an earlier draw again with new buffer offsets
// instead of checking and resolving (GL) or writing (Vulkan) the bindings anew: per-draw uniform
// data at successive offsets of the frame's uniform memory (CommandList::set_buffer) changes
// nothing else. Both backends ask these, so that they reuse in exactly the same cases.
#include <cstdint>

#include "loom/rhi/descriptions.hpp"

namespace loom::rhi {

/// The entry of `group` at `binding` that draws use: the last one given for it (null when the
/// group is null or has none). The validation layer and both backends look entries up this way.
const BindingEntry* bound_entry(const BindGroup* group, uint32_t binding);

/// `now` is `then` but for the offset of a buffer range of explicit, non-zero size: same kind,
/// same objects, same sizes and texture ranges.
bool differs_only_in_buffer_offset(const BindingEntry& now, const BindingEntry& then);

/// A uniform range's new offset keeps it aligned to `alignment` and inside `buffer_size` bytes
/// (otherwise the backend checks the binding anew, which reports the error).
bool uniform_offset_fits(const BufferBinding& range, uint64_t buffer_size, uint64_t alignment);

}  // namespace loom::rhi
