#include "gl_test_util.hpp"

namespace loom::test {

void GlTest::SetUp() {
    rhi::DeviceDesc desc;
    desc.backend = rhi::Backend::OpenGL;
    auto device = gl::create_gl_device(desc);
    ASSERT_TRUE(device.ok()) << device.error().to_string();
    device_ = std::move(*device);
}

void GlTest::TearDown() {
    if (device_) {
        EXPECT_TRUE(device_->wait_idle().ok());
        device_.reset();
    }
}

}  // namespace loom::test
