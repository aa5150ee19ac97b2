// loom's Vulkan memory allocator: alignment, reuse and merging of freed ranges, separate blocks
// for buffers and images, dedicated allocations.
#include <gtest/gtest.h>

#include "loom/vulkan/context.hpp"
#include "loom/vulkan/memory_allocator.hpp"

namespace loom::test {
namespace {

using vulkan::AllocationRequest;
using vulkan::MemoryAllocation;
using vulkan::ResourceKind;

constexpr VkDeviceSize kKiB = 1024;

class AllocatorTest : public ::testing::Test {
protected:
    void SetUp() override {
        auto context = vulkan::VulkanContext::create({});
        ASSERT_TRUE(context.ok()) << context.error().to_string();
        context_ = std::move(*context);
        vulkan::AllocatorOptions options;
        options.block_size = 1024 * kKiB;
        options.dedicated_threshold = 1024 * kKiB;  // everything below a block is sub-allocated
        allocator_ = std::make_unique<vulkan::MemoryAllocator>(context_->physical_device(), context_->device(), options);
    }
    void TearDown() override {
        allocator_.reset();
        context_.reset();
    }

    MemoryAllocation allocate(VkDeviceSize size, VkDeviceSize alignment, ResourceKind kind = ResourceKind::Buffer) {
        AllocationRequest request;
        request.requirements = {size, alignment, ~0u};
        request.kind = kind;
        auto a = allocator_->allocate(request);
        EXPECT_TRUE(a.ok()) << a.error().to_string();
        return a.ok() ? *a : MemoryAllocation{};
    }

    std::unique_ptr<vulkan::VulkanContext> context_;
    std::unique_ptr<vulkan::MemoryAllocator> allocator_;
};

TEST_F(AllocatorTest, OffsetsRespectAlignment) {
    const MemoryAllocation a = allocate(100, 1);
    const MemoryAllocation b = allocate(100, 256);
    const MemoryAllocation c = allocate(10, 4096);
    EXPECT_EQ(a.offset, 0u);
    EXPECT_EQ(b.offset, 256u) << "first multiple of 256 after [0, 100)";
    EXPECT_EQ(c.offset, 4096u);
    EXPECT_EQ(a.memory, b.memory);
    EXPECT_EQ(b.memory, c.memory);
    EXPECT_EQ(allocator_->stats().blocks, 1u);
    EXPECT_EQ(allocator_->stats().sub_allocations, 3u);
    EXPECT_EQ(allocator_->stats().sub_allocated_bytes, 210u);
    allocator_->free(a);
    allocator_->free(b);
    allocator_->free(c);
    EXPECT_EQ(allocator_->stats().sub_allocated_bytes, 0u);
}

TEST_F(AllocatorTest, FreedRangesAreReusedAndMerged) {
    const MemoryAllocation a = allocate(300 * kKiB, 256);
    const MemoryAllocation b = allocate(300 * kKiB, 256);
    const MemoryAllocation c = allocate(300 * kKiB, 256);
    ASSERT_EQ(allocator_->stats().blocks, 1u);
    EXPECT_EQ(b.offset, 300 * kKiB);
    EXPECT_EQ(c.offset, 600 * kKiB);

    // A freed range is handed out again.
    allocator_->free(b);
    const MemoryAllocation b2 = allocate(200 * kKiB, 256);
    EXPECT_EQ(b2.memory, b.memory);
    EXPECT_EQ(b2.offset, 300 * kKiB);
    allocator_->free(b2);

    // Neighbouring free ranges merge: 550 KiB fits only in [0, 600K) once a and b are both free.
    allocator_->free(a);
    const MemoryAllocation big = allocate(550 * kKiB, 256);
    EXPECT_EQ(big.memory, a.memory);
    EXPECT_EQ(big.offset, 0u);
    EXPECT_EQ(allocator_->stats().blocks, 1u) << "no new block was needed";

    // No room left in the block: a second block.
    const MemoryAllocation d = allocate(500 * kKiB, 256);
    EXPECT_NE(d.memory, a.memory);
    EXPECT_EQ(allocator_->stats().blocks, 2u);
    allocator_->free(big);
    allocator_->free(c);
    allocator_->free(d);
    EXPECT_EQ(allocator_->stats().blocks, 1u) << "one empty block is kept, the other freed";
    EXPECT_EQ(allocator_->stats().sub_allocations, 0u);
}

TEST_F(AllocatorTest, BuffersAndImagesUseSeparateBlocks) {
    // bufferImageGranularity never matters: linear and optimal resources never share a block.
    const MemoryAllocation buffer = allocate(1000, 16, ResourceKind::Buffer);
    const MemoryAllocation image = allocate(1000, 16, ResourceKind::Image);
    EXPECT_NE(buffer.memory, image.memory);
    EXPECT_EQ(allocator_->stats().blocks, 2u);
    allocator_->free(buffer);
    allocator_->free(image);
}

TEST_F(AllocatorTest, BigRequestsGetDedicatedMemory) {
    const MemoryAllocation small = allocate(64 * kKiB, 256);
    EXPECT_FALSE(small.dedicated);
    const MemoryAllocation big = allocate(2048 * kKiB, 256);
    EXPECT_TRUE(big.dedicated);
    EXPECT_EQ(big.offset, 0u);
    EXPECT_NE(big.memory, small.memory);
    EXPECT_EQ(allocator_->stats().dedicated_allocations, 1u);
    EXPECT_EQ(allocator_->stats().dedicated_bytes, 2048 * kKiB);
    AllocationRequest forced;
    forced.requirements = {4 * kKiB, 256, ~0u};
    forced.dedicated = true;
    auto explicit_dedicated = allocator_->allocate(forced);
    ASSERT_TRUE(explicit_dedicated.ok());
    EXPECT_TRUE(explicit_dedicated->dedicated);
    EXPECT_EQ(allocator_->stats().dedicated_allocations, 2u);
    allocator_->free(*explicit_dedicated);
    allocator_->free(big);
    allocator_->free(small);
    EXPECT_EQ(allocator_->stats().dedicated_allocations, 0u);
    EXPECT_EQ(allocator_->stats().dedicated_bytes, 0u);
}

TEST_F(AllocatorTest, HostVisibleMemoryIsMapped) {
    AllocationRequest request;
    request.requirements = {4096, 64, ~0u};
    request.required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    auto a = allocator_->allocate(request);
    ASSERT_TRUE(a.ok()) << a.error().to_string();
    ASSERT_NE(a->mapped, nullptr);
    static_cast<unsigned char*>(a->mapped)[4095] = 0xAB;  // writable to the last byte
    allocator_->free(*a);
}

TEST_F(AllocatorTest, ImpossibleMemoryPropertiesAreUnsupported) {
    AllocationRequest request;
    request.requirements = {4096, 64, 0u};  // no memory type allowed
    auto a = allocator_->allocate(request);
    ASSERT_FALSE(a.ok());
    EXPECT_EQ(a.error().code, ErrorCode::Unsupported);
}

}  // namespace
}  // namespace loom::test
