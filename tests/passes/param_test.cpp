// Lazy parameter nodes and uniform sets (no GPU): values are computed only when read and only
// after an input changed; invalidation reaches every dependant once; a uniform set goes stale
// with its inputs, tells its owner once, and reports a change only when its bytes changed.
#include <cstring>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "loom/passes/param.hpp"
#include "loom/passes/uniform_set.hpp"

namespace loom::test {
namespace {

using passes::compute;
using passes::InputParam;
using passes::UniformSet;
using passes::UpdateFrequency;

TEST(ParamTest, ComputesOnlyWhenReadAndOnlyAfterAChange) {
    auto a = std::make_shared<InputParam<int>>(4);
    auto b = std::make_shared<InputParam<int>>(8);
    auto sum = compute<int>([](const int& x, const int& y) { return x + y; }, a, b);
    auto product = compute<int>([](const int& x, const int& y) { return x * y; }, a, b);
    // The manual's example: (4 + 8) * (4 * 8) = 384.
    auto result = compute<int>([](const int& x, const int& y) { return x * y; }, sum, product);
    EXPECT_EQ(sum->computations(), 0u);  // nothing computed before it is read
    EXPECT_EQ(result->value(), 384);
    EXPECT_EQ(sum->computations(), 1u);
    EXPECT_EQ(result->value(), 384);
    EXPECT_EQ(result->computations(), 1u);  // cached

    a->set(5);
    EXPECT_FALSE(sum->valid());
    EXPECT_FALSE(result->valid());
    EXPECT_EQ(result->computations(), 1u);  // invalid, but not recomputed until read
    EXPECT_EQ(result->value(), (5 + 8) * (5 * 8));
    EXPECT_EQ(result->computations(), 2u);
    EXPECT_EQ(sum->computations(), 2u);
    EXPECT_EQ(product->computations(), 2u);
}

TEST(ParamTest, InvalidationStopsAtNodesThatAreInvalidAlready) {
    auto time = std::make_shared<InputParam<float>>(0.0f);
    auto doubled = compute<float>([](const float& t) { return 2.0f * t; }, time);
    int notified = 0;
    auto set = std::make_shared<UniformSet>(
        "Block", UpdateFrequency::PerObject, 4,
        [doubled](std::span<std::byte> out) {
            const float v = doubled->value();
            std::memcpy(out.data(), &v, 4);
        },
        std::vector<std::shared_ptr<passes::ParamNode>>{doubled});
    set->on_stale([&](UniformSet&) { ++notified; });
    EXPECT_TRUE(set->stale());  // new sets are stale
    EXPECT_TRUE(set->refresh());
    EXPECT_FALSE(set->stale());

    time->set(1.0f);
    time->set(2.0f);  // the chain is invalid already: no second notification
    EXPECT_EQ(notified, 1);
    EXPECT_TRUE(set->refresh());
    EXPECT_EQ(doubled->computations(), 2u);  // once for 0, once for 2 (never for 1)
    float stored = 0.0f;
    std::memcpy(&stored, set->bytes().data(), 4);
    EXPECT_EQ(stored, 4.0f);

    time->set(3.0f);
    EXPECT_EQ(notified, 2);
}

TEST(ParamTest, ASetWhoseBytesDidNotChangeNeedsNoUpload) {
    auto value = std::make_shared<InputParam<int>>(7);
    auto clamped = compute<int>([](const int& v) { return v > 10 ? 10 : v; }, value);
    UniformSet set("Block", UpdateFrequency::PerMaterial, 16,
                   [clamped](std::span<std::byte> out) {
                       const int v = clamped->value();
                       std::memcpy(out.data(), &v, sizeof(v));
                   },
                   {clamped});
    EXPECT_TRUE(set.refresh());   // the first refresh always counts as a change
    EXPECT_FALSE(set.refresh());  // not stale: nothing recomputed
    EXPECT_EQ(set.recomputations(), 1u);
    value->set(12);
    EXPECT_TRUE(set.refresh());   // 7 -> 10
    value->set(15);
    EXPECT_TRUE(set.stale());
    EXPECT_FALSE(set.refresh());  // recomputed, but still 10: same bytes
    EXPECT_EQ(set.recomputations(), 3u);
}

TEST(ParamTest, NodesLeaveTheGraphCleanly) {
    auto parent = std::make_shared<InputParam<int>>(1);
    {
        auto child = compute<int>([](const int& p) { return p + 1; }, parent);
        EXPECT_EQ(parent->sink_count(), 1u);
        EXPECT_EQ(child->value(), 2);
    }
    EXPECT_EQ(parent->sink_count(), 0u);
    parent->set(2);  // no dangling dependant to notify
    EXPECT_EQ(parent->value(), 2);
}

TEST(ParamTest, ManyDependantsOfOneInputAreEachInvalidatedOnce) {
    auto time = std::make_shared<InputParam<float>>(0.0f);
    std::vector<std::shared_ptr<UniformSet>> sets;
    int notified = 0;
    for (int i = 0; i < 100; ++i) {
        auto offset = compute<float>([i](const float& t) { return t + static_cast<float>(i); }, time);
        auto set = std::make_shared<UniformSet>(
            "Block", UpdateFrequency::PerObject, 4,
            [offset](std::span<std::byte> out) {
                const float v = offset->value();
                std::memcpy(out.data(), &v, 4);
            },
            std::vector<std::shared_ptr<passes::ParamNode>>{offset});
        set->on_stale([&](UniformSet&) { ++notified; });
        set->refresh();
        sets.push_back(set);
    }
    time->set(1.0f);
    EXPECT_EQ(notified, 100);
    EXPECT_EQ(time->sink_count(), 100u);
}

}  // namespace
}  // namespace loom::test
