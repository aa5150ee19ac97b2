// Uploads and readbacks: every format round-trips byte for byte in loom's CPU layout (packed
// depth/stencil included), partial regions, mips, array layers, cube faces and 3D slices.
#include <cstring>

#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

using rhi::Format;

class TransferTest : public RenderTest {};

/// A deterministic image whose texels are valid values of `format` and differ from each other.
rhi::Image pattern(Format format, uint32_t w, uint32_t h, uint32_t seed = 0) {
    rhi::Image image(w, h, format);
    const rhi::FormatInfo& info = rhi::format_info(format);
    for (uint32_t y = 0; y < h; ++y) {
        for (uint32_t x = 0; x < w; ++x) {
            const uint32_t n = x + y * w + seed * 17;
            auto* p = image.texel(x, y).data();
            switch (format) {
                case Format::Depth16: {
                    const auto v = static_cast<uint16_t>(n * 977 + 3);
                    std::memcpy(p, &v, 2);
                    continue;
                }
                case Format::Depth24: {
                    const uint32_t v = (n * 123457u + 99u) & 0xFFFFFFu;
                    std::memcpy(p, &v, 4);
                    continue;
                }
                case Format::Depth24Stencil8: {
                    const uint32_t v = ((n * 123457u + 99u) & 0xFFFFFFu) | (((n * 29u) & 0xFFu) << 24);
                    std::memcpy(p, &v, 4);
                    continue;
                }
                case Format::Depth32F: {
                    const float v = static_cast<float>(n % 64) / 64.0f;  // depth is clamped to 0..1
                    std::memcpy(p, &v, 4);
                    continue;
                }
                case Format::Depth32FStencil8: {
                    const float v = static_cast<float>(n % 64) / 64.0f;
                    std::memcpy(p, &v, 4);
                    p[4] = static_cast<std::byte>((n * 29u) & 0xFFu);
                    continue;
                }
                default: break;
            }
            std::array<double, 4> v{};
            for (std::size_t c = 0; c < 4; ++c) {
                const double k = static_cast<double>((n * 7 + c * 3) % 16);
                switch (info.color_kind()) {
                    case rhi::ChannelKind::Unorm: v[c] = k / 15.0; break;
                    case rhi::ChannelKind::Snorm: v[c] = k / 7.5 - 1.0; break;
                    case rhi::ChannelKind::Uint: v[c] = k * 11; break;
                    case rhi::ChannelKind::Sint: v[c] = k * 11 - 80; break;
                    case rhi::ChannelKind::Float: v[c] = info.features.color[0].bits == 11 || info.features.shared_exponent_bits ? k * 0.25 : k * 0.5 - 3.0; break;
                    case rhi::ChannelKind::None: break;
                }
            }
            image.store(x, y, v);
        }
    }
    return image;
}

TEST_P(TransferTest, EveryFormatRoundTripsExactly) {
    for (Format format : rhi::all_formats()) {
        SCOPED_TRACE(std::string(rhi::format_name(format)));
        if (format == Format::Stencil8 || !device().capabilities().format(format).sampled) continue;
        rhi::TextureDesc desc;
        desc.name = "round trip";
        desc.format = format;
        desc.width = 5;  // odd sizes: rows are tightly packed, not 4-byte aligned
        desc.height = 3;
        desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst | rhi::TextureUsage::CopySrc;
        LOOM_ASSIGN_OR_FAIL(auto texture, device().create_texture(desc));
        const rhi::Image source = pattern(format, 5, 3);
        LOOM_ASSERT_OK(device().write_texture(texture, {}, source.pixels));
        LOOM_ASSIGN_OR_FAIL(rhi::Image back, device().read_texture(texture));
        ASSERT_EQ(back.format, format);
        auto comparison = rhi::compare_images(source, back);
        ASSERT_TRUE(comparison.ok());
        EXPECT_TRUE(comparison->equal()) << comparison->summary();
        EXPECT_EQ(back.pixels, source.pixels);
        LOOM_ASSERT_OK(device().destroy(texture));
    }
}

