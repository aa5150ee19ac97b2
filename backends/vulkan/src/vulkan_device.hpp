#pragma once
// The Vulkan implementation of rhi::Device.

#include <array>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command_list.hpp"
#include "descriptors.hpp"
#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/handle_pool.hpp"
#include "loom/rhi/validation.hpp"
#include "loom/vulkan/context.hpp"
#include "loom/vulkan/memory_allocator.hpp"
#include "loom/vulkan/resource_states.hpp"
#include "loom/vulkan/vulkan_embed.hpp"
#include "objects.hpp"
#include "staging_ring.hpp"
#include "submissions.hpp"
#include "swapchain.hpp"

namespace loom::vulkan {

inline constexpr uint32_t kFramesInFlight = 2;
inline constexpr uint32_t kMaxTimersPerFrame = 32;

/// Everything one frame in flight owns; reused when that frame's submission has completed.
struct FrameSlot {
    VkCommandPool command_pool = VK_NULL_HANDLE;
    std::vector<VkCommandBuffer> command_buffers;  ///< a frame split by a readback uses several
    std::size_t used_command_buffers = 0;
    uint64_t serial = 0;  ///< last submission of this frame
    std::unique_ptr<FrameDescriptorPools> descriptors;
    rhi::BufferHandle uniform_ring;
    std::byte* uniform_ring_data = nullptr;  ///< the ring's persistent mapping (no lookup per draw)
    uint64_t uniform_ring_size = 0;
    uint64_t uniform_ring_offset = 0;
    VkQueryPool timestamps = VK_NULL_HANDLE;
    std::vector<std::string> timer_labels;  ///< timer i uses queries 2i and 2i+1
    bool timers_pending = false;            ///< results not read yet
    VkSemaphore image_available = VK_NULL_HANDLE;
    /// Binary semaphores between the frame's queue batches (CommandList::signal_queue), reused
    /// once the frame has finished: every one signalled was waited by then (join_queues).
    std::vector<VkSemaphore> queue_semaphores;
    std::size_t used_queue_semaphores = 0;
};

/// Which command stream a texture state change belongs to (see Texture::frame_start_states).
enum class Stream : uint8_t { Frame, Setup };

class VulkanDevice final : public rhi::Device {
public:
    static loom::Result<std::unique_ptr<rhi::Device>> create(const rhi::DeviceDesc& desc);
    /// A device on the application's Vulkan objects (loom/vulkan/vulkan_embed.hpp).
    static loom::Result<std::unique_ptr<rhi::Device>> create_external(const ExternalDeviceDesc& desc);
    ~VulkanDevice() override;

    [[nodiscard]] rhi::Backend backend() const override { return rhi::Backend::Vulkan; }
    [[nodiscard]] const rhi::Capabilities& capabilities() const override { return caps_; }

    loom::Result<rhi::TextureHandle> create_texture(const rhi::TextureDesc& desc) override;
    loom::Result<rhi::BufferHandle> create_buffer(const rhi::BufferDesc& desc) override;
    loom::Result<rhi::SamplerHandle> create_sampler(const rhi::SamplerDesc& desc) override;
    loom::Result<rhi::ShaderHandle> create_shader(const rhi::ShaderModule& module) override;
    loom::Result<rhi::PipelineHandle> create_graphics_pipeline(const rhi::GraphicsPipelineDesc& desc) override;
    loom::Result<rhi::PipelineHandle> create_compute_pipeline(const rhi::ComputePipelineDesc& desc) override;
    loom::Result<rhi::HeapHandle> create_heap(const rhi::HeapDesc& desc) override;
    loom::Result<rhi::MemoryRequirements> texture_memory_requirements(const rhi::TextureDesc& desc) override;
    loom::Result<rhi::MemoryRequirements> buffer_memory_requirements(const rhi::BufferDesc& desc) override;

    loom::Status destroy(rhi::TextureHandle texture) override;
    loom::Status destroy(rhi::BufferHandle buffer) override;
    loom::Status destroy(rhi::SamplerHandle sampler) override;
    loom::Status destroy(rhi::ShaderHandle shader) override;
    loom::Status destroy(rhi::PipelineHandle pipeline) override;
    loom::Status destroy(rhi::HeapHandle heap) override;

