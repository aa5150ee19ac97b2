// Creation and destruction of textures, buffers, samplers, shaders, pipelines and heaps;
// image views; the per-subresource state tracking behind every texture barrier.
#include <algorithm>
#include <cmath>

#include "formats.hpp"
#include "pipelines.hpp"
#include "vulkan_device.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::vulkan {

using rhi::ResourceState;

namespace {

using rhi::validation::in_quotes;

uint64_t view_key(uint32_t kind, uint32_t mip, uint32_t layer) {
    return (uint64_t{kind} << 48) | (uint64_t{mip} << 24) | layer;
}

}  // namespace

// ---- textures ----------------------------------------------------------------------------------

VkImageCreateInfo VulkanDevice::image_create_info(const rhi::TextureDesc& d) const {
    auto info = vk_init<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
    const bool is3d = d.dimension == rhi::TextureDimension::Tex3D;
    info.imageType = is3d ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
    info.format = to_vk_format(d.format);
    info.extent = {d.width, d.height, is3d ? d.depth_or_layers : 1};
    info.mipLevels = d.mip_levels;
    info.arrayLayers = is3d ? 1 : d.depth_or_layers;
    info.samples = static_cast<VkSampleCountFlagBits>(d.samples);
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    if (d.dimension == rhi::TextureDimension::Cube) info.flags |= VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
    // Uploads and readbacks are always allowed; sampling too where the format can be sampled,
    // so that the ShaderRead state (and layout) is legal for every texture.
    const rhi::FormatCapabilities& fc = caps_.format(d.format);
    info.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    if (fc.sampled) info.usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
    if (rhi::has_all(d.usage, rhi::TextureUsage::ColorAttachment)) info.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    if (rhi::has_all(d.usage, rhi::TextureUsage::DepthStencilAttachment)) info.usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    if (rhi::has_all(d.usage, rhi::TextureUsage::Storage)) info.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    return info;
}

loom::Result<rhi::MemoryRequirements> VulkanDevice::texture_memory_requirements(const rhi::TextureDesc& desc) {
    LOOM_TRY(rhi::validation::texture_memory_query(desc, caps_));
    const VkImageCreateInfo info = image_create_info(desc);
    auto query = vk_init<VkDeviceImageMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS);
    query.pCreateInfo = &info;
    auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
    vkGetDeviceImageMemoryRequirements(context_->device(), &query, &req);
    return rhi::MemoryRequirements{req.memoryRequirements.size, req.memoryRequirements.alignment};
}