TEST_P(TransferTest, PartialRegionLeavesTheRest) {
    LOOM_ASSIGN_OR_FAIL(auto texture, make_target(device(), "partial", Format::RGBA8Unorm, 8, 6));
    const rhi::Image base = pattern(Format::RGBA8Unorm, 8, 6, 1);
    LOOM_ASSERT_OK(device().write_texture(texture, {}, base.pixels));
    const rhi::Image patch = pattern(Format::RGBA8Unorm, 3, 2, 2);
    rhi::TextureRegion region;
    region.origin = {4, 3, 0};
    region.extent = {3, 2, 1};
    LOOM_ASSERT_OK(device().write_texture(texture, region, patch.pixels));
    LOOM_ASSIGN_OR_FAIL(rhi::Image back, device().read_texture(texture));
    for (uint32_t y = 0; y < 6; ++y) {
        for (uint32_t x = 0; x < 8; ++x) {
            const bool patched = x >= 4 && x < 7 && y >= 3 && y < 5;
            const auto expected = patched ? patch.load(x - 4, y - 3) : base.load(x, y);
            ASSERT_EQ(back.load(x, y), expected) << "texel " << x << "," << y;
        }
    }
}

TEST_P(TransferTest, MipsLayersFacesAndSlices) {
    struct Case {
        rhi::TextureDimension dimension;
        uint32_t depth_or_layers;
        const char* name;
    };
    for (const Case& c : {Case{rhi::TextureDimension::Tex2D, 1, "2d"}, Case{rhi::TextureDimension::Tex2DArray, 3, "array"},
                          Case{rhi::TextureDimension::Cube, 6, "cube"}, Case{rhi::TextureDimension::Tex3D, 4, "3d"}}) {
        SCOPED_TRACE(c.name);
        rhi::TextureDesc desc;
        desc.name = c.name;
        desc.dimension = c.dimension;
        desc.format = Format::RGBA16Float;
        desc.width = desc.height = 8;
        desc.depth_or_layers = c.depth_or_layers;
        desc.mip_levels = 3;
        desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst | rhi::TextureUsage::CopySrc;
        LOOM_ASSIGN_OR_FAIL(auto texture, device().create_texture(desc));
        const bool is3d = c.dimension == rhi::TextureDimension::Tex3D;
        std::vector<std::vector<rhi::Image>> uploaded;  // [mip][layer]
        for (uint32_t mip = 0; mip < 3; ++mip) {
            const uint32_t size = 8u >> mip;
            const uint32_t layers = is3d ? std::max(1u, c.depth_or_layers >> mip) : c.depth_or_layers;
            uploaded.emplace_back();
            for (uint32_t layer = 0; layer < layers; ++layer) {
                rhi::Image image = pattern(Format::RGBA16Float, size, size, mip * 10 + layer + 1);
                rhi::TextureRegion region;
                region.mip = mip;
                if (is3d) {
                    region.origin.z = layer;
                    region.extent = {size, size, 1};
                } else {
                    region.layer = layer;
                }
                LOOM_ASSERT_OK(device().write_texture(texture, region, image.pixels));
                uploaded.back().push_back(std::move(image));
            }
        }
        for (uint32_t mip = 0; mip < 3; ++mip) {
            for (uint32_t layer = 0; layer < uploaded[mip].size(); ++layer) {
                LOOM_ASSIGN_OR_FAIL(rhi::Image back, device().read_texture(texture, mip, layer));
                EXPECT_EQ(back.pixels, uploaded[mip][layer].pixels) << "mip " << mip << " layer " << layer;
            }
        }
        EXPECT_EQ(device().read_texture(texture, 3, 0).error().code, ErrorCode::InvalidArgument);
        LOOM_ASSERT_OK(device().destroy(texture));
    }
}

TEST_P(TransferTest, BufferWriteAtOffsetAndReadRange) {
    LOOM_ASSIGN_OR_FAIL(auto buffer, device().create_buffer(rhi::BufferDesc{"bytes", 32, rhi::BufferUsage::Storage}));
    std::vector<std::byte> zeros(32);
    LOOM_ASSERT_OK(device().write_buffer(buffer, 0, zeros));
    const std::vector<std::byte> middle = {std::byte{1}, std::byte{2}, std::byte{3}};
    LOOM_ASSERT_OK(device().write_buffer(buffer, 10, middle));
    LOOM_ASSIGN_OR_FAIL(auto range, device().read_buffer(buffer, 9, 5));
    EXPECT_EQ(range, (std::vector<std::byte>{std::byte{0}, std::byte{1}, std::byte{2}, std::byte{3}, std::byte{0}}));
    EXPECT_EQ(device().read_buffer(buffer, 30, 3).error().code, ErrorCode::InvalidArgument);
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(TransferTest);

}  // namespace loom::test
