// The pass/object protocol on the GPU: render_with() defers to the object's render() by
// default, a pass that overrides it takes full control of how objects are drawn, and a pass
// draws from any draw source besides its objects.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/passes/draw_source.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom_test/render_fixture.hpp"

namespace loom::test {
namespace {

using passes::Bindings;
using passes::DrawContext;
using passes::ObjectKind;
using passes::ShaderPart;
using rhi::ShaderStage;

/// Mirrors FlatUniforms of the "flat-geometry" part.
struct FlatUniforms {
    float color[4];
};

/// A kind whose objects are 2D triangles in NDC with a uniform colour.
std::shared_ptr<const ObjectKind> flat_kind() {
    const char* block =
        "layout(set = LOOM_SET, binding = LOOM_BINDING(0)) uniform FlatUniforms { vec4 color; } flat_object;\n";
    ShaderPart geometry("flat-geometry", 1);
    geometry.stage(ShaderStage::Vertex, std::string(block) +
                                            "layout(location = 0) in vec2 in_position;\n"
                                            "ObjectVertex object_vertex() {\n"
                                            "    ObjectVertex v;\n"
                                            "    v.world_position = vec3(in_position, 0.0);\n"
                                            "    v.world_normal = vec3(0.0, 0.0, 1.0);\n"
                                            "    v.uv = vec2(0.0);\n"
                                            "    v.color = vec4(1.0);\n"
                                            "    return v;\n"
                                            "}\n");
    geometry.stage(ShaderStage::Fragment, std::string(block) +
                                              "MaterialSample object_material(SurfaceInput s) {\n"
                                              "    MaterialSample m;\n"
                                              "    m.albedo = flat_object.color.rgb;\n"
                                              "    m.metallic = 0.0;\n"
                                              "    m.roughness = 1.0;\n"
                                              "    m.emissive = vec3(0.0);\n"
                                              "    return m;\n"
                                              "}\n");
    rhi::VertexBufferLayout layout;
    layout.stride = 8;
    layout.attributes = {{0, rhi::VertexFormat::Float2, 0}};
    return std::make_shared<ObjectKind>("flat", std::vector<ShaderPart>{geometry},
                                        std::vector<rhi::VertexBufferLayout>{layout});
}

/// A triangle with its own vertex buffer; counts how often it was asked to render itself.
class FlatTriangle final : public passes::Object {
public:
    FlatTriangle(std::shared_ptr<const ObjectKind> kind, rhi::BufferHandle vertices, std::array<float, 4> color)
        : kind_(std::move(kind)), vertices_(vertices), color_(color) {}

    [[nodiscard]] const std::shared_ptr<const ObjectKind>& kind() const override { return kind_; }
    [[nodiscard]] rhi::RasterState raster() const override { return {}; }  // no culling
    Status render(DrawContext& context) const override {
        ++renders;
        FlatUniforms uniforms{{color_[0], color_[1], color_[2], color_[3]}};
        LOOM_TRY(Bindings(context.program, context.commands, passes::kObjectSet).uniforms("FlatUniforms", uniforms).bind());
        context.commands.set_vertex_buffer(0, vertices_);
        context.commands.draw(3);
        return {};
    }
    [[nodiscard]] rhi::BufferHandle vertices() const { return vertices_; }

    mutable int renders = 0;

private:
    std::shared_ptr<const ObjectKind> kind_;
    rhi::BufferHandle vertices_;
    std::array<float, 4> color_;
};

/// Draws its objects' material colour into "color" (RGBA8Unorm).
class FlatPass : public passes::ShaderPass {
public:
    explicit FlatPass(std::string name) : ShaderPass(std::move(name)) {
        passes::PassPart part("flat-pass");
        part.ports.output("color", fg::TextureSpec::of(rhi::Format::RGBA8Unorm).with_usage(rhi::TextureUsage::CopySrc));
        part.shader.stage(ShaderStage::Vertex,
                          "void main() { gl_Position = vec4(object_vertex().world_position, 1.0); }\n");
        part.shader.stage(ShaderStage::Fragment,
                          "layout(location = 0) out vec4 out_color;\n"
                          "void main() {\n"
                          "    SurfaceInput s;\n"
                          "    s.world_position = vec3(0.0);\n"
                          "    s.world_normal = vec3(0.0, 0.0, 1.0);\n"
                          "    s.uv = vec2(0.0);\n"
                          "    s.color = vec4(1.0);\n"
                          "    out_color = vec4(object_material(s).albedo, 1.0);\n"
                          "}\n");
        add(part);
    }

