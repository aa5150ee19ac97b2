#include "cross_backend.hpp"

#include <algorithm>

#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

#include "loom/image_io/image_io.hpp"

namespace loom::test {

bool both_backends_available(std::string& why_not) {
    const auto backends = backends_under_test();
    const bool gl = std::find(backends.begin(), backends.end(), rhi::Backend::OpenGL) != backends.end();
    const bool vk = std::find(backends.begin(), backends.end(), rhi::Backend::Vulkan) != backends.end();
    if (gl && vk) return true;
    why_not = std::string("cross-backend comparison needs both backends; missing: ") + (gl ? "" : "gl ") + (vk ? "" : "vulkan") +
              " (not compiled in, or excluded by LOOM_TEST_BACKENDS)";
    return false;
}

void CrossBackendTest::SetUp() {
    std::string why_not;
    if (!both_backends_available(why_not)) GTEST_SKIP() << why_not;
    for (rhi::Backend backend : {rhi::Backend::OpenGL, rhi::Backend::Vulkan}) {
        auto device = create_test_device(backend);
        ASSERT_TRUE(device.ok()) << device.error().to_string();
        (backend == rhi::Backend::OpenGL ? gl_ : vulkan_) = std::move(*device);
    }
}

void CrossBackendTest::TearDown() {
    for (auto* device : {&gl_, &vulkan_}) {
        if (*device) {
            auto status = (*device)->wait_idle();
            EXPECT_TRUE(status.ok()) << status.error().to_string();
            device->reset();
        }
    }
}

void CrossBackendTest::expect_same(const std::string& name, const Scene& scene, double threshold) {
    auto a = scene(*gl_);
    ASSERT_TRUE(a.ok()) << name << " on gl: " << a.error().to_string();
    auto b = scene(*vulkan_);
    ASSERT_TRUE(b.ok()) << name << " on vulkan: " << b.error().to_string();
    rhi::ImageCompareOptions options;
    options.threshold = threshold;
    auto comparison = image_io::compare_and_report(*a, *b, output_dir() / "cross_backend", name, options);
    ASSERT_TRUE(comparison.ok()) << name << ": " << comparison.error().to_string();
    EXPECT_TRUE(comparison->equal()) << name << " differs between gl (a) and vulkan (b): " << comparison->summary()
                                     << "; see " << (output_dir() / "cross_backend" / (name + ".diff.png")).string();
}

}  // namespace loom::test
