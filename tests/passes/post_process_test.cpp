// The post-process passes (blur, high pass, composite / tone map, blit) against their CPU
// references (cpu_reference.hpp), on every backend: a known image is uploaded, imported as the
// output of a source pass, run through a small graph by the executor and read back.
//
// Tolerance: exact, except one case. The shaders compute in float and store half floats; the
// references compute the same formulas in float in the same order and round to half as the
// GPU does (toward zero: llvmpipe and lavapipe truncate when writing RGBA16F; with
// round-to-nearest 87% of the blurred texels were one step off). Blur, high pass, linear
// composite and blit then match bit for bit. The sRGB encoding calls pow(), which llvmpipe
// approximates (exp2 and log2 polynomials): 0.05% of the texels of a 256x256 composite land one
// half-float step from std::pow's, so the sRGB composite may be one step away at each
// texel's own magnitude (format_steps.hpp).
//
// Other drivers may contract a multiply and an add into one FMA or evaluate a sum in another
// order, which moves a result that lies at a rounding boundary by one step: on NVIDIA's driver
// (H200, 580.159) one texel in 2,257 of the blurs and the high pass and 19 in 65,536 of the
// linear composite were one half-float step away, and the RGBA32F blur's 9-tap sums were up to 3
// float steps away. So "exact" holds on Mesa's software drivers, which CI runs, and elsewhere
// one step is allowed (four float steps for the 9-tap RGBA32F sums: at most half a step for each
// of the rounding points a fused multiply-add skips) — still far below what a wrong weight, tap
// offset or edge clamp gives.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include "cpu_reference.hpp"
#include "format_steps.hpp"
#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/image_io/image_io.hpp"
#include "loom/passes/blit_pass.hpp"
#include "loom/passes/blur_pass.hpp"
#include "loom/passes/composite_pass.hpp"
#include "loom/passes/high_pass_pass.hpp"
#include "loom_test/render_fixture.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

using passes::BlurAxis;
using passes::PassConfig;
using rhi::Format;

/// A known HDR image: smooth gradients, hashed noise, and a few very bright texels (values up
/// to about 40, as a lamp in the deferred pass makes), rounded to `format` when stored.
rhi::Image known_image(uint32_t width, uint32_t height, Format format, uint32_t seed) {
    rhi::Image image(width, height, format);
    for (uint32_t y = 0; y < height; ++y) {
        for (uint32_t x = 0; x < width; ++x) {
            uint32_t h = (x * 73856093u) ^ (y * 19349663u) ^ (seed * 83492791u);
            h ^= h >> 13;
            h *= 0x5bd1e995u;
            h ^= h >> 15;
            const double noise = static_cast<double>(h & 0xffff) / 65535.0;
            const double gx = static_cast<double>(x) / width, gy = static_cast<double>(y) / height;
            std::array<double, 4> v{gx * 2.0 + noise * 0.5, gy * 1.5 + noise * 0.25, (1.0 - gx) * noise * 3.0, 1.0};
            if (h % 97 == 0) v = {40.0 * noise, 25.0 * noise, 10.0, 1.0};
            image.store(x, y, v);
        }
    }
    return image;
}

class PostProcessTest : public RenderTest {
protected:
    void TearDown() override {
        executor_.reset();
        graph_.reset();
        for (rhi::TextureHandle texture : inputs_) (void)device().destroy(texture);
        RenderTest::TearDown();
    }

    /// A graph with one source pass per input ("source0", "source1", ... with output "color"),
    /// whose textures are the uploaded images.
    fg::FrameGraph& graph_with_sources(const std::vector<rhi::Image>& images, const PassConfig& config) {
        graph_ = std::make_unique<fg::FrameGraph>();
        executor_ = std::make_unique<fg::Executor>(device());
        for (std::size_t i = 0; i < images.size(); ++i) {
            const std::string name = "source" + std::to_string(i);
            EXPECT_TRUE(graph_->add_pass(fg::Pass(name).output("color", passes::color_spec(config))).ok());
            rhi::TextureDesc desc;
            desc.name = name;
            desc.format = images[i].format;
            desc.width = images[i].width;
            desc.height = images[i].height;
            desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::CopyDst;
            auto texture = device().create_texture(desc);
            EXPECT_TRUE(texture.ok()) << texture.error().to_string();
            if (!texture) continue;
            inputs_.push_back(*texture);
            auto written = device().write_texture(*texture, {}, images[i].pixels);
            EXPECT_TRUE(written.ok()) << written.error().to_string();
            executor_->import_texture(fg::port(name, "color"), *texture, rhi::ResourceState::ShaderRead);
        }
        return *graph_;
    }

    /// Runs one frame of the graph at `width` x `height` and reads `pass`.`port` back.
    rhi::Image run(uint32_t width, uint32_t height, const std::string& pass, const std::string& port) {
        fg::PlanOptions options;
        options.frame = {width, height};
        auto status = executor_->run_frame(*graph_, options);
        EXPECT_TRUE(status.ok()) << status.error().to_string();
        if (!status) return {};
        auto image = device().read_texture(executor_->texture(pass, port));
        EXPECT_TRUE(image.ok()) << image.error().to_string();
        return image ? std::move(*image) : rhi::Image{};
    }

