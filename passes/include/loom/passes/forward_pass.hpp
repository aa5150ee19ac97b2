#pragma once
// The forward pass: lights its objects while drawing them, with the lighting of the deferred
// pass; composed from "camera" + "forward-render" and, like the deferred pass, optionally
// "shadow-render" and "high-pass-render" (the same parts, reused). Outputs color, depth and
// high_pass; reads shadow_map. Behind the objects it draws the deferred pass's sky (a program
// of its own: "fullscreen" + "sky-render" + "high-pass-render"), so that both pipelines show the
// same background.

#include <memory>

#include <string>

#include "loom/passes/deferred_pass.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::passes {

class ForwardPass final : public ShaderPass {
public:
    explicit ForwardPass(const PassConfig& config = {}, LightingParts parts = {}, std::string name = "forward");
    ~ForwardPass() override;

    void set_view(const SceneView& view) { view_ = view; }
    void set_threshold(float threshold) { threshold_ = threshold; }

    Status execute(fg::PassContext& context) override;
    /// Also releases the sky program's GPU objects.
    void release_gpu() override;

private:
    class Sky;
    std::unique_ptr<Sky> sky_;
    LightingParts parts_;
    SceneView view_;
    float threshold_ = 1.0f;
};

}  // namespace loom::passes
