#include "embed_test_support.hpp"

#include <sstream>

#include "loom/image_io/image_io.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {

Rgba8 expected_pattern(uint32_t x, uint32_t y) {
    return {static_cast<uint8_t>(17 * (x % 16)), static_cast<uint8_t>(17 * (y % 16)),
            static_cast<uint8_t>(((x / 16 + y / 16) % 2) * 255), 255};
}

Rgba8 expected_overlay(uint32_t x, uint32_t y, uint32_t width, uint32_t height) {
    if (x < width / 2 && y < height / 2) return expected_pattern(x, y);
    return kEngineClearBytes;
}

::testing::AssertionResult matches_overlay(const rhi::Image& image, const std::string& name) {
    if (image.format != rhi::Format::RGBA8Unorm) {
        return ::testing::AssertionFailure() << name << ": image is " << rhi::format_name(image.format) << ", not RGBA8Unorm";
    }
    uint64_t wrong = 0;
    std::ostringstream first;
    for (uint32_t y = 0; y < image.height; ++y) {
        for (uint32_t x = 0; x < image.width; ++x) {
            const auto texel = image.texel(x, y);
            const Rgba8 want = expected_overlay(x, y, image.width, image.height);
            Rgba8 got{};
            for (std::size_t c = 0; c < 4; ++c) got[c] = static_cast<uint8_t>(texel[c]);
            if (got == want) continue;
            if (wrong++ == 0) {
                first << "(" << x << ", " << y << ") is (" << int(got[0]) << ", " << int(got[1]) << ", " << int(got[2]) << ", "
                      << int(got[3]) << "), expected (" << int(want[0]) << ", " << int(want[1]) << ", " << int(want[2])
                      << ", " << int(want[3]) << ")";
            }
        }
    }
    if (wrong == 0) return ::testing::AssertionSuccess();
    const auto path = output_dir() / "embed" / (name + ".png");
    std::filesystem::create_directories(path.parent_path());
    (void)image_io::write_png(image, path);
    return ::testing::AssertionFailure() << name << ": " << wrong << " of " << image.width * image.height
                                         << " texels differ, first " << first.str() << "; picture: " << path.string();
}

Result<rhi::ShaderHandle> compile_shader(rhi::Device& device, rhi::ShaderStage stage, const std::string& name,
                                         const std::string& source) {
    return shader_compiler::ShaderCompiler().create_shader(device, {name, stage, source, {}});
}

}  // namespace loom::test
