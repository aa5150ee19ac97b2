// The pass/object protocol without a GPU: composing stages from parts, one program per
// (pass, object kind), errors that name pass, kind, stage and line, and the deferred pass built
// from three parts.
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "loom/passes/blit_pass.hpp"
#include "loom/passes/blur_pass.hpp"
#include "loom/passes/composer.hpp"
#include "loom/passes/composite_pass.hpp"
#include "loom/passes/deferred_pass.hpp"
#include "loom/passes/forward_pass.hpp"
#include "loom/passes/geometry_pass.hpp"
#include "loom/passes/high_pass_pass.hpp"
#include "loom/passes/mesh_object.hpp"
#include "loom/passes/shadow_map_pass.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::passes {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using rhi::ShaderStage;

/// An object that records nothing; only its kind matters here.
class KindOnlyObject final : public Object {
public:
    explicit KindOnlyObject(std::shared_ptr<const ObjectKind> kind) : kind_(std::move(kind)) {}
    [[nodiscard]] const std::shared_ptr<const ObjectKind>& kind() const override { return kind_; }
    Status render(DrawContext&) const override { return {}; }

private:
    std::shared_ptr<const ObjectKind> kind_;
};

std::shared_ptr<const Object> object_of(std::shared_ptr<const ObjectKind> kind) {
    return std::make_shared<KindOnlyObject>(std::move(kind));
}

std::vector<std::string> port_names(const fg::Pass& pass) {
    std::vector<std::string> names;
    for (const fg::Port& port : pass.ports()) names.push_back(port.name);
    return names;
}

bool has_output_location(const rhi::ShaderModule& module, uint32_t location) {
    return std::any_of(module.reflection.outputs.begin(), module.reflection.outputs.end(),
                       [&](const rhi::StageVariable& v) { return v.location == location; });
}

TEST(Composition, StageListsPartsInOrderWithTheirSetsBindingsAndLines) {
    GeometryPass pass;
    const auto kind = pbr_mesh_kind();
    auto source = pass.coerce_shader(kind.get(), ShaderStage::Vertex);
    ASSERT_TRUE(source.ok()) << source.error().to_string();
    EXPECT_EQ(source->name, "geometry/pbr-mesh.vert");
    const std::string& code = source->code;
    EXPECT_THAT(code, HasSubstr("#define LOOM_STAGE_VERTEX 1\n"));
    EXPECT_THAT(code, HasSubstr("#define LOOM_OBJECT 1\n"));
    EXPECT_THAT(code, HasSubstr("#define LOOM_PART_MESH_GEOMETRY 1\n"));
    EXPECT_THAT(code, HasSubstr("#define LOOM_PART_G_BUFFER 1\n"));
    // The object's part first (set 1), then the pass's camera part (set 0); the g-buffer part has
    // no vertex code.
    const auto object_part = code.find("#line 1 \"object kind pbr-mesh, part mesh-geometry (loom/parts/mesh_geometry.vert.glsl)\"");
    const auto camera_part = code.find("#line 1 \"pass geometry, part camera (loom/parts/camera.vert.glsl)\"");
    ASSERT_NE(object_part, std::string::npos) << code;
    ASSERT_NE(camera_part, std::string::npos) << code;
    EXPECT_LT(object_part, camera_part);
    EXPECT_LT(code.rfind("#define LOOM_SET 1", object_part), object_part);
    EXPECT_LT(code.rfind("#define LOOM_SET 0", camera_part), camera_part);
    EXPECT_GT(code.rfind("#define LOOM_SET 0", camera_part), object_part);
    EXPECT_THAT(code, Not(HasSubstr("part g-buffer (")));
}

TEST(Composition, ShadowPassLeavesTheObjectsMaterialOut) {
    ShadowMapPass pass;
    const auto kind = checker_mesh_kind();
    auto vertex = pass.coerce_shader(kind.get(), ShaderStage::Vertex);
    auto fragment = pass.coerce_shader(kind.get(), ShaderStage::Fragment);
    ASSERT_TRUE(vertex.ok() && fragment.ok());
    EXPECT_THAT(vertex->code, HasSubstr("part mesh-geometry"));
    EXPECT_THAT(fragment->code, Not(HasSubstr("part checker-material (")));
    EXPECT_THAT(fragment->code, Not(HasSubstr("#define LOOM_OBJECT")));
}

