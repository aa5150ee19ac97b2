// The command line shared by the samples (loom::sample_common).
#include <gtest/gtest.h>

#include "loom/sample_common/options.hpp"

namespace loom::samples {
namespace {

Result<CommonOptions> parse(std::vector<std::string> args) {
    CommonDefaults defaults;
    defaults.width = 320;
    defaults.height = 200;
    defaults.out = "out/default.png";
    return parse_common_options(args, defaults);
}

TEST(SampleOptions, DefaultsApplyWithoutArguments) {
    auto options = parse({});
    ASSERT_TRUE(options.ok());
    EXPECT_EQ(options->backend, rhi::Backend::OpenGL);
    EXPECT_EQ(options->width, 320u);
    EXPECT_EQ(options->height, 200u);
    EXPECT_EQ(options->out, "out/default.png");
    EXPECT_FALSE(options->window);
    EXPECT_FALSE(options->help);
    EXPECT_TRUE(options->rest.empty());
}

TEST(SampleOptions, ParsesEveryOptionInBothSpellings) {
    auto options = parse({"--backend", "vk", "--size=1920x1080", "--out", "a/b.png", "--window", "--extra", "7"});
    ASSERT_TRUE(options.ok()) << options.error().to_string();
    EXPECT_EQ(options->backend, rhi::Backend::Vulkan);
    EXPECT_EQ(options->width, 1920u);
    EXPECT_EQ(options->height, 1080u);
    EXPECT_EQ(options->out, "a/b.png");
    EXPECT_TRUE(options->window);
    EXPECT_EQ(options->rest, (std::vector<std::string>{"--extra", "7"}));
    auto help = parse({"-h"});
    ASSERT_TRUE(help.ok());
    EXPECT_TRUE(help->help);
    const rhi::DeviceDesc desc = device_desc(*options, "title");
    EXPECT_EQ(desc.backend, rhi::Backend::Vulkan);
    EXPECT_FALSE(desc.headless);
    EXPECT_EQ(desc.window.width, 1920u);
    EXPECT_EQ(desc.window.title, "title");
}

TEST(SampleOptions, ErrorsNameTheArgument) {
    for (const auto& args : std::vector<std::vector<std::string>>{
             {"--backend", "metal"}, {"--size", "640"}, {"--size", "0x480"}, {"--size", "12x-3"}, {"--size"}, {"--out="}}) {
        auto options = parse(args);
        ASSERT_FALSE(options.ok()) << args.front();
        EXPECT_EQ(options.error().code, ErrorCode::InvalidArgument);
        EXPECT_NE(options.error().message.find(args.front().substr(0, args.front().find('='))), std::string::npos)
            << options.error().message;
    }
}

TEST(SampleOptions, HelpMentionsTheDefaults) {
    CommonDefaults defaults;
    defaults.width = 123;
    defaults.height = 45;
    defaults.out = "out/x.png";
    const std::string help = common_options_help(defaults);
    EXPECT_NE(help.find("123x45"), std::string::npos);
    EXPECT_NE(help.find("out/x.png"), std::string::npos);
    EXPECT_NE(help.find("--backend"), std::string::npos);
}

}  // namespace
}  // namespace loom::samples