loom::Result<rhi::TextureHandle> VulkanDevice::create_texture(const rhi::TextureDesc& desc) {
    LOOM_TRY(rhi::validation::texture_desc(desc, caps_));
    const std::string tex = "texture " + in_quotes(desc.name);
    VkDevice device = context_->device();
    Heap* heap = nullptr;
    if (desc.placement) {
        auto h = heaps_.get(desc.placement->heap);
        if (!h.ok()) return Error{ErrorCode::InvalidArgument, tex + ": placement heap: " + h.error().message};
        heap = *h;
    }

    Texture t;
    t.desc = desc;
    const VkImageCreateInfo info = image_create_info(desc);
    t.format = info.format;
    t.aspect = aspect_mask(info.format);
    t.depth_stencil = rhi::format_info(desc.format).is_depth_stencil();
    t.array_layers = info.arrayLayers;
    if (VkResult r = vkCreateImage(device, &info, nullptr, &t.image); r != VK_SUCCESS) return vk_error(r, "vkCreateImage for " + tex);
    context_->set_name(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(t.image), desc.name);

    auto req_info = vk_init<VkImageMemoryRequirementsInfo2>(VK_STRUCTURE_TYPE_IMAGE_MEMORY_REQUIREMENTS_INFO_2);
    req_info.image = t.image;
    auto dedicated = vk_init<VkMemoryDedicatedRequirements>(VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS);
    auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
    req.pNext = &dedicated;
    vkGetImageMemoryRequirements2(device, &req_info, &req);
    const VkMemoryRequirements& mr = req.memoryRequirements;

    if (heap) {
        const std::string heap_name = "heap " + in_quotes(heap->desc.name);
        const uint64_t offset = desc.placement->offset;
        auto fail = [&](std::string message) -> Error {
            vkDestroyImage(device, t.image, nullptr);
            return Error{ErrorCode::InvalidArgument, tex + " placed in " + heap_name + ": " + std::move(message)};
        };
        if (offset % mr.alignment != 0) {
            return fail("offset " + std::to_string(offset) + " is not a multiple of the alignment " + std::to_string(mr.alignment));
        }
        if (offset + mr.size > heap->memory.size || offset > heap->memory.size) {
            return fail("range " + std::to_string(offset) + "+" + std::to_string(mr.size) + " exceeds the heap size " +
                        std::to_string(heap->memory.size));
        }
        if (!(mr.memoryTypeBits & (1u << heap->memory.memory_type))) {
            return fail("the image cannot live in the heap's memory type " + std::to_string(heap->memory.memory_type));
        }
        if (dedicated.requiresDedicatedAllocation) return fail("the driver requires a dedicated allocation for this image");
        if (VkResult r = vkBindImageMemory(device, t.image, heap->memory.memory, heap->memory.offset + offset); r != VK_SUCCESS) {
            vkDestroyImage(device, t.image, nullptr);
            return vk_error(r, "vkBindImageMemory for " + tex);
        }
        ++heap->placed_textures;
        t.heap_offset = offset;
        t.heap_size = mr.size;
    } else {
        AllocationRequest request;
        request.requirements = mr;
        request.preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        request.kind = ResourceKind::Image;
        request.dedicated = dedicated.requiresDedicatedAllocation || dedicated.prefersDedicatedAllocation;
        if (request.dedicated) request.dedicated_image = t.image;
        auto memory = allocator_->allocate(request);
        if (!memory.ok()) {
            vkDestroyImage(device, t.image, nullptr);
            Error e = memory.take_error();
            e.message = tex + ": " + e.message;
            return e;
        }
        t.memory = *memory;
        t.bytes = t.memory.size;
        if (VkResult r = vkBindImageMemory(device, t.image, t.memory.memory, t.memory.offset); r != VK_SUCCESS) {
            allocator_->free(t.memory);
            vkDestroyImage(device, t.image, nullptr);
            return vk_error(r, "vkBindImageMemory for " + tex);
        }
    }

    if (info.usage & VK_IMAGE_USAGE_SAMPLED_BIT) {
        auto vi = vk_init<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
        vi.image = t.image;
        switch (desc.dimension) {
            case rhi::TextureDimension::Tex2D: vi.viewType = VK_IMAGE_VIEW_TYPE_2D; break;
            case rhi::TextureDimension::Tex2DArray: vi.viewType = VK_IMAGE_VIEW_TYPE_2D_ARRAY; break;
            case rhi::TextureDimension::Tex3D: vi.viewType = VK_IMAGE_VIEW_TYPE_3D; break;
            case rhi::TextureDimension::Cube: vi.viewType = VK_IMAGE_VIEW_TYPE_CUBE; break;
        }
        vi.format = t.format;
        // A sampler reads one aspect: depth for depth(/stencil) formats.
        VkImageAspectFlags aspect = t.aspect;
        if (aspect & VK_IMAGE_ASPECT_DEPTH_BIT) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
        vi.subresourceRange = {aspect, 0, desc.mip_levels, 0, t.array_layers};
        if (VkResult r = vkCreateImageView(device, &vi, nullptr, &t.sampled_view); r != VK_SUCCESS) {
            release_texture(t);
            return vk_error(r, "vkCreateImageView for " + tex);
        }
    }
    t.states.assign(std::size_t{desc.mip_levels} * t.array_layers, ResourceState::Undefined);
    t.frame_start_states = t.states;
    const rhi::TextureHandle handle = textures_.insert(std::move(t));
    if (heap) heap->placed.push_back(handle);
    return handle;
}

loom::Result<rhi::TextureHandle> VulkanDevice::wrap_swapchain_image(VkImage image, VkFormat format, uint32_t width,
                                                                     uint32_t height, uint32_t index) {
    Texture t;
    t.desc.name = "backbuffer " + std::to_string(index);
    t.desc.format = swapchain_->loom_format();
    t.desc.width = width;
    t.desc.height = height;
    t.desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopySrc;
    t.image = image;
    t.format = format;
    t.aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    t.swapchain = true;
    t.states.assign(1, ResourceState::Undefined);
    t.frame_start_states = t.states;
    return textures_.insert(std::move(t));
}

void VulkanDevice::release_texture(Texture& t) {
    // Views and image go once the GPU is done with what was recorded so far.
    std::vector<VkImageView> views;
    if (t.sampled_view) views.push_back(t.sampled_view);
    for (auto& [key, view] : t.views) views.push_back(view);
    for (auto& [key, view] : t.range_views) views.push_back(view);
    VkImage image = t.swapchain || t.imported ? VK_NULL_HANDLE : t.image;
    MemoryAllocation memory = t.memory;
    VkDevice device = context_->device();
    MemoryAllocator* allocator = allocator_.get();
    submissions_->defer([device, allocator, views, image, memory] {
        for (VkImageView v : views) vkDestroyImageView(device, v, nullptr);
        if (image) vkDestroyImage(device, image, nullptr);
        allocator->free(memory);
    });
    t.sampled_view = VK_NULL_HANDLE;
    t.views.clear();
    t.range_views.clear();
    t.image = VK_NULL_HANDLE;
    t.memory = {};
}

