#pragma once
// One direction of a separable Gaussian blur (ports previous_pass → color, as the paper's
// Listing 6 names them). Two passes, horizontal then vertical, make the 2D blur. Whole-texel
// taps with clamped edges and CPU-computed weights, so the result is reproducible.

#include <cstdint>
#include <string>
#include <vector>

#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

enum class BlurAxis : uint8_t { Horizontal, Vertical };

/// The largest radius the blur part holds weights for.
inline constexpr uint32_t kMaxBlurRadius = 63;

/// Normalised Gaussian weights for offsets 0..radius (sigma = radius / 3, at least 0.5):
/// w[0] + 2 * (w[1] + ... + w[radius]) == 1 up to rounding. Radius 0 gives {1}.
std::vector<float> gaussian_weights(uint32_t radius);

class BlurPass final : public ShaderPass {
public:
    /// `radius` is clamped to kMaxBlurRadius.
    BlurPass(const PassConfig& config, BlurAxis axis, uint32_t radius, std::string name);

    /// Taps on each side; above kMaxBlurRadius is an InvalidArgument error (the radius stays).
    Status set_radius(uint32_t radius);
    [[nodiscard]] uint32_t radius() const { return radius_; }
    [[nodiscard]] BlurAxis axis() const { return axis_; }

    Status execute(fg::PassContext& context) override;

private:
    BlurAxis axis_;
    uint32_t radius_;
};

}  // namespace loom::passes
