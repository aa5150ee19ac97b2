#include "descriptors.hpp"

#include <algorithm>

#include "loom/vulkan/context.hpp"

namespace loom::vulkan {
namespace {

std::string_view descriptor_type_name(VkDescriptorType type) {
    switch (type) {
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC: return "uniform buffer";
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER: return "storage buffer";
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER: return "sampled texture";
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE: return "storage image";
        default: return "descriptor";
    }
}

std::string set_layout_key(const std::vector<SetBinding>& bindings) {
    std::string key;
    for (const SetBinding& b : bindings) {
        // The declared texture kind is not part of the Vulkan layout, but the view each draw
        // makes is picked from the cached entry's bindings: layouts differing in it stay apart.
        key += std::to_string(b.binding) + ":" + std::to_string(b.type) + ":" + std::to_string(b.count) + ":" +
               std::to_string(b.stages) + ":" + std::to_string(static_cast<int>(b.kind)) + ";";
    }
    return key;
}

}  // namespace

LayoutCache::~LayoutCache() {
    for (auto& [key, layout] : pipeline_layouts_) vkDestroyPipelineLayout(device_, layout->layout, nullptr);
    for (auto& [key, layout] : set_layouts_) vkDestroyDescriptorSetLayout(device_, layout->layout, nullptr);
}

loom::Result<const SetLayout*> LayoutCache::get_set_layout(std::vector<SetBinding> bindings) {
    std::sort(bindings.begin(), bindings.end(), [](const SetBinding& a, const SetBinding& b) { return a.binding < b.binding; });
    const std::string key = set_layout_key(bindings);
    if (auto it = set_layouts_.find(key); it != set_layouts_.end()) return it->second.get();

    std::vector<VkDescriptorSetLayoutBinding> vk_bindings;
    for (const SetBinding& b : bindings) {
        VkDescriptorSetLayoutBinding vb{};
        vb.binding = b.binding;
        vb.descriptorType = b.type;
        vb.descriptorCount = b.count;
        vb.stageFlags = b.stages;
        vk_bindings.push_back(vb);
    }
    auto info = vk_init<VkDescriptorSetLayoutCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO);
    info.bindingCount = static_cast<uint32_t>(vk_bindings.size());
    info.pBindings = vk_bindings.data();
    auto layout = std::make_unique<SetLayout>();
    if (VkResult r = vkCreateDescriptorSetLayout(device_, &info, nullptr, &layout->layout); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateDescriptorSetLayout");
    }
    layout->bindings = std::move(bindings);
    for (const SetBinding& b : layout->bindings) layout->dynamic_count += b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC ? 1 : 0;
    const SetLayout* out = layout.get();
    set_layouts_.emplace(key, std::move(layout));
    return out;
}

