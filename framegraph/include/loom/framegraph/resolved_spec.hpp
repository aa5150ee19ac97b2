#pragma once
// A joined spec made concrete: an rhi::Format, an evaluated size, counts and usage flags. This
// is what a physical texture is created from.
//
// Defaults for properties nobody constrained: format RGBA8Unorm, size = the frame size,
// 1 sample, 1 mip level, 1 array layer.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

inline constexpr rhi::Format kDefaultFormat = rhi::Format::RGBA8Unorm;

/// How a resolved format was chosen.
enum class FormatMatch : uint8_t {
    Default,   ///< no port constrained the format: kDefaultFormat
    Exact,     ///< the joined features are exactly one enum value
    Covering,  ///< no enum value has the joined features; the smallest covering format was taken
};

/// "exact", "covering" or "default".
std::string_view format_match_name(FormatMatch match);

/// A format picked for a feature set, and how.
struct FormatResolution {
    rhi::Format format = kDefaultFormat;
    FormatMatch match = FormatMatch::Default;

    friend bool operator==(const FormatResolution&, const FormatResolution&) = default;
};

/// True when `candidate` can hold everything `wanted` asks for: same flags and sharing, every
/// wanted channel present with the same kind and at least the bits, no extra channel except an
/// added alpha channel, depth and stencil likewise (nothing added).
bool covers(const rhi::FormatFeatures& candidate, const rhi::FormatFeatures& wanted);

/// The format for `features`: the exact match (rhi::format_from_features), else the covering
/// format with the fewest bytes per texel (ties: enum order), else an ErrorCode::Join error
/// naming `what`. No features → kDefaultFormat.
Result<FormatResolution> resolve_format(const std::optional<rhi::FormatFeatures>& features, std::string_view what);

/// A concrete texture description, minus the name.
struct ResolvedSpec {
    rhi::Format format = kDefaultFormat;
    FormatMatch format_match = FormatMatch::Default;
    Extent2D extent{};
    uint32_t samples = 1;
    uint32_t mips = 1;
    uint32_t layers = 1;
    rhi::TextureUsage usage = rhi::TextureUsage::None;
    bool cube = false;  ///< a cube map (6 square layers)

    friend bool operator==(const ResolvedSpec&, const ResolvedSpec&) = default;
};

/// Makes `spec` concrete for a frame of size `frame` (defaults above). Usage is copied as is;
/// the planner adds what the ports' roles need. Errors (ErrorCode::Join for formats, Graph for
/// impossible counts such as 3 samples, more mips than the size allows, multisampled mips)
/// name `what`.
Result<ResolvedSpec> resolve(const TextureSpec& spec, Extent2D frame, std::string_view what);

/// `spec` (made by resolve from a spec whose size was `size`) made concrete for a frame of size
/// `frame` instead: the extent evaluated for it and every check of resolve run again, the
/// format, counts and usage kept. Errors as resolve's.
Result<ResolvedSpec> resolve_for_frame(ResolvedSpec spec, const std::optional<SizeSpec>& size, Extent2D frame,
                                       std::string_view what);

/// True when two resolved specs can hold each other's contents without any change: same
/// format, extent, samples, mips and layers (usage is not compared: it is a union).
bool same_texture_shape(const ResolvedSpec& a, const ResolvedSpec& b);

/// The rhi description of a texture with this spec (2D, or a 2D array when layers > 1).
rhi::TextureDesc to_texture_desc(const ResolvedSpec& spec, std::string name);

/// "RGBA16Float 1920x1080" plus " x4 samples", " 5 mips", " 6 layers" where they are not 1.
std::string describe_resolved(const ResolvedSpec& spec);

}  // namespace loom::fg