TEST(Composition, ObjectsOfOneKindShareAProgramAndASecondKindGetsItsOwn) {
    auto library = std::make_shared<ShaderLibrary>();
    PassConfig config;
    config.library = library;
    GeometryPass pass(config);
    const auto pbr = pbr_mesh_kind();
    const auto cube = object_of(pbr);
    const auto sphere = object_of(pbr);
    const auto ground = object_of(checker_mesh_kind());

    ASSERT_TRUE(register_object(pass, cube).ok());
    EXPECT_EQ(pass.program_count(), 1u);
    EXPECT_EQ(library->compilations(), 2u);  // vertex + fragment
    ASSERT_TRUE(register_object(pass, sphere).ok());
    EXPECT_EQ(pass.program_count(), 1u);
    EXPECT_EQ(library->compilations(), 2u);  // nothing composed again
    EXPECT_EQ(library->requests(), 2u);
    const Program* program = program_for(pass, *cube);
    ASSERT_NE(program, nullptr);
    EXPECT_EQ(program, program_for(pass, *sphere));
    EXPECT_EQ(program->name(), "geometry/pbr-mesh");

    ASSERT_TRUE(register_object(pass, ground).ok());
    EXPECT_EQ(pass.program_count(), 2u);
    const Program* checker = program_for(pass, *ground);
    ASSERT_NE(checker, nullptr);
    EXPECT_NE(checker, program);
    EXPECT_EQ(checker->kind(), "checker-mesh");
    // The second kind's program is composed and compiled on its own (two more stages).
    EXPECT_EQ(library->compilations(), 4u);
    EXPECT_EQ(pass.objects().size(), 3u);

    // A kind never registered has no program.
    const auto stranger = object_of(std::make_shared<ObjectKind>("stranger", std::vector<ShaderPart>{},
                                                                 std::vector<rhi::VertexBufferLayout>{}));
    EXPECT_EQ(program_for(pass, *stranger), nullptr);
}

TEST(Composition, ProgramsArePerPass) {
    auto library = std::make_shared<ShaderLibrary>();
    PassConfig config;
    config.library = library;
    GeometryPass geometry(config);
    ShadowMapPass shadow(config);
    const auto cube = object_of(pbr_mesh_kind());
    ASSERT_TRUE(register_object(geometry, cube).ok());
    ASSERT_TRUE(register_object(shadow, cube).ok());
    ASSERT_NE(program_for(geometry, *cube), nullptr);
    ASSERT_NE(program_for(shadow, *cube), nullptr);
    EXPECT_NE(program_for(geometry, *cube), program_for(shadow, *cube));
    EXPECT_EQ(program_for(shadow, *cube)->name(), "shadow/pbr-mesh");
}

TEST(Composition, AnotherKindUnderATakenNameIsRefused) {
    GeometryPass pass;
    ASSERT_TRUE(register_object(pass, object_of(pbr_mesh_kind())).ok());
    auto impostor = std::make_shared<ObjectKind>("pbr-mesh", checker_mesh_kind()->parts(),
                                                 std::vector<rhi::VertexBufferLayout>{mesh_vertex_layout()});
    auto status = register_object(pass, object_of(impostor));
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidArgument);
    EXPECT_THAT(status.error().message, HasSubstr("pass 'geometry'"));
    EXPECT_THAT(status.error().message, HasSubstr("object kind 'pbr-mesh'"));
    EXPECT_EQ(pass.objects().size(), 1u);
}

TEST(Composition, AnErrorInAnObjectPartNamesPassKindStageAndLine) {
    GeometryPass pass;
    const std::string broken_material =
        "MaterialSample object_material(SurfaceInput surface) {\n"
        "    MaterialSample m;\n"
        "    m.albedo = undefined_colour;\n"
        "    return m;\n"
        "}\n";
    auto kind = std::make_shared<ObjectKind>(
        "broken-mesh",
        std::vector<ShaderPart>{pbr_mesh_kind()->parts()[0],
                                ShaderPart("broken-material").stage(ShaderStage::Fragment, broken_material)},
        std::vector<rhi::VertexBufferLayout>{mesh_vertex_layout()});
    auto status = register_object(pass, object_of(kind));
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::ShaderCompile);
    const std::string& message = status.error().message;
    EXPECT_THAT(message, HasSubstr("pass 'geometry', object kind 'broken-mesh', fragment stage"));
    EXPECT_THAT(message, HasSubstr("object kind broken-mesh, part broken-material (inline):3: 'undefined_colour'"));
    EXPECT_EQ(pass.program_count(), 0u);
    EXPECT_TRUE(pass.objects().empty());
}

