// InlineVector keeps up to N elements without the heap, so that a RenderPassDesc built per frame
// allocates nothing; beyond N it still works (validation, not the container, refuses a list
// too long for the device). Heap allocations are counted by replacing operator new in this
// test program (it has no other tests).
#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include <gtest/gtest.h>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/inline_vector.hpp"

namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
    ++g_allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace loom::rhi {
namespace {

TEST(InlineVectorTest, ARenderPassBuiltPerFrameAllocatesNothing) {
    const TextureHandle texture{};
    const std::size_t before = g_allocations.load();
    for (int frame = 0; frame < 3; ++frame) {
        RenderPassDesc pass;
        pass.label = "gbuffer";
        for (uint32_t i = 0; i < 4; ++i) pass.colors.push_back({.texture = texture, .layer = i});
        pass.colors.push_back(ColorAttachment{texture, 1, 0, LoadOp::Load, StoreOp::Store, {}});
        pass.depth = DepthAttachment{texture};
        RenderPassDesc copy = pass;  // passing it by value allocates nothing either
        ASSERT_EQ(copy.colors.size(), 5u);
        EXPECT_EQ(copy.colors[4].mip, 1u);
        EXPECT_EQ(copy.colors[3].layer, 3u);
    }
    const RenderPassDesc braced{"braced", {ColorAttachment{}, ColorAttachment{}}, std::nullopt};
    EXPECT_EQ(braced.colors.size(), 2u);
    EXPECT_EQ(g_allocations.load() - before, 0u);
}

TEST(InlineVectorTest, MoreElementsThanItHoldsGoToTheHeapAndBack) {
    InlineVector<int, 3> v{1, 2, 3};
    EXPECT_EQ(v.size(), 3u);
    const std::size_t before = g_allocations.load();
    v.push_back(4);
    EXPECT_GT(g_allocations.load(), before) << "the fourth element must spill";
    v.emplace_back(5);
    ASSERT_EQ(v.size(), 5u);
    int sum = 0;
    for (int x : v) sum += x;
    EXPECT_EQ(sum, 15);
    EXPECT_EQ(v.back(), 5);
    InlineVector<int, 3> copy = v;
    EXPECT_TRUE(copy == v);
    v.resize(2);  // back inside
    ASSERT_EQ(v.size(), 2u);
    EXPECT_EQ(v[0], 1);
    EXPECT_EQ(v[1], 2);
    v.resize(6, 9);
    ASSERT_EQ(v.size(), 6u);
    EXPECT_EQ(v[1], 2);
    EXPECT_EQ(v[2], 9);
    EXPECT_EQ(v[5], 9);
    v.resize(4);
    EXPECT_EQ(v.size(), 4u);
    EXPECT_EQ(v.back(), 9);
    v.pop_back();
    EXPECT_EQ(v.size(), 3u);
    EXPECT_EQ(copy.size(), 5u) << "a copy is independent";
    EXPECT_EQ(copy[4], 5);
    v.clear();
    EXPECT_TRUE(v.empty());
    v.push_back(7);
    EXPECT_EQ(v.front(), 7);
}

}  // namespace
}  // namespace loom::rhi