    loom::Result<rhi::TextureDesc> texture_desc(rhi::TextureHandle texture) override;
    loom::Result<rhi::BufferDesc> buffer_desc(rhi::BufferHandle buffer) override;

    loom::Status write_buffer(rhi::BufferHandle buffer, uint64_t offset, std::span<const std::byte> data) override;
    loom::Status write_texture(rhi::TextureHandle texture, const rhi::TextureRegion& region,
                               std::span<const std::byte> data) override;
    loom::Result<rhi::Image> read_texture(rhi::TextureHandle texture, uint32_t mip, uint32_t layer) override;
    loom::Result<std::vector<std::byte>> read_buffer(rhi::BufferHandle buffer, uint64_t offset, uint64_t size) override;

    rhi::CommandList& begin_frame() override;
    loom::Status end_frame() override;
    loom::Status wait_idle() override;
    std::vector<rhi::TimerResult> timer_results() override;

    [[nodiscard]] rhi::ResourceStats resource_stats() const override;
    [[nodiscard]] rhi::FrameStats last_frame_stats() const override { return last_frame_stats_; }

    bool poll_window() override;
    [[nodiscard]] rhi::Extent3D window_size() const override;
    [[nodiscard]] const rhi::WindowInput& window_input() const override;
    rhi::TextureHandle backbuffer() override;

    // ---- embedding (device_embed.cpp, loom/vulkan/vulkan_embed.hpp) ---------------------------
    loom::Result<rhi::CommandList*> begin_external_frame(VkCommandBuffer cmd);
    loom::Result<FrameSignal> external_frame_signal() const;
    loom::Result<rhi::TextureHandle> import_image(const ExternalImage& image);
    loom::Status set_image_layout(rhi::TextureHandle texture, VkImageLayout layout);
    loom::Result<VkImageLayout> image_layout(rhi::TextureHandle texture);
    loom::Result<VkImage> image(rhi::TextureHandle texture);
    /// True while a frame recorded into an application command buffer is open.
    [[nodiscard]] bool recording_external_frame() const { return frame_recording() && external_frame_; }

    // ---- for the command list ---------------------------------------------------------------
    [[nodiscard]] VulkanContext& context() { return *context_; }
    /// The buffers, textures and samplers of this device as the validation layer sees them.
    const rhi::validation::ResourceLookup& resource_lookup();
    /// The pipelines of this device as the command-list state sees them.
    rhi::PipelineLookup pipeline_lookup();
    rhi::HandlePool<rhi::TextureTag, Texture>& textures() { return textures_; }
    rhi::HandlePool<rhi::BufferTag, Buffer>& buffers() { return buffers_; }
    rhi::HandlePool<rhi::SamplerTag, Sampler>& samplers() { return samplers_; }
    rhi::HandlePool<rhi::PipelineTag, Pipeline>& pipelines() { return pipelines_; }
    FrameSlot& current_frame() { return frames_[frame_index_ % kFramesInFlight]; }

    /// Moves subresources [mip, mip+mips) x [layer, layer+layers) of `texture` to `to` in the
    /// given stream, adding the barriers to `batch`. With `discard`, old contents are dropped.
    void transition_texture(BarrierBatch& batch, Texture& texture, uint32_t mip, uint32_t mips, uint32_t layer,
                            uint32_t layers, rhi::ResourceState to, Stream stream, bool discard = false);
    /// The tracked state of every subresource is `state` (in the frame stream).
    static bool texture_all_in(const Texture& texture, rhi::ResourceState state);
    /// The tracked state of every subresource in the (resolved) `range` is `state`; `first_other`
    /// gets the state of the first one that is not.
    static bool range_all_in(const Texture& texture, const rhi::TextureRange& range, rhi::ResourceState state,
                             rhi::ResourceState* first_other = nullptr);
    /// For a placed texture or buffer: the placed resource overlapping its bytes that was used
    /// after it, the latest ("texture 'x'", "buffer 'y'"; so its contents are gone), or nothing.
    std::optional<std::string> alias_owner(const Texture& texture);
    std::optional<std::string> alias_owner(const Buffer& buffer);
    /// A placed buffer is about to be used: when another alias used its bytes since it did, its
    /// contents are gone and its tracked state restarts from Undefined (the next barrier orders
    /// it after everything before); then it owns the bytes. Nothing for other buffers.
    void take_over_bytes(Buffer& buffer);
    /// The tracked state of one subresource as seen by `stream`.
    rhi::ResourceState tracked_state(const Texture& texture, uint32_t subresource, Stream stream) const;

