// The part table (parts.hpp) without a GPU: every row names a distinct part and embedded files,
// every part file in shaders/include/loom/parts/ is embedded and belongs to a row, a row's ports
// follow the options, and a row with a missing file or a name without a row fails naming the
// part (and the file) — what adding a part (a .glsl file and a row) relies on.
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "loom/framegraph/pass.hpp"
#include "loom/passes/parts.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/shaders/builtin.hpp"

namespace loom::passes {
namespace {

using ::testing::HasSubstr;

bool is_stage_file(std::string_view file) { return file.ends_with(".vert.glsl") || file.ends_with(".frag.glsl"); }

TEST(PartTable, EveryRowNamesADistinctPartAndEmbeddedFilesOfItsStages) {
    const auto& files = shaders::include_files();
    std::set<std::string_view> names;
    for (const PartDesc& desc : standard_parts()) {
        SCOPED_TRACE(std::string(desc.name));
        EXPECT_TRUE(names.insert(desc.name).second) << "a second row of that name";
        EXPECT_EQ(fg::name_problem(desc.name), std::nullopt);
        EXPECT_FALSE(desc.vertex_file.empty() && desc.fragment_file.empty()) << "no code";
        if (!desc.vertex_file.empty()) {
            EXPECT_TRUE(desc.vertex_file.ends_with(".vert.glsl")) << desc.vertex_file;
            EXPECT_TRUE(files.contains(std::string(desc.vertex_file))) << desc.vertex_file << " is not embedded";
        }
        if (!desc.fragment_file.empty()) {
            EXPECT_TRUE(desc.fragment_file.ends_with(".frag.glsl")) << desc.fragment_file;
            EXPECT_TRUE(files.contains(std::string(desc.fragment_file))) << desc.fragment_file << " is not embedded";
        }
    }
}

TEST(PartTable, EveryPartFileIsEmbeddedAndEveryStageFileBelongsToARow) {
    std::set<std::string, std::less<>> in_rows;
    for (const PartDesc& desc : standard_parts()) {
        in_rows.emplace(desc.vertex_file);
        in_rows.emplace(desc.fragment_file);
    }
    const auto& files = shaders::include_files();
    std::size_t stage_files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(LOOM_PARTS_DIR)) {
        const std::string name = "loom/parts/" + entry.path().filename().string();
        EXPECT_TRUE(files.contains(name)) << name << " is not embedded";
        // A stage file no row names is a part without its row; other .glsl files are included
        // by parts (gltf_object.glsl).
        if (!is_stage_file(name)) continue;
        ++stage_files;
        EXPECT_TRUE(in_rows.contains(name)) << name << " belongs to no row of the part table";
    }
    EXPECT_GT(stage_files, 0u);
}

TEST(PartTable, PortsFollowTheOptions) {
    PassConfig config;
    config.capturable = true;
    const PassPart shadow = standard_part("shadow-caster", {.config = config, .shadow_map_size = 512});
    ASSERT_EQ(shadow.ports.declarations().size(), 1u);
    EXPECT_EQ(shadow.ports.declarations()[0].name, "shadow_map");
    EXPECT_EQ(shadow.ports.declarations()[0].spec, depth_spec(config).with_size(512, 512));
    EXPECT_EQ(shadow.shader.bindings(), 1u);
    EXPECT_EQ(shadow.shader.code(rhi::ShaderStage::Vertex)->origin, "loom/parts/shadow_caster.vert.glsl");
    EXPECT_EQ(shadow.shader.code(rhi::ShaderStage::Fragment)->origin, "loom/parts/shadow_caster.frag.glsl");

    const fg::TextureSpec target = fg::TextureSpec::of(rhi::Format::RGBA16Float).with_size(64, 32);
    const PassPart blit = standard_part("blit", {.config = config, .blit_target = target});
    ASSERT_EQ(blit.ports.declarations().size(), 2u);
    EXPECT_EQ(blit.ports.declarations()[0].spec, color_spec(config));
    EXPECT_EQ(blit.ports.declarations()[1].spec, target);

    // The shortcuts are their rows.
    const PassPart shortcut = shadow_caster_part(config, 512);
    EXPECT_EQ(shortcut.shader, shadow.shader);
    EXPECT_EQ(shortcut.ports.declarations(), shadow.ports.declarations());

    // Object parts declare no ports.
    const PassPart material = standard_part("pbr-material");
    EXPECT_TRUE(material.ports.declarations().empty());
    EXPECT_EQ(material.shader.code(rhi::ShaderStage::Vertex), nullptr);
}

TEST(PartTable, ARowWhoseFileIsMissingFailsNamingThePartAndTheFile) {
    const PartDesc ghost{"ghost", 0, {}, "loom/parts/ghost.frag.glsl", nullptr};
    ShaderPass pass("lost");
    pass.add(fullscreen_part());
    pass.add(make_part(ghost));
    auto program = pass.own_program();
    ASSERT_FALSE(program.ok());
    EXPECT_EQ(program.error().code, ErrorCode::InvalidArgument);
    EXPECT_THAT(program.error().message,
                HasSubstr("pass 'lost', object kind 'none', vertex stage: part 'ghost': its fragment code file "
                          "'loom/parts/ghost.frag.glsl' is not embedded"));
}

TEST(PartTable, ANameWithoutARowFailsNamingItAndTheTable) {
    ShaderPass pass("lost");
    pass.add(fullscreen_part());
    pass.add(standard_part("gaussian-blurr"));
    auto program = pass.own_program();
    ASSERT_FALSE(program.ok());
    EXPECT_EQ(program.error().code, ErrorCode::InvalidArgument);
    EXPECT_THAT(program.error().message,
                HasSubstr("part 'gaussian-blurr': no row of the part table has this name (its rows: fullscreen, "));
    EXPECT_THAT(program.error().message, HasSubstr("gaussian-blur, composite"));
}

}  // namespace
}  // namespace loom::passes
