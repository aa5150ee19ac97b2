// Passes composed from port sets (the paper's Listings 3-5), and what happens when two port
// sets declare the same port.
#include <gtest/gtest.h>

#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/pass.hpp"

namespace loom::fg {
namespace {

using rhi::ChannelKind;
using rhi::Format;

// A pass class in the style of the paper: its constructor composes it from port sets, the way
// deferred+shadow-pass inherits from deferred-render, shadow-render and high-pass-render.
class DeferredShadowPass : public Pass {
public:
    DeferredShadowPass() : Pass("deferred") {
        add(PortSet("deferred-render")
                .input("position_map")
                .input("normal_map")
                .input("albedo_map")
                .output("color", TextureSpec::color(3, 16, ChannelKind::Float)));
        add(PortSet("shadow-render").input("shadow_map", TextureSpec::of(Format::Depth32F)).output("color", TextureSpec::of(Format::RGBA16Float)));
        add(PortSet("high-pass-render").output("high_pass", TextureSpec::of(Format::RGBA16Float)));
    }
};

TEST(PassComposition, PortsOfAllPortSetsInFirstDeclarationOrder) {
    DeferredShadowPass pass;
    ASSERT_TRUE(pass.status().ok()) << pass.status().error().to_string();
    std::vector<std::string> names;
    for (const Port& p : pass.ports()) names.push_back(p.name);
    EXPECT_EQ(names, (std::vector<std::string>{"position_map", "normal_map", "albedo_map", "color", "shadow_map", "high_pass"}));
    EXPECT_EQ(pass.find_port("shadow_map")->kind, PortKind::Input);
    EXPECT_EQ(pass.find_port("shadow_map")->port_sets, (std::vector<std::string>{"shadow-render"}));
}

TEST(PassComposition, SameNameSameKindMergesByJoiningSpecs) {
    DeferredShadowPass pass;
    const Port* color = pass.find_port("color");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->kind, PortKind::Output);
    // "RGB, 16-bit float" joined with RGBA16Float is RGBA16Float.
    EXPECT_EQ(color->spec.format, rhi::format_info(Format::RGBA16Float).features);
    EXPECT_EQ(color->port_sets, (std::vector<std::string>{"deferred-render", "shadow-render"}));
}

TEST(PassComposition, AMergedPortIsOptionalOnlyIfEveryPortSetSaysSo) {
    Pass both_optional("a");
    both_optional.add(PortSet("p").optional_input("x")).add(PortSet("q").optional_input("x"));
    EXPECT_TRUE(both_optional.find_port("x")->optional);
    Pass one_required("b");
    one_required.add(PortSet("p").optional_input("x")).add(PortSet("q").input("x"));
    EXPECT_FALSE(one_required.find_port("x")->optional);
}

TEST(PassComposition, DifferentKindsAreAnErrorNamingBothPortSets) {
    Pass pass("tonemap");
    pass.add(PortSet("exposure").output("color")).add(PortSet("grading").input("color"));
    ASSERT_FALSE(pass.status().ok());
    const Error error = pass.status().error();
    EXPECT_EQ(error.code, ErrorCode::Graph);
    EXPECT_EQ(error.message,
              "pass 'tonemap': port 'color' is declared as output by port set 'exposure' and as input by port set 'grading'");

    // The graph refuses the pass with the same error.
    FrameGraph graph;
    auto added = graph.add_pass(pass);
    ASSERT_FALSE(added.ok());
    EXPECT_EQ(added.error().message, error.message);
}

TEST(PassComposition, SpecsThatDoNotJoinAreAnErrorNamingBothPortSets) {
    Pass pass("deferred");
    pass.add(PortSet("deferred-render").output("color", TextureSpec::of(Format::RGBA16Float)))
        .add(PortSet("shadow-render").output("color", TextureSpec::of(Format::RGBA8Unorm)));
    ASSERT_FALSE(pass.status().ok());
    const Error error = pass.status().error();
    EXPECT_EQ(error.code, ErrorCode::Join);
    EXPECT_NE(error.message.find("deferred.color (port set 'deferred-render')"), std::string::npos) << error.message;
    EXPECT_NE(error.message.find("deferred.color (port set 'shadow-render')"), std::string::npos) << error.message;
    EXPECT_NE(error.message.find("channel R kind 16 float vs 8 unorm"), std::string::npos) << error.message;
}

TEST(PassComposition, OwnDeclarationsFormAPortSetNamedAfterThePass) {
    Pass pass("blur");
    pass.input("source").output("color", TextureSpec::of(Format::RGBA16Float)).add(PortSet("mips").output("color", TextureSpec{}.with_mips(1)));
    ASSERT_TRUE(pass.status().ok());
    EXPECT_EQ(pass.find_port("color")->port_sets, (std::vector<std::string>{"blur", "mips"}));
    EXPECT_EQ(pass.find_port("color")->spec.mips, 1u);
    EXPECT_EQ(pass.port_index("color"), 1u);
    EXPECT_FALSE(pass.port_index("missing").has_value());
}

}  // namespace
}  // namespace loom::fg
