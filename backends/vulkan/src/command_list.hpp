#pragma once
// rhi::CommandList on a Vulkan command buffer. Resource bindings are kept on the CPU and
// turned into descriptor sets at the draw or dispatch that needs them, once the pipeline
// (and so the descriptor types) is known. Misuse is recorded; the first error is returned
// by Device::end_frame().

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "loom/vulkan/resource_states.hpp"

namespace loom::vulkan {

class VulkanDevice;
struct Pipeline;
struct Texture;

class VulkanCommandList final : public rhi::CommandList {
public:
    explicit VulkanCommandList(VulkanDevice& device) : device_(device) {}

    /// Starts recording into `cmd` (a new frame or the continuation of a split one).
    void begin(VkCommandBuffer cmd, bool new_frame);
    /// Ends an open render pass / timer (recording errors) before the frame is submitted.
    void finish();
    /// The first error recorded since the frame began, then clears it.
    std::optional<Error> take_error();
    [[nodiscard]] bool inside_render_pass() const { return in_render_pass_; }
    [[nodiscard]] VkCommandBuffer command_buffer() const { return cmd_; }
    [[nodiscard]] const rhi::FrameStats& stats() const { return stats_; }
    /// Records misuse detected outside the list (e.g. by the device), returned by end_frame.
    void record_error(ErrorCode code, std::string message) { fail(code, std::move(message)); }
    /// Counts vkCmd* calls made by the device on this frame's command buffer.
    void count_api_calls(uint64_t calls) { stats_.api_calls += calls; }

    void begin_render_pass(const rhi::RenderPassDesc& desc) override;
    void end_render_pass() override;
    void set_pipeline(rhi::PipelineHandle pipeline) override;
    void set_viewport(const rhi::Viewport& viewport) override;
    void set_scissor(const rhi::Rect& rect) override;
    void set_bind_group(uint32_t set, const rhi::BindGroup& group) override;
    void push_constants(std::span<const std::byte> data, uint32_t offset = 0) override;
    void set_vertex_buffer(uint32_t slot, rhi::BufferHandle buffer, uint64_t offset = 0) override;
    void set_index_buffer(rhi::BufferHandle buffer, rhi::IndexType type, uint64_t offset = 0) override;
    rhi::BufferBinding transient_uniforms(std::span<const std::byte> data) override;
    void draw(uint32_t vertex_count, uint32_t instance_count = 1, uint32_t first_vertex = 0,
              uint32_t first_instance = 0) override;
    void draw_indexed(uint32_t index_count, uint32_t instance_count = 1, uint32_t first_index = 0,
                      int32_t base_vertex = 0, uint32_t first_instance = 0) override;
    void dispatch(uint32_t groups_x, uint32_t groups_y = 1, uint32_t groups_z = 1) override;
    void draw_indexed_indirect(rhi::BufferHandle buffer, uint64_t offset, uint32_t draw_count,
                               uint32_t stride = sizeof(rhi::DrawIndexedIndirectCommand)) override;
    void copy_buffer(rhi::BufferHandle src, uint64_t src_offset, rhi::BufferHandle dst, uint64_t dst_offset,
                     uint64_t size) override;
    void copy_texture(const rhi::TextureCopy& copy) override;
    void transition(rhi::TextureHandle texture, rhi::ResourceState state) override;
    void transition(rhi::BufferHandle buffer, rhi::ResourceState state) override;
    void begin_timer(std::string_view label) override;
    void end_timer() override;
    void push_debug_group(std::string_view label) override;
    void pop_debug_group() override;

private:
    void fail(ErrorCode code, std::string message);
    bool require_outside_pass(std::string_view what);
    bool require_inside_pass(std::string_view what);
    /// Binds the pipeline's descriptor sets and push constants if anything changed.
    bool flush_bindings(VkPipelineBindPoint bind_point, std::string_view what);
    bool write_set(uint32_t set, VkDescriptorSet& out, std::string_view what);
    bool prepare_draw(std::string_view what);
    /// The pipeline's attachment formats and samples are those of the open render pass.
    bool matches_pass(const Pipeline& pipeline) const;
    std::string pass_mismatch(const Pipeline& pipeline) const;

    VulkanDevice& device_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::optional<Error> error_;
    rhi::FrameStats stats_;

    // render pass
    bool in_render_pass_ = false;
    std::string pass_label_;
    std::vector<rhi::Format> pass_color_formats_;
    rhi::Format pass_depth_format_ = rhi::Format::Undefined;
    uint32_t pass_samples_ = 1;
    VkExtent2D pass_extent_{};

    // bound state
    rhi::PipelineHandle pipeline_handle_;
    const Pipeline* pipeline_ = nullptr;
    struct GroupState {
        std::optional<rhi::BindGroup> group;
        bool dirty = false;
    };
    std::array<GroupState, rhi::kMaxBindGroups> groups_{};
    VkPipelineLayout bound_layout_ = VK_NULL_HANDLE;
    std::array<std::byte, rhi::kMaxPushConstantBytes> push_data_{};
    uint32_t push_size_ = 0;  ///< bytes of push_data_ set so far
    bool push_dirty_ = false;
    struct VertexBinding {
        rhi::BufferHandle buffer;
        uint64_t offset = 0;
    };
    std::array<VertexBinding, rhi::kMaxVertexBuffers> vertex_buffers_{};
    rhi::BufferHandle index_buffer_;
    rhi::IndexType index_type_ = rhi::IndexType::Uint32;
    uint64_t index_offset_ = 0;
    VkPipeline bound_graphics_ = VK_NULL_HANDLE;
    VkPipeline bound_compute_ = VK_NULL_HANDLE;

    // timers and debug groups
    bool timer_open_ = false;
    int debug_depth_ = 0;
};

}  // namespace loom::vulkan
