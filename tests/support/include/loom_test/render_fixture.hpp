#pragma once
// A gtest fixture for render tests, parameterised over every backend compiled into the build
// (optionally narrowed by the LOOM_TEST_BACKENDS environment variable, e.g. "gl,vulkan").
// Each test gets a fresh headless device with API debug output on; any debug or validation
// error fails the test (see test_main.cpp).

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {

/// Backends compiled in, filtered by $LOOM_TEST_BACKENDS when set.
std::vector<rhi::Backend> backends_under_test();

/// A headless device of `backend` with API debug output on, as every render test gets.
Result<std::unique_ptr<rhi::Device>> create_test_device(rhi::Backend backend);

/// Names parameterised tests "gl" / "vulkan".
struct BackendParamName {
    std::string operator()(const ::testing::TestParamInfo<rhi::Backend>& info) const;
};

class RenderTest : public ::testing::TestWithParam<rhi::Backend> {
protected:
    void SetUp() override;
    void TearDown() override;

    rhi::Device& device() { return *device_; }
    rhi::Backend backend() const { return GetParam(); }

    std::unique_ptr<rhi::Device> device_;
};

}  // namespace loom::test

/// Instantiates a RenderTest-derived fixture once per backend under test.
#define LOOM_INSTANTIATE_RENDER_TEST(Fixture)                                                    \
    GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(Fixture);                                      \
    INSTANTIATE_TEST_SUITE_P(Backends, Fixture, ::testing::ValuesIn(::loom::test::backends_under_test()), \
                             ::loom::test::BackendParamName{})
