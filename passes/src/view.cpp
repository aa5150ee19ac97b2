#include "loom/passes/view.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace loom::passes {

glm::mat4 fit_directional_shadow(const glm::vec3& towards_light, const scene::Bounds& bounds) {
    const glm::vec3 direction = glm::normalize(towards_light);
    const glm::vec3 center = (bounds.min + bounds.max) * 0.5f;
    const float radius = std::max(glm::length(bounds.max - bounds.min) * 0.5f, 1e-3f);
    // Any up vector not parallel to the light works; the fit below is tight either way.
    const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    const glm::mat4 view = glm::lookAtRH(center + direction * (2.0f * radius), center, up);

    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                               (i & 4) ? bounds.max.z : bounds.min.z);
        const glm::vec3 v = glm::vec3(view * glm::vec4(corner, 1.0f));
        lo = glm::min(lo, v);
        hi = glm::max(hi, v);
    }
    // A little room so that surfaces on the box's faces are not clipped.
    const float pad = radius * 1e-3f;
    lo -= glm::vec3(pad);
    hi += glm::vec3(pad);
    // View space looks down -z: the nearest corner has the largest z.
    const glm::mat4 projection = glm::orthoRH_ZO(lo.x, hi.x, lo.y, hi.y, -hi.z, -lo.z);
    return projection * view;
}

}  // namespace loom::passes
