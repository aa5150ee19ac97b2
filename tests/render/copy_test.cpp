// copy_buffer and copy_texture move exactly the requested bytes / texels.
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

class CopyTest : public RenderTest {};

TEST_P(CopyTest, CopyBufferRange) {
    std::vector<uint8_t> source(64);
    for (std::size_t i = 0; i < source.size(); ++i) source[i] = static_cast<uint8_t>(i + 1);
    const std::vector<uint8_t> zeros(64, 0);
    LOOM_ASSIGN_OR_FAIL(auto src, make_buffer_of(device(), "copy source", rhi::BufferUsage::CopySrc, source));
    LOOM_ASSIGN_OR_FAIL(auto dst, make_buffer_of(device(), "copy destination", rhi::BufferUsage::CopyDst, zeros));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_buffer(src, 8, dst, 20, 16); }));
    LOOM_ASSIGN_OR_FAIL(auto bytes, device().read_buffer(dst, 0, 64));
    for (std::size_t i = 0; i < 64; ++i) {
        const uint8_t expected = (i >= 20 && i < 36) ? static_cast<uint8_t>(i - 20 + 8 + 1) : 0;
        ASSERT_EQ(static_cast<uint8_t>(bytes[i]), expected) << "byte " << i;
    }
}

TEST_P(CopyTest, CopyTextureRegion) {
    // Source: 8x8 with texel (x, y) = (x, y, 7, 255). Copy a 3x2 block from (1, 2) to (4, 5).
    rhi::Image pattern(8, 8, rhi::Format::RGBA8Uint);
    for (uint32_t y = 0; y < 8; ++y) {
        for (uint32_t x = 0; x < 8; ++x) pattern.store(x, y, {double(x), double(y), 7, 255});
    }
    rhi::TextureDesc desc;
    desc.format = rhi::Format::RGBA8Uint;
    desc.width = desc.height = 8;
    desc.usage = rhi::TextureUsage::CopySrc | rhi::TextureUsage::CopyDst;
    desc.name = "copy source";
    LOOM_ASSIGN_OR_FAIL(auto src, device().create_texture(desc));
    desc.name = "copy destination";
    LOOM_ASSIGN_OR_FAIL(auto dst, device().create_texture(desc));
    LOOM_ASSERT_OK(device().write_texture(src, {}, pattern.pixels));
    LOOM_ASSERT_OK(device().write_texture(dst, {}, rhi::Image(8, 8, rhi::Format::RGBA8Uint).pixels));
    rhi::TextureCopy copy;
    copy.src = src;
    copy.src_region.origin = {1, 2, 0};
    copy.src_region.extent = {3, 2, 1};
    copy.dst = dst;
    copy.dst_region.origin = {4, 5, 0};
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_texture(copy); }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image result, device().read_texture(dst));
    for (uint32_t y = 0; y < 8; ++y) {
        for (uint32_t x = 0; x < 8; ++x) {
            const bool copied = x >= 4 && x < 7 && y >= 5 && y < 7;
            const std::array<double, 4> expected =
                copied ? std::array<double, 4>{double(x - 3), double(y - 3), 7, 255} : std::array<double, 4>{0, 0, 0, 0};
            ASSERT_EQ(result.load(x, y), expected) << "texel " << x << "," << y;
        }
    }
}

TEST_P(CopyTest, CopyBetweenArrayLayersAndMips) {
    // A 2-layer, 2-mip array: copy mip 1 of layer 1 into mip 0 of a 2D texture.
    rhi::TextureDesc desc;
    desc.name = "array";
    desc.dimension = rhi::TextureDimension::Tex2DArray;
    desc.format = rhi::Format::R32Float;
    desc.width = desc.height = 4;
    desc.depth_or_layers = 2;
    desc.mip_levels = 2;
    desc.usage = rhi::TextureUsage::CopySrc | rhi::TextureUsage::CopyDst;
    LOOM_ASSIGN_OR_FAIL(auto array, device().create_texture(desc));
    rhi::Image mip1(2, 2, rhi::Format::R32Float);
    for (uint32_t i = 0; i < 4; ++i) mip1.store(i % 2, i / 2, {1.5 + i, 0, 0, 0});
    rhi::TextureRegion region;
    region.mip = 1;
    region.layer = 1;
    LOOM_ASSERT_OK(device().write_texture(array, region, mip1.pixels));
    rhi::TextureDesc flat;
    flat.name = "flat";
    flat.format = rhi::Format::R32Float;
    flat.width = flat.height = 2;
    flat.usage = rhi::TextureUsage::CopyDst;
    LOOM_ASSIGN_OR_FAIL(auto dst, device().create_texture(flat));
    rhi::TextureCopy copy;
    copy.src = array;
    copy.src_region.mip = 1;
    copy.src_region.layer = 1;
    copy.dst = dst;
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_texture(copy); }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image result, device().read_texture(dst));
    EXPECT_EQ(result.pixels, mip1.pixels);
    // Reading mip 1 of layer 1 straight back returns what was uploaded there.
    LOOM_ASSIGN_OR_FAIL(rhi::Image layer1, device().read_texture(array, 1, 1));
    EXPECT_EQ(layer1.pixels, mip1.pixels);
}

