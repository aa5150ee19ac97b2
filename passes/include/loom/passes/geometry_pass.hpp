#pragma once
// The geometry pass: draws its objects into the G-buffer — position, normal and albedo maps,
// with metallic and roughness in their alpha channels (the paper's three connected maps), and
// an emission map with the emitted radiance in RGB (packing in
// shaders/include/loom/passes/gbuffer.glsl) — and its own depth
// texture (port "depth", transient: nothing reads it after the pass).

#include <string>

#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::passes {

class GeometryPass final : public ShaderPass {
public:
    explicit GeometryPass(const PassConfig& config = {}, std::string name = "geometry");

    void set_camera(const scene::CameraMatrices& camera) { camera_ = camera; }

    Status execute(fg::PassContext& context) override;

private:
    scene::CameraMatrices camera_;
};

}  // namespace loom::passes
