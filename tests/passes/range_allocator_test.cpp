// The first-fit range allocator of the shared buffers and slot pools (no GPU).
#include <gtest/gtest.h>

#include "loom/passes/range_allocator.hpp"

namespace loom::test {
namespace {

using passes::RangeAllocator;

TEST(RangeAllocatorTest, FirstFitFreesMergeAndAreReused) {
    RangeAllocator ranges(100);
    EXPECT_EQ(ranges.allocate(10), 0u);
    EXPECT_EQ(ranges.allocate(20), 10u);
    EXPECT_EQ(ranges.allocate(30), 30u);
    EXPECT_EQ(ranges.used(), 60u);
    EXPECT_EQ(ranges.high_water(), 60u);
    EXPECT_FALSE(ranges.allocate(41).has_value());  // 40 left

    ranges.free(10, 20);
    EXPECT_EQ(ranges.free_ranges(), 2u);       // [10,30) and [60,100)
    EXPECT_EQ(ranges.allocate(15), 10u);       // first fit: the hole, not the end
    EXPECT_EQ(ranges.allocate(10), 60u);       // 5 left in the hole: too small
    ranges.free(0, 10);
    ranges.free(10, 15);
    EXPECT_EQ(ranges.free_ranges(), 2u);       // [0,30) merged, [70,100)
    EXPECT_EQ(ranges.allocate(30), 0u);        // the merged hole exactly
    ranges.free(30, 30);
    ranges.free(60, 10);
    ranges.free(0, 30);
    EXPECT_EQ(ranges.used(), 0u);
    EXPECT_EQ(ranges.free_ranges(), 1u);       // everything merged back into one range
    EXPECT_EQ(ranges.high_water(), 0u);
}

TEST(RangeAllocatorTest, GrowingAddsFreeSpaceAtTheEnd) {
    RangeAllocator ranges(8);
    EXPECT_EQ(ranges.allocate(6), 0u);
    EXPECT_FALSE(ranges.allocate(4).has_value());
    ranges.grow(16);
    EXPECT_EQ(ranges.free_ranges(), 1u);  // [6,16): the old tail merged with the new space
    EXPECT_EQ(ranges.allocate(4), 6u);
    EXPECT_EQ(ranges.capacity(), 16u);
    EXPECT_FALSE(ranges.allocate(0).has_value());
}

}  // namespace
}  // namespace loom::test
