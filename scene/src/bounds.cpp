#include "loom/scene/bounds.hpp"

namespace loom::scene {

void Bounds::extend(const glm::vec3& point) {
    min = glm::min(min, point);
    max = glm::max(max, point);
}

void Bounds::extend(const Bounds& other) {
    if (other.empty()) return;
    min = glm::min(min, other.min);
    max = glm::max(max, other.max);
}

std::array<glm::vec3, 8> Bounds::corners() const {
    std::array<glm::vec3, 8> result{};
    for (unsigned i = 0; i < 8; ++i) {
        result[i] = glm::vec3((i & 1u) ? max.x : min.x, (i & 2u) ? max.y : min.y, (i & 4u) ? max.z : min.z);
    }
    return result;
}

Bounds Bounds::transformed(const glm::mat4& matrix) const {
    Bounds result;
    if (empty()) return result;
    for (const glm::vec3& corner : corners()) result.extend(glm::vec3(matrix * glm::vec4(corner, 1.0f)));
    return result;
}

}  // namespace loom::scene
