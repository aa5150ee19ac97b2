#include "loom/scene/animation.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace loom::scene {

float Animation::duration() const {
    float last = 0.0f;
    for (const AnimationSampler& s : samplers) {
        if (!s.times.empty()) last = std::max(last, s.times.back());
    }
    return last;
}

glm::quat slerp_shortest(const glm::quat& a, const glm::quat& b, float t) {
    float d = glm::dot(a, b);
    // q and -q are the same rotation: the other sign of b is the shorter way round.
    const glm::quat to = d < 0.0f ? -b : b;
    d = std::abs(d);
    if (d > 0.9995f) {
        // Nearly the same rotation: sin(theta) would be close to 0; the chord is the arc.
        return glm::normalize(a * (1.0f - t) + to * t);
    }
    const float theta = std::acos(d);
    const float sin_theta = std::sin(theta);
    return a * (std::sin((1.0f - t) * theta) / sin_theta) + to * (std::sin(t * theta) / sin_theta);
}

namespace {

glm::quat quat_at(std::span<const float> v) { return glm::quat(v[3], v[0], v[1], v[2]); }  // (w, x, y, z)

void store(const glm::quat& q, std::span<float> out) {
    out[0] = q.x;
    out[1] = q.y;
    out[2] = q.z;
    out[3] = q.w;
}

}  // namespace

void sample(const AnimationSampler& sampler, float time, bool rotation, std::span<float> out) {
    const std::size_t n = sampler.components;
    const std::vector<float>& times = sampler.times;
    const bool spline = sampler.interpolation == Interpolation::CubicSpline;
    const std::span<const float> values = sampler.values;
    // Group g of spline keyframe k: 0 its in-tangent, 1 its value, 2 its out-tangent.
    const auto spline_group = [&](std::size_t k, std::size_t g) { return values.subspan((3 * k + g) * n, n); };
    const auto value = [&](std::size_t k) { return spline ? spline_group(k, 1) : values.subspan(k * n, n); };
    const auto copy = [&](std::span<const float> v) { std::copy(v.begin(), v.end(), out.begin()); };
    if (times.size() == 1 || time <= times.front()) return copy(value(0));
    if (time >= times.back()) return copy(value(times.size() - 1));
    // The keyframe k with times[k] <= time < times[k + 1].
    const std::size_t k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
    if (sampler.interpolation == Interpolation::Step) return copy(value(k));
    const float span = times[k + 1] - times[k];
    const float t = (time - times[k]) / span;
    if (sampler.interpolation == Interpolation::Linear) {
        if (rotation) return store(slerp_shortest(quat_at(value(k)), quat_at(value(k + 1)), t), out);
        const std::span<const float> a = value(k), b = value(k + 1);
        for (std::size_t i = 0; i < n; ++i) out[i] = a[i] + (b[i] - a[i]) * t;
        return;
    }
    // Cubic Hermite: the value and out-tangent of k, the in-tangent and value of k + 1, the
    // tangents scaled by the time between the keyframes.
    const float t2 = t * t, t3 = t2 * t;
    const float h00 = 2 * t3 - 3 * t2 + 1, h10 = t3 - 2 * t2 + t, h01 = -2 * t3 + 3 * t2, h11 = t3 - t2;
    const std::span<const float> v0 = value(k), v1 = value(k + 1);
    const std::span<const float> out_tangent = spline_group(k, 2), in_tangent = spline_group(k + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = h00 * v0[i] + h10 * span * out_tangent[i] + h01 * v1[i] + h11 * span * in_tangent[i];
    }
    if (rotation) store(glm::normalize(quat_at(out)), out);
}

}  // namespace loom::scene
