// The geometry of mip levels, layers and depth slices that the validation layer and both
// backends share (loom/rhi/subresources.hpp).
#include <gtest/gtest.h>

#include "loom/rhi/subresources.hpp"

namespace loom::rhi {
namespace {

TEST(Subresources, MipExtentsLayersAndChains) {
    TextureDesc desc;
    desc.width = 37;
    desc.height = 4;
    desc.dimension = TextureDimension::Tex3D;
    desc.depth_or_layers = 9;
    EXPECT_EQ(max_mip_levels(desc), 6u);  // 37 -> 18 -> 9 -> 4 -> 2 -> 1
    const Extent3D mip2 = mip_extent(desc, 2);
    EXPECT_EQ(mip2.width, 9u);
    EXPECT_EQ(mip2.height, 1u);
    EXPECT_EQ(mip2.depth, 2u);
    EXPECT_EQ(mip_layers(desc, 2), 2u);
    EXPECT_EQ(mip_extent(desc, 40).width, 1u);  // shifts past 31 bits stay at 1
    desc.dimension = TextureDimension::Tex2DArray;
    EXPECT_EQ(mip_layers(desc, 2), 9u);
    EXPECT_EQ(mip_extent(desc, 2).depth, 1u);
    EXPECT_EQ(max_mip_levels(desc), 6u);
}

}  // namespace
}  // namespace loom::rhi