loom::Result<VkImageView> VulkanDevice::attachment_view(Texture& t, uint32_t mip, uint32_t layer) {
    const uint64_t key = view_key(1, mip, layer);
    if (auto it = t.views.find(key); it != t.views.end()) return it->second;
    auto vi = vk_init<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vi.image = t.image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = t.format;
    vi.subresourceRange = {t.aspect, mip, 1, layer, 1};
    VkImageView view = VK_NULL_HANDLE;
    if (VkResult r = vkCreateImageView(context_->device(), &vi, nullptr, &view); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateImageView (attachment of texture " + in_quotes(t.desc.name) + ")");
    }
    t.views.emplace(key, view);
    return view;
}

loom::Result<VkImageView> VulkanDevice::range_view(Texture& t, const rhi::TextureRange& range, rhi::TextureKind kind, bool storage) {
    VkImageViewType type = VK_IMAGE_VIEW_TYPE_2D;
    switch (kind) {
        case rhi::TextureKind::Tex2D: type = VK_IMAGE_VIEW_TYPE_2D; break;
        case rhi::TextureKind::Tex2DArray: type = VK_IMAGE_VIEW_TYPE_2D_ARRAY; break;
        case rhi::TextureKind::Tex3D: type = VK_IMAGE_VIEW_TYPE_3D; break;
        case rhi::TextureKind::Cube: type = VK_IMAGE_VIEW_TYPE_CUBE; break;
    }
    const std::array<uint32_t, 6> key{storage ? 1u : 0u, static_cast<uint32_t>(type), range.base_mip, range.mip_count, range.base_layer,
                                      range.layer_count};
    if (auto it = t.range_views.find(key); it != t.range_views.end()) return it->second;
    auto vi = vk_init<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
    vi.image = t.image;
    vi.viewType = type;
    vi.format = t.format;
    // A sampler reads one aspect: depth for depth(/stencil) formats.
    VkImageAspectFlags aspect = t.aspect;
    if (aspect & VK_IMAGE_ASPECT_DEPTH_BIT) aspect = VK_IMAGE_ASPECT_DEPTH_BIT;
    vi.subresourceRange = {aspect, range.base_mip, range.mip_count, range.base_layer, range.layer_count};
    VkImageView view = VK_NULL_HANDLE;
    if (VkResult r = vkCreateImageView(context_->device(), &vi, nullptr, &view); r != VK_SUCCESS) {
        return vk_error(r, std::string("vkCreateImageView (") + (storage ? "storage" : "sampled") + " view of texture " + in_quotes(t.desc.name) +
                               ", mips " + std::to_string(range.base_mip) + "+" + std::to_string(range.mip_count) + ", layers " +
                               std::to_string(range.base_layer) + "+" + std::to_string(range.layer_count) + ")");
    }
    t.range_views.emplace(key, view);
    return view;
}

std::optional<std::string> VulkanDevice::alias_owner_of(rhi::HeapHandle handle, uint64_t offset, uint64_t size, uint64_t stamp,
                                                       const void* self) {
    Heap* heap = heaps_.find(handle);
    if (!heap) return std::nullopt;
    // Textures and buffers of a heap hand its bytes to each other alike: the latest user of
    // overlapping bytes, if it came after `stamp`, owns them.
    uint64_t best = stamp;
    std::optional<std::string> owner;
    auto consider = [&](const void* other, uint64_t other_offset, uint64_t other_size, uint64_t other_stamp, const char* kind,
                        const std::string& name) {
        if (other == self || other_stamp <= best) return;
        if (other_offset < offset + size && offset < other_offset + other_size) {
            best = other_stamp;
            owner = std::string(kind) + " " + in_quotes(name);
        }
    };
    for (rhi::TextureHandle h : heap->placed) {
        if (const Texture* other = textures_.find(h)) consider(other, other->heap_offset, other->heap_size, other->alias_stamp, "texture", other->desc.name);
    }
    for (rhi::BufferHandle h : heap->placed_buffers) {
        if (const Buffer* other = buffers_.find(h)) consider(other, other->heap_offset, other->heap_size, other->alias_stamp, "buffer", other->desc.name);
    }
    return owner;
}

std::optional<std::string> VulkanDevice::alias_owner(const Texture& t) {
    if (!t.desc.placement) return std::nullopt;
    return alias_owner_of(t.desc.placement->heap, t.heap_offset, t.heap_size, t.alias_stamp, &t);
}

std::optional<std::string> VulkanDevice::alias_owner(const Buffer& b) {
    if (!b.desc.placement) return std::nullopt;
    return alias_owner_of(b.desc.placement->heap, b.heap_offset, b.heap_size, b.alias_stamp, &b);
}

void VulkanDevice::take_over_bytes(Buffer& b) {
    if (!b.desc.placement) return;
    if (alias_owner(b)) b.state = ResourceState::Undefined;
    if (Heap* heap = heaps_.find(b.desc.placement->heap)) b.alias_stamp = ++heap->stamp;
}

