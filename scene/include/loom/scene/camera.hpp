#pragma once
// Cameras: a world transform plus glTF projection parameters, turned into view and projection
// matrices for the project's conventions (right-handed view space looking down -Z, +Y up;
// clip depth 0..1; NDC y-up), and a helper that frames a bounding box automatically.

#include <optional>
#include <string>
#include <variant>

#include "loom/scene/bounds.hpp"
#include "loom/scene/glm.hpp"

namespace loom::scene {

/// glTF perspective camera parameters (angles in radians).
struct PerspectiveProjection {
    float yfov = 0.7853982f;  ///< vertical field of view, > 0 and < pi
    /// Width / height of the field of view; when absent the viewport's aspect ratio is used.
    std::optional<float> aspect_ratio;
    float znear = 0.1f;       ///< > 0
    /// Far plane (> znear); when absent the projection is infinite (depth 1 at infinity).
    std::optional<float> zfar;

    friend bool operator==(const PerspectiveProjection&, const PerspectiveProjection&) = default;
};

/// glTF orthographic camera parameters: half the width and height of the view volume.
struct OrthographicProjection {
    float xmag = 1.0f;
    float ymag = 1.0f;
    float znear = 0.0f;
    float zfar = 100.0f;

    friend bool operator==(const OrthographicProjection&, const OrthographicProjection&) = default;
};

/// What the passes draw a frame with: a camera's world-to-view and view-to-clip matrices
/// (clip depth 0..1, NDC y up) and its position. Camera::matrices() makes them; a renderer with
/// a camera model of its own fills them in directly.
struct CameraMatrices {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 position{0.0f};

    [[nodiscard]] glm::mat4 view_projection() const { return projection * view; }
};

/// A camera placed in the world. Its local frame follows glTF: the lens looks along local -Z,
/// +Y is up and +X is right.
struct Camera {
    std::string name;
    /// Camera-to-world transform (the glTF node's world matrix). Any scale in it is ignored by
    /// view_matrix().
    glm::mat4 world{1.0f};
    std::variant<PerspectiveProjection, OrthographicProjection> projection{PerspectiveProjection{}};

    /// World-to-view matrix: the inverse of `world` with its scale (and shear) removed.
    [[nodiscard]] glm::mat4 view_matrix() const;
    /// View-to-clip matrix with depth 0..1 (near → 0, far → 1). `viewport_aspect` (width /
    /// height) is used by perspective cameras that have no aspect ratio of their own;
    /// orthographic cameras use xmag and ymag as they are.
    [[nodiscard]] glm::mat4 projection_matrix(float viewport_aspect) const;
    /// projection_matrix(viewport_aspect) * view_matrix().
    [[nodiscard]] glm::mat4 view_projection(float viewport_aspect) const;
    /// Camera position in world space.
    [[nodiscard]] glm::vec3 position() const;
    /// Unit viewing direction in world space (local -Z).
    [[nodiscard]] glm::vec3 forward() const;
    /// view_matrix(), projection_matrix(viewport_aspect) and position() together.
    [[nodiscard]] CameraMatrices matrices(float viewport_aspect) const;
};

/// An infinite perspective projection with depth 0..1 (near plane → 0, infinitely far → 1),
/// right-handed view space; GLM's own infinitePerspective maps depth to -1..1.
glm::mat4 infinite_perspective(float yfov, float aspect, float znear);

/// How frame_bounds() places its camera.
struct FramingOptions {
    /// Direction from the centre of the bounds towards the camera (normalised internally):
    /// by default from the front (+Z), to the right and above, so that three faces of a box
    /// are visible.
    glm::vec3 direction{0.55f, 0.45f, 1.0f};
    /// World up; must not be parallel to `direction`.
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float yfov = 0.7853982f;  ///< 45 degrees
    /// Extra room around the bounds: 1.0 lets the outermost corner touch the viewport's edge.
    float margin = 1.1f;
};

/// A perspective camera that looks at the centre of `bounds` from options.direction, at the
/// smallest distance where all eight corners of the box lie inside a viewport of aspect ratio
/// `viewport_aspect` (and of any wider one), with near and far planes enclosing the box. The
/// camera has no aspect ratio of its own. Empty bounds are treated as a unit box around the
/// origin; flat or point-like bounds get a small extent.
Camera frame_bounds(const Bounds& bounds, float viewport_aspect, const FramingOptions& options = {});

}  // namespace loom::scene
