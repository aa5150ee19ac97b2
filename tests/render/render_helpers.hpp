#pragma once
// Helpers shared by the render tests: inline shaders, buffers and targets in one call, one-frame
// recording, and reading texels back. API-neutral: everything goes through rhi::Device.

#include <cstring>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/rhi/device.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"

/// Assigns the value of a Result expression to `lhs`, or fails the test with its error.
#define LOOM_CONCAT_INNER(a, b) a##b
#define LOOM_CONCAT(a, b) LOOM_CONCAT_INNER(a, b)
#define LOOM_ASSIGN_OR_FAIL(lhs, expr)                                                         \
    auto LOOM_CONCAT(loom_result_, __LINE__) = (expr);                                         \
    ASSERT_TRUE(LOOM_CONCAT(loom_result_, __LINE__).ok())                                      \
        << #expr << ": " << LOOM_CONCAT(loom_result_, __LINE__).error().to_string();           \
    lhs = std::move(*LOOM_CONCAT(loom_result_, __LINE__))

/// Fails the test when a Status expression is an error.
#define LOOM_ASSERT_OK(expr)                                                                   \
    do {                                                                                       \
        auto loom_status_ = (expr);                                                            \
        ASSERT_TRUE(loom_status_.ok()) << #expr << ": " << loom_status_.error().to_string();   \
    } while (false)

namespace loom::test {

/// A vertex shader passing `position` (location 0, vec3, NDC) through.
extern const char* const kPositionVert;
/// A fragment shader writing the vec4 push constant `color`.
extern const char* const kPushColorFrag;

/// Compiles inline GLSL 450 (Vulkan-style bindings) and creates the shader on `device`.
Result<rhi::ShaderHandle> make_shader(rhi::Device& device, rhi::ShaderStage stage, const std::string& name,
                                      const std::string& code);

/// A buffer holding `data`.
Result<rhi::BufferHandle> make_buffer(rhi::Device& device, const std::string& name, rhi::BufferUsage usage,
                                      std::span<const std::byte> data);

template <class T>
Result<rhi::BufferHandle> make_buffer_of(rhi::Device& device, const std::string& name, rhi::BufferUsage usage,
                                         const std::vector<T>& values) {
    return make_buffer(device, name, usage, std::as_bytes(std::span<const T>(values)));
}

/// A 2D texture usable as colour or depth attachment (by format), sampled and copied.
Result<rhi::TextureHandle> make_target(rhi::Device& device, const std::string& name, rhi::Format format, uint32_t width,
                                       uint32_t height, rhi::TextureUsage extra = rhi::TextureUsage::None);

/// Options of make_solid_pipeline.
struct SolidPipelineOptions {
    rhi::CullMode cull = rhi::CullMode::None;
    rhi::DepthState depth{};
    rhi::Format depth_format = rhi::Format::Undefined;
    rhi::PrimitiveTopology topology = rhi::PrimitiveTopology::TriangleList;
};

/// A pipeline drawing vec3 positions (one buffer, stride 12) in the push-constant colour.
Result<rhi::PipelineHandle> make_solid_pipeline(rhi::Device& device, rhi::Format color_format,
                                                const SolidPipelineOptions& options = {});

/// Records one frame with `record` and ends it; returns end_frame()'s status.
Status run_frame(rhi::Device& device, const std::function<void(rhi::CommandList&)>& record);

/// A render pass clearing one colour attachment (and optionally a depth attachment to 1.0).
rhi::RenderPassDesc clear_pass(const std::string& label, rhi::TextureHandle color, std::array<double, 4> clear,
                               rhi::TextureHandle depth = {});

/// Colour of an RGBA8 pixel as 0..255 integers.
std::array<int, 4> rgba8_at(const rhi::Image& image, uint32_t x, uint32_t y);

/// Writes `image` under output_dir()/render/<name>.png for inspection.
void save_picture(const rhi::Image& image, const std::string& name);

/// The bytes of a trivially copyable value.
template <class T>
std::vector<std::byte> bytes_of(const T& value) {
    std::vector<std::byte> out(sizeof(T));
    std::memcpy(out.data(), &value, sizeof(T));
    return out;
}

}  // namespace loom::test