void VulkanDevice::transition_texture(BarrierBatch& batch, Texture& t, uint32_t mip, uint32_t mips, uint32_t layer,
                                      uint32_t layers, ResourceState to, Stream stream, bool discard) {
    if (t.desc.placement) {
        // The aliasing hand-over: when an overlapping texture used the bytes since this one
        // last did, whatever this one held is gone and its next barrier starts from UNDEFINED.
        if (alias_owner(t)) {
            std::fill(t.states.begin(), t.states.end(), ResourceState::Undefined);
            std::fill(t.frame_start_states.begin(), t.frame_start_states.end(), ResourceState::Undefined);
        }
        if (Heap* heap = heaps_.find(t.desc.placement->heap)) t.alias_stamp = ++heap->stamp;
    }
    std::vector<ResourceState>* states = &t.states;
    if (stream == Stream::Frame) {
        if (frame_recording() && t.touched_epoch != epoch_) {
            t.frame_start_states = t.states;
            t.touched_epoch = epoch_;
        }
    } else if (frame_recording() && t.touched_epoch == epoch_) {
        // The frame recorded so far runs after this setup work: start from (and update) the
        // states the frame's commands expect to find.
        states = &t.frame_start_states;
    }
    for (uint32_t m = mip; m < mip + mips; ++m) {
        // One barrier per run of layers that share an old state.
        uint32_t l = layer;
        while (l < layer + layers) {
            const ResourceState from = (*states)[t.subresource(m, l)];
            uint32_t end = l + 1;
            while (end < layer + layers && (*states)[t.subresource(m, end)] == from) ++end;
            batch.image(t.image, {t.aspect, m, 1, l, end - l}, from, to, t.depth_stencil, discard);
            for (uint32_t i = l; i < end; ++i) (*states)[t.subresource(m, i)] = to;
            l = end;
        }
    }
}

ResourceState VulkanDevice::tracked_state(const Texture& t, uint32_t subresource, Stream stream) const {
    const bool frame_view = stream == Stream::Setup && frame_recording() && t.touched_epoch == epoch_;
    return (frame_view ? t.frame_start_states : t.states)[subresource];
}

bool VulkanDevice::texture_all_in(const Texture& t, ResourceState state) {
    return std::all_of(t.states.begin(), t.states.end(), [&](ResourceState s) { return s == state; });
}

bool VulkanDevice::range_all_in(const Texture& t, const rhi::TextureRange& range, ResourceState state, ResourceState* first_other) {
    for (uint32_t m = range.base_mip; m < range.base_mip + range.mip_count; ++m) {
        for (uint32_t l = range.base_layer; l < range.base_layer + range.layer_count; ++l) {
            const ResourceState s = t.states[t.subresource(m, l)];
            if (s != state) {
                if (first_other) *first_other = s;
                return false;
            }
        }
    }
    return true;
}

loom::Result<rhi::TextureDesc> VulkanDevice::texture_desc(rhi::TextureHandle handle) {
    auto t = textures_.get(handle);
    if (!t.ok()) return t.take_error();
    return (*t)->desc;
}

loom::Result<rhi::BufferDesc> VulkanDevice::buffer_desc(rhi::BufferHandle handle) {
    auto b = buffers_.get(handle);
    if (!b.ok()) return b.take_error();
    return (*b)->desc;
}

loom::Status VulkanDevice::destroy(rhi::TextureHandle handle) {
    auto t = textures_.get(handle);
    if (!t.ok()) return t.take_error();
    if ((*t)->swapchain) return Error{ErrorCode::InvalidArgument, "the backbuffer belongs to the swapchain and cannot be destroyed"};
    auto removed = textures_.remove(handle);
    Texture& texture = *removed;
    if (texture.desc.placement) {
        if (Heap* heap = heaps_.find(texture.desc.placement->heap)) {
            --heap->placed_textures;
            std::erase(heap->placed, handle);
        }
    }
    release_texture(texture);
    return {};
}

// ---- heaps -------------------------------------------------------------------------------------

VkBufferCreateInfo VulkanDevice::buffer_create_info(const rhi::BufferDesc& desc) const {
    auto info = vk_init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = desc.size;
    info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    if (rhi::has_all(desc.usage, rhi::BufferUsage::Vertex)) info.usage |= VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    if (rhi::has_all(desc.usage, rhi::BufferUsage::Index)) info.usage |= VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    if (rhi::has_all(desc.usage, rhi::BufferUsage::Uniform)) info.usage |= VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    if (rhi::has_all(desc.usage, rhi::BufferUsage::Storage)) info.usage |= VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    if (rhi::has_all(desc.usage, rhi::BufferUsage::Indirect)) info.usage |= VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    return info;
}