    /// Image view of one mip/layer for an attachment.
    loom::Result<VkImageView> attachment_view(Texture& texture, uint32_t mip, uint32_t layer);
    /// Image view of a (resolved) subresource range as the shader declares it (`kind`), for
    /// sampling or, with `storage`, as a storage image (one mip); made on first use and kept
    /// until the texture goes. The whole texture seen as its own dimension is its sampled view.
    loom::Result<VkImageView> range_view(Texture& texture, const rhi::TextureRange& range, rhi::TextureKind kind, bool storage);

    /// Copies `data` into this frame's uniform ring (growing it if needed).
    loom::Result<rhi::BufferBinding> allocate_transient_uniforms(std::span<const std::byte> data) {
        // The command list has checked that a frame is being recorded. Inline: per draw for
        // per-draw uniform data, and nearly always the ring has room.
        FrameSlot& slot = current_frame();
        const uint64_t alignment = std::max<uint64_t>(caps_.uniform_buffer_offset_alignment, 16);
        const uint64_t size = std::max<uint64_t>(data.size(), 16);
        uint64_t offset = checked::align_up_in_range(slot.uniform_ring_offset, alignment);
        if (offset + size > slot.uniform_ring_size || !slot.uniform_ring_data) [[unlikely]] {
            LOOM_TRY(grow_uniform_ring(slot, size));
            offset = 0;
        }
        std::memcpy(slot.uniform_ring_data + offset, data.data(), data.size());
        slot.uniform_ring_offset = offset + size;
        return rhi::BufferBinding{slot.uniform_ring, offset, data.size()};
    }
    /// A ring of at least twice `size` bytes for `slot` (allocate_transient_uniforms found no room).
    loom::Status grow_uniform_ring(FrameSlot& slot, uint64_t size);

    /// Submits the frame's command buffer recorded so far and starts a new one, so that a
    /// readback in the middle of a frame sees the commands recorded before it.
    loom::Status split_frame();

    // ---- queues (device_queues.cpp): the frame's commands as batches, each submitted to the
    // graphics or the compute queue with the semaphores CommandList::signal_queue/wait_queue ask
    // for, in recording order. Frames recorded into an application's command buffer run in
    // order on its queue and need none of it.
    /// set_queue: submits the batch so far and continues on `queue`.
    loom::Status switch_queue(rhi::QueueType queue);
    /// signal_queue: submits the batch so far with a new semaphore (signal number `index`).
    loom::Status signal_queue(uint32_t index);
    /// wait_queue: submits the batch so far; the next one waits for signal `index`.
    loom::Status wait_queue(uint32_t index);
    [[nodiscard]] uint32_t min_uniform_alignment() const { return static_cast<uint32_t>(caps_.uniform_buffer_offset_alignment); }
    [[nodiscard]] uint32_t min_storage_alignment() const { return static_cast<uint32_t>(caps_.storage_buffer_offset_alignment); }
    [[nodiscard]] uint64_t max_uniform_range() const { return context_->properties().limits.maxUniformBufferRange; }
    [[nodiscard]] uint64_t frame_epoch() const { return epoch_; }
    /// A frame is being recorded (the command list's state says; none before it exists).
    [[nodiscard]] bool frame_recording() const { return command_list_ && command_list_->state().recording(); }

private:
    VulkanDevice() = default;
    loom::Status init(const rhi::DeviceDesc& desc);
    /// Everything after the context exists: allocator, pools, frames, capabilities.
    loom::Status init_device(const rhi::DeviceDesc& desc);
    void destroy_everything();

