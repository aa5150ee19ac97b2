#pragma once
// A fixture holding one GL and one Vulkan device (both with API validation on) and the check
// that a scene renders to identical bytes on both.

#include <functional>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom/rhi/image.hpp"

namespace loom::test {

/// Draws something on a device and reads it back.
using Scene = std::function<Result<rhi::Image>(rhi::Device&)>;

class CrossBackendTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

    /// Renders `scene` on both devices and expects identical images (or differences within
    /// `threshold`, in the format's natural units, which a test must justify). On a difference
    /// the images and a heat map are written under output_dir()/cross_backend/<name>.*.png.
    void expect_same(const std::string& name, const Scene& scene, double threshold = 0.0);

    rhi::Device& gl() { return *gl_; }
    rhi::Device& vulkan() { return *vulkan_; }

    std::unique_ptr<rhi::Device> gl_;
    std::unique_ptr<rhi::Device> vulkan_;
};

/// Skips the test unless both backends are compiled in and selected.
bool both_backends_available(std::string& why_not);

}  // namespace loom::test
