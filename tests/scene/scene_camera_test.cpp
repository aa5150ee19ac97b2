// Cameras: view and projection matrices in the project's conventions (depth 0..1, y up, no
// flip) and automatic framing of bounds.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "loom/scene/camera.hpp"

namespace loom::test {
namespace {

using scene::Bounds;
using scene::Camera;

glm::vec3 project(const glm::mat4& view_projection, const glm::vec3& point) {
    const glm::vec4 clip = view_projection * glm::vec4(point, 1.0f);
    return glm::vec3(clip) / clip.w;
}

TEST(SceneCamera, PerspectiveDepthRunsZeroToOneAndYIsUp) {
    Camera camera;
    camera.projection = scene::PerspectiveProjection{1.0f, std::nullopt, 0.5f, 10.0f};
    const glm::mat4 projection = camera.projection_matrix(1.0f);
    EXPECT_NEAR(project(projection, glm::vec3(0, 0, -0.5f)).z, 0.0f, 1e-6f);
    EXPECT_NEAR(project(projection, glm::vec3(0, 0, -10.0f)).z, 1.0f, 1e-6f);
    EXPECT_GT(project(projection, glm::vec3(0, 1, -2)).y, 0.0f);  // above the axis is up in NDC
    EXPECT_GT(project(projection, glm::vec3(1, 0, -2)).x, 0.0f);
}

TEST(SceneCamera, OrthographicMapsTheMagnificationToTheEdges) {
    Camera camera;
    camera.projection = scene::OrthographicProjection{2.0f, 1.0f, 0.0f, 4.0f};
    const glm::mat4 projection = camera.projection_matrix(3.0f);  // the aspect does not matter
    const glm::vec3 corner = project(projection, glm::vec3(2.0f, 1.0f, -4.0f));
    EXPECT_NEAR(corner.x, 1.0f, 1e-6f);
    EXPECT_NEAR(corner.y, 1.0f, 1e-6f);
    EXPECT_NEAR(corner.z, 1.0f, 1e-6f);
    EXPECT_NEAR(project(projection, glm::vec3(-2.0f, -1.0f, 0.0f)).z, 0.0f, 1e-6f);
}

TEST(SceneCamera, InfinitePerspective) {
    const glm::mat4 projection = scene::infinite_perspective(1.2f, 1.5f, 0.25f);
    EXPECT_NEAR(project(projection, glm::vec3(0, 0, -0.25f)).z, 0.0f, 1e-6f);
    const float far_depth = project(projection, glm::vec3(0, 0, -1e7f)).z;
    EXPECT_GT(far_depth, 0.99999f);
    EXPECT_LE(far_depth, 1.0f);
    // Same field of view as the finite one.
    const glm::mat4 finite = Camera{"", glm::mat4(1.0f), scene::PerspectiveProjection{1.2f, 1.5f, 0.25f, 100.0f}}.projection_matrix(1.0f);
    EXPECT_FLOAT_EQ(projection[0][0], finite[0][0]);
    EXPECT_FLOAT_EQ(projection[1][1], finite[1][1]);
}

TEST(SceneCamera, ViewMatrixIgnoresScaleInTheWorldTransform) {
    Camera camera;
    glm::mat4 world(1.0f);
    world[0] *= 3.0f;  // scaled camera node
    world[1] *= 3.0f;
    world[2] *= 3.0f;
    world[3] = glm::vec4(1, 2, 3, 1);
    camera.world = world;
    const glm::vec3 seen = glm::vec3(camera.view_matrix() * glm::vec4(1, 2, 1, 1));
    EXPECT_NEAR(seen.x, 0.0f, 1e-6f);
    EXPECT_NEAR(seen.y, 0.0f, 1e-6f);
    EXPECT_NEAR(seen.z, -2.0f, 1e-6f);  // two units in front
    EXPECT_EQ(camera.position(), glm::vec3(1, 2, 3));
    EXPECT_EQ(camera.forward(), glm::vec3(0, 0, -1));
}

void expect_framed(const Bounds& bounds, float aspect, const scene::FramingOptions& options = {}) {
    const Camera camera = scene::frame_bounds(bounds, aspect, options);
    const glm::mat4 view_projection = camera.view_projection(aspect);
    float largest = 0.0f;
    const Bounds box = bounds.empty() ? Bounds{glm::vec3(-0.5f), glm::vec3(0.5f)} : bounds;
    for (const glm::vec3& corner : box.corners()) {
        const glm::vec3 ndc = project(view_projection, corner);
        EXPECT_LE(std::abs(ndc.x), 1.0f);
        EXPECT_LE(std::abs(ndc.y), 1.0f);
        EXPECT_GE(ndc.z, 0.0f);
        EXPECT_LE(ndc.z, 1.0f);
        largest = std::max({largest, std::abs(ndc.x), std::abs(ndc.y)});
    }
    // Tight: the outermost corner reaches 1 / margin of the half-viewport.
    EXPECT_NEAR(largest, 1.0f / options.margin, 1e-3f) << "the bounds are not framed tightly";
    // The camera looks at the centre.
    const glm::vec3 center = project(view_projection, box.center());
    EXPECT_NEAR(center.x, 0.0f, 1e-4f);
    EXPECT_NEAR(center.y, 0.0f, 1e-4f);
}

TEST(SceneCamera, MatricesAreTheViewProjectionAndPositionOfOneFrame) {
    Camera camera;
    camera.world = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 2.0f, 3.0f)) *
                   glm::rotate(glm::mat4(1.0f), 0.5f, glm::vec3(0.0f, 1.0f, 0.0f));
    camera.projection = scene::PerspectiveProjection{0.9f, std::nullopt, 0.2f, 40.0f};
    const scene::CameraMatrices m = camera.matrices(1.5f);
    EXPECT_EQ(m.view, camera.view_matrix());
    EXPECT_EQ(m.projection, camera.projection_matrix(1.5f));
    EXPECT_EQ(m.position, glm::vec3(1.0f, 2.0f, 3.0f));
    EXPECT_EQ(m.view_projection(), camera.view_projection(1.5f));
    // The camera's own position lands on the view-space origin.
    const glm::vec4 eye = m.view * glm::vec4(m.position, 1.0f);
    EXPECT_NEAR(glm::length(glm::vec3(eye)), 0.0f, 1e-5f);
}