    // resources (device_resources.cpp)
    VkImageCreateInfo image_create_info(const rhi::TextureDesc& desc) const;
    /// The shaders of this device as the validation layer sees them.
    rhi::validation::ShaderLookup shader_lookup();
    loom::Result<rhi::TextureHandle> wrap_swapchain_image(VkImage image, VkFormat format, uint32_t width, uint32_t height,
                                                          uint32_t index);
    void release_texture(Texture& texture);
    void release_buffer(Buffer& buffer);
    /// The memory type bits and alignment a heap needs so that every texture and buffer loom
    /// places can live in it (probes of colour/depth images and of a buffer of every usage).
    void heap_requirements(uint32_t& type_bits, VkDeviceSize& alignment) const;
    /// The requirements of a buffer of `desc` inside a heap, rounded to bufferImageGranularity
    /// so that a buffer never shares a granularity page with a neighbouring image by accident.
    rhi::MemoryRequirements placed_buffer_requirements(const VkMemoryRequirements& requirements) const;
    VkBufferCreateInfo buffer_create_info(const rhi::BufferDesc& desc) const;
    std::optional<std::string> alias_owner_of(rhi::HeapHandle heap, uint64_t offset, uint64_t size, uint64_t stamp, const void* self);
    loom::Result<rhi::BufferHandle> create_buffer_internal(const rhi::BufferDesc& desc, bool internal);
    /// Where a host-visible buffer is mapped (null for a missing or unmapped one).
    std::byte* mapped_bytes(rhi::BufferHandle buffer) {
        const Buffer* b = buffers_.find(buffer);
        return b ? static_cast<std::byte*>(b->memory.mapped) : nullptr;
    }

    // transfers (device_transfer.cpp)
    VkCommandBuffer setup_commands();
    /// A staging span of `size` bytes, waiting for older submissions when the ring is full;
    /// for requests larger than the ring, a temporary buffer destroyed after use.
    loom::Result<StagingRing::Span> staging(VkDeviceSize size);
    loom::Status flush_setup();
    /// read_texture after its checks: copies one subresource out through staging.
    loom::Result<rhi::Image> read_subresource(Texture& texture, uint32_t mip, uint32_t layer);
    /// read_texture of a multisampled colour texture: resolves it into a temporary texture first.
    loom::Result<rhi::Image> read_resolved(rhi::TextureHandle texture);
    /// Submits the pending uploads and `frame_commands` (when `frame_part`, as the current frame's
    /// latest submission) to `queue`, waiting for `waits` and signalling `signals`. Uploads go
    /// before it (on a compute queue of its own, to the graphics queue first, waited for); the
    /// swapchain acquire wait goes only with a graphics submission.
    loom::Status submit(std::span<const VkCommandBuffer> frame_commands, bool frame_part,
                        std::span<const VkSemaphore> signals, std::span<const VkSemaphore> waits = {},
                        rhi::QueueType queue = rhi::QueueType::Graphics);
    void recycle_setup_buffers();

    // frames (device_frames.cpp)
    loom::Status begin_frame_commands();
    /// Waits for the frame that used the current slot and makes the slot ready to record; an
    /// error when that frame never finished (an application frame never submitted).
    loom::Status recycle_current_slot();
    /// end_frame of a frame recorded into an application command buffer (device_embed.cpp).
    loom::Status end_external_frame();
    void collect_timers(FrameSlot& slot);
    loom::Status acquire_backbuffer();
    loom::Status recreate_swapchain();

    // queues (device_queues.cpp)
    /// An unsignalled semaphore of the current frame slot.
    loom::Result<VkSemaphore> queue_semaphore();
    /// Ends the current command buffer and submits it to the batch's queue with its waits and
    /// `signals`; then starts the next command buffer (on `next` queue).
    loom::Status submit_batch(std::span<const VkSemaphore> signals, rhi::QueueType next);
    /// submit_batch signalling a new semaphore of the slot, which it returns.
    loom::Result<VkSemaphore> submit_batch_signalling(rhi::QueueType next);
    /// Before the frame's last submission: back on the graphics queue, with every semaphore of
    /// the frame waited and the compute queue's work joined into it.
    loom::Status join_queues();
    /// Forgets the frame's batches (a new frame starts on the graphics queue).
    void reset_queues();

