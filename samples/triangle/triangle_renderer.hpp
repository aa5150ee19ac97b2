#pragma once
// The GPU objects of the triangle sample and the commands that draw it.

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::samples {

/// Background colour: dark blue-grey. Each channel is chosen away from a rounding tie in
/// 8 bits (0.08 * 255 = 20.4, 0.12 * 255 = 30.6), so its RGBA8 value is unambiguous.
inline constexpr std::array<double, 4> kTriangleBackground{0.08, 0.08, 0.12, 1.0};

/// Owns the pipeline and vertex buffer of the triangle (red bottom-left, green bottom-right,
/// blue top, in NDC (-0.5,-0.5), (0.5,-0.5), (0,0.5)) and destroys them with itself.
class TriangleRenderer {
public:
    /// Creates the objects on `device` for colour targets of `format`.
    static Result<TriangleRenderer> create(rhi::Device& device, rhi::Format format);
    TriangleRenderer(TriangleRenderer&& other) noexcept;
    TriangleRenderer& operator=(TriangleRenderer&&) = delete;
    TriangleRenderer(const TriangleRenderer&) = delete;
    ~TriangleRenderer();

    /// Records a render pass that clears `target` to the background and draws the triangle.
    void record(rhi::CommandList& list, rhi::TextureHandle target) const;

private:
    explicit TriangleRenderer(rhi::Device& device) : device_(&device) {}

    rhi::Device* device_;
    rhi::PipelineHandle pipeline_;
    rhi::BufferHandle vertices_;
};

}  // namespace loom::samples
