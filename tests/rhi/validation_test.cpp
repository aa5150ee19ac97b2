// The shared validation layer against made-up devices: the rules that depend on Capabilities
// (format features, per-format sample counts, limits), which real test devices cannot all
// show. The same rules on real devices of both
// backends: tests/render/misuse_table_test.cpp.
#include <limits>

#include <gtest/gtest.h>

#include "loom/rhi/validation.hpp"

namespace loom::rhi {
namespace {

// A device that can do everything with every format, up to modest limits.
Capabilities capable_device() {
    Capabilities caps;
    for (FormatCapabilities& f : caps.formats) {
        f = FormatCapabilities{true, true, true, true, true, true, 1u | 2u | 4u};
    }
    caps.max_texture_size = 1024;
    caps.max_texture_size_3d = 256;
    caps.max_texture_size_cube = 512;
    caps.max_texture_layers = 64;
    caps.max_samples = 4;
    caps.placed_resources = true;
    return caps;
}

TextureDesc texture(Format format, TextureUsage usage) {
    TextureDesc desc;
    desc.name = std::string(1, 't');  // not = "t": GCC 12 -O3 -Wrestrict false positive (bug 105651)
    desc.format = format;
    desc.width = desc.height = 16;
    desc.usage = usage;
    return desc;
}

void expect_error(const Status& status, ErrorCode code, const std::string& message) {
    ASSERT_FALSE(status.ok()) << "accepted, expected: " << message;
    EXPECT_EQ(error_code_name(status.error().code), error_code_name(code));
    EXPECT_EQ(status.error().message, message);
}

TEST(Validation, AValidTextureOnACapableDevicePasses) {
    const Capabilities caps = capable_device();
    EXPECT_TRUE(validation::texture_desc(texture(Format::RGBA8Unorm, TextureUsage::Sampled | TextureUsage::ColorAttachment), caps).ok());
    TextureDesc ms = texture(Format::Depth32F, TextureUsage::DepthStencilAttachment);
    ms.samples = 4;
    EXPECT_TRUE(validation::texture_desc(ms, caps).ok());
    TextureDesc cube = texture(Format::RGBA16Float, TextureUsage::Sampled);
    cube.dimension = TextureDimension::Cube;
    cube.width = cube.height = 512;
    cube.depth_or_layers = 6;
    cube.mip_levels = 10;
    EXPECT_TRUE(validation::texture_desc(cube, caps).ok());
}

TEST(Validation, FormatFeaturesAreCheckedPerUsage) {
    Capabilities caps = capable_device();
    FormatCapabilities& rgba = caps.formats[static_cast<std::size_t>(Format::RGBA8Unorm)];
    rgba.storage = false;
    expect_error(validation::texture_desc(texture(Format::RGBA8Unorm, TextureUsage::Storage), caps), ErrorCode::Unsupported,
                 "texture 't': RGBA8Unorm cannot be a storage image on this device");
    rgba.color_attachment = false;
    expect_error(validation::texture_desc(texture(Format::RGBA8Unorm, TextureUsage::ColorAttachment), caps), ErrorCode::Unsupported,
                 "texture 't': RGBA8Unorm cannot be a colour attachment on this device");
    rgba.sampled = false;
    rgba.depth_stencil_attachment = false;  // (a colour format; the made-up device claims it)
    expect_error(validation::texture_desc(texture(Format::RGBA8Unorm, TextureUsage::Sampled | TextureUsage::Storage), caps),
                 ErrorCode::Unsupported, "texture 't': RGBA8Unorm cannot be used on this device");
    caps.formats[static_cast<std::size_t>(Format::Depth24Stencil8)].depth_stencil_attachment = false;
    expect_error(validation::texture_desc(texture(Format::Depth24Stencil8, TextureUsage::DepthStencilAttachment), caps),
                 ErrorCode::Unsupported, "texture 't': Depth24Stencil8 cannot be a depth/stencil attachment on this device");
    caps.formats[static_cast<std::size_t>(Format::R32Float)].sampled = false;
    expect_error(validation::texture_desc(texture(Format::R32Float, TextureUsage::Sampled), caps), ErrorCode::Unsupported,
                 "texture 't': R32Float cannot be sampled on this device");
}

TEST(Validation, SampleCountsArePerFormat) {
    Capabilities caps = capable_device();
    caps.formats[static_cast<std::size_t>(Format::RGBA32Float)].sample_counts = 1;
    TextureDesc desc = texture(Format::RGBA32Float, TextureUsage::ColorAttachment);
    desc.samples = 4;
    expect_error(validation::texture_desc(desc, caps), ErrorCode::Unsupported,
                 "texture 't': 4 samples of RGBA32Float are not supported on this device");
    desc.format = Format::RGBA8Unorm;
    EXPECT_TRUE(validation::texture_desc(desc, caps).ok());
    desc.samples = 8;
    expect_error(validation::texture_desc(desc, caps), ErrorCode::Unsupported,
                 "texture 't': 8 samples of RGBA8Unorm are not supported on this device");
}

TEST(Validation, LimitsArePerDimension) {
    const Capabilities caps = capable_device();
    TextureDesc flat = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    flat.width = 1024;
    EXPECT_TRUE(validation::texture_desc(flat, caps).ok());
    flat.height = 1025;
    expect_error(validation::texture_desc(flat, caps), ErrorCode::Unsupported,
                 "texture 't': size 1024x1025x1 exceeds this device's limit of 1024 texels for a Tex2D texture");
    TextureDesc volume = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    volume.dimension = TextureDimension::Tex3D;
    volume.width = 300;  // within the 2D limit, past the 3D one
    volume.depth_or_layers = 2;
    expect_error(validation::texture_desc(volume, caps), ErrorCode::Unsupported,
                 "texture 't': size 300x16x2 exceeds this device's limit of 256 texels for a Tex3D texture");
    TextureDesc cube = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    cube.dimension = TextureDimension::Cube;
    cube.width = cube.height = 1024;
    cube.depth_or_layers = 6;
    expect_error(validation::texture_desc(cube, caps), ErrorCode::Unsupported,
                 "texture 't': size 1024x1024x1 exceeds this device's limit of 512 texels for a Cube texture");
    TextureDesc array = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    array.dimension = TextureDimension::Tex2DArray;
    array.depth_or_layers = 65;
    expect_error(validation::texture_desc(array, caps), ErrorCode::Unsupported,
                 "texture 't': 65 layers exceed this device's limit of 64");
}

TEST(Validation, MalformedBeforeUnsupported) {
    // A description wrong on any device is reported as such even on a device that also could
    // not create it: the fix is in the description first.
    Capabilities caps = capable_device();
    caps.formats[static_cast<std::size_t>(Format::RGBA8Unorm)] = FormatCapabilities{};
    TextureDesc desc = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    desc.mip_levels = 9;
    expect_error(validation::texture_desc(desc, caps), ErrorCode::InvalidArgument,
                 "texture 't': mip_levels 9 is not in 1..5 for a 16x16x1 texture");
}

TEST(Validation, SamplerValuesAreQuotedAndNaNIsRefused) {
    SamplerDesc sampler;
    sampler.name = "s";
    sampler.min_lod = std::numeric_limits<float>::quiet_NaN();
    expect_error(validation::sampler_desc(sampler), ErrorCode::InvalidArgument, "sampler 's': min_lod nan is above max_lod 1000");
    sampler.min_lod = 0;
    sampler.max_anisotropy = std::numeric_limits<float>::quiet_NaN();
    expect_error(validation::sampler_desc(sampler), ErrorCode::InvalidArgument, "sampler 's': max_anisotropy nan is below 1");
}

TEST(Validation, TextureWritesResolveTheRestOfTheMip) {
    TextureDesc desc = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    desc.width = 10;
    desc.height = 6;
    desc.mip_levels = 2;
    auto write = validation::texture_write(desc, {.mip = 1, .origin = {1, 2, 0}}, 4u * 1u * 1u * 4u);
    ASSERT_TRUE(write.ok()) << write.error().message;
    EXPECT_EQ(write->extent.width, 4u);  // mip 1 is 5x3
    EXPECT_EQ(write->extent.height, 1u);
    EXPECT_EQ(write->extent.depth, 1u);
    EXPECT_EQ(write->bytes, 16u);
    TextureDesc volume = desc;
    volume.dimension = TextureDimension::Tex3D;
    volume.depth_or_layers = 5;
    volume.mip_levels = 1;
    auto slices = validation::texture_write(volume, {.origin = {0, 0, 3}}, 10u * 6u * 2u * 4u);
    ASSERT_TRUE(slices.ok()) << slices.error().message;
    EXPECT_EQ(slices->extent.depth, 2u);
    EXPECT_EQ(slices->layer, 0u);
}

TEST(Validation, TransitionsNeedAStateOfTheResourceWithItsUsage) {
    Capabilities caps = capable_device();
    const TextureDesc color = texture(Format::RGBA8Unorm, TextureUsage::Sampled | TextureUsage::ColorAttachment);
    for (ResourceState state : {ResourceState::Undefined, ResourceState::ShaderRead, ResourceState::RenderTarget,
                                ResourceState::CopySrc, ResourceState::CopyDst, ResourceState::Present}) {
        EXPECT_TRUE(validation::texture_transition(color, state, caps).ok()) << resource_state_name(state);
    }
    expect_error(validation::texture_transition(color, ResourceState::DepthRead, caps), ErrorCode::InvalidArgument,
                 "transition: texture 't' (RGBA8Unorm) cannot be in state DepthRead");
    expect_error(validation::texture_transition(color, ResourceState::IndexBuffer, caps), ErrorCode::InvalidArgument,
                 "transition: texture 't' (RGBA8Unorm) cannot be in state IndexBuffer");
    expect_error(validation::texture_transition(color, ResourceState::Storage, caps), ErrorCode::InvalidArgument,
                 "transition: texture 't' to Storage needs Storage usage");
    const TextureDesc depth = texture(Format::Depth32F, TextureUsage::Sampled);
    EXPECT_TRUE(validation::texture_transition(depth, ResourceState::DepthRead, caps).ok());
    expect_error(validation::texture_transition(depth, ResourceState::RenderTarget, caps), ErrorCode::InvalidArgument,
                 "transition: texture 't' (Depth32F) cannot be in state RenderTarget");
    expect_error(validation::texture_transition(depth, ResourceState::DepthWrite, caps), ErrorCode::InvalidArgument,
                 "transition: texture 't' to DepthWrite needs DepthStencilAttachment usage");
    caps.formats[static_cast<std::size_t>(Format::Depth32F)].sampled = false;
    expect_error(validation::texture_transition(depth, ResourceState::DepthRead, caps), ErrorCode::Unsupported,
                 "transition: texture 't' to DepthRead: Depth32F cannot be sampled on this device");

    const BufferDesc buffer{"b", 64, BufferUsage::Storage};
    EXPECT_TRUE(validation::buffer_transition(buffer, ResourceState::IndirectArgument).ok());
    expect_error(validation::buffer_transition(buffer, ResourceState::Present), ErrorCode::InvalidArgument,
                 "transition: buffer 'b' cannot be in state Present");
}

TEST(Validation, TextureRangesResolveToTheLastOneAndStayInside) {
    TextureDesc array = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    array.dimension = TextureDimension::Tex2DArray;
    array.depth_or_layers = 6;
    array.mip_levels = 5;
    auto whole = validation::texture_range("t", array, TextureRange{});
    ASSERT_TRUE(whole.ok());
    EXPECT_EQ(*whole, (TextureRange{0, 5, 0, 6}));
    auto rest = validation::texture_range("t", array, TextureRange{.base_mip = 3, .base_layer = 2, .layer_count = 1});
    ASSERT_TRUE(rest.ok());
    EXPECT_EQ(*rest, (TextureRange{3, 2, 2, 1}));
    auto no_mip = validation::texture_range("x", array, {.base_mip = 5});
    ASSERT_FALSE(no_mip.ok());
    EXPECT_EQ(no_mip.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(no_mip.error().message, "x: mips 5.. are not inside its 5 mip levels");
    auto past = validation::texture_range("x", array, {.base_layer = 4, .layer_count = 3});
    ASSERT_FALSE(past.ok());
    EXPECT_EQ(past.error().message, "x: layers 4..6 are not inside its 6 layers");
    // Counts near 2^32 do not wrap.
    auto huge = validation::texture_range("x", array, {.base_mip = 1, .mip_count = 0xFFFFFFFEu});
    ASSERT_FALSE(huge.ok());
    TextureDesc volume = texture(Format::RGBA8Unorm, TextureUsage::Sampled);
    volume.dimension = TextureDimension::Tex3D;
    volume.depth_or_layers = 8;
    auto slices = validation::texture_range("x", volume, {.base_layer = 0, .layer_count = 8});
    ASSERT_FALSE(slices.ok());
    EXPECT_EQ(slices.error().message, "x: layers 0..7 are not inside its 1 layer (the depth slices of a Tex3D texture are not layers)");
}

TEST(Validation, BufferPlacementsAreAlignedAndInsideTheHeap) {
    BufferDesc desc{"b", 100, BufferUsage::Storage};
    desc.placement = BufferPlacement{HeapHandle{}, 256};
    const HeapDesc heap{"h", 1024};
    EXPECT_TRUE(validation::buffer_placement(desc, heap, {256, 256}).ok());
    expect_error(validation::buffer_placement(desc, heap, {256, 512}), ErrorCode::InvalidArgument,
                 "buffer 'b' placed in heap 'h': offset 256 is not a multiple of the alignment 512");
    expect_error(validation::buffer_placement(desc, heap, {1024, 256}), ErrorCode::InvalidArgument,
                 "buffer 'b' placed in heap 'h': range 256+1024 exceeds the heap size 1024");
    desc.placement->offset = std::numeric_limits<uint64_t>::max() - 255;
    expect_error(validation::buffer_placement(desc, heap, {512, 256}), ErrorCode::InvalidArgument,
                 "buffer 'b' placed in heap 'h': range 18446744073709551360+512 exceeds the heap size 1024");
    Capabilities no_heaps = capable_device();
    no_heaps.placed_resources = false;
    expect_error(validation::buffer_desc(desc, no_heaps), ErrorCode::Unsupported,
                 "buffer 'b': placement in a heap needs placed resources, which this device lacks");
    EXPECT_TRUE(validation::buffer_desc(desc, capable_device()).ok());
}

}  // namespace
}  // namespace loom::rhi
