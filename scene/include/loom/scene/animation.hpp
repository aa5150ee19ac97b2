#pragma once
// Keyframe animation of node properties, as glTF 2.0 defines it (section 3.11, "Animations"):
// samplers of keyframe times and values with step, linear or cubic-spline interpolation, and
// channels that drive one property of one node. Sampling is plain data in, values out; playing
// an animation on a scene's nodes builds on it.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "loom/scene/glm.hpp"

#include <glm/gtc/quaternion.hpp>

namespace loom::scene {

enum class Interpolation : uint8_t {
    Step,         ///< the value of the last keyframe at or before the time
    Linear,       ///< linear between keyframes; rotations by spherical linear interpolation
    CubicSpline,  ///< cubic Hermite spline with a tangent on each side of each keyframe
};

/// The node property a channel drives, and how many floats one of its values has.
enum class AnimatedProperty : uint8_t {
    Translation,  ///< 3 floats
    Rotation,     ///< 4 floats, a unit quaternion (x, y, z, w)
    Scale,        ///< 3 floats
    Weights,      ///< one float per morph target
};

/// Keyframe times (seconds, strictly increasing) and values. Linear and Step samplers hold
/// `components` floats per keyframe; CubicSpline ones three groups of `components` floats per
/// keyframe: the in-tangent, the value, the out-tangent.
struct AnimationSampler {
    std::vector<float> times;
    std::vector<float> values;
    Interpolation interpolation = Interpolation::Linear;
    uint32_t components = 3;
};

/// One property of one node driven by one sampler.
struct AnimationChannel {
    uint32_t node = 0;     ///< index into Scene::nodes
    uint32_t sampler = 0;  ///< index into Animation::samplers
    AnimatedProperty property = AnimatedProperty::Translation;
};

struct Animation {
    std::string name;
    std::vector<AnimationSampler> samplers;
    std::vector<AnimationChannel> channels;

    /// The last keyframe time of all samplers (0 without keyframes).
    [[nodiscard]] float duration() const;
};

/// The value of `sampler` at `time` into `out` (sampler.components floats). Before the first
/// keyframe it is the first value, after the last the last one. `rotation`: the values are unit
/// quaternions, interpolated along the shorter arc (Linear) or normalised after the spline
/// (CubicSpline). The sampler must be well formed (a loader checks counts and times): at least
/// one keyframe and as many values as the interpolation needs.
void sample(const AnimationSampler& sampler, float time, bool rotation, std::span<float> out);

/// Spherical linear interpolation from `a` to `b` (unit quaternions) by `t` in [0, 1], along
/// the shorter arc; normalised linear interpolation when they are nearly equal.
glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t);

}  // namespace loom::scene