rhi::MemoryRequirements VulkanDevice::placed_buffer_requirements(const VkMemoryRequirements& mr) const {
    // Linear and optimal resources closer than bufferImageGranularity alias each other in the
    // eyes of the spec; aligning start and size to it keeps neighbours that do not overlap apart.
    const uint64_t granularity = std::max<uint64_t>(1, context_->properties().limits.bufferImageGranularity);
    const uint64_t alignment = std::max<uint64_t>(mr.alignment, granularity);
    const uint64_t size = (mr.size + granularity - 1) / granularity * granularity;
    return rhi::MemoryRequirements{size, alignment};
}

loom::Result<rhi::MemoryRequirements> VulkanDevice::buffer_memory_requirements(const rhi::BufferDesc& desc) {
    LOOM_TRY(rhi::validation::buffer_memory_query(desc));
    const VkBufferCreateInfo info = buffer_create_info(desc);
    auto query = vk_init<VkDeviceBufferMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS);
    query.pCreateInfo = &info;
    auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
    vkGetDeviceBufferMemoryRequirements(context_->device(), &query, &req);
    return placed_buffer_requirements(req.memoryRequirements);
}

void VulkanDevice::heap_requirements(uint32_t& type_bits, VkDeviceSize& alignment) const {
    // A memory type every attachment and sampled image can live in: the intersection over
    // representative colour and depth images ...
    type_bits = ~0u;
    alignment = 1;
    const rhi::Format formats[] = {rhi::Format::RGBA8Unorm, rhi::Format::RGBA16Float, rhi::Format::Depth32F,
                                   rhi::Format::Depth24Stencil8};
    for (rhi::Format f : formats) {
        rhi::TextureDesc probe;
        probe.format = f;
        probe.width = probe.height = 64;
        probe.usage = rhi::format_info(f).is_color() ? rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled
                                                     : rhi::TextureUsage::DepthStencilAttachment | rhi::TextureUsage::Sampled;
        if (!caps_.format(f).sampled || (!caps_.format(f).color_attachment && !caps_.format(f).depth_stencil_attachment)) continue;
        const VkImageCreateInfo info = image_create_info(probe);
        auto query = vk_init<VkDeviceImageMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_IMAGE_MEMORY_REQUIREMENTS);
        query.pCreateInfo = &info;
        auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
        vkGetDeviceImageMemoryRequirements(context_->device(), &query, &req);
        type_bits &= req.memoryRequirements.memoryTypeBits;
        alignment = std::max(alignment, req.memoryRequirements.alignment);
    }
    // ... and buffers of every usage (each usage alone too: a driver may restrict one).
    const rhi::BufferUsage usages[] = {rhi::BufferUsage::Vertex | rhi::BufferUsage::Index | rhi::BufferUsage::Uniform |
                                           rhi::BufferUsage::Storage | rhi::BufferUsage::Indirect,
                                       rhi::BufferUsage::Vertex, rhi::BufferUsage::Index, rhi::BufferUsage::Uniform,
                                       rhi::BufferUsage::Storage, rhi::BufferUsage::Indirect, rhi::BufferUsage::None};
    for (rhi::BufferUsage usage : usages) {
        rhi::BufferDesc probe;
        probe.size = 64 * 1024;
        probe.usage = usage;
        const VkBufferCreateInfo info = buffer_create_info(probe);
        auto query = vk_init<VkDeviceBufferMemoryRequirements>(VK_STRUCTURE_TYPE_DEVICE_BUFFER_MEMORY_REQUIREMENTS);
        query.pCreateInfo = &info;
        auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
        vkGetDeviceBufferMemoryRequirements(context_->device(), &query, &req);
        type_bits &= req.memoryRequirements.memoryTypeBits;
        alignment = std::max(alignment, placed_buffer_requirements(req.memoryRequirements).alignment);
    }
}

loom::Result<rhi::HeapHandle> VulkanDevice::create_heap(const rhi::HeapDesc& desc) {
    LOOM_TRY(rhi::validation::heap_desc(desc, caps_));
    uint32_t type_bits = 0;
    VkDeviceSize alignment = 1;
    heap_requirements(type_bits, alignment);
    if (type_bits == 0) {
        return Error{ErrorCode::Unsupported, "heap " + in_quotes(desc.name) + ": no memory type fits colour and depth images and buffers"};
    }
    AllocationRequest request;
    request.requirements = {desc.size, alignment, type_bits};
    request.preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    request.kind = ResourceKind::Image;
    request.dedicated = true;
    auto memory = allocator_->allocate(request);
    if (!memory.ok()) {
        Error e = memory.take_error();
        e.message = "heap " + in_quotes(desc.name) + ": " + e.message;
        return e;
    }
    context_->set_name(VK_OBJECT_TYPE_DEVICE_MEMORY, reinterpret_cast<uint64_t>(memory->memory), desc.name);
    Heap heap;
    heap.desc = desc;
    heap.memory = *memory;
    return heaps_.insert(std::move(heap));
}