    std::unique_ptr<Window> window_;  // destroyed after the context (the surface needs it)
    std::unique_ptr<VulkanContext> context_;
    std::unique_ptr<MemoryAllocator> allocator_;
    std::unique_ptr<SubmissionTracker> submissions_;
    std::unique_ptr<StagingRing> staging_;
    std::unique_ptr<LayoutCache> layouts_;
    std::unique_ptr<Swapchain> swapchain_;
    VkPipelineCache pipeline_cache_ = VK_NULL_HANDLE;
    rhi::Capabilities caps_;
    rhi::validation::ResourceLookup resource_lookup_;  ///< see resource_lookup()
    bool debug_ = false;

    uint16_t device_id_ = rhi::next_device_id();
    rhi::HandlePool<rhi::TextureTag, Texture> textures_{device_id_};
    rhi::HandlePool<rhi::BufferTag, Buffer> buffers_{device_id_};
    rhi::HandlePool<rhi::SamplerTag, Sampler> samplers_{device_id_};
    rhi::HandlePool<rhi::ShaderTag, Shader> shaders_{device_id_};
    rhi::HandlePool<rhi::PipelineTag, Pipeline> pipelines_{device_id_};
    rhi::HandlePool<rhi::HeapTag, Heap> heaps_{device_id_};

    struct CachedPipeline {
        VkPipeline pipeline = VK_NULL_HANDLE;
        uint32_t users = 0;
    };
    std::map<std::string, CachedPipeline> pipeline_cache_entries_;

    std::array<FrameSlot, kFramesInFlight> frames_;
    uint64_t frame_index_ = 0;
    uint64_t epoch_ = 1;  ///< advances whenever frame commands are submitted
    std::unique_ptr<VulkanCommandList> command_list_;
    rhi::FrameStats last_frame_stats_;
    std::vector<rhi::TimerResult> timer_results_;

    VkCommandPool setup_pool_ = VK_NULL_HANDLE;
    VkCommandBuffer setup_cmd_ = VK_NULL_HANDLE;
    bool setup_has_buffer_writes_ = false;
    struct UsedSetupBuffer {
        VkCommandBuffer cmd;
        uint64_t serial;
    };
    std::vector<UsedSetupBuffer> used_setup_buffers_;
    std::vector<VkCommandBuffer> free_setup_buffers_;
    uint64_t bytes_uploaded_ = 0;  ///< since the last frame began

    // frames recorded into application command buffers (device_embed.cpp)
    bool external_frame_ = false;                      ///< the open frame records into the application's buffer
    VkSemaphore frame_timeline_ = VK_NULL_HANDLE;      ///< signalled by the application's submissions
    uint64_t frame_timeline_value_ = 0;                ///< value of the latest external frame

    // windowed devices
    uint32_t backbuffer_index_ = UINT32_MAX;
    std::vector<rhi::TextureHandle> backbuffers_;
    VkSemaphore pending_wait_ = VK_NULL_HANDLE;  ///< acquire semaphore the next frame submission waits on

    // the frame's queue batches (device_queues.cpp)
    rhi::QueueType batch_queue_ = rhi::QueueType::Graphics;  ///< the queue of the command buffer recording
    std::vector<VkSemaphore> batch_waits_;     ///< what that command buffer's submission waits for
    struct BatchSignal {
        VkSemaphore semaphore = VK_NULL_HANDLE;
        rhi::QueueType queue = rhi::QueueType::Graphics;
        bool waited = false;
    };
    std::vector<BatchSignal> frame_signals_;   ///< per signal_queue of the frame
    bool compute_used_ = false;                ///< a batch of this frame went to the compute queue
    bool swapchain_dirty_ = false;
};

}  // namespace loom::vulkan
