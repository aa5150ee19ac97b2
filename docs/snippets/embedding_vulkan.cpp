// docs/embedding.md, Vulkan: loom on the application's instance, device, queue and command
// buffers, compiled (samples/embed_vulkan and tests/embed run the same calls).
#include "embedding_graph.hpp"

// [docs:vk-includes]
#include "loom/framegraph/framegraph.hpp"
#include "loom/vulkan/vulkan_embed.hpp"
// [/docs:vk-includes]

namespace loom::docs {

/// The application's objects, as an engine keeps them.
struct Engine {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    VkQueue queue = VK_NULL_HANDLE;
    uint32_t queue_family = 0;
    VkPhysicalDeviceFeatures enabled_features{};
    VkImage color = VK_NULL_HANDLE;  ///< R8G8B8A8_UNORM, width x height
    uint32_t width = 0, height = 0;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
};

Result<std::unique_ptr<rhi::Device>> create_on(const Engine& engine) {
    // [docs:vk-device]
    vulkan::ExternalDeviceDesc desc;
    desc.instance = engine.instance;
    desc.physical_device = engine.physical_device;
    desc.device = engine.device;  // Vulkan 1.3: dynamicRendering, synchronization2, timelineSemaphore enabled
    desc.queue = engine.queue;    // a graphics + compute queue of queue_family
    desc.queue_family = engine.queue_family;
    desc.enabled_features = engine.enabled_features;  // loom uses the optional ones enabled here
    desc.debug_utils = true;  // the instance has VK_EXT_debug_utils: loom names objects and passes
    auto device = vulkan::create_vulkan_device_on(desc);
    // [/docs:vk-device]
    return device;
}

Result<rhi::TextureHandle> import_color(rhi::Device& device, const Engine& engine) {
    // [docs:vk-import]
    vulkan::ExternalImage image;
    image.name = "engine color";
    image.image = engine.color;
    image.format = VK_FORMAT_R8G8B8A8_UNORM;
    image.width = engine.width;
    image.height = engine.height;
    image.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    image.layout = VK_IMAGE_LAYOUT_UNDEFINED;  // every subresource's layout now
    auto texture = vulkan::import_vulkan_image(device, image);
    // [/docs:vk-import]
    return texture;
}

Status engine_frame(rhi::Device& device, fg::Executor& executor, fg::FrameGraph& graph, rhi::TextureHandle color,
                    const Engine& engine) {
    // [docs:vk-frame]
    // The engine began engine.cmd and cleared its image with its own commands, leaving it in
    // TRANSFER_DST_OPTIMAL: loom's barriers start from there.
    LOOM_TRY(vulkan::set_image_layout(device, color, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL));
    auto commands = vulkan::begin_external_frame(device, engine.cmd);
    if (!commands) return commands.take_error();
    // Handed back after its last use in the frame in TRANSFER_SRC_OPTIMAL (layout_for_state).
    executor.import_texture(fg::port("ui", "target"), color, rhi::ResourceState::CopySrc);
    fg::PlanOptions options;
    options.frame = {engine.width, engine.height};
    LOOM_TRY(executor.execute(graph, **commands, options));  // recorded into engine.cmd
    LOOM_TRY(device.end_frame());  // neither ends nor submits engine.cmd; submits the frame's uploads
    auto signal = vulkan::external_frame_signal(device);
    if (!signal) return signal.take_error();

    // The engine's part again: more commands (a copy of the image, say), then its submission,
    // which signals loom's timeline value so that loom can reuse the frame's resources.
    vkEndCommandBuffer(engine.cmd);
    VkCommandBufferSubmitInfo buffer{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO, nullptr, engine.cmd, 0};
    VkSemaphoreSubmitInfo loom_done{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, nullptr, signal->semaphore, signal->value,
                                    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, 0};
    VkSubmitInfo2 submit{};
    submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2;
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &buffer;
    submit.signalSemaphoreInfoCount = 1;
    submit.pSignalSemaphoreInfos = &loom_done;
    vkQueueSubmit2(engine.queue, 1, &submit, engine.fence);
    // [/docs:vk-frame]
    return {};
}

Status run_engine(Engine& engine) {
    auto device = create_on(engine);
    if (!device) return device.take_error();
    auto color = import_color(**device, engine);
    if (!color) return color.take_error();
    auto embedded = EmbeddingGraph::create(**device, rhi::Format::RGBA8Unorm);
    if (!embedded) return embedded.take_error();
    {
        fg::Executor executor(**device);
        LOOM_TRY(engine_frame(**device, executor, (*embedded)->graph, *color, engine));
    }
    // [docs:vk-release]
    // After the application submitted the frame: wait_idle waits for its timeline value too.
    LOOM_TRY((*device)->wait_idle());
    LOOM_TRY((*device)->destroy(*color));  // forgets the wrapper (and loom's views); the image stays
    embedded->reset();
    device->reset();  // before the application destroys its VkDevice
    // [/docs:vk-release]
    return {};
}

}  // namespace loom::docs
