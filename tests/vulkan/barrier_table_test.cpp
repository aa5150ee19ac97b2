// The state -> (layout, stages, access) table and the barriers BarrierBatch emits from it.
#include <gtest/gtest.h>

#include "loom/vulkan/resource_states.hpp"

namespace loom::test {
namespace {

using rhi::ResourceState;
using vulkan::BarrierBatch;
using vulkan::buffer_state_access;
using vulkan::texture_state_access;

TEST(VulkanBarrierTable, TextureLayouts) {
    EXPECT_EQ(texture_state_access(ResourceState::Undefined, false).layout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(texture_state_access(ResourceState::ShaderRead, false).layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::ShaderRead, true).layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::RenderTarget, false).layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::DepthWrite, true).layout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::DepthRead, true).layout, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::Storage, false).layout, VK_IMAGE_LAYOUT_GENERAL);
    EXPECT_EQ(texture_state_access(ResourceState::CopySrc, false).layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::CopyDst, false).layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    EXPECT_EQ(texture_state_access(ResourceState::Present, false).layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
}

TEST(VulkanBarrierTable, StagesAccessesAndWrites) {
    const auto rt = texture_state_access(ResourceState::RenderTarget, false);
    EXPECT_EQ(rt.stages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    EXPECT_EQ(rt.access, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    EXPECT_TRUE(rt.writes);
    const auto depth = texture_state_access(ResourceState::DepthWrite, true);
    EXPECT_EQ(depth.stages, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT);
    EXPECT_TRUE(depth.access & VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    const auto read = texture_state_access(ResourceState::ShaderRead, false);
    EXPECT_EQ(read.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    EXPECT_TRUE(read.stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
    EXPECT_TRUE(read.stages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
    EXPECT_FALSE(read.writes);
    const auto copy_dst = texture_state_access(ResourceState::CopyDst, false);
    EXPECT_EQ(copy_dst.stages, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT);
    EXPECT_EQ(copy_dst.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    // Undefined as a source waits for everything before (aliasing hand-over, acquire).
    const auto undefined = texture_state_access(ResourceState::Undefined, false);
    EXPECT_EQ(undefined.stages, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    EXPECT_EQ(undefined.access, VK_ACCESS_2_MEMORY_WRITE_BIT);
}

TEST(VulkanBarrierTable, StatesThatDoNotFitTheResourceAreInvalid) {
    EXPECT_FALSE(texture_state_access(ResourceState::RenderTarget, true).valid);
    EXPECT_FALSE(texture_state_access(ResourceState::DepthWrite, false).valid);
    EXPECT_FALSE(texture_state_access(ResourceState::DepthRead, false).valid);
    EXPECT_FALSE(texture_state_access(ResourceState::VertexBuffer, false).valid);
    EXPECT_FALSE(texture_state_access(ResourceState::IndexBuffer, false).valid);
    EXPECT_FALSE(buffer_state_access(ResourceState::RenderTarget).valid);
    EXPECT_FALSE(buffer_state_access(ResourceState::Present).valid);
    EXPECT_TRUE(buffer_state_access(ResourceState::VertexBuffer).valid);
    EXPECT_EQ(buffer_state_access(ResourceState::VertexBuffer).access, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT);
    EXPECT_EQ(buffer_state_access(ResourceState::IndexBuffer).stages, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT);
    EXPECT_EQ(buffer_state_access(ResourceState::IndirectArgument).access, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT);
}

TEST(VulkanBarrierTable, BatchEmitsOnlyNeededBarriers) {
    const VkImage image = reinterpret_cast<VkImage>(uintptr_t{0x1000});
    const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    BarrierBatch batch;
    batch.image(image, range, ResourceState::ShaderRead, ResourceState::ShaderRead, false);
    EXPECT_TRUE(batch.empty()) << "read -> same read needs no barrier";
    batch.image(image, range, ResourceState::RenderTarget, ResourceState::RenderTarget, false);
    ASSERT_EQ(batch.image_barriers().size(), 1u) << "write -> same write still needs a dependency";
    batch.image(image, range, ResourceState::RenderTarget, ResourceState::ShaderRead, false);
    ASSERT_EQ(batch.image_barriers().size(), 2u);
    const VkImageMemoryBarrier2& b = batch.image_barriers()[1];
    EXPECT_EQ(b.oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    EXPECT_EQ(b.newLayout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    EXPECT_EQ(b.srcStageMask, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
    EXPECT_EQ(b.dstAccessMask, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    // Discarding: the old layout is UNDEFINED whatever the tracked state was.
    batch.image(image, range, ResourceState::ShaderRead, ResourceState::RenderTarget, false, true);
    EXPECT_EQ(batch.image_barriers()[2].oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);
    EXPECT_EQ(batch.image_barriers()[2].srcStageMask, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);

    const VkBuffer buffer = reinterpret_cast<VkBuffer>(uintptr_t{0x2000});
    batch.buffer(buffer, ResourceState::ShaderRead, ResourceState::Storage);
    ASSERT_EQ(batch.buffer_barriers().size(), 1u);
    EXPECT_EQ(batch.buffer_barriers()[0].srcAccessMask, VK_ACCESS_2_NONE) << "after reads only an execution dependency";
    batch.buffer(buffer, ResourceState::Storage, ResourceState::VertexBuffer);
    EXPECT_EQ(batch.buffer_barriers()[1].srcAccessMask, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    EXPECT_EQ(batch.buffer_barriers()[1].dstStageMask, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT);
    // Storage to Storage (a second pass reads what the first wrote) is a barrier too.
    batch.buffer(buffer, ResourceState::Storage, ResourceState::Storage);
    ASSERT_EQ(batch.buffer_barriers().size(), 3u);
    EXPECT_EQ(batch.buffer_barriers()[2].dstAccessMask, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    // From Undefined (a placed buffer taking over bytes an alias wrote): every earlier write.
    batch.buffer(buffer, ResourceState::Undefined, ResourceState::Storage);
    ASSERT_EQ(batch.buffer_barriers().size(), 4u);
    EXPECT_EQ(batch.buffer_barriers()[3].srcStageMask, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    EXPECT_EQ(batch.buffer_barriers()[3].srcAccessMask, VK_ACCESS_2_MEMORY_WRITE_BIT);
    EXPECT_EQ(batch.size(), 7u);
}

TEST(VulkanBarrierTable, AspectsOfFormats) {
    EXPECT_EQ(vulkan::aspect_mask(VK_FORMAT_R8G8B8A8_UNORM), VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
    EXPECT_EQ(vulkan::aspect_mask(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
    EXPECT_EQ(vulkan::aspect_mask(VK_FORMAT_S8_UINT), VkImageAspectFlags{VK_IMAGE_ASPECT_STENCIL_BIT});
    EXPECT_EQ(vulkan::aspect_mask(VK_FORMAT_D24_UNORM_S8_UINT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT});
}

}  // namespace
}  // namespace loom::test