loom::Status VulkanDevice::destroy(rhi::HeapHandle handle) {
    auto h = heaps_.get(handle);
    if (!h.ok()) return h.take_error();
    const Heap& live = **h;
    if (live.placed_textures > 0 || !live.placed_buffers.empty()) {
        std::string held;
        if (live.placed_textures > 0) held = std::to_string(live.placed_textures) + " placed texture(s)";
        if (!live.placed_buffers.empty()) {
            held += (held.empty() ? "" : " and ") + std::to_string(live.placed_buffers.size()) + " placed buffer(s)";
        }
        return Error{ErrorCode::InvalidState, "heap " + in_quotes(live.desc.name) + " still holds " + held + "; destroy them first"};
    }
    auto heap = heaps_.remove(handle);
    MemoryAllocation memory = heap->memory;
    MemoryAllocator* allocator = allocator_.get();
    submissions_->defer([allocator, memory] { allocator->free(memory); });
    return {};
}

// ---- buffers -----------------------------------------------------------------------------------

loom::Result<rhi::BufferHandle> VulkanDevice::create_buffer(const rhi::BufferDesc& desc) { return create_buffer_internal(desc, false); }

loom::Result<rhi::BufferHandle> VulkanDevice::create_buffer_internal(const rhi::BufferDesc& desc, bool internal) {
    LOOM_TRY(rhi::validation::buffer_desc(desc, caps_));
    const std::string buf = "buffer " + in_quotes(desc.name);
    Heap* heap = nullptr;
    if (desc.placement) {
        auto h = heaps_.get(desc.placement->heap);
        if (!h.ok()) return Error{ErrorCode::InvalidArgument, buf + ": placement heap: " + h.error().message};
        heap = *h;
    }
    const VkBufferCreateInfo info = buffer_create_info(desc);
    Buffer b;
    b.desc = desc;
    b.internal = internal;
    VkDevice device = context_->device();
    if (VkResult r = vkCreateBuffer(device, &info, nullptr, &b.buffer); r != VK_SUCCESS) return vk_error(r, "vkCreateBuffer for " + buf);
    context_->set_name(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(b.buffer), desc.name);
    auto req_info = vk_init<VkBufferMemoryRequirementsInfo2>(VK_STRUCTURE_TYPE_BUFFER_MEMORY_REQUIREMENTS_INFO_2);
    req_info.buffer = b.buffer;
    auto dedicated = vk_init<VkMemoryDedicatedRequirements>(VK_STRUCTURE_TYPE_MEMORY_DEDICATED_REQUIREMENTS);
    auto req = vk_init<VkMemoryRequirements2>(VK_STRUCTURE_TYPE_MEMORY_REQUIREMENTS_2);
    req.pNext = &dedicated;
    vkGetBufferMemoryRequirements2(device, &req_info, &req);

    if (heap) {
        const VkMemoryRequirements& mr = req.memoryRequirements;
        const rhi::MemoryRequirements placed = placed_buffer_requirements(mr);
        auto fail = [&](Error e) -> Error {
            vkDestroyBuffer(device, b.buffer, nullptr);
            return e;
        };
        if (Status where = rhi::validation::buffer_placement(desc, heap->desc, placed); !where.ok()) return fail(where.take_error());
        const std::string placed_in = buf + " placed in heap " + in_quotes(heap->desc.name) + ": ";
        if (!(mr.memoryTypeBits & (1u << heap->memory.memory_type))) {
            return fail(Error{ErrorCode::Unsupported,
                              placed_in + "the buffer cannot live in the heap's memory type " + std::to_string(heap->memory.memory_type)});
        }
        if (dedicated.requiresDedicatedAllocation) {
            return fail(Error{ErrorCode::Unsupported, placed_in + "the driver requires a dedicated allocation for this buffer"});
        }
        const uint64_t offset = desc.placement->offset;
        if (VkResult r = vkBindBufferMemory(device, b.buffer, heap->memory.memory, heap->memory.offset + offset); r != VK_SUCCESS) {
            vkDestroyBuffer(device, b.buffer, nullptr);
            return vk_error(r, "vkBindBufferMemory for " + buf);
        }
        b.heap_offset = offset;
        b.heap_size = placed.size;
        const rhi::BufferHandle handle = buffers_.insert(std::move(b));
        heap->placed_buffers.push_back(handle);
        return handle;
    }

    AllocationRequest request;
    request.requirements = req.memoryRequirements;
    // Transient uniform rings are written by the CPU directly; other buffers go through staging.
    request.required = internal ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : 0;
    request.preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    request.kind = ResourceKind::Buffer;
    request.dedicated = dedicated.requiresDedicatedAllocation || dedicated.prefersDedicatedAllocation;
    if (request.dedicated) request.dedicated_buffer = b.buffer;
    auto memory = allocator_->allocate(request);
    if (!memory.ok()) {
        vkDestroyBuffer(device, b.buffer, nullptr);
        Error e = memory.take_error();
        e.message = buf + ": " + e.message;
        return e;
    }
    b.memory = *memory;
    if (VkResult r = vkBindBufferMemory(device, b.buffer, b.memory.memory, b.memory.offset); r != VK_SUCCESS) {
        allocator_->free(b.memory);
        vkDestroyBuffer(device, b.buffer, nullptr);
        return vk_error(r, "vkBindBufferMemory for " + buf);
    }
    return buffers_.insert(std::move(b));
}

