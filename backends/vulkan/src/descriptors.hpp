#pragma once
// Descriptor set layouts built from the shaders' reflection (the union over the stages of a
// pipeline), pipeline layouts cached by their content, and descriptor pools per frame in
// flight that are reset when that frame's submission has completed.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::vulkan {

/// One binding of a set as the pipeline's shaders declare it.
struct SetBinding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    uint32_t count = 1;
    VkShaderStageFlags stages = 0;
    std::string name;  ///< the variable or block name, for error messages
    /// Textures and storage images: the declared dimension, which picks the image view type
    /// (not part of the layout: a sampler2D and a sampler2DArray are the same descriptor).
    rhi::TextureKind kind = rhi::TextureKind::Tex2D;
};

struct SetLayout {
    VkDescriptorSetLayout layout = VK_NULL_HANDLE;
    std::vector<SetBinding> bindings;  ///< sorted by binding
    /// Bindings of type UNIFORM_BUFFER_DYNAMIC: each takes a dynamic offset when the set is bound.
    uint32_t dynamic_count = 0;
};

struct PipelineLayout {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::array<const SetLayout*, rhi::kMaxBindGroups> sets{};  ///< empty layouts for unused sets below the last
    uint32_t set_count = 0;
    uint32_t push_constant_size = 0;
    VkShaderStageFlags push_constant_stages = 0;
};

/// A stage of a pipeline, for building its layout.
struct StageReflection {
    const rhi::ShaderModule* module = nullptr;
    VkShaderStageFlagBits stage = VK_SHADER_STAGE_VERTEX_BIT;
};

/// Owns every set layout and pipeline layout of a device (they live as long as it).
class LayoutCache {
public:
    /// `max_dynamic_uniform_buffers`: the device's maxDescriptorSetUniformBuffersDynamic.
    LayoutCache(VkDevice device, uint32_t max_dynamic_uniform_buffers)
        : device_(device), max_dynamic_uniform_buffers_(max_dynamic_uniform_buffers) {}
    ~LayoutCache();
    LayoutCache(const LayoutCache&) = delete;
    LayoutCache& operator=(const LayoutCache&) = delete;

    /// The layout of a pipeline made of `stages`. ShaderLink when two stages declare the same
    /// (set, binding) differently; Unsupported when a set or binding is beyond loom's limits.
    loom::Result<const PipelineLayout*> get(std::span<const StageReflection> stages, const std::string& pipeline_name);

    [[nodiscard]] std::size_t set_layout_count() const { return set_layouts_.size(); }
    [[nodiscard]] std::size_t pipeline_layout_count() const { return pipeline_layouts_.size(); }

private:
    loom::Result<const SetLayout*> get_set_layout(std::vector<SetBinding> bindings);

    VkDevice device_;
    uint32_t max_dynamic_uniform_buffers_;
    std::map<std::string, std::unique_ptr<SetLayout>> set_layouts_;
    std::map<std::string, std::unique_ptr<PipelineLayout>> pipeline_layouts_;
};

/// Descriptor pools of one frame in flight: sets are allocated during the frame and all
/// returned at once by reset() when the frame's submission has completed.
class FrameDescriptorPools {
public:
    explicit FrameDescriptorPools(VkDevice device) : device_(device) {}
    ~FrameDescriptorPools();
    FrameDescriptorPools(const FrameDescriptorPools&) = delete;
    FrameDescriptorPools& operator=(const FrameDescriptorPools&) = delete;

    loom::Result<VkDescriptorSet> allocate(VkDescriptorSetLayout layout);
    void reset();
    [[nodiscard]] std::size_t pool_count() const { return pools_.size(); }

private:
    loom::Status add_pool();

    VkDevice device_;
    std::vector<VkDescriptorPool> pools_;
    std::size_t current_ = 0;
};

}  // namespace loom::vulkan
