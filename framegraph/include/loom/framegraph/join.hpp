#pragma once
// The join of two texture specs: Hafner (ELS 2019) §6.1 for the internal format, extended to
// every other property. Connected ports are reduced to one spec by joining them pairwise.
//
// Format (destructured into rhi::FormatFeatures):
//   - the feature flags (sRGB, compression, BGRA memory order) and the shared-exponent bits
//     ("sharing") must be the same;
//   - depth/stencil formats join only with depth/stencil formats, colour only with colour;
//   - depth and stencil are joined separately; each colour channel R, G, B, A is joined on
//     its own: both present → same kind required, bits take the maximum; one present → that
//     one; none → the channel stays absent.
// Size: equal once evaluated against the frame size. Samples, mip levels, layers: equal, or
// unconstrained on one side. Usage: the union.

#include <optional>
#include <string>
#include <string_view>

#include "loom/framegraph/buffer_spec.hpp"
#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// What a join needs besides the two specs: the frame size (to compare a relative size with an
/// absolute one) and the names of the two sides for the error message ("deferred.color"). The
/// names are views: the strings they show must outlive the join call.
struct JoinContext {
    std::optional<Extent2D> frame;
    std::string_view a_name = "a";
    std::string_view b_name = "b";
};

/// Join of two format feature sets (§6.1). Fails with ErrorCode::Join naming both sides, the
/// property ("format") and the conflicting values.
Result<rhi::FormatFeatures> join_features(const rhi::FormatFeatures& a, const rhi::FormatFeatures& b,
                                          const JoinContext& context = {});

/// Join of two specs, property by property. Fails with ErrorCode::Join naming both sides, the
/// conflicting property and its two values.
Result<TextureSpec> join(const TextureSpec& a, const TextureSpec& b, const JoinContext& context = {});

/// Join of two buffer specs (buffer_spec.hpp): sizes equal once evaluated for the frame, the
/// largest alignment, the union of the usages. Fails with ErrorCode::Join naming both sides,
/// the property and its two values.
Result<BufferSpec> join_buffer_specs(const BufferSpec& a, const BufferSpec& b, const JoinContext& context = {});

/// True when join(a, b, {frame}) succeeds.
bool joinable(const TextureSpec& a, const TextureSpec& b, std::optional<Extent2D> frame = std::nullopt);

}  // namespace loom::fg
