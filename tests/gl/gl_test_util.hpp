#pragma once
// A fixture with a headless GL device for the GL-only tests.

#include <memory>

#include <gtest/gtest.h>

#include "loom/gl/gl_device.hpp"

namespace loom::test {

class GlTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;
    rhi::Device& device() { return *device_; }
    /// The device's cache sizes (the device is a GL device).
    gl::GlCacheStats caches() const { return *gl::gl_cache_stats(*device_); }

    std::unique_ptr<rhi::Device> device_;
};

}  // namespace loom::test
