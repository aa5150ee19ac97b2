#include "loom_test/render_fixture.hpp"

#include <cstdlib>
#include <sstream>

namespace loom::test {

std::vector<rhi::Backend> backends_under_test() {
    std::vector<rhi::Backend> out;
    const char* filter = std::getenv("LOOM_TEST_BACKENDS");
    for (rhi::Backend b : rhi::compiled_backends()) {
        if (filter && *filter) {
            bool wanted = false;
            std::stringstream list(filter);
            std::string item;
            while (std::getline(list, item, ',')) {
                if (rhi::parse_backend(item) == b) wanted = true;
            }
            if (!wanted) continue;
        }
        out.push_back(b);
    }
    return out;
}

std::string BackendParamName::operator()(const ::testing::TestParamInfo<rhi::Backend>& info) const {
    return std::string(rhi::backend_name(info.param));
}

Result<std::unique_ptr<rhi::Device>> create_test_device(rhi::Backend backend) {
    rhi::DeviceDesc desc;
    desc.backend = backend;
    desc.headless = true;
    desc.debug = true;
    return rhi::create_device(desc);
}

void RenderTest::SetUp() {
    auto device = create_test_device(GetParam());
    ASSERT_TRUE(device.ok()) << device.error().to_string();
    device_ = std::move(*device);
}

void RenderTest::TearDown() {
    if (device_) {
        auto status = device_->wait_idle();
        EXPECT_TRUE(status.ok()) << status.error().to_string();
        device_.reset();
    }
}

}  // namespace loom::test
