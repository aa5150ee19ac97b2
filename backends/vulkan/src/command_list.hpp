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

#include "loom/rhi/command_list_state.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "descriptors.hpp"
#include "loom/vulkan/resource_states.hpp"

namespace loom::vulkan {

class VulkanDevice;
struct Pipeline;
struct Texture;

class VulkanCommandList final : public rhi::CommandList {
public:
    explicit VulkanCommandList(VulkanDevice& device);

    /// Starts recording into `cmd` (a new frame or the continuation of a split one).
    void begin(VkCommandBuffer cmd, bool new_frame);
    /// Ends what the frame left open (recording an error for the first) before it is submitted.
    void finish();
    /// The first error recorded since the frame began, then clears it.
    std::optional<Error> take_error();
    /// What is open and bound; also whether a frame is being recorded (the device begins and
    /// ends frames on it).
    [[nodiscard]] rhi::CommandListState& state() { return state_; }
    [[nodiscard]] const rhi::CommandListState& state() const { return state_; }
    [[nodiscard]] VkCommandBuffer command_buffer() const { return cmd_; }
    [[nodiscard]] const rhi::FrameStats& stats() const { return stats_; }
    /// Records misuse detected outside the list (e.g. by the device), returned by end_frame.
    void record_error(Error error) { fail(error.code, std::move(error.message)); }
    /// Counts vkCmd* calls made by the device on this frame's command buffer.
    void count_api_calls(uint64_t calls) { stats_.api_calls += calls; }

    void begin_render_pass(const rhi::RenderPassDesc& desc) override;
    void end_render_pass() override;
    void set_pipeline(rhi::PipelineHandle pipeline) override;
    void set_viewport(const rhi::Viewport& viewport) override;
    void set_scissor(const rhi::Rect& rect) override;
    void set_bind_group(uint32_t set, const rhi::BindGroup& group) override;
    void set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) override;
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
    void transition(rhi::TextureHandle texture, rhi::ResourceState state, const rhi::TextureRange& range) override;
    void transition(rhi::BufferHandle buffer, rhi::ResourceState state) override;
    void begin_timer(std::string_view label) override;
    void end_timer() override;
    void push_debug_group(std::string_view label) override;
    void pop_debug_group() override;
    void set_queue(rhi::QueueType queue) override;
    rhi::QueueSignal signal_queue() override;
    void wait_queue(rhi::QueueSignal signal) override;

private:
    void fail(ErrorCode code, std::string message);
    /// True when `status` is ok; else records its error (the command is then skipped).
    bool accepted(Status status) {
        if (status.ok()) [[likely]] return true;  // inline: most commands ask it
        const Error& e = status.error();
        fail(e.code, e.message);
        return false;
    }
    /// Binds the pipeline's descriptor sets and push constants if anything changed.
    bool flush_bindings(const Pipeline& pipeline, std::string_view what);
    /// Checks the group bound at `set` against the pipeline and writes a descriptor set for it
    /// (its dynamic offsets into dynamic_offsets_); remembered in written_[set].
    bool write_set(const Pipeline& pipeline, uint32_t set, VkDescriptorSet& out, std::string_view what);
    /// The set written last for `set` holds the group bound now but for the offsets of its
    /// dynamic uniform buffers (which fit their buffers): those offsets go to dynamic_offsets_.
    bool reuse_written_set(const SetLayout& layout, uint32_t set);
    /// Written sets are not bound again after a texture's state changed or an object was destroyed.
    void forget_written_sets();
    /// The state tracker's draw checks, then the bindings; the pipeline to draw with, or null.
    const Pipeline* prepare_draw(std::string_view what, bool indexed);
    /// Objects the device has destroyed so far (bindings and draw checks made before a
    /// destruction are made again: their objects may be gone).
    [[nodiscard]] uint64_t device_removals() const;
    /// After a destruction, forgets every draw check and written set (they are made again).
    void notice_removals();

    VulkanDevice& device_;
    rhi::CommandListState state_;
    VkCommandBuffer cmd_ = VK_NULL_HANDLE;
    std::optional<Error> error_;
    rhi::FrameStats stats_;

    // What the command buffer has bound, to skip binds that change nothing.
    std::array<bool, rhi::kMaxBindGroups> group_dirty_{};  ///< set_bind_group since the set was last written
    VkPipelineLayout bound_layout_ = VK_NULL_HANDLE;
    bool push_dirty_ = false;
    VkPipeline bound_graphics_ = VK_NULL_HANDLE;
    VkPipeline bound_compute_ = VK_NULL_HANDLE;
    /// The last draw's checks hold for the next one (indexed or not): no pipeline, vertex or
    /// index buffer bound, no render pass begun or ended, nothing destroyed since.
    const Pipeline* checked_pipeline_ = nullptr;
    bool checked_indexed_ = false;
    uint64_t checked_removals_ = 0;
    /// The descriptor set last written for each set number, its layout and the entries it was
    /// written from (one per layout binding, in its order), to be bound again with new dynamic
    /// offsets when only those changed.
    struct WrittenSet {
        VkDescriptorSet set = VK_NULL_HANDLE;
        const SetLayout* layout = nullptr;
        std::vector<rhi::BindingEntry> entries;
    };
    std::array<WrittenSet, rhi::kMaxBindGroups> written_{};
    std::vector<uint32_t> dynamic_offsets_;
    // Storage for write_set's descriptor writes, kept so that steady-state recording allocates nothing.
    std::vector<VkDescriptorBufferInfo> buffer_infos_;
    std::vector<VkDescriptorImageInfo> image_infos_;
    std::vector<VkWriteDescriptorSet> writes_;
    /// The open timer has a begin timestamp (there is none without timestamp queries, or past
    /// kMaxTimersPerFrame).
    bool timestamp_written_ = false;
};

}  // namespace loom::vulkan
