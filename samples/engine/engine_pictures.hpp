#pragma once
// What loom-engine writes out: every captured intermediate read back (one image per mip level
// and layer) and turned into something viewable.

#include <map>
#include <string>
#include <vector>

#include "engine_frame.hpp"
#include "loom/rhi/image.hpp"

namespace loom::engine {

/// Every captured intermediate of the latest frame as the device holds it, by picture name:
/// "depth", "ssao_raw", "ssao", "hzb.mip0" … "hzb.mip4", "shadow_cascades.layer0" … 3, "hdr",
/// "bloom_down.mip0" … 4, "bloom_up.mip0" … 3, "final"; and "light_list", the light count of
/// each tile as an R32Uint image of tiles. Errors: the device's read-back errors.
Result<std::map<std::string, rhi::Image>> read_intermediates(rhi::Device& device, EngineFrame& frame);

/// A viewable RGBA8 picture of `image` (named as read_intermediates names it): depths and the
/// hierarchical Z as grey from near to far (the sky white), HDR colours tone-mapped, the light
/// list as a heat map over `final` (the frame's picture; tiles blocks of kTileSize pixels).
rhi::Image viewable(const std::string& name, const rhi::Image& image, const rhi::Image& final);

/// The pictures `names` (from `pictures`) on a grid of `columns`, each fitted into a cell of
/// `cell` texels (aspect kept, nearest texel, black around): the README's overview.
rhi::Image contact_sheet(const std::map<std::string, rhi::Image>& pictures, const std::vector<std::string>& names,
                         uint32_t columns, fg::Extent2D cell);

}  // namespace loom::engine
