// Validation messages reach loom's logger as errors (and so fail tests), and synchronisation
// validation is on: both provoked deliberately on a raw VulkanContext.
#include <algorithm>

#include <gtest/gtest.h>

#include "loom/vulkan/context.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

bool any_contains(const std::vector<std::string>& messages, std::string_view needle) {
    return std::any_of(messages.begin(), messages.end(),
                       [&](const std::string& m) { return m.find(needle) != std::string::npos; });
}

TEST(VulkanValidation, InvalidCallIsLoggedAsError) {
    auto context = vulkan::VulkanContext::create({});
    ASSERT_TRUE(context.ok()) << context.error().to_string();
    ASSERT_TRUE((*context)->validation_enabled()) << "VK_LAYER_KHRONOS_validation must be installed (scripts/install-deps.sh)";
    std::vector<std::string> messages;
    {
        ScopedLogCapture capture;
        // size 0 is invalid usage (VUID-VkBufferCreateInfo-size-00912).
        auto info = vulkan::vk_init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
        info.size = 0;
        info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        VkBuffer buffer = VK_NULL_HANDLE;
        if (vkCreateBuffer((*context)->device(), &info, nullptr, &buffer) == VK_SUCCESS && buffer) {
            vkDestroyBuffer((*context)->device(), buffer, nullptr);
        }
        messages = capture.messages();
    }
    EXPECT_TRUE(any_contains(messages, "[vulkan]")) << "no validation message reached the logger";
    EXPECT_TRUE(any_contains(messages, "VUID-VkBufferCreateInfo-size")) << (messages.empty() ? "" : messages.front());
}

TEST(VulkanValidation, MissingBarrierIsASynchronisationHazard) {
    auto context = vulkan::VulkanContext::create({});
    ASSERT_TRUE(context.ok()) << context.error().to_string();
    if (!(*context)->synchronization_validation_enabled()) GTEST_SKIP() << "synchronisation validation is off (LOOM_VK_SYNC_VALIDATION=0)";
    VkDevice device = (*context)->device();

    auto buffer_info = vulkan::vk_init<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer_info.size = 256;
    buffer_info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateBuffer(device, &buffer_info, nullptr, &buffer), VK_SUCCESS);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    auto alloc = vulkan::vk_init<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = static_cast<uint32_t>(__builtin_ctz(req.memoryTypeBits));
    VkDeviceMemory memory = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateMemory(device, &alloc, nullptr, &memory), VK_SUCCESS);
    ASSERT_EQ(vkBindBufferMemory(device, buffer, memory, 0), VK_SUCCESS);

    auto pool_info = vulkan::vk_init<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
    pool_info.queueFamilyIndex = (*context)->queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    ASSERT_EQ(vkCreateCommandPool(device, &pool_info, nullptr, &pool), VK_SUCCESS);
    auto cb_info = vulkan::vk_init<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
    cb_info.commandPool = pool;
    cb_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cb_info.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    ASSERT_EQ(vkAllocateCommandBuffers(device, &cb_info, &cmd), VK_SUCCESS);

    std::vector<std::string> messages;
    {
        ScopedLogCapture capture;
        auto begin = vulkan::vk_init<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        vkBeginCommandBuffer(cmd, &begin);
        // Two writes of the same bytes with no barrier between them.
        vkCmdFillBuffer(cmd, buffer, 0, 256, 1u);
        vkCmdFillBuffer(cmd, buffer, 0, 256, 2u);
        vkEndCommandBuffer(cmd);
        messages = capture.messages();
    }
    EXPECT_TRUE(any_contains(messages, "SYNC-HAZARD-WRITE-AFTER-WRITE")) << (messages.empty() ? "(no message)" : messages.front());

    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
}

}  // namespace
}  // namespace loom::test
