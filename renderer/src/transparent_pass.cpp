#include "loom/renderer/transparent_pass.hpp"

#include <algorithm>
#include <numeric>

#include "loom/passes/part_uniforms.hpp"
#include "loom/passes/parts.hpp"

namespace loom::renderer {
namespace {

/// The standard "shadow-render" code with this pass's ports: the shadow map in, and colour
/// in/out (the standard part's colour is an output: here the lit frame is blended onto).
passes::PassPart shadow_receiver_part(const passes::PassConfig& config) {
    passes::PassPart part = passes::shadow_render_part(config);
    part.ports = fg::PortSet(part.name());
    part.ports.input("shadow_map", fg::TextureSpec::of(rhi::Format::Depth32F)).inout("color", passes::color_spec(config));
    return part;
}

/// The standard "high-pass-render" code (blend-render writes its output with alpha) with the
/// high pass in/out.
passes::PassPart blended_high_pass_part(const passes::PassConfig& config) {
    passes::PassPart part = passes::high_pass_render_part(config);
    part.ports = fg::PortSet(part.name());
    part.ports.inout("high_pass", passes::color_spec(config));
    return part;
}

}  // namespace

TransparentPass::TransparentPass(const passes::PassConfig& config, passes::LightingParts parts, std::string name)
    : ShaderPass(std::move(name), config.library), parts_(parts) {
    add(passes::camera_part());
    if (parts_.shadows) add(shadow_receiver_part(config));
    // Before blend-render, whose main() writes the high-pass output this part declares.
    if (parts_.high_pass) add(blended_high_pass_part(config));
    add(passes::standard_part("blend-render", {.config = config}));  // in/out color and depth
}

Status TransparentPass::register_object(std::shared_ptr<const passes::Object> object, const scene::Bounds& world_bounds) {
    return register_object(std::move(object), [world_bounds] { return world_bounds; });
}

Status TransparentPass::register_object(std::shared_ptr<const passes::Object> object,
                                        std::function<scene::Bounds()> world_bounds) {
    if (!world_bounds) {
        return make_error(ErrorCode::InvalidArgument, "pass '" + name() + "': object '" +
                                                          (object ? object->name() : std::string("(none)")) +
                                                          "' has no function for its world bounds");
    }
    LOOM_TRY(ShaderPass::register_object(std::move(object)));
    bounds_.push_back(std::move(world_bounds));
    return {};
}

Status TransparentPass::register_object(std::shared_ptr<const passes::Object> object) {
    return make_error(ErrorCode::InvalidArgument,
                      "pass '" + name() + "': object '" + (object ? object->name() : std::string("(none)")) +
                          "' needs world bounds to be sorted by: use register_object(object, bounds)");
}

void TransparentPass::clear_objects() {
    ShaderPass::clear_objects();
    bounds_.clear();
    last_order_.clear();
}

std::vector<std::size_t> TransparentPass::sorted() const {
    std::vector<std::size_t> order(objects().size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    // View-space z grows towards the eye: the smallest is the farthest.
    const glm::mat4& view = view_.camera.view;
    std::vector<float> depths(order.size());
    for (std::size_t i = 0; i < depths.size(); ++i) {
        const scene::Bounds bounds = bounds_[i]();
        depths[i] = (view * glm::vec4((bounds.min + bounds.max) * 0.5f, 1.0f)).z;
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return depths[a] < depths[b]; });
    return order;
}

std::vector<std::string> TransparentPass::draw_order() const {
    std::vector<std::string> names;
    for (std::size_t i : last_order_) names.push_back(objects()[i]->name());
    return names;
}

Status TransparentPass::execute(fg::PassContext& context) {
    if (bounds_.size() != objects().size()) {
        return make_error(ErrorCode::InvalidState, "pass '" + name() + "': " + std::to_string(objects().size()) +
                                                       " objects but " + std::to_string(bounds_.size()) +
                                                       " bounds (objects cleared through ShaderPass)");
    }
    std::vector<std::string> colors{"color"};
    if (parts_.high_pass) colors.emplace_back("high_pass");
    auto state = attachment_state(context, colors, "depth");
    if (!state) return state.take_error();
    state->depth = rhi::DepthState{true, false, rhi::CompareOp::Less};
    state->blend.assign(colors.size(), rhi::BlendState::over());
    rhi::SamplerHandle comparison;
    if (parts_.shadows) {
        auto made = sampler(context.device(), passes::shadow_comparison_sampler_desc());
        if (!made) return made.take_error();
        comparison = *made;
    }
    auto bind_pass = [&](passes::Bindings& set) -> Status {
        set.uniforms("CameraUniforms", passes::camera_uniforms(view_.camera))
            .uniforms("LightingUniforms", passes::lighting_uniforms(view_));
        if (parts_.shadows) {
            set.uniforms("ShadowUniforms", passes::shadow_uniforms(view_.shadow, context.extent("shadow_map").width))
                .texture("shadow_map", context.texture("shadow_map"), comparison);
        }
        if (parts_.high_pass) set.uniforms("HighPassUniforms", passes::HighPassUniforms{glm::vec4(threshold_, 0, 0, 0)});
        return set.status();
    };

    last_order_ = sorted();
    std::vector<fg::ColorPort> ports(colors.begin(), colors.end());
    context.begin_render_pass(ports, fg::DepthPort("depth"));
    rhi::CommandList& commands = context.commands();
    Status drawn;
    rhi::PipelineHandle bound;
    for (std::size_t index : last_order_) {
        const passes::Object& object = *objects()[index];
        const passes::Program* program = program_for(object);
        if (!program) {
            drawn = make_error(ErrorCode::InvalidState, "pass '" + name() + "': object '" + object.name() + "' has no program");
            break;
        }
        passes::PipelineState object_state = *state;
        const rhi::RasterState raster = object.raster();
        object_state.raster.cull = raster.cull;
        object_state.raster.front_face = raster.front_face;
        auto handle = pipeline(context.device(), *program, object_state, object.kind().get());
        if (!handle) {
            drawn = handle.take_error();
            break;
        }
        if (*handle != bound) {
            commands.set_pipeline(*handle);
            bound = *handle;
            passes::Bindings pass_set(*program, commands, passes::kPassSet);
            drawn = bind_pass(pass_set);
            if (drawn) drawn = pass_set.bind();
            if (!drawn) break;
        }
        passes::DrawContext draw{commands, *program};
        drawn = render_with(draw, object);
        if (!drawn) break;
    }
    context.end_render_pass();
    LOOM_TRY(drawn);
    return record_capture(context);
}

}  // namespace loom::renderer
