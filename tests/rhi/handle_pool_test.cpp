#include <string>

#include <gtest/gtest.h>

#include "loom/rhi/handle_pool.hpp"

using namespace loom;
using namespace loom::rhi;

TEST(HandlePool, InsertGetRemove) {
    HandlePool<TextureTag, std::string> pool(next_device_id());
    auto a = pool.insert("a");
    auto b = pool.insert("b");
    EXPECT_NE(a, b);
    ASSERT_TRUE(pool.get(a).ok());
    EXPECT_EQ(**pool.get(a), "a");
    EXPECT_EQ(pool.size(), 2u);
    auto removed = pool.remove(a);
    ASSERT_TRUE(removed.ok());
    EXPECT_EQ(*removed, "a");
    EXPECT_EQ(pool.size(), 1u);
}

TEST(HandlePool, StaleHandleIsAnErrorEvenWhenTheSlotIsReused) {
    HandlePool<TextureTag, int> pool(next_device_id());
    auto a = pool.insert(1);
    ASSERT_TRUE(pool.remove(a).ok());
    auto b = pool.insert(2);  // reuses the slot
    EXPECT_EQ(a.index, b.index);
    auto stale = pool.get(a);
    ASSERT_FALSE(stale.ok());
    EXPECT_EQ(stale.error().code, ErrorCode::InvalidHandle);
    EXPECT_NE(stale.error().message.find("stale"), std::string::npos) << stale.error().message;
    EXPECT_NE(stale.error().message.find("texture"), std::string::npos);
    EXPECT_EQ(pool.find(a), nullptr);
    EXPECT_FALSE(pool.remove(a).ok());
    EXPECT_EQ(**pool.get(b), 2);
}

TEST(HandlePool, ForeignAndNullHandlesAreErrors) {
    HandlePool<BufferTag, int> first(next_device_id());
    HandlePool<BufferTag, int> second(next_device_id());
    auto h = first.insert(7);
    auto foreign = second.get(h);
    ASSERT_FALSE(foreign.ok());
    EXPECT_NE(foreign.error().message.find("belongs to device"), std::string::npos) << foreign.error().message;
    auto null = first.get(BufferHandle{});
    ASSERT_FALSE(null.ok());
    EXPECT_NE(null.error().message.find("buffer handle is null"), std::string::npos);
}

TEST(HandlePool, ClearVisitsEveryLiveObject) {
    HandlePool<SamplerTag, int> pool(next_device_id());
    pool.insert(1);
    auto two = pool.insert(2);
    pool.insert(3);
    ASSERT_TRUE(pool.remove(two).ok());
    int sum = 0;
    pool.clear([&](SamplerHandle, int& v) { sum += v; });
    EXPECT_EQ(sum, 4);
    EXPECT_EQ(pool.size(), 0u);
}
