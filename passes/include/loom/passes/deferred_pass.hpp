#pragma once
// The deferred lighting pass of the paper's Figure 2, composed from three parts as its
// Listings 3-5: "deferred-render" (G-buffer in, colour out), "shadow-render" (shadow map in) and
// "high-pass-render" (high-pass out). Its ports are the union of the parts' ports; its program is
// the parts' code composed. Leaving a part out leaves out its ports and its code.

#include <string>

#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::passes {

/// Which optional parts a lit pass (deferred or forward) is composed of.
struct LightingParts {
    bool shadows = true;    ///< "shadow-render": port shadow_map
    bool high_pass = true;  ///< "high-pass-render": port high_pass
};

class DeferredPass final : public ShaderPass {
public:
    explicit DeferredPass(const PassConfig& config = {}, LightingParts parts = {}, std::string name = "deferred");

    void set_view(const SceneView& view) { view_ = view; }
    /// Luminance above which colour goes to the high-pass output.
    void set_threshold(float threshold) { threshold_ = threshold; }
    [[nodiscard]] const LightingParts& parts() const { return parts_; }

    Status execute(fg::PassContext& context) override;

private:
    LightingParts parts_;
    SceneView view_;
    float threshold_ = 1.0f;
};

}  // namespace loom::passes