void VulkanDevice::release_buffer(Buffer& b) {
    VkDevice device = context_->device();
    MemoryAllocator* allocator = allocator_.get();
    VkBuffer buffer = b.buffer;
    MemoryAllocation memory = b.memory;
    submissions_->defer([device, allocator, buffer, memory] {
        vkDestroyBuffer(device, buffer, nullptr);
        allocator->free(memory);
    });
    b.buffer = VK_NULL_HANDLE;
    b.memory = {};
}

loom::Status VulkanDevice::destroy(rhi::BufferHandle handle) {
    auto b = buffers_.get(handle);
    if (!b.ok()) return b.take_error();
    if ((*b)->internal) return Error{ErrorCode::InvalidArgument, "buffer " + in_quotes((*b)->desc.name) + " belongs to the backend"};
    auto removed = buffers_.remove(handle);
    if (removed->desc.placement) {
        if (Heap* heap = heaps_.find(removed->desc.placement->heap)) std::erase(heap->placed_buffers, handle);
    }
    release_buffer(*removed);
    return {};
}

// ---- samplers and shaders ----------------------------------------------------------------------

loom::Result<rhi::SamplerHandle> VulkanDevice::create_sampler(const rhi::SamplerDesc& d) {
    LOOM_TRY(rhi::validation::sampler_desc(d));
    const std::string name = "sampler " + in_quotes(d.name);
    auto info = vk_init<VkSamplerCreateInfo>(VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO);
    info.magFilter = to_vk(d.mag_filter);
    info.minFilter = to_vk(d.min_filter);
    info.mipmapMode = to_vk_mipmap(d.mipmap_filter);
    info.addressModeU = to_vk(d.address_u);
    info.addressModeV = to_vk(d.address_v);
    info.addressModeW = to_vk(d.address_w);
    info.minLod = d.min_lod;
    info.maxLod = d.max_lod;
    const float max_aniso = context_->properties().limits.maxSamplerAnisotropy;
    info.anisotropyEnable = d.max_anisotropy > 1.0f && context_->sampler_anisotropy();
    info.maxAnisotropy = std::min(d.max_anisotropy, max_aniso);
    info.compareEnable = d.compare.has_value();
    info.compareOp = d.compare ? to_vk(*d.compare) : VK_COMPARE_OP_ALWAYS;
    info.borderColor = to_vk(d.border);
    Sampler s;
    s.name = d.name;
    if (VkResult r = vkCreateSampler(context_->device(), &info, nullptr, &s.sampler); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateSampler for " + name);
    }
    context_->set_name(VK_OBJECT_TYPE_SAMPLER, reinterpret_cast<uint64_t>(s.sampler), d.name);
    return samplers_.insert(std::move(s));
}

loom::Status VulkanDevice::destroy(rhi::SamplerHandle handle) {
    auto s = samplers_.remove(handle);
    if (!s.ok()) return s.take_error();
    VkDevice device = context_->device();
    VkSampler sampler = s->sampler;
    submissions_->defer([device, sampler] { vkDestroySampler(device, sampler, nullptr); });
    return {};
}

loom::Result<rhi::ShaderHandle> VulkanDevice::create_shader(const rhi::ShaderModule& module) {
    const std::string name = "shader " + in_quotes(module.name);
    if (module.spirv.empty() || module.spirv.front() != 0x07230203u) {
        return Error{ErrorCode::InvalidArgument, name + ": no SPIR-V (the module must come from shader_compiler::ShaderCompiler)"};
    }
    auto info = vk_init<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    info.codeSize = module.spirv.size() * sizeof(uint32_t);
    info.pCode = module.spirv.data();
    Shader s;
    s.module.name = module.name;
    s.module.stage = module.stage;
    s.module.entry_point = module.entry_point;
    s.module.reflection = module.reflection;
    if (VkResult r = vkCreateShaderModule(context_->device(), &info, nullptr, &s.shader); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateShaderModule for " + name);
    }
    context_->set_name(VK_OBJECT_TYPE_SHADER_MODULE, reinterpret_cast<uint64_t>(s.shader), module.name);
    return shaders_.insert(std::move(s));
}

loom::Status VulkanDevice::destroy(rhi::ShaderHandle handle) {
    auto s = shaders_.remove(handle);
    if (!s.ok()) return s.take_error();
    VkDevice device = context_->device();
    VkShaderModule module = s->shader;
    submissions_->defer([device, module] { vkDestroyShaderModule(device, module, nullptr); });
    return {};
}