    /// Steps a driver may round differently from the reference (see the top of this file):
    /// none on Mesa's llvmpipe and lavapipe, `elsewhere` on other drivers.
    double rounding_steps(double elsewhere = 1.0) {
        return device().capabilities().device_name.find("llvmpipe") != std::string::npos ? 0.0 : elsewhere;
    }

    /// Expects every channel within `steps` half-float steps of the reference at its magnitude
    /// (0: bit for bit).
    void expect_near_reference(const rhi::Image& gpu, const rhi::Image& reference, const std::string& name,
                               double steps) {
        ASSERT_EQ(gpu.width, reference.width);
        ASSERT_EQ(gpu.height, reference.height);
        ASSERT_EQ(gpu.format, reference.format);
        const StepComparison comparison = compare_steps(gpu, reference);
        std::cout << rhi::backend_name(backend()) << ", " << name << " vs CPU: " << comparison.summary() << "\n";
        EXPECT_LE(comparison.max_local_steps, steps) << name << ": " << comparison.summary();
        if (comparison.max_local_steps > steps) {
            const std::filesystem::path dir = output_dir() / "passes" / "post_process";
            std::filesystem::create_directories(dir);
            (void)image_io::compare_and_report(gpu, reference, dir,
                                          name + "_" + std::string(rhi::backend_name(backend())));
        }
    }

    std::unique_ptr<fg::FrameGraph> graph_;
    std::unique_ptr<fg::Executor> executor_;
    std::vector<rhi::TextureHandle> inputs_;
};

// An odd size, so that edges and the clamp to them are exercised in both directions.
constexpr uint32_t kWidth = 61;
constexpr uint32_t kHeight = 37;
constexpr uint32_t kCompositeSize = 256;

TEST_P(PostProcessTest, BlurInEachDirectionMatchesTheReference) {
    for (BlurAxis axis : {BlurAxis::Horizontal, BlurAxis::Vertical}) {
        const rhi::Image input = known_image(kWidth, kHeight, Format::RGBA16Float, 1);
        PassConfig config;
        fg::FrameGraph& graph = graph_with_sources({input}, config);
        ASSERT_TRUE(graph.add_pass(std::make_unique<passes::BlurPass>(config, axis, 7, "blur")).ok());
        ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("blur", "previous_pass")).ok());
        ASSERT_TRUE(graph.mark_output(fg::port("blur", "color")).ok());
        const rhi::Image gpu = run(kWidth, kHeight, "blur", "color");
        const rhi::Image reference = reference_blur(input, axis, passes::gaussian_weights(7));
        expect_near_reference(gpu, reference, axis == BlurAxis::Horizontal ? "blur_h" : "blur_v", rounding_steps());
        // The blur really spreads: a bright texel's neighbours along the axis got some of it.
        EXPECT_GT(compare_steps(gpu, input).fraction_differing(), 0.9);
    }
}

TEST_P(PostProcessTest, BlurInFloat32MatchesTheReference) {
    // The passes take their colour format from PassConfig: with RGBA32F nothing is rounded to
    // half, so this shows the float arithmetic itself agrees.
    const rhi::Image input = known_image(kWidth, kHeight, Format::RGBA32Float, 6);
    PassConfig config;
    config.color_format = Format::RGBA32Float;
    fg::FrameGraph& graph = graph_with_sources({input}, config);
    ASSERT_TRUE(graph.add_pass(std::make_unique<passes::BlurPass>(config, BlurAxis::Horizontal, 9, "blur")).ok());
    ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("blur", "previous_pass")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("blur", "color")).ok());
    const rhi::Image gpu = run(kWidth, kHeight, "blur", "color");
    const rhi::Image reference = reference_blur(input, BlurAxis::Horizontal, passes::gaussian_weights(9));
    ASSERT_EQ(gpu.format, Format::RGBA32Float);
    const StepComparison comparison = compare_steps(gpu, reference);
    std::cout << rhi::backend_name(backend()) << ", blur_f32 vs CPU: " << comparison.summary() << "\n";
    if (rounding_steps() == 0.0) {
        EXPECT_EQ(comparison.pixels_differing, 0u) << comparison.summary();
    } else {
        EXPECT_LE(comparison.max_local_steps, rounding_steps(4.0)) << comparison.summary();
    }
}

