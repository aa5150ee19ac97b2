#pragma once
// The blit / present pass: copies its source texel for texel into its target (port "target",
// by default RGBA8Unorm at the frame size), converting to the target's format. Bind a window's
// back buffer to the target with fg::Executor::import_texture to present.

#include <string>

#include "loom/framegraph/texture_spec.hpp"
#include "loom/passes/shader_pass.hpp"

namespace loom::passes {

/// RGBA8Unorm at the frame size, the default target of BlitPass.
fg::TextureSpec default_blit_target();

class BlitPass final : public ShaderPass {
public:
    explicit BlitPass(const PassConfig& config = {}, const fg::TextureSpec& target = default_blit_target(),
                      std::string name = "present");

    Status execute(fg::PassContext& context) override;
};

}  // namespace loom::passes