// ---- pipelines ---------------------------------------------------------------------------------

const rhi::validation::ResourceLookup& VulkanDevice::resource_lookup() {
    // Made once: every draw asks for it.
    if (!resource_lookup_.buffer) resource_lookup_ = rhi::validation::lookup_in(buffers_, textures_, samplers_);
    return resource_lookup_;
}

rhi::PipelineLookup VulkanDevice::pipeline_lookup() {
    return [this](rhi::PipelineHandle handle) -> loom::Result<rhi::PipelineFacts> {
        auto found = pipelines_.get(handle);
        if (!found.ok()) return found.take_error();
        const Pipeline& p = **found;
        return rhi::PipelineFacts{.name = p.name,
                                  .compute = p.bind_point == VK_PIPELINE_BIND_POINT_COMPUTE,
                                  .color_formats = p.color_formats,
                                  .depth_format = p.depth_format,
                                  .samples = p.samples,
                                  .vertex_buffers = p.vertex_buffer_count};
    };
}

rhi::validation::ShaderLookup VulkanDevice::shader_lookup() {
    return [this](rhi::ShaderHandle handle) -> loom::Result<rhi::validation::ShaderFacts> {
        auto found = shaders_.get(handle);
        if (!found.ok()) return found.take_error();
        const rhi::ShaderModule& module = (*found)->module;
        return rhi::validation::ShaderFacts{module.name, module.stage, &module.reflection};
    };
}

loom::Result<rhi::PipelineHandle> VulkanDevice::create_graphics_pipeline(const rhi::GraphicsPipelineDesc& desc) {
    LOOM_TRY(rhi::validation::graphics_pipeline(desc, caps_, shader_lookup()));
    // Both shaders were found by the validation above.
    auto vs = shaders_.get(desc.vertex);
    auto fs = shaders_.get(desc.fragment);
    const StageReflection stages[] = {{&(*vs)->module, VK_SHADER_STAGE_VERTEX_BIT}, {&(*fs)->module, VK_SHADER_STAGE_FRAGMENT_BIT}};
    auto layout = layouts_->get(stages, desc.name);
    if (!layout.ok()) return layout.take_error();

    Pipeline p;
    p.name = desc.name;
    p.key = graphics_pipeline_key(desc);
    p.layout = *layout;
    p.bind_point = VK_PIPELINE_BIND_POINT_GRAPHICS;
    p.color_formats = desc.color_formats;
    p.depth_format = desc.depth_format;
    p.samples = desc.samples;
    p.vertex_buffer_count = static_cast<uint32_t>(desc.vertex_buffers.size());
    CachedPipeline& entry = pipeline_cache_entries_[p.key];
    if (!entry.pipeline) {
        auto built = build_graphics_pipeline(*context_, pipeline_cache_, desc, **vs, **fs, **layout);
        if (!built.ok()) {
            pipeline_cache_entries_.erase(p.key);
            return built.take_error();
        }
        entry.pipeline = *built;
    }
    ++entry.users;
    p.pipeline = entry.pipeline;
    return pipelines_.insert(std::move(p));
}

loom::Result<rhi::PipelineHandle> VulkanDevice::create_compute_pipeline(const rhi::ComputePipelineDesc& desc) {
    LOOM_TRY(rhi::validation::compute_pipeline(desc, shader_lookup()));
    auto cs = shaders_.get(desc.compute);
    const StageReflection stages[] = {{&(*cs)->module, VK_SHADER_STAGE_COMPUTE_BIT}};
    auto layout = layouts_->get(stages, desc.name);
    if (!layout.ok()) return layout.take_error();
    Pipeline p;
    p.name = desc.name;
    p.key = compute_pipeline_key(desc);
    p.layout = *layout;
    p.bind_point = VK_PIPELINE_BIND_POINT_COMPUTE;
    CachedPipeline& entry = pipeline_cache_entries_[p.key];
    if (!entry.pipeline) {
        auto built = build_compute_pipeline(*context_, pipeline_cache_, desc, **cs, **layout);
        if (!built.ok()) {
            pipeline_cache_entries_.erase(p.key);
            return built.take_error();
        }
        entry.pipeline = *built;
    }
    ++entry.users;
    p.pipeline = entry.pipeline;
    return pipelines_.insert(std::move(p));
}

loom::Status VulkanDevice::destroy(rhi::PipelineHandle handle) {
    auto p = pipelines_.remove(handle);
    if (!p.ok()) return p.take_error();
    auto it = pipeline_cache_entries_.find(p->key);
    if (it != pipeline_cache_entries_.end() && --it->second.users == 0) {
        VkDevice device = context_->device();
        VkPipeline pipeline = it->second.pipeline;
        pipeline_cache_entries_.erase(it);
        submissions_->defer([device, pipeline] { vkDestroyPipeline(device, pipeline, nullptr); });
    }
    return {};
}

}  // namespace loom::vulkan