TEST_P(PostProcessTest, SeparableBlurOfTwoPassesMatchesTheReference) {
    const rhi::Image input = known_image(kWidth, kHeight, Format::RGBA16Float, 2);
    PassConfig config;
    fg::FrameGraph& graph = graph_with_sources({input}, config);
    ASSERT_TRUE(graph.add_pass(std::make_unique<passes::BlurPass>(config, BlurAxis::Horizontal, 20, "blur-h")).ok());
    ASSERT_TRUE(graph.add_pass(std::make_unique<passes::BlurPass>(config, BlurAxis::Vertical, 20, "blur-v")).ok());
    ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("blur-h", "previous_pass")).ok());
    ASSERT_TRUE(graph.connect(fg::port("blur-h", "color"), fg::port("blur-v", "previous_pass")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("blur-v", "color")).ok());
    const rhi::Image gpu = run(kWidth, kHeight, "blur-v", "color");
    const std::vector<float> weights = passes::gaussian_weights(20);
    const rhi::Image reference =
        reference_blur(reference_blur(input, BlurAxis::Horizontal, weights), BlurAxis::Vertical, weights);
    expect_near_reference(gpu, reference, "blur_hv", rounding_steps());
}

TEST_P(PostProcessTest, HighPassMatchesTheReference) {
    const rhi::Image input = known_image(kWidth, kHeight, Format::RGBA16Float, 3);
    PassConfig config;
    fg::FrameGraph& graph = graph_with_sources({input}, config);
    auto pass = std::make_unique<passes::HighPassPass>(config);
    pass->set_threshold(1.5f);
    ASSERT_TRUE(graph.add_pass(std::move(pass)).ok());
    ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("high-pass", "source")).ok());
    ASSERT_TRUE(graph.mark_output(fg::port("high-pass", "high_pass")).ok());
    const rhi::Image gpu = run(kWidth, kHeight, "high-pass", "high_pass");
    const rhi::Image reference = reference_high_pass(input, 1.5f);
    expect_near_reference(gpu, reference, "high_pass", rounding_steps());
    // Dim texels are cut to black, bright ones kept: both happen in this image.
    uint32_t black = 0, kept = 0;
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
            const auto v = gpu.load(x, y);
            (v[0] == 0.0 && v[1] == 0.0 && v[2] == 0.0 ? black : kept) += 1;
        }
    }
    EXPECT_GT(black, 100u);
    EXPECT_GT(kept, 100u);
}

TEST_P(PostProcessTest, CompositeMatchesTheReference) {
    for (bool srgb : {true, false}) {
        const rhi::Image color = known_image(kCompositeSize, kCompositeSize, Format::RGBA16Float, 4);
        const rhi::Image bloom = known_image(kCompositeSize, kCompositeSize, Format::RGBA16Float, 5);
        PassConfig config;
        fg::FrameGraph& graph = graph_with_sources({color, bloom}, config);
        auto pass = std::make_unique<passes::CompositePass>(config);
        pass->set_exposure(0.8f);
        pass->set_bloom_strength(0.6f);
        pass->set_encode_srgb(srgb);
        ASSERT_TRUE(graph.add_pass(std::move(pass)).ok());
        ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("composite", "color")).ok());
        ASSERT_TRUE(graph.connect(fg::port("source1", "color"), fg::port("composite", "bloom")).ok());
        ASSERT_TRUE(graph.mark_output(fg::port("composite", "final")).ok());
        const rhi::Image gpu = run(kCompositeSize, kCompositeSize, "composite", "final");
        const rhi::Image reference = reference_composite(color, bloom, 0.8f, 0.6f, srgb);
        expect_near_reference(gpu, reference, srgb ? "composite_srgb" : "composite_linear",
                              srgb ? 1.0 : rounding_steps());
    }
}

TEST_P(PostProcessTest, BlitCopiesExactly) {
    // RGBA16F to RGBA16F is a copy; to RGBA8 a conversion whose texels lie away from rounding
    // ties (level + 0.25), so that any correct conversion gives the same byte.
    rhi::Image input(kWidth, kHeight, Format::RGBA16Float);
    for (uint32_t y = 0; y < kHeight; ++y) {
        for (uint32_t x = 0; x < kWidth; ++x) {
            const double level = static_cast<double>((x * 7 + y * 13) % 255) + 0.25;
            input.store(x, y, {level / 255.0, (254.0 - level) / 255.0, level / 510.0, 1.0});
        }
    }
    for (Format target : {Format::RGBA16Float, Format::RGBA8Unorm}) {
        PassConfig config;
        fg::FrameGraph& graph = graph_with_sources({input}, config);
        ASSERT_TRUE(graph.add_pass(std::make_unique<passes::BlitPass>(
                                       config, fg::TextureSpec::of(target).with_scale(1.0f)))
                        .ok());
        ASSERT_TRUE(graph.connect(fg::port("source0", "color"), fg::port("present", "source")).ok());
        ASSERT_TRUE(graph.mark_output(fg::port("present", "target")).ok());
        const rhi::Image gpu = run(kWidth, kHeight, "present", "target");
        const rhi::Image reference = reference_blit(input, target);
        auto comparison = rhi::compare_images(gpu, reference);
        ASSERT_TRUE(comparison.ok()) << comparison.error().to_string();
        EXPECT_TRUE(comparison->equal()) << rhi::format_name(target) << ": " << comparison->summary();
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(PostProcessTest);

}  // namespace loom::test