TEST(SceneCamera, FramingFitsBoundsOfEveryShapeAndAspect) {
    const std::vector<Bounds> boxes = {
        {glm::vec3(-1), glm::vec3(1)},
        {glm::vec3(100, 200, -50), glm::vec3(101, 260, -49)},  // tall, far from the origin
        {glm::vec3(-1000, 0, -1000), glm::vec3(1000, 1, 1000)},  // flat and wide
        {glm::vec3(0.001f, 0.001f, 0.001f), glm::vec3(0.002f, 0.002f, 0.002f)},  // tiny
        {glm::vec3(5, 5, 5), glm::vec3(5, 5, 5)},  // a single point
    };
    for (const Bounds& box : boxes) {
        for (const float aspect : {0.25f, 1.0f, 2.5f}) {
            SCOPED_TRACE(std::to_string(box.min.x) + " aspect " + std::to_string(aspect));
            if (box.size() == glm::vec3(0.0f)) {
                // A point has no extent to fill the view with; it only has to be in the middle
                // of the view (to float precision at its distance from the origin).
                const Camera camera = scene::frame_bounds(box, aspect);
                const glm::vec3 ndc = project(camera.view_projection(aspect), box.min);
                EXPECT_NEAR(ndc.x, 0.0f, 1e-3f);
                EXPECT_NEAR(ndc.y, 0.0f, 1e-3f);
                EXPECT_GE(ndc.z, 0.0f);
                EXPECT_LE(ndc.z, 1.0f);
                continue;
            }
            expect_framed(box, aspect);
        }
    }
}

TEST(SceneCamera, FramingEmptyBoundsAndDirections) {
    expect_framed(Bounds{}, 1.0f);
    scene::FramingOptions from_above;
    from_above.direction = glm::vec3(0, 1, 0);  // parallel to up: another up vector is chosen
    expect_framed(Bounds{glm::vec3(-1), glm::vec3(1)}, 1.5f, from_above);
    const Camera camera = scene::frame_bounds(Bounds{glm::vec3(-1), glm::vec3(1)}, 1.5f, from_above);
    EXPECT_NEAR(camera.forward().y, -1.0f, 1e-5f);
    // The default direction looks from the front right, above: +X, +Y, +Z of the centre.
    const Camera front = scene::frame_bounds(Bounds{glm::vec3(-1), glm::vec3(1)}, 1.0f);
    EXPECT_GT(front.position().x, 0.0f);
    EXPECT_GT(front.position().y, 0.0f);
    EXPECT_GT(front.position().z, 0.0f);
    EXPECT_FALSE(std::get<scene::PerspectiveProjection>(front.projection).aspect_ratio.has_value());
}

}  // namespace
}  // namespace loom::test
