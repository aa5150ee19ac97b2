#pragma once
// Axis-aligned bounding boxes, for primitives (local space), draw items and whole scenes
// (world space), and what the passes fit their shadow maps to.

#include <array>
#include <limits>

#include "loom/scene/glm.hpp"

namespace loom::scene {

/// An axis-aligned box given by its minimum and maximum corners. A default-constructed box is
/// empty (min = +inf, max = -inf) and grows with extend().
struct Bounds {
    glm::vec3 min{std::numeric_limits<float>::infinity()};
    glm::vec3 max{-std::numeric_limits<float>::infinity()};

    /// True when the box contains no point (nothing was added yet).
    [[nodiscard]] bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
    /// Grows the box to contain `point`.
    void extend(const glm::vec3& point);
    /// Grows the box to contain `other` (an empty box changes nothing).
    void extend(const Bounds& other);
    /// Centre of the box (meaningless when empty).
    [[nodiscard]] glm::vec3 center() const { return (min + max) * 0.5f; }
    /// Edge lengths (meaningless when empty).
    [[nodiscard]] glm::vec3 size() const { return max - min; }
    /// The eight corners, in the order (x, y, z) = bits 0, 1, 2 of the index choosing max.
    [[nodiscard]] std::array<glm::vec3, 8> corners() const;
    /// The box of the eight transformed corners (conservative for rotations).
    [[nodiscard]] Bounds transformed(const glm::mat4& matrix) const;

    friend bool operator==(const Bounds&, const Bounds&) = default;
};

}  // namespace loom::scene
