// loom::renderer without a GPU: viewpoints, the transparent pass's contract.
#include <gtest/gtest.h>

#include "loom/passes/forward_pass.hpp"
#include "loom/passes/geometry_pass.hpp"
#include "loom/passes/program.hpp"
#include "loom/passes/shadow_map_pass.hpp"
#include "loom/renderer/gltf_object.hpp"
#include "loom/renderer/scene_objects.hpp"
#include "loom/renderer/transparent_pass.hpp"
#include "synthetic_scene.hpp"

namespace loom::test {
namespace {

TEST(SceneViewpoint, TakesTheFirstCameraOrTheOneAskedForOrFramesTheBounds) {
    SceneBuilder b;
    b.quad(b.material({}));
    scene::Scene framed = b.build();
    auto view = renderer::SceneViewpoint::choose(framed);
    ASSERT_TRUE(view.ok());
    EXPECT_EQ(view->describe(), "framing the bounds");
    // Every corner of the quad lies inside the view.
    const scene::CameraMatrices camera = view->camera(16.0f / 9.0f);
    for (const glm::vec3& corner : framed.bounds.corners()) {
        const glm::vec4 clip = camera.view_projection() * glm::vec4(corner, 1.0f);
        EXPECT_LE(std::abs(clip.x / clip.w), 1.0f);
        EXPECT_LE(std::abs(clip.y / clip.w), 1.0f);
    }

    b.camera(3.0f);
    scene::Scene with_camera = b.build();
    view = renderer::SceneViewpoint::choose(with_camera);
    ASSERT_TRUE(view.ok());
    EXPECT_EQ(view->describe(), "camera 0 'test camera'");
    EXPECT_EQ(view->camera(1.0f).position, glm::vec3(0.0f, 0.0f, 3.0f));

    auto missing = renderer::SceneViewpoint::choose(with_camera, 1);
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(missing.error().message, "synthetic.gltf: camera 1 does not exist (the scene has 1 camera(s))");
}

TEST(ViewerSun, ShinesFromAboveAndBehindTheViewer) {
    SceneBuilder b;
    b.quad(b.material({}));
    b.camera(3.0f);
    const scene::Scene scene = b.build();
    const scene::CameraMatrices camera = renderer::SceneViewpoint::choose(scene)->camera(1.0f);
    const passes::DirectionalLight sun = renderer::viewer_sun(camera);
    EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-6f);
    EXPECT_GT(sun.direction.y, 0.5f);  // above
    EXPECT_GT(sun.direction.z, 0.0f);  // the camera looks down -z: behind it is +z
    EXPECT_LT(sun.direction.x, 0.0f);  // to its left
}

/// An object of the "gltf-mesh" kind that draws nothing (composition needs only the kind).
struct GltfKindOnly final : passes::Object {
    const std::shared_ptr<const passes::ObjectKind>& kind() const override { return renderer::gltf_mesh_kind(); }
    Status render(passes::DrawContext&) const override { return {}; }
};

TEST(GltfMeshKind, ComposesWithTheStandardPasses) {
    // The geometry and forward passes evaluate the material (its five samplers); the shadow
    // map takes only the vertex part (no samplers, but the object's uniforms).
    auto library = std::make_shared<passes::ShaderLibrary>();
    passes::PassConfig config;
    config.library = library;
    passes::GeometryPass geometry(config);
    passes::ForwardPass forward(config);
    passes::ShadowMapPass shadow(config);
    auto object = std::make_shared<GltfKindOnly>();
    for (passes::ShaderPass* pass : std::initializer_list<passes::ShaderPass*>{&geometry, &forward, &shadow}) {
        Status registered = passes::register_object(*pass, object);
        ASSERT_TRUE(registered.ok()) << pass->name() << ": " << registered.error().to_string();
        const passes::Program* program = passes::program_for(*pass, *object);
        ASSERT_NE(program, nullptr);
        EXPECT_TRUE(program->find("GltfObjectUniforms").has_value()) << pass->name();
        const bool material = pass != &shadow;
        for (const char* sampler : {"gltf_base_color", "gltf_metallic_roughness", "gltf_normal", "gltf_occlusion",
                                    "gltf_emissive"}) {
            EXPECT_EQ(program->find(sampler).has_value(), material) << pass->name() << ": " << sampler;
        }
    }
    // The object's resources are in set 1, the uniforms first, then the samplers in order.
    const passes::Program* program = passes::program_for(geometry, *object);
    EXPECT_EQ(program->find("GltfObjectUniforms")->set, passes::kObjectSet);
    EXPECT_EQ(program->find("GltfObjectUniforms")->binding, 0u);
    EXPECT_EQ(program->find("gltf_emissive")->binding, 5u);
    EXPECT_EQ(program->find("GltfObjectUniforms")->size, 384u);
}

TEST(TransparentPass, NeedsBoundsToSortBy) {
    renderer::TransparentPass pass;
    using Nothing = GltfKindOnly;
    Status refused = pass.register_object(std::make_shared<Nothing>());
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidArgument);
    EXPECT_NE(refused.error().message.find("needs world bounds"), std::string::npos) << refused.error().message;
    EXPECT_TRUE(pass.objects().empty());
    // With bounds it composes the program (gltf-mesh with blend-render) and keeps the object.
    Status accepted = pass.register_object(std::make_shared<Nothing>(), scene::Bounds{});
    ASSERT_TRUE(accepted.ok()) << accepted.error().to_string();
    EXPECT_EQ(pass.objects().size(), 1u);
    EXPECT_EQ(pass.program_count(), 1u);
    // Its ports: colour, high pass and depth blended in place, the shadow map read.
    ASSERT_NE(pass.find_port("color"), nullptr);
    EXPECT_EQ(pass.find_port("color")->kind, fg::PortKind::InOut);
    EXPECT_EQ(pass.find_port("high_pass")->kind, fg::PortKind::InOut);
    EXPECT_EQ(pass.find_port("depth")->kind, fg::PortKind::InOut);
    EXPECT_EQ(pass.find_port("shadow_map")->kind, fg::PortKind::Input);
}

}  // namespace
}  // namespace loom::test