TEST_P(CopyTest, CopyBetweenColourFormatsOfOneTexelSize) {
    // Copies move bytes: RGBA8 texels land in an R32Uint texture unchanged, on every backend.
    rhi::TextureDesc desc;
    desc.name = "bytes";
    desc.format = rhi::Format::RGBA8Unorm;
    desc.width = desc.height = 2;
    desc.usage = rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto src, device().create_texture(desc));
    std::vector<std::byte> texels(16);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::byte>(0x11 * (i % 15) + 1);
    LOOM_ASSERT_OK(device().write_texture(src, {}, texels));
    desc.name = "words";
    desc.format = rhi::Format::R32Uint;
    LOOM_ASSIGN_OR_FAIL(auto dst, device().create_texture(desc));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_texture({src, {}, dst, {}}); }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image words, device().read_texture(dst));
    EXPECT_EQ(words.pixels, texels);
}

TEST_P(CopyTest, CopyBetweenMipsOfOneTexture) {
    // Mip 1 (2x2) copied into the lower-right quarter of mip 0 (4x4) of the same texture.
    rhi::TextureDesc desc;
    desc.name = "mipped";
    desc.format = rhi::Format::R32Float;
    desc.width = desc.height = 4;
    desc.mip_levels = 2;
    desc.usage = rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto texture, device().create_texture(desc));
    LOOM_ASSERT_OK(device().write_texture(texture, {}, rhi::Image(4, 4, rhi::Format::R32Float).pixels));
    rhi::Image mip1(2, 2, rhi::Format::R32Float);
    for (uint32_t i = 0; i < 4; ++i) mip1.store(i % 2, i / 2, {2.5 + i, 0, 0, 0});
    LOOM_ASSERT_OK(device().write_texture(texture, {.mip = 1}, mip1.pixels));
    rhi::TextureCopy copy{texture, {.mip = 1}, texture, {.origin = {2, 2, 0}}};
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_texture(copy); }));
    LOOM_ASSIGN_OR_FAIL(rhi::Image mip0, device().read_texture(texture));
    for (uint32_t y = 0; y < 4; ++y) {
        for (uint32_t x = 0; x < 4; ++x) {
            const double expected = x >= 2 && y >= 2 ? 2.5 + (x - 2) + 2 * (y - 2) : 0.0;
            EXPECT_EQ(mip0.load(x, y)[0], expected) << "texel " << x << "," << y;
        }
    }
}

TEST_P(CopyTest, CopyOfAWhole3DMipCopiesEveryDepthSlice) {
    // A zero extent means "the rest of the source mip" in depth too.
    rhi::TextureDesc desc;
    desc.name = "volume";
    desc.dimension = rhi::TextureDimension::Tex3D;
    desc.format = rhi::Format::R32Float;
    desc.width = desc.height = 2;
    desc.depth_or_layers = 3;
    desc.usage = rhi::TextureUsage::Sampled;
    LOOM_ASSIGN_OR_FAIL(auto src, device().create_texture(desc));
    std::vector<float> values(12);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = 1.0f + static_cast<float>(i);
    LOOM_ASSERT_OK(device().write_texture(src, {}, std::as_bytes(std::span<const float>(values))));
    desc.name = "volume copy";
    LOOM_ASSIGN_OR_FAIL(auto dst, device().create_texture(desc));
    LOOM_ASSERT_OK(device().write_texture(dst, {}, std::vector<std::byte>(48)));
    LOOM_ASSERT_OK(run_frame(device(), [&](rhi::CommandList& list) { list.copy_texture({src, {}, dst, {}}); }));
    for (uint32_t slice = 0; slice < 3; ++slice) {
        LOOM_ASSIGN_OR_FAIL(rhi::Image image, device().read_texture(dst, 0, slice));
        for (uint32_t i = 0; i < 4; ++i) EXPECT_EQ(image.load(i % 2, i / 2)[0], values[slice * 4 + i]) << "slice " << slice << " texel " << i;
    }
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(CopyTest);

}  // namespace loom::test