    Status execute(fg::PassContext& context) override {
        const std::string colors[] = {"color"};
        auto state = attachment_state(context, colors);
        if (!state) return state.take_error();
        context.begin_render_pass({{"color", {0.0, 0.0, 0.0, 1.0}}});
        Status drawn = draw_objects(context, *state, [](Bindings& set) { return set.status(); });
        context.end_render_pass();
        return drawn;
    }
};

/// Takes full control: never calls the objects' render(); draws their triangles in blue itself.
class BluePass final : public FlatPass {
public:
    BluePass() : FlatPass("blue") {}
    Status render_with(DrawContext& context, const passes::Object& object) override {
        const auto* triangle = dynamic_cast<const FlatTriangle*>(&object);
        if (!triangle) return make_error(ErrorCode::InvalidArgument, "blue pass draws flat triangles only");
        LOOM_TRY(Bindings(context.program, context.commands, passes::kObjectSet)
                     .uniforms("FlatUniforms", FlatUniforms{{0.0f, 0.0f, 1.0f, 1.0f}})
                     .bind());
        context.commands.set_vertex_buffer(0, triangle->vertices());
        context.commands.draw(3);
        return {};
    }
};

/// A draw source of its own, not the retained scene: draws its flat triangles in blue through
/// the pipelines and set 0 of the pass it serves, and counts what the pass asked of it.
class BlueTriangleSource final : public passes::DrawSource {
public:
    explicit BlueTriangleSource(std::vector<std::shared_ptr<FlatTriangle>> triangles) : triangles_(std::move(triangles)) {}

    Status attach(passes::ShaderPass& pass) {
        auto program = pass.prepare_kind(flat_kind_);
        if (!program) return program.take_error();
        return pass.attach_draw_source(*this);
    }

    Status draw(passes::DrawSourceContext& context) override {
        ++draws;
        const passes::Program* program = context.pass().program_for_kind(*flat_kind_);
        if (!program) return make_error(ErrorCode::InvalidState, "the flat kind was not prepared");
        passes::PipelineState state = context.state();
        state.raster.cull = rhi::CullMode::None;
        auto pipeline = context.pipeline(*program, state, *flat_kind_);
        if (!pipeline) return pipeline.take_error();
        rhi::CommandList& commands = context.pass_context().commands();
        commands.set_pipeline(*pipeline);
        LOOM_TRY(context.bind_pass_set(*program));
        for (const auto& triangle : triangles_) {
            LOOM_TRY(Bindings(*program, commands, passes::kObjectSet)
                         .uniforms("FlatUniforms", FlatUniforms{{0.0f, 0.0f, 1.0f, 1.0f}})
                         .bind());
            commands.set_vertex_buffer(0, triangle->vertices());
            commands.draw(3);
        }
        return {};
    }

    void detach(passes::ShaderPass& pass) override {
        ++detaches;
        pass.detach_draw_source(*this);
    }

    int draws = 0;
    int detaches = 0;

private:
    std::shared_ptr<const ObjectKind> flat_kind_ = flat_kind();
    std::vector<std::shared_ptr<FlatTriangle>> triangles_;
};

class ProtocolTest : public RenderTest {
protected:
    void TearDown() override {
        for (rhi::BufferHandle buffer : buffers_) (void)device().destroy(buffer);
        RenderTest::TearDown();
    }

    /// Two triangles: one over the left half (red), one over the right half (green).
    std::vector<std::shared_ptr<FlatTriangle>> triangles() {
        const auto kind = flat_kind();
        const std::vector<float> left{-1.0f, -1.0f, -0.05f, -1.0f, -1.0f, 1.0f};
        const std::vector<float> right{1.0f, 1.0f, 0.05f, 1.0f, 1.0f, -1.0f};
        std::vector<std::shared_ptr<FlatTriangle>> out;
        for (const auto* vertices : {&left, &right}) {
            rhi::BufferDesc desc;
            desc.name = "triangle";
            desc.size = vertices->size() * sizeof(float);
            desc.usage = rhi::BufferUsage::Vertex;
            auto buffer = device().create_buffer(desc);
            EXPECT_TRUE(buffer.ok());
            buffers_.push_back(*buffer);
            EXPECT_TRUE(device().write_buffer(*buffer, 0, std::as_bytes(std::span<const float>(*vertices))).ok());
        }
        out.push_back(std::make_shared<FlatTriangle>(kind, buffers_[buffers_.size() - 2], std::array<float, 4>{1, 0, 0, 1}));
        out.push_back(std::make_shared<FlatTriangle>(kind, buffers_.back(), std::array<float, 4>{0, 1, 0, 1}));
        return out;
    }

    /// Runs a graph of `pass` alone and reads its colour back.
    rhi::Image render(std::unique_ptr<FlatPass> pass) {
        const std::string name = pass->name();
        fg::FrameGraph graph;
        EXPECT_TRUE(graph.add_pass(std::unique_ptr<fg::Pass>(std::move(pass))).ok());
        EXPECT_TRUE(graph.mark_output(fg::port(name, "color")).ok());
        fg::Executor executor(device());
        fg::PlanOptions options;
        options.frame = {32, 16};
        auto status = executor.run_frame(graph, options);
        EXPECT_TRUE(status.ok()) << status.error().to_string();
        auto image = device().read_texture(executor.texture(name, "color"));
        EXPECT_TRUE(image.ok());
        return image ? std::move(*image) : rhi::Image{};
    }