TEST(Composition, AnErrorInAPassPartNamesThePartsFileAndLine) {
    ShaderPass pass("tinted");
    pass.add_shader(ShaderPart("fullscreen").stage_file(ShaderStage::Vertex, "loom/parts/fullscreen.vert.glsl"));
    pass.add_shader(ShaderPart("tint", 1).stage(ShaderStage::Fragment,
                                                "layout(location = 0) out vec4 out_color;\n"
                                                "void main() {\n"
                                                "    out_color = vec4(1.0);\n"
                                                "    out_color.rgb *= missing_tint();\n"
                                                "}\n",
                                                "tint.frag.glsl"));
    auto program = pass.own_program();
    ASSERT_FALSE(program.ok());
    const std::string& message = program.error().message;
    EXPECT_THAT(message, HasSubstr("pass 'tinted', object kind 'none', fragment stage"));
    EXPECT_THAT(message, HasSubstr("pass tinted, part tint (tint.frag.glsl):4: 'missing_tint'"));
}

TEST(Composition, NamesThatWouldRewriteTheComposedSourceAreRefused) {
    // Names go into #line directives of the composed GLSL: a newline in one would start a line
    // of code of its own (here a #define that changes the pass's output) instead of an error.
    ShaderPart vertex("fullscreen");
    vertex.stage(ShaderStage::Vertex, "void main() {}\n");
    ShaderPart evil("tint\n#define out_color discard");
    evil.stage(ShaderStage::Fragment, "void main() {}\n");
    Composition composition;
    composition.pass = "tinted";
    composition.pass_parts = {&vertex, &evil};
    auto source = compose_stage(composition, ShaderStage::Fragment);
    ASSERT_FALSE(source.ok());
    EXPECT_EQ(source.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(source.error().message,
              "pass 'tinted', object kind 'none', fragment stage: the part name 'tint\\n#define out_color discard' "
              "contains a control character (code 10)");

    ShaderPart quoted("a\"b");
    quoted.stage(ShaderStage::Fragment, "void main() {}\n");
    composition.pass_parts = {&vertex, &quoted};
    EXPECT_THAT(compose_stage(composition, ShaderStage::Fragment).error().message,
                HasSubstr("the part name 'a\"b' contains '\"', which would end the #line name"));

    // The code's origin (an embedded file name) is written into the #line directive too.
    ShaderPart ghost("ghost");
    ghost.stage(ShaderStage::Fragment, "void main() {}\n", "x.glsl\n#error injected");
    composition.pass_parts = {&vertex, &ghost};
    EXPECT_THAT(compose_stage(composition, ShaderStage::Fragment).error().message,
                HasSubstr("part 'ghost': the code origin 'x.glsl\\n#error injected' contains a control character"));
    // A file of that name is not embedded: it is the part's problem, reported on one line.
    ShaderPart lost("lost");
    lost.stage_file(ShaderStage::Fragment, "x.glsl\n#error injected");
    composition.pass_parts = {&vertex, &lost};
    EXPECT_THAT(compose_stage(composition, ShaderStage::Fragment).error().message,
                HasSubstr("part 'lost': its fragment code file 'x.glsl\\n#error injected' is not embedded"));

    composition.pass_parts = {&vertex};
    composition.pass = "a\nb";
    EXPECT_EQ(compose_stage(composition, ShaderStage::Vertex).error().message,
              "pass 'a\\nb', object kind 'none', vertex stage: the pass name 'a\\nb' contains a control character "
              "(code 10)");
    composition.pass = "tinted";
    composition.defines = {{"LOOM X", "1"}};
    EXPECT_THAT(compose_stage(composition, ShaderStage::Vertex).error().message,
                HasSubstr("the define 'LOOM X' is not a GLSL identifier"));
    composition.defines = {{"LOOM_X", "1\n#version 460"}};
    EXPECT_THAT(compose_stage(composition, ShaderStage::Vertex).error().message,
                HasSubstr("the value of define LOOM_X, '1\\n#version 460' contains a control character (code 10)"));
    composition.defines = {{"LOOM_X", "(1 + 2)"}};
    EXPECT_TRUE(compose_stage(composition, ShaderStage::Vertex).ok());
}

TEST(Composition, AMissingEmbeddedFileIsReportedWithThePart) {
    ShaderPass pass("lost");
    pass.add_shader(ShaderPart("fullscreen").stage_file(ShaderStage::Vertex, "loom/parts/fullscreen.vert.glsl"));
    pass.add_shader(ShaderPart("ghost").stage_file(ShaderStage::Fragment, "loom/parts/no_such_part.frag.glsl"));
    auto program = pass.own_program();
    ASSERT_FALSE(program.ok());
    EXPECT_EQ(program.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(program.error().message,
              "pass 'lost', object kind 'none', vertex stage: part 'ghost': its fragment code file "
              "'loom/parts/no_such_part.frag.glsl' is not embedded (shaders::include_files())");
}

TEST(Composition, AStageWithoutPassCodeIsAnError) {
    ShaderPass pass("vertexless");
    pass.add_shader(ShaderPart("colour").stage(ShaderStage::Fragment, "void main() {}\n"));
    auto program = pass.own_program();
    ASSERT_FALSE(program.ok());
    EXPECT_EQ(program.error().code, ErrorCode::InvalidArgument);
    EXPECT_THAT(program.error().message, HasSubstr("pass 'vertexless', object kind 'none', vertex stage"));
}

TEST(Composition, DeferredPassHasTheUnionOfItsPartsPortsAndResources) {
    DeferredPass pass;
    EXPECT_EQ(port_names(pass),
              (std::vector<std::string>{"position", "normal", "albedo", "emission", "color", "shadow_map", "high_pass"}));
    EXPECT_EQ(pass.find_port("color")->port_sets, (std::vector<std::string>{"deferred-render", "shadow-render"}));
    EXPECT_EQ(pass.find_port("shadow_map")->port_sets, (std::vector<std::string>{"shadow-render"}));
    EXPECT_EQ(pass.find_port("high_pass")->port_sets, (std::vector<std::string>{"high-pass-render"}));
    EXPECT_EQ(pass.find_port("shadow_map")->kind, fg::PortKind::Input);
    EXPECT_EQ(pass.find_port("high_pass")->kind, fg::PortKind::Output);

    auto program = pass.own_program();
    ASSERT_TRUE(program.ok()) << program.error().to_string();
    // Resources numbered part after part: deferred-render 0..4, shadow-render 5..6, high-pass 7.
    auto slot = [&](const char* name) { return (*program)->find(name); };
    EXPECT_EQ(slot("LightingUniforms"), (ResourceSlot{0, 0, 176}));
    EXPECT_EQ(slot("gbuffer_position"), (ResourceSlot{0, 1, 0}));
    EXPECT_EQ(slot("gbuffer_normal"), (ResourceSlot{0, 2, 0}));
    EXPECT_EQ(slot("gbuffer_albedo"), (ResourceSlot{0, 3, 0}));
    EXPECT_EQ(slot("gbuffer_emission"), (ResourceSlot{0, 4, 0}));
    EXPECT_EQ(slot("ShadowUniforms"), (ResourceSlot{0, 5, 80}));
    EXPECT_EQ(slot("shadow_map"), (ResourceSlot{0, 6, 0}));
    EXPECT_EQ(slot("HighPassUniforms"), (ResourceSlot{0, 7, 16}));
    EXPECT_TRUE(has_output_location((*program)->fragment(), 0));
    EXPECT_TRUE(has_output_location((*program)->fragment(), 1));
}

TEST(Composition, LeavingPartsOutLeavesOutTheirPortsAndCode) {
    DeferredPass pass(PassConfig{}, LightingParts{.shadows = false, .high_pass = false}, "plain");
    EXPECT_EQ(port_names(pass), (std::vector<std::string>{"position", "normal", "albedo", "emission", "color"}));
    EXPECT_EQ(pass.find_port("color")->port_sets, (std::vector<std::string>{"deferred-render"}));
    auto program = pass.own_program();
    ASSERT_TRUE(program.ok()) << program.error().to_string();
    EXPECT_FALSE((*program)->find("ShadowUniforms").has_value());
    EXPECT_FALSE((*program)->find("shadow_map").has_value());
    EXPECT_FALSE((*program)->find("HighPassUniforms").has_value());
    EXPECT_FALSE(has_output_location((*program)->fragment(), 1));

    DeferredPass shadowed(PassConfig{}, LightingParts{.shadows = true, .high_pass = false}, "shadowed");
    EXPECT_EQ(port_names(shadowed), (std::vector<std::string>{"position", "normal", "albedo", "emission", "color", "shadow_map"}));
}

/// Every standard pass composes and compiles, for its own program or for both mesh kinds, and
/// the GL source SPIRV-Cross makes of it is valid GLSL 450.
TEST(Composition, EveryStandardProgramCompilesForBothApis) {
    auto library = std::make_shared<ShaderLibrary>();
    PassConfig config;
    config.library = library;
    std::vector<std::unique_ptr<ShaderPass>> object_passes;
    object_passes.push_back(std::make_unique<ShadowMapPass>(config));
    object_passes.push_back(std::make_unique<GeometryPass>(config));
    object_passes.push_back(std::make_unique<ForwardPass>(config));
    std::vector<std::unique_ptr<ShaderPass>> post_passes;
    post_passes.push_back(std::make_unique<DeferredPass>(config));
    post_passes.push_back(std::make_unique<BlurPass>(config, BlurAxis::Horizontal, 8, "blur"));
    post_passes.push_back(std::make_unique<CompositePass>(config));
    post_passes.push_back(std::make_unique<BlitPass>(config));
    post_passes.push_back(std::make_unique<HighPassPass>(config));

    auto check = [](const Program& program) {
        for (const rhi::ShaderModule* module : {&program.vertex(), &program.fragment()}) {
            EXPECT_FALSE(module->spirv.empty()) << module->name;
            auto gl = shader_compiler::ShaderCompiler::check_gl_source(*module);
            EXPECT_TRUE(gl.ok()) << gl.error().to_string();
        }
    };
    for (auto& pass : object_passes) {
        for (const auto& kind : {pbr_mesh_kind(), checker_mesh_kind()}) {
            ASSERT_TRUE(register_object(*pass, object_of(kind)).ok()) << pass->name() << "/" << kind->name();
        }
        EXPECT_EQ(pass->program_count(), 2u);
        for (const auto& object : pass->objects()) check(*program_for(*pass, *object));
    }
    for (auto& pass : post_passes) {
        auto program = pass->own_program();
        ASSERT_TRUE(program.ok()) << pass->name() << ": " << program.error().to_string();
        check(**program);
    }
}

TEST(Composition, UniformBlockSizesAreChecked) {
    CompositePass pass;
    auto program = pass.own_program();
    ASSERT_TRUE(program.ok());
    EXPECT_TRUE((*program)->uniform_slot("CompositeUniforms", 16).ok());
    auto wrong = (*program)->uniform_slot("CompositeUniforms", 32);
    ASSERT_FALSE(wrong.ok());
    EXPECT_THAT(wrong.error().message, HasSubstr("16 bytes in the shader but 32 bytes on the CPU"));
    auto missing = (*program)->slot("NoSuchBlock");
    ASSERT_FALSE(missing.ok());
    EXPECT_THAT(missing.error().message, HasSubstr("program 'composite' has no resource named 'NoSuchBlock'"));
}

TEST(Composition, PartDefinesAreDerivedFromNames) {
    EXPECT_EQ(ShaderPart("high-pass-render").define(), "LOOM_PART_HIGH_PASS_RENDER");
    EXPECT_EQ(ShaderPart("g-buffer").define(), "LOOM_PART_G_BUFFER");
    EXPECT_EQ(ShaderPart("Blur2x").define(), "LOOM_PART_BLUR2X");
}

TEST(Composition, GaussianWeightsAreNormalisedAndDecreasing) {
    for (uint32_t radius : {0u, 1u, 4u, 24u, kMaxBlurRadius}) {
        const std::vector<float> w = gaussian_weights(radius);
        ASSERT_EQ(w.size(), radius + 1);
        double total = w[0];
        for (uint32_t i = 1; i <= radius; ++i) {
            total += 2.0 * w[i];
            EXPECT_LT(w[i], w[i - 1]);
        }
        EXPECT_NEAR(total, 1.0, 1e-6) << "radius " << radius;
    }
    EXPECT_EQ(gaussian_weights(0), std::vector<float>{1.0f});
    EXPECT_EQ(gaussian_weights(1000).size(), kMaxBlurRadius + 1);
}

}  // namespace
}  // namespace loom::passes
