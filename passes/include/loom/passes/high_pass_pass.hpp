#pragma once
// The high-pass filter as a stand-alone post-process pass (port source → high_pass): the
// "high-pass-render" part of the deferred pass on top of a part that feeds it every texel of
// a texture. Same formula, same code.

#include <string>

#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

class HighPassPass final : public ShaderPass {
public:
    explicit HighPassPass(const PassConfig& config = {}, std::string name = "high-pass");

    void set_threshold(float threshold) { threshold_ = threshold; }

    Status execute(fg::PassContext& context) override;

private:
    float threshold_ = 1.0f;
};

}  // namespace loom::passes