    std::vector<rhi::BufferHandle> buffers_;
};

std::array<double, 4> at(const rhi::Image& image, uint32_t x, uint32_t y) { return image.load(x, y); }

TEST_P(ProtocolTest, RenderWithDefersToTheObjectsRender) {
    auto objects = triangles();
    auto pass = std::make_unique<FlatPass>("flat");
    for (const auto& object : objects) ASSERT_TRUE(passes::register_object(*pass, object).ok());
    EXPECT_EQ(pass->program_count(), 1u);  // one kind, one program
    const rhi::Image image = render(std::move(pass));
    ASSERT_EQ(image.width, 32u);
    // Each object drew itself with its own colour: red on the left, green on the right.
    EXPECT_EQ(at(image, 2, 8), (std::array<double, 4>{1, 0, 0, 1}));
    EXPECT_EQ(at(image, 29, 8), (std::array<double, 4>{0, 1, 0, 1}));
    EXPECT_EQ(at(image, 16, 8), (std::array<double, 4>{0, 0, 0, 1}));  // the gap between them
    EXPECT_EQ(objects[0]->renders, 1);
    EXPECT_EQ(objects[1]->renders, 1);
}

TEST_P(ProtocolTest, APassOverridingRenderWithTakesFullControl) {
    auto objects = triangles();
    auto pass = std::make_unique<BluePass>();
    for (const auto& object : objects) ASSERT_TRUE(passes::register_object(*pass, object).ok());
    const rhi::Image image = render(std::move(pass));
    // The pass drew both triangles its own way; the objects' render() never ran.
    EXPECT_EQ(at(image, 2, 8), (std::array<double, 4>{0, 0, 1, 1}));
    EXPECT_EQ(at(image, 29, 8), (std::array<double, 4>{0, 0, 1, 1}));
    EXPECT_EQ(at(image, 16, 8), (std::array<double, 4>{0, 0, 0, 1}));
    EXPECT_EQ(objects[0]->renders, 0);
    EXPECT_EQ(objects[1]->renders, 0);
}

TEST_P(ProtocolTest, APassDrawsFromAnyDrawSourceAfterItsObjects) {
    auto objects = triangles();
    auto pass = std::make_unique<FlatPass>("flat");
    ASSERT_TRUE(passes::register_object(*pass, objects[0]).ok());  // the left one, red, drawn by the pass
    BlueTriangleSource source({objects[1]});                       // the right one, drawn by the source
    ASSERT_TRUE(source.attach(*pass).ok());
    EXPECT_EQ(pass->draw_source(), &source);

    // A pass draws from one source.
    BlueTriangleSource other({});
    auto refused = other.attach(*pass);
    ASSERT_FALSE(refused.ok());
    EXPECT_EQ(refused.error().code, ErrorCode::InvalidState);
    EXPECT_EQ(refused.error().message, "pass 'flat' is attached to another draw source");

    const rhi::Image image = render(std::move(pass));
    EXPECT_EQ(at(image, 2, 8), (std::array<double, 4>{1, 0, 0, 1}));
    EXPECT_EQ(at(image, 29, 8), (std::array<double, 4>{0, 0, 1, 1}));
    EXPECT_EQ(at(image, 16, 8), (std::array<double, 4>{0, 0, 0, 1}));
    EXPECT_EQ(objects[1]->renders, 0);
    EXPECT_EQ(source.draws, 1);
    // The pass went with its graph and detached itself; the other source never held it.
    EXPECT_EQ(source.detaches, 1);
    EXPECT_EQ(other.detaches, 0);
}

/// An object whose render() fails.
class BrokenObject final : public passes::Object {
public:
    explicit BrokenObject(std::shared_ptr<const ObjectKind> kind) : kind_(std::move(kind)) {}
    [[nodiscard]] const std::shared_ptr<const ObjectKind>& kind() const override { return kind_; }
    Status render(DrawContext&) const override {
        return make_error(ErrorCode::InvalidState, "object 'broken' lost its vertices");
    }

private:
    std::shared_ptr<const ObjectKind> kind_;
};

TEST_P(ProtocolTest, AnObjectsErrorFailsTheFrameNamingThePass) {
    auto pass = std::make_unique<FlatPass>("flat");
    ASSERT_TRUE(passes::register_object(*pass, std::make_shared<BrokenObject>(flat_kind())).ok());
    fg::FrameGraph graph;
    ASSERT_TRUE(graph.add_pass(std::unique_ptr<fg::Pass>(std::move(pass))).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("flat", "color")).ok());
    fg::Executor executor(device());
    fg::PlanOptions options;
    options.frame = {8, 8};
    auto status = executor.run_frame(graph, options);
    ASSERT_FALSE(status.ok());
    EXPECT_EQ(status.error().code, ErrorCode::InvalidState);
    EXPECT_NE(status.error().message.find("flat"), std::string::npos) << status.error().message;
    EXPECT_NE(status.error().message.find("object 'broken' lost its vertices"), std::string::npos)
        << status.error().message;
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(ProtocolTest);

}  // namespace loom::test
