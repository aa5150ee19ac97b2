#include "uniforms.hpp"

namespace loom::passes {

CameraUniforms camera_uniforms(const scene::CameraMatrices& camera) {
    return CameraUniforms{camera.view_projection(), glm::vec4(camera.position, 1.0f)};
}

LightingUniforms lighting_uniforms(const SceneView& view) {
    LightingUniforms u;
    u.inverse_view_projection = glm::inverse(view.camera.view_projection());
    u.camera_position = glm::vec4(view.camera.position, 1.0f);
    u.light_direction = glm::vec4(glm::normalize(view.light.direction), 0.0f);
    u.light_radiance = glm::vec4(view.light.color * view.light.intensity, 0.0f);
    u.sky_radiance = glm::vec4(view.environment.sky, 0.0f);
    u.horizon_radiance = glm::vec4(view.environment.horizon, 0.0f);
    u.ground_radiance = glm::vec4(view.environment.ground, 0.0f);
    u.fog = glm::vec4(view.environment.fog_density, view.environment.fog_start, 0.0f, 0.0f);
    return u;
}

ShadowUniforms shadow_uniforms(const ShadowSettings& settings, uint32_t map_size) {
    return ShadowUniforms{settings.light_view_projection,
                          glm::vec4(1.0f / static_cast<float>(map_size == 0 ? 1 : map_size), settings.normal_offset,
                                    settings.depth_bias, static_cast<float>(settings.pcf_radius))};
}

rhi::SamplerDesc shadow_comparison_sampler_desc() {
    rhi::SamplerDesc desc;
    desc.name = "shadow comparison";
    desc.min_filter = rhi::Filter::Linear;
    desc.mag_filter = rhi::Filter::Linear;
    desc.max_lod = 0.0f;
    desc.compare = rhi::CompareOp::LessEqual;
    return desc;
}

namespace detail {

Status bind_shadow_receiver(Bindings& set, const ShadowSettings& settings, rhi::TextureHandle shadow_map,
                            uint32_t map_size, rhi::SamplerHandle comparison_sampler) {
    set.uniforms("ShadowUniforms", shadow_uniforms(settings, map_size)).texture("shadow_map", shadow_map, comparison_sampler);
    return set.status();
}

}  // namespace detail
}  // namespace loom::passes
