#pragma once
// The composite pass: colour + bloom × strength, times the exposure, ACES filmic tone mapping,
// sRGB encoding (ports color, bloom → final). The formulas are in
// shaders/include/loom/parts/composite.frag.glsl and loom/passes/tonemap.glsl.

#include <string>

#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

class CompositePass final : public ShaderPass {
public:
    explicit CompositePass(const PassConfig& config = {}, std::string name = "composite");

    void set_exposure(float exposure) { exposure_ = exposure; }
    void set_bloom_strength(float strength) { bloom_strength_ = strength; }
    /// Off for targets that encode sRGB themselves (an sRGB back buffer).
    void set_encode_srgb(bool encode) { encode_srgb_ = encode; }
    [[nodiscard]] float exposure() const { return exposure_; }
    [[nodiscard]] float bloom_strength() const { return bloom_strength_; }
    [[nodiscard]] bool encode_srgb() const { return encode_srgb_; }

    Status execute(fg::PassContext& context) override;

private:
    float exposure_ = 1.0f;
    float bloom_strength_ = 0.8f;
    bool encode_srgb_ = true;
};

}  // namespace loom::passes
