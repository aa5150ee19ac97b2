#include "loom/passes/blur_pass.hpp"

#include <algorithm>
#include <cmath>

#include "loom/passes/parts.hpp"
#include "uniforms.hpp"

namespace loom::passes {

std::vector<float> gaussian_weights(uint32_t radius) {
    radius = std::min(radius, kMaxBlurRadius);
    const double sigma = std::max(static_cast<double>(radius) / 3.0, 0.5);
    std::vector<double> raw(radius + 1);
    double total = 0.0;
    for (uint32_t i = 0; i <= radius; ++i) {
        raw[i] = std::exp(-static_cast<double>(i) * static_cast<double>(i) / (2.0 * sigma * sigma));
        total += i == 0 ? raw[i] : 2.0 * raw[i];
    }
    std::vector<float> weights(radius + 1);
    for (uint32_t i = 0; i <= radius; ++i) weights[i] = static_cast<float>(raw[i] / total);
    return weights;
}

BlurPass::BlurPass(const PassConfig& config, BlurAxis axis, uint32_t radius, std::string name)
    : ShaderPass(std::move(name), config.library), axis_(axis), radius_(std::min(radius, kMaxBlurRadius)) {
    add_shader(fullscreen_part().shader);
    add(gaussian_blur_part(config));
}

Status BlurPass::set_radius(uint32_t radius) {
    if (radius > kMaxBlurRadius) {
        return make_error(ErrorCode::InvalidArgument, "blur pass '" + name() + "': radius " + std::to_string(radius) +
                                                          " is above the maximum of " + std::to_string(kMaxBlurRadius));
    }
    radius_ = radius;
    return {};
}

Status BlurPass::execute(fg::PassContext& context) {
    const std::string colors[] = {"color"};
    auto state = attachment_state(context, colors);
    if (!state) return state.take_error();
    auto nearest = nearest_sampler(context.device());
    if (!nearest) return nearest.take_error();

    detail::BlurUniforms uniforms{};
    uniforms.params[0] = static_cast<int32_t>(radius_);
    uniforms.params[1] = axis_ == BlurAxis::Horizontal ? 1 : 0;
    uniforms.params[2] = axis_ == BlurAxis::Vertical ? 1 : 0;
    const std::vector<float> weights = gaussian_weights(radius_);
    std::copy(weights.begin(), weights.end(), uniforms.weights);

    fg::ColorPort port("color");
    port.writes_every_texel = true;
    context.begin_render_pass({port});
    Status drawn = draw_fullscreen(context, *state, [&](Bindings& set) {
        set.uniforms("BlurUniforms", uniforms).texture("source", context.texture("previous_pass"), *nearest);
        return set.status();
    });
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::passes
