// loom-engine's frame on both APIs (samples/engine, docs/engine.md): the same bytes for every
// intermediate on GL and Vulkan, CPU references for the hierarchical Z and the light list,
// async compute drawing what one queue draws, the plan pinned, and errors named.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
#include <set>

#include <glm/glm.hpp>

#include "cross_backend.hpp"
#include "engine_frame.hpp"
#include "engine_pictures.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/image_io/image_io.hpp"
#include "render_helpers.hpp"
#include "loom_test/test_support.hpp"

namespace loom::test {
namespace {

using engine::EngineFrame;

constexpr fg::Extent2D kSize{320, 180};

const engine::EngineScene& courtyard() {
    static const engine::EngineScene scene = [] {
        engine::SceneSettings settings;
        auto made = engine::make_engine_scene(settings);
        if (!made) std::abort();
        return std::move(*made);
    }();
    return scene;
}

engine::FrameSettings small_shadows() {
    engine::FrameSettings settings;
    settings.shadow_size = 512;
    return settings;
}

/// Renders `frames` frames of `scene` and reads every intermediate back.
Result<std::map<std::string, rhi::Image>> render(rhi::Device& device, const engine::EngineScene& scene,
                                                 const engine::FrameSettings& settings, int frames = 1) {
    auto frame = EngineFrame::create(device, scene, settings);
    if (!frame) return frame.take_error();
    for (int i = 0; i < frames; ++i) LOOM_TRY((*frame)->render(kSize));
    LOOM_TRY(device.wait_idle());
    return engine::read_intermediates(device, **frame);
}

/// How far GL and Vulkan may differ for one picture, and why. llvmpipe and lavapipe share
/// Mesa's rasteriser, but the two APIs place the framebuffer differently (GL's upper-left clip
/// control against Vulkan's negative viewport height): pixels whose centres lie on an edge
/// shared by two triangles go to one triangle on GL and to the other on Vulkan, and the two
/// depth planes differ in the last bits there. Everything computed from depth inherits those
/// few pixels. The final picture is held to one level at no more than 0.1 % of its pixels.
struct Tolerance {
    double max_diff = 0.0;        ///< in the format's natural units
    double max_fraction = 0.0;    ///< of the pixels that may differ at all
};

Tolerance tolerance(const std::string& name) {
    auto starts = [&](const char* prefix) { return name.rfind(prefix, 0) == 0; };
    if (name == "final") return {1.0, 0.001};
    if (name == "depth" || starts("hzb") || starts("shadow_cascades")) return {1e-6, 0.1};  // a few float ulps at depth ~1
    if (starts("ssao")) return {1.0, 0.005};                                            // one level of 255
    if (name == "hdr") return {0.01, 0.005};                                            // a few half-float ulps
    if (starts("bloom")) return {0.001, 1.0};  // hdr's few pixels, spread over the whole pyramid by the blur
    if (name == "light_list") return {0.0, 0.0};                                        // exact: one light more is a bug
    return {};
}

class EngineFrameTest : public CrossBackendTest {};

TEST_F(EngineFrameTest, EveryIntermediateIsTheSameOnGlAndVulkan) {
    auto on_gl = render(gl(), courtyard(), small_shadows(), 2);
    ASSERT_TRUE(on_gl.ok()) << on_gl.error().to_string();
    auto on_vulkan = render(vulkan(), courtyard(), small_shadows(), 2);
    ASSERT_TRUE(on_vulkan.ok()) << on_vulkan.error().to_string();
    ASSERT_EQ(on_gl->size(), on_vulkan->size());
    EXPECT_EQ(on_gl->size(), 24u);  // 23 texture levels and layers, and the light list
    for (const auto& [name, image] : *on_gl) {
        SCOPED_TRACE(name);
        ASSERT_TRUE(on_vulkan->count(name));
        auto comparison = image_io::compare_and_report(image, on_vulkan->at(name), output_dir() / "engine", name, {});
        ASSERT_TRUE(comparison.ok()) << comparison.error().to_string();
        const Tolerance allowed = tolerance(name);
        EXPECT_LE(comparison->max_channel_diff, allowed.max_diff) << comparison->summary();
        EXPECT_LE(static_cast<double>(comparison->pixels_above_threshold),
                  allowed.max_fraction * static_cast<double>(comparison->pixel_count))
            << comparison->summary();
        std::printf("  %-24s %s\n", name.c_str(), comparison->summary().c_str());
    }
}


/// The hierarchical Z, recomputed on the CPU from the captured depth: every level holds the
/// nearest and farthest depth of exactly the texels it covers (the last row and column of an
/// odd-sized level take the texel left over), bit for bit.
TEST_F(EngineFrameTest, HierarchicalZHoldsTheDepthRangeOfTheTexelsItCovers) {
    for (rhi::Device* device : {&gl(), &vulkan()}) {
        SCOPED_TRACE(rhi::backend_name(device->backend()));
        auto images = render(*device, courtyard(), small_shadows());
        ASSERT_TRUE(images.ok()) << images.error().to_string();
        // (nearest, farthest) per texel, level by level, from the depth buffer.
        const rhi::Image& depth = images->at("depth");
        std::vector<std::vector<std::array<double, 2>>> level(1);
        uint32_t width = depth.width, height = depth.height;
        for (uint32_t y = 0; y < height; ++y) {
            for (uint32_t x = 0; x < width; ++x) level[0].push_back({depth.load(x, y)[0], depth.load(x, y)[0]});
        }
        for (uint32_t k = 0; k < engine::kHzbLevels; ++k) {
            const rhi::Image& hzb = images->at("hzb.mip" + std::to_string(k));
            ASSERT_EQ(hzb.width, width);
            ASSERT_EQ(hzb.height, height);
            for (uint32_t y = 0; y < height; ++y) {
                for (uint32_t x = 0; x < width; ++x) {
                    const auto texel = hzb.load(x, y);
                    ASSERT_EQ(texel[0], level.back()[y * width + x][0]) << "level " << k << " at " << x << "," << y;
                    ASSERT_EQ(texel[1], level.back()[y * width + x][1]) << "level " << k << " at " << x << "," << y;
                }
            }
            const uint32_t cw = std::max(width / 2, 1u), ch = std::max(height / 2, 1u);
            std::vector<std::array<double, 2>> coarse(std::size_t{cw} * ch, {2.0, -1.0});
            for (uint32_t y = 0; y < height; ++y) {
                for (uint32_t x = 0; x < width; ++x) {
                    auto& c = coarse[std::min(y / 2, ch - 1) * cw + std::min(x / 2, cw - 1)];
                    c[0] = std::min(c[0], level.back()[y * width + x][0]);
                    c[1] = std::max(c[1], level.back()[y * width + x][1]);
                }
            }
            level.push_back(std::move(coarse));
            width = cw;
            height = ch;
        }
    }
}

/// The light list against a CPU reference in double precision: each tile's box in view space
/// between its nearest and farthest depth (from the hierarchical Z), each light's sphere. A
/// light clearly inside (or clearly outside) must be listed (or not); lights are listed in
/// index order, at most 63 per tile; tiles that see only sky list none.
TEST_F(EngineFrameTest, LightListHoldsTheLightsThatReachEachTile) {
    for (rhi::Device* device : {&gl(), &vulkan()}) {
        SCOPED_TRACE(rhi::backend_name(device->backend()));
        auto frame = EngineFrame::create(*device, courtyard(), small_shadows());
        ASSERT_TRUE(frame.ok()) << frame.error().to_string();
        LOOM_ASSERT_OK((*frame)->render(kSize));
        LOOM_ASSERT_OK(device->wait_idle());
        auto images = engine::read_intermediates(*device, **frame);
        ASSERT_TRUE(images.ok()) << images.error().to_string();
        auto bytes = device->read_buffer((*frame)->captured_light_list(), 0, (*frame)->captured_light_list_bytes());
        ASSERT_TRUE(bytes.ok()) << bytes.error().to_string();
        std::vector<uint32_t> list(bytes->size() / 4);
        std::memcpy(list.data(), bytes->data(), list.size() * 4);

        const scene::CameraMatrices camera = (*frame)->camera(kSize);
        const glm::dmat4 view(camera.view);
        const glm::dmat4 inverse_projection = glm::inverse(glm::dmat4(camera.projection));
        const rhi::Image& hzb = images->at("hzb.mip4");
        const fg::Extent2D tiles = EngineFrame::tile_count(kSize);
        ASSERT_EQ(list.size(), std::size_t{tiles.width} * tiles.height * engine::kTileStride);
        const auto& lights = courtyard().lights;
        uint32_t listed = 0, sky_tiles = 0, crowded = 0;
        for (uint32_t ty = 0; ty < tiles.height; ++ty) {
            for (uint32_t tx = 0; tx < tiles.width; ++tx) {
                const uint32_t* entry = &list[(std::size_t{ty} * tiles.width + tx) * engine::kTileStride];
                const uint32_t count = entry[0];
                ASSERT_LE(count, engine::kTileStride - 1) << "tile " << tx << "," << ty;
                for (uint32_t i = 1; i < count; ++i) ASSERT_LT(entry[i], entry[i + 1]) << "tile " << tx << "," << ty;
                listed += count;
                const auto range = hzb.load(std::min(tx, hzb.width - 1), std::min(ty, hzb.height - 1));
                if (range[0] >= 1.0) {
                    EXPECT_EQ(count, 0u) << "sky tile " << tx << "," << ty;
                    ++sky_tiles;
                    continue;
                }
                glm::dvec3 lo(1e30), hi(-1e30);
                for (int c = 0; c < 8; ++c) {
                    const double px = std::min<double>((tx + (c & 1)) * engine::kTileSize, kSize.width);
                    const double py = std::min<double>((ty + ((c >> 1) & 1)) * engine::kTileSize, kSize.height);
                    const glm::dvec4 ndc(px / kSize.width * 2.0 - 1.0, 1.0 - py / kSize.height * 2.0, (c & 4) ? range[1] : range[0], 1.0);
                    glm::dvec4 v = inverse_projection * ndc;
                    const glm::dvec3 p = glm::dvec3(v) / v.w;
                    lo = glm::min(lo, p);
                    hi = glm::max(hi, p);
                }
                const std::set<uint32_t> in_list(entry + 1, entry + 1 + count);
                if (count == engine::kTileStride - 1) ++crowded;
                for (uint32_t l = 0; l < lights.size(); ++l) {
                    const glm::dvec3 centre = glm::dvec3(view * glm::dvec4(glm::dvec3(lights[l].position_radius), 1.0));
                    const glm::dvec3 d = centre - glm::clamp(centre, lo, hi);
                    const double d2 = glm::dot(d, d);
                    const double r2 = double(lights[l].position_radius.w) * lights[l].position_radius.w;
                    if (d2 < r2 * 0.999 && (count < engine::kTileStride - 1 || l < entry[count])) {
                        EXPECT_TRUE(in_list.count(l)) << "light " << l << " reaches tile " << tx << "," << ty << " but is not listed";
                    }
                    if (d2 > r2 * 1.001 + 1e-6) {
                        EXPECT_FALSE(in_list.count(l)) << "light " << l << " is listed in tile " << tx << "," << ty << " but misses it";
                    }
                }
            }
        }
        EXPECT_GT(sky_tiles, 0u);
        EXPECT_GT(listed, tiles.width * tiles.height) << "fewer than one light per tile on average: the lights missed the courtyard";
        std::printf("  %s: %u lights listed over %u tiles (%u sky tiles, %u full)\n", rhi::backend_name(device->backend()).data(), listed,
                    tiles.width * tiles.height, sky_tiles, crowded);
    }
}

/// SSAO leaves the sky alone and darkens the scene only somewhat; its blur keeps the range.
TEST_F(EngineFrameTest, AmbientOcclusionDarkensGeometryOnly) {
    auto images = render(vulkan(), courtyard(), small_shadows());
    ASSERT_TRUE(images.ok()) << images.error().to_string();
    const rhi::Image& depth = images->at("depth");
    const rhi::Image& raw = images->at("ssao_raw");
    const rhi::Image& blurred = images->at("ssao");
    double sum = 0.0;
    uint32_t geometry = 0, occluded = 0;
    for (uint32_t y = 0; y < depth.height; ++y) {
        for (uint32_t x = 0; x < depth.width; ++x) {
            if (depth.load(x, y)[0] >= 1.0) {
                ASSERT_EQ(raw.load(x, y)[0], 1.0) << "sky at " << x << "," << y;
                continue;
            }
            ++geometry;
            sum += blurred.load(x, y)[0];
            if (raw.load(x, y)[0] < 0.8) ++occluded;
        }
    }
    ASSERT_GT(geometry, 0u);
    const double mean = sum / geometry;
    EXPECT_GT(mean, 0.6);
    EXPECT_LT(mean, 0.99);
    EXPECT_GT(occluded, geometry / 100) << "creases at the feet of the pillars and crates should be darker";
}

/// SSAO on the async compute queue draws what it draws on the graphics queue, and the heap
/// allocator (aliasing in bytes) what the interval one (whole textures) draws: every
/// intermediate is identical to the serial, interval frame's.
TEST_F(EngineFrameTest, AsyncComputeAndHeapAliasingChangeNoPixel) {
    for (rhi::Device* device : {&gl(), &vulkan()}) {
        SCOPED_TRACE(rhi::backend_name(device->backend()));
        engine::FrameSettings reference_settings = small_shadows();
        reference_settings.async_compute = false;
        reference_settings.allocator = fg::AllocatorKind::Interval;
        auto reference = render(*device, courtyard(), reference_settings, 2);
        ASSERT_TRUE(reference.ok()) << reference.error().to_string();
        for (fg::AllocatorKind allocator : {fg::AllocatorKind::Interval, fg::AllocatorKind::Heap}) {
            for (bool async : {false, true}) {
                if (allocator == fg::AllocatorKind::Interval && !async) continue;
                engine::FrameSettings settings = small_shadows();
                settings.allocator = allocator;
                settings.async_compute = async;
                auto images = render(*device, courtyard(), settings, 2);
                ASSERT_TRUE(images.ok()) << images.error().to_string();
                for (const auto& [name, image] : *reference) {
                    ASSERT_TRUE(images->count(name)) << name;
                    EXPECT_TRUE(images->at(name).pixels == image.pixels) << name << " with allocator " << fg::allocator_name(allocator) << ", async " << async;
                }
            }
        }
    }
}

/// The plan of the frame, pinned: 24 passes in this order, SSAO and its blur on the async queue
/// with two semaphores, and the bytes of each allocator at 320x180 (no device memory model).
TEST_F(EngineFrameTest, PlanIsPinned) {
    auto frame = EngineFrame::create(gl(), courtyard(), small_shadows());
    ASSERT_TRUE(frame.ok()) << frame.error().to_string();
    fg::PlanOptions options = (*frame)->plan_options(kSize);
    EXPECT_TRUE(options.allocator == fg::AllocatorKind::Heap);  // the sample's default
    options.allocator = fg::AllocatorKind::Interval;
    auto plan = fg::build_plan((*frame)->graph(), options);
    ASSERT_TRUE(plan.ok()) << plan.error().to_string();
    std::vector<std::string> order;
    for (const auto& pass : plan->order) order.push_back(pass.name);
    EXPECT_EQ(order, (std::vector<std::string>{"depth_prepass", "ssao", "ssao_blur", "hzb_0", "hzb_1", "hzb_2", "hzb_3", "hzb_4",
                                               "light_cull", "shadow_cascade_0", "shadow_cascade_1", "shadow_cascade_2",
                                               "shadow_cascade_3", "shade", "bloom_prefilter", "bloom_down_1", "bloom_down_2",
                                               "bloom_down_3", "bloom_down_4", "bloom_up_3", "bloom_up_2", "bloom_up_1",
                                               "bloom_up_0", "tonemap"}));
    EXPECT_EQ(plan->order[1].queue, fg::Queue::AsyncCompute);
    EXPECT_EQ(plan->order[2].queue, fg::Queue::AsyncCompute);
    EXPECT_EQ(plan->queue_syncs, (std::vector<fg::QueueSync>{{fg::Queue::Graphics, fg::Queue::AsyncCompute, 0, 1},
                                                             {fg::Queue::AsyncCompute, fg::Queue::Graphics, 2, 13}}));
    // Every resource has a shape of its own, so the interval allocator (which shares whole
    // textures of one shape) keeps them all; the heap allocator packs them into the fewest bytes
    // any allocation can have, the peak of the bytes alive at once.
    const fg::PlanSummary& s = plan->summary;
    EXPECT_EQ(plan->resources.size(), 9u);
    EXPECT_EQ(s.naive_textures, 8u);
    EXPECT_EQ(s.textures, 8u);
    EXPECT_EQ(s.naive_bytes, 6287360u);
    EXPECT_EQ(s.bytes, 6287360u);
    EXPECT_EQ(s.lower_bound_bytes, 5107712u);
    options.allocator = fg::AllocatorKind::Heap;
    auto heap = fg::build_plan((*frame)->graph(), options);
    ASSERT_TRUE(heap.ok()) << heap.error().to_string();
    EXPECT_EQ(heap->summary.bytes, heap->summary.lower_bound_bytes);
    EXPECT_EQ(heap->summary.bytes, 5107712u);
}

TEST_F(EngineFrameTest, ErrorsNameWhatIsWrong) {
    auto frame = EngineFrame::create(gl(), courtyard(), small_shadows());
    ASSERT_TRUE(frame.ok()) << frame.error().to_string();
    const Status small = (*frame)->render({48, 200});
    ASSERT_FALSE(small.ok());
    EXPECT_EQ(small.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(small.error().message,
              "loom-engine: a 48x200 frame is too small (at least 64x64, so that every level of the Z and bloom pyramids has a texel)");
    const Status again = (*frame)->render(kSize);  // the frame is still usable
    EXPECT_TRUE(again.ok()) << again.error().to_string();

    engine::FrameSettings no_shadows = small_shadows();
    no_shadows.shadow_size = 0;
    auto refused = EngineFrame::create(gl(), courtyard(), no_shadows);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("shadow size 0 is out of range"), std::string::npos) << refused.error().message;

    engine::SceneSettings dark;
    dark.lights = 0;
    auto no_lights = engine::make_engine_scene(dark);
    ASSERT_FALSE(no_lights.ok());
    EXPECT_EQ(no_lights.error().message, "lights: 0 is out of range (1..4096)");

    engine::SceneSettings missing;
    missing.model = "no/such/model.gltf";
    auto not_found = engine::make_engine_scene(missing);
    ASSERT_FALSE(not_found.ok());
    EXPECT_NE(not_found.error().message.find("no/such/model.gltf"), std::string::npos) << not_found.error().message;
}

/// A glTF model in the middle of the courtyard (the Duck): drawn with its texture, the same on
/// both APIs within the tolerances above.
TEST_F(EngineFrameTest, GltfModelRendersTheSameOnGlAndVulkan) {
    LOOM_REQUIRE_DATA_DIR(data);
    engine::SceneSettings settings;
    settings.model = data / "gltf" / "Duck" / "glTF-Binary" / "Duck.glb";
    auto scene = engine::make_engine_scene(settings);
    ASSERT_TRUE(scene.ok()) << scene.error().to_string();
    EXPECT_NE(scene->description.find("Duck.glb"), std::string::npos) << scene->description;
    auto on_gl = render(gl(), *scene, small_shadows());
    ASSERT_TRUE(on_gl.ok()) << on_gl.error().to_string();
    auto on_vulkan = render(vulkan(), *scene, small_shadows());
    ASSERT_TRUE(on_vulkan.ok()) << on_vulkan.error().to_string();
    auto courtyard_only = render(vulkan(), courtyard(), small_shadows());
    ASSERT_TRUE(courtyard_only.ok()) << courtyard_only.error().to_string();
    for (const char* name : {"final", "hdr", "depth"}) {
        auto comparison = image_io::compare_and_report(on_gl->at(name), on_vulkan->at(name), output_dir() / "engine", std::string("duck.") + name, {});
        ASSERT_TRUE(comparison.ok()) << comparison.error().to_string();
        const Tolerance allowed = tolerance(name);
        EXPECT_LE(comparison->max_channel_diff, allowed.max_diff) << name << ": " << comparison->summary();
        EXPECT_LE(static_cast<double>(comparison->pixels_above_threshold), allowed.max_fraction * static_cast<double>(comparison->pixel_count))
            << name << ": " << comparison->summary();
    }
    // The duck stands where the torus stood: the middle of the picture changed.
    auto changed = rhi::compare_images(on_vulkan->at("final"), courtyard_only->at("final"));
    ASSERT_TRUE(changed.ok());
    EXPECT_GT(changed->pixels_above_threshold, 500u);
}

/// The program: headless on each backend it writes the picture, every intermediate, the plan
/// and a summary with each allocator's bytes.
TEST(EngineSample, WritesEveryPictureThePlanAndTheSummary) {
    std::string why_not;
    for (const char* backend : {"gl", "vulkan"}) {
        const std::filesystem::path dir = output_dir() / "engine-sample" / backend;
        std::filesystem::remove_all(dir);
        const std::string command = std::string(LOOM_ENGINE_EXE) + " --backend " + backend +
                                    " --size 128x96 --shadow-size 256 --lights 32 --out " + dir.string() + " > " +
                                    (dir.parent_path() / (std::string(backend) + ".log")).string() + " 2>&1";
        std::filesystem::create_directories(dir.parent_path());
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
        for (const char* file : {"final.png", "depth.png", "hzb.mip4.png", "light_list.png", "shadow_cascades.layer3.png", "ssao.png",
                                 "hdr.png", "bloom_up.mip0.png", "plan.json", "plan.dot", "summary.txt"}) {
            EXPECT_TRUE(std::filesystem::exists(dir / file)) << backend << ": " << file;
        }
        std::ifstream in(dir / "summary.txt");
        std::stringstream buffer;
        buffer << in.rdbuf();
        const std::string text = buffer.str();
        EXPECT_NE(text.find("24 passes (17 compute, 2 of them on the async queue)"), std::string::npos) << text;
        EXPECT_NE(text.find("lower bound"), std::string::npos) << text;
    }
}

}  // namespace
}  // namespace loom::test
