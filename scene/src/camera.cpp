#include "loom/scene/camera.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace loom::scene {
namespace {

// The rotation part of a camera's world matrix with scale and shear removed: the viewing axis
// (local Z) is kept exactly, up is made perpendicular to it, right completes a right-handed
// frame. Degenerate matrices give the identity rotation.
glm::mat3 camera_rotation(const glm::mat4& world) {
    const glm::vec3 z_axis(world[2]);
    const glm::vec3 y_axis(world[1]);
    if (glm::length(z_axis) <= 0.0f) return glm::mat3(1.0f);
    const glm::vec3 z = glm::normalize(z_axis);
    glm::vec3 y = y_axis - z * glm::dot(z, y_axis);
    if (glm::length(y) <= 1e-12f) return glm::mat3(1.0f);
    y = glm::normalize(y);
    const glm::vec3 x = glm::cross(y, z);
    return glm::mat3(x, y, z);
}

float usable_aspect(float aspect) { return aspect > 0.0f && std::isfinite(aspect) ? aspect : 1.0f; }

}  // namespace

glm::mat4 Camera::view_matrix() const {
    const glm::mat3 rotation = camera_rotation(world);
    const glm::mat3 inverse_rotation = glm::transpose(rotation);
    glm::mat4 view(inverse_rotation);
    view[3] = glm::vec4(-(inverse_rotation * glm::vec3(world[3])), 1.0f);
    return view;
}

glm::mat4 Camera::projection_matrix(float viewport_aspect) const {
    if (const auto* perspective = std::get_if<PerspectiveProjection>(&projection)) {
        const float aspect = usable_aspect(perspective->aspect_ratio.value_or(viewport_aspect));
        if (perspective->zfar) return glm::perspective(perspective->yfov, aspect, perspective->znear, *perspective->zfar);
        return infinite_perspective(perspective->yfov, aspect, perspective->znear);
    }
    const auto& ortho = std::get<OrthographicProjection>(projection);
    return glm::ortho(-ortho.xmag, ortho.xmag, -ortho.ymag, ortho.ymag, ortho.znear, ortho.zfar);
}

glm::mat4 Camera::view_projection(float viewport_aspect) const {
    return projection_matrix(viewport_aspect) * view_matrix();
}

glm::vec3 Camera::position() const { return glm::vec3(world[3]); }

glm::vec3 Camera::forward() const { return -(camera_rotation(world)[2]); }

glm::mat4 infinite_perspective(float yfov, float aspect, float znear) {
    const float focal = 1.0f / std::tan(yfov * 0.5f);
    glm::mat4 m(0.0f);
    m[0][0] = focal / usable_aspect(aspect);
    m[1][1] = focal;
    m[2][2] = -1.0f;  // clip z = -z_view - znear, clip w = -z_view: depth 0 at the near plane,
    m[2][3] = -1.0f;  // approaching 1 at infinity
    m[3][2] = -znear;
    return m;
}

CameraMatrices Camera::matrices(float viewport_aspect) const {
    return CameraMatrices{view_matrix(), projection_matrix(viewport_aspect), position()};
}

Camera frame_bounds(const Bounds& bounds, float viewport_aspect, const FramingOptions& options) {
    glm::vec3 center(0.0f);
    glm::vec3 half(0.5f);  // empty bounds: a unit box around the origin
    if (!bounds.empty()) {
        center = bounds.center();
        half = 0.5f * bounds.size();
    }
    // Give flat or point-like bounds some extent, relative to their distance from the origin
    // so that the camera does not sit closer than float precision can place it.
    const float magnitude = std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
    half = glm::max(half, glm::vec3(std::max(1e-3f * magnitude, 1e-6f)));

    glm::vec3 direction = options.direction;
    direction = glm::length(direction) > 0.0f ? glm::normalize(direction) : glm::vec3(0.0f, 0.0f, 1.0f);
    glm::vec3 up = options.up;
    if (!(glm::length(glm::cross(direction, up)) > 1e-4f * glm::length(up))) {
        up = std::abs(direction.y) < 0.9f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 0.0f, -1.0f);
    }
    // The camera's frame: it looks along -direction.
    const glm::vec3 right = glm::normalize(glm::cross(up, direction));
    const glm::vec3 camera_up = glm::cross(direction, right);

    const float yfov = options.yfov > 0.0f && options.yfov < 3.1f ? options.yfov : 0.7853982f;
    const float tan_y = std::tan(0.5f * yfov);
    const float tan_x = tan_y * usable_aspect(viewport_aspect);
    const float margin = std::max(options.margin, 1.0f);

    // A corner at offset o from the centre, seen from distance d along `direction`, is at depth
    // d - dot(o, direction); it is inside the view when |dot(o, right)| <= depth * tan_x and
    // |dot(o, camera_up)| <= depth * tan_y. The smallest d satisfying every corner (with the
    // margin) frames the box tightly.
    Bounds box{center - half, center + half};
    float distance = 0.0f;
    float max_toward = -std::numeric_limits<float>::infinity();
    for (const glm::vec3& corner : box.corners()) {
        const glm::vec3 offset = corner - center;
        const float toward = glm::dot(offset, direction);
        const float needed = margin * std::max(std::abs(glm::dot(offset, right)) / tan_x,
                                               std::abs(glm::dot(offset, camera_up)) / tan_y);
        distance = std::max(distance, toward + needed);
        max_toward = std::max(max_toward, toward);
    }
    distance = std::max(distance, max_toward + 0.01f * glm::length(half));
    float nearest = std::numeric_limits<float>::infinity();
    float farthest = 0.0f;
    for (const glm::vec3& corner : box.corners()) {
        const float depth = distance - glm::dot(corner - center, direction);
        nearest = std::min(nearest, depth);
        farthest = std::max(farthest, depth);
    }

    Camera camera;
    camera.name = "framing camera";
    const glm::vec3 eye = center + direction * distance;
    camera.world = glm::inverse(glm::lookAt(eye, center, camera_up));
    PerspectiveProjection perspective;
    perspective.yfov = yfov;
    perspective.znear = 0.9f * nearest;
    perspective.zfar = 1.1f * farthest;
    camera.projection = perspective;
    return camera;
}

}  // namespace loom::scene