loom::Result<const PipelineLayout*> LayoutCache::get(std::span<const StageReflection> stages,
                                                     const std::string& pipeline_name) {
    std::array<std::vector<SetBinding>, rhi::kMaxBindGroups> sets;
    uint32_t push_size = 0;
    VkShaderStageFlags push_stages = 0;

    auto add = [&](const StageReflection& stage, uint32_t set, uint32_t binding, VkDescriptorType type, uint32_t count,
                   const std::string& name, rhi::TextureKind kind = rhi::TextureKind::Tex2D) -> loom::Status {
        if (set >= rhi::kMaxBindGroups || binding >= rhi::kMaxBindingsPerGroup) {
            return Error{ErrorCode::Unsupported, "pipeline '" + pipeline_name + "': shader '" + stage.module->name + "' declares '" +
                                                     name + "' at set " + std::to_string(set) + " binding " +
                                                     std::to_string(binding) + "; loom supports sets < " +
                                                     std::to_string(rhi::kMaxBindGroups) + " and bindings < " +
                                                     std::to_string(rhi::kMaxBindingsPerGroup)};
        }
        for (SetBinding& existing : sets[set]) {
            if (existing.binding != binding) continue;
            if (existing.type != type || existing.count != count) {
                return Error{ErrorCode::ShaderLink, "pipeline '" + pipeline_name + "': set " + std::to_string(set) + " binding " +
                                                        std::to_string(binding) + " is a " +
                                                        std::string(descriptor_type_name(existing.type)) + " ('" + existing.name +
                                                        "') in one stage and a " + std::string(descriptor_type_name(type)) +
                                                        " ('" + name + "') in shader '" + stage.module->name + "'"};
            }
            existing.stages |= stage.stage;
            return {};
        }
        sets[set].push_back({binding, type, count, static_cast<VkShaderStageFlags>(stage.stage), name, kind});
        return {};
    };

    for (const StageReflection& stage : stages) {
        const rhi::ShaderReflection& r = stage.module->reflection;
        for (const auto& u : r.uniform_blocks) LOOM_TRY(add(stage, u.set, u.binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, u.name));
        for (const auto& s : r.storage_buffers) LOOM_TRY(add(stage, s.set, s.binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, s.name));
        for (const auto& t : r.textures) {
            LOOM_TRY(add(stage, t.set, t.binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, std::max(1u, t.array_size), t.name, t.kind));
        }
        for (const auto& i : r.storage_images) {
            LOOM_TRY(add(stage, i.set, i.binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, i.name, i.kind));
        }
        for (const auto& p : r.push_constants) {
            push_size = std::max(push_size, p.size);
            push_stages |= stage.stage;
        }
    }

    // Uniform buffers take dynamic offsets (as many as the device allows in a layout, in set
    // and binding order): per-draw uniform data at a new offset of the same buffer then binds
    // the set written before with another offset instead of writing a new one.
    uint32_t dynamic = 0;
    for (auto& set : sets) {
        std::sort(set.begin(), set.end(), [](const SetBinding& a, const SetBinding& b) { return a.binding < b.binding; });
        for (SetBinding& b : set) {
            if (b.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER && dynamic < max_dynamic_uniform_buffers_) {
                b.type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC;
                ++dynamic;
            }
        }
    }
    uint32_t set_count = 0;
    for (uint32_t s = 0; s < rhi::kMaxBindGroups; ++s) {
        if (!sets[s].empty()) set_count = s + 1;
    }
    auto layout = std::make_unique<PipelineLayout>();
    std::string key;
    for (uint32_t s = 0; s < set_count; ++s) {
        auto set_layout = get_set_layout(sets[s]);
        if (!set_layout.ok()) return set_layout.take_error();
        layout->sets[s] = *set_layout;
        key += std::to_string(reinterpret_cast<uintptr_t>(*set_layout)) + "|";
    }
    layout->set_count = set_count;
    layout->push_constant_size = (push_size + 3u) & ~3u;
    layout->push_constant_stages = push_stages;
    key += "pc" + std::to_string(layout->push_constant_size) + ":" + std::to_string(push_stages);
    if (auto it = pipeline_layouts_.find(key); it != pipeline_layouts_.end()) return it->second.get();

    std::array<VkDescriptorSetLayout, rhi::kMaxBindGroups> vk_sets{};
    for (uint32_t s = 0; s < set_count; ++s) vk_sets[s] = layout->sets[s]->layout;
    VkPushConstantRange range{push_stages, 0, layout->push_constant_size};
    auto info = vk_init<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    info.setLayoutCount = set_count;
    info.pSetLayouts = vk_sets.data();
    info.pushConstantRangeCount = layout->push_constant_size > 0 ? 1 : 0;
    info.pPushConstantRanges = &range;
    if (VkResult r = vkCreatePipelineLayout(device_, &info, nullptr, &layout->layout); r != VK_SUCCESS) {
        return vk_error(r, "vkCreatePipelineLayout for '" + pipeline_name + "'");
    }
    const PipelineLayout* out = layout.get();
    pipeline_layouts_.emplace(key, std::move(layout));
    return out;
}

FrameDescriptorPools::~FrameDescriptorPools() {
    for (VkDescriptorPool pool : pools_) vkDestroyDescriptorPool(device_, pool, nullptr);
}

loom::Status FrameDescriptorPools::add_pool() {
    constexpr uint32_t kSets = 256;
    const VkDescriptorPoolSize sizes[] = {
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSets * 4},
        {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, kSets * 4},
        {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kSets * 2},
        {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kSets * 4},
        {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, kSets},
    };
    auto info = vk_init<VkDescriptorPoolCreateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO);
    info.maxSets = kSets;
    info.poolSizeCount = static_cast<uint32_t>(std::size(sizes));
    info.pPoolSizes = sizes;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    if (VkResult r = vkCreateDescriptorPool(device_, &info, nullptr, &pool); r != VK_SUCCESS) {
        return vk_error(r, "vkCreateDescriptorPool");
    }
    pools_.push_back(pool);
    return {};
}

loom::Result<VkDescriptorSet> FrameDescriptorPools::allocate(VkDescriptorSetLayout layout) {
    for (;;) {
        if (current_ == pools_.size()) LOOM_TRY(add_pool());
        auto info = vk_init<VkDescriptorSetAllocateInfo>(VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO);
        info.descriptorPool = pools_[current_];
        info.descriptorSetCount = 1;
        info.pSetLayouts = &layout;
        VkDescriptorSet set = VK_NULL_HANDLE;
        const VkResult r = vkAllocateDescriptorSets(device_, &info, &set);
        if (r == VK_SUCCESS) return set;
        if (r != VK_ERROR_OUT_OF_POOL_MEMORY && r != VK_ERROR_FRAGMENTED_POOL) return vk_error(r, "vkAllocateDescriptorSets");
        ++current_;  // this pool is full: the next one (or a new one)
    }
}

void FrameDescriptorPools::reset() {
    for (VkDescriptorPool pool : pools_) vkResetDescriptorPool(device_, pool, 0);
    current_ = 0;
}

}  // namespace loom::vulkan
