#include "engine_frame.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>
#include <tuple>

#include "loom/framegraph/resolved_spec.hpp"
#include "loom/rhi/format.hpp"
#include "loom/scene/glm.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include "loom/scene/mesh.hpp"
#include "loom/shader_compiler/shader_compiler.hpp"
#include "loom_engine_shaders.hpp"

namespace loom::engine {
namespace {

using rhi::ResourceState;

/// Mirrors the Frame block of shaders/engine/frame.glsl (std140).
struct FrameUniforms {
    glm::mat4 view;
    glm::mat4 projection;
    glm::mat4 view_projection;
    glm::mat4 inverse_projection;
    glm::mat4 inverse_view_projection;
    std::array<glm::mat4, kCascades> cascade_view_projection;
    glm::vec4 cascade_far;
    glm::vec4 cascade_texel;
    glm::vec4 camera_position;
    glm::vec4 sun_direction;
    glm::vec4 sun_color;
    glm::vec4 sky_zenith;
    glm::vec4 sky_horizon;
    glm::vec4 ground_color;
    glm::vec4 screen;
    glm::uvec4 tiles;
    glm::vec4 lighting;
    glm::vec4 post;
};
static_assert(sizeof(FrameUniforms) == 9 * 64 + 12 * 16);

/// Mirrors the Draw block of shaders/engine/draw.glsl (std140).
struct DrawUniforms {
    glm::mat4 model;
    glm::mat4 normal_matrix;
    glm::vec4 base_color;
    glm::vec4 emissive;
    glm::vec4 factors;
    glm::vec4 alpha;
    glm::ivec4 uv_sets;
    glm::ivec4 textures;
};
static_assert(sizeof(DrawUniforms) == 224);

/// Push constants of shadow.vert.
struct CasterConstants {
    glm::mat4 model;
    glm::ivec4 cascade;
};

/// Tuning of the frame (see FrameUniforms::lighting and ::post).
constexpr float kAmbient = 0.3f;
constexpr float kSsaoRadius = 0.9f;
constexpr float kSsaoStrength = 4.0f;
constexpr float kBloomThreshold = 1.1f;
constexpr float kBloomStrength = 0.2f;
constexpr float kExposure = 0.75f;
/// How the cascades split the view distance between the scene's shadow_start and shadow_end
/// (the practical split scheme: this much logarithmic, the rest uniform).
constexpr float kSplitLambda = 0.6f;

uint32_t groups(uint32_t size) { return (size + 7) / 8; }

std::string level_port(const char* base, uint32_t level) { return std::string(base) + "_" + std::to_string(level); }

}  // namespace

struct EngineFrame::Programs {
    struct RasterKey {
        rhi::CullMode cull;
        rhi::FrontFace front;
        bool operator<(const RasterKey& o) const { return std::tie(cull, front) < std::tie(o.cull, o.front); }
    };
    std::map<std::string, rhi::ShaderHandle> shaders;
    std::map<RasterKey, rhi::PipelineHandle> prepass;
    std::map<RasterKey, rhi::PipelineHandle> shade;
    rhi::PipelineHandle sky, shadow, tonemap;
    rhi::PipelineHandle hzb_copy, hzb_reduce, light_cull, ssao, ssao_blur, bloom_prefilter, bloom_down, bloom_up;
    rhi::SamplerHandle nearest, linear;
};

EngineFrame::EngineFrame(rhi::Device& device, const EngineScene& scene, FrameSettings settings)
    : device_(&device), scene_(scene), settings_(std::move(settings)), programs_(std::make_unique<Programs>()), executor_(device) {}

EngineFrame::~EngineFrame() {
    // The executor's textures go first (it is destroyed after this body), then everything made here.
    (void)device_->wait_idle();
    for (const Intermediate& captured : captures_) (void)device_->destroy(captured.texture);
    if (light_list_capture_) (void)device_->destroy(light_list_capture_);
    for (const auto& [key, pipeline] : programs_->prepass) (void)device_->destroy(pipeline);
    for (const auto& [key, pipeline] : programs_->shade) (void)device_->destroy(pipeline);
    for (rhi::PipelineHandle pipeline : {programs_->sky, programs_->shadow, programs_->tonemap, programs_->hzb_copy,
                                         programs_->hzb_reduce, programs_->light_cull, programs_->ssao, programs_->ssao_blur,
                                         programs_->bloom_prefilter, programs_->bloom_down, programs_->bloom_up}) {
        if (pipeline) (void)device_->destroy(pipeline);
    }
    for (const auto& [name, shader] : programs_->shaders) (void)device_->destroy(shader);
    if (programs_->nearest) (void)device_->destroy(programs_->nearest);
    if (programs_->linear) (void)device_->destroy(programs_->linear);
    if (lights_) (void)device_->destroy(lights_);
    if (draws_) (void)device_->destroy(draws_);
}

Result<std::unique_ptr<EngineFrame>> EngineFrame::create(rhi::Device& device, const EngineScene& scene, FrameSettings settings) {
    if (settings.shadow_size == 0 || settings.shadow_size > device.capabilities().max_texture_size) {
        return make_error(ErrorCode::InvalidArgument, "shadow size " + std::to_string(settings.shadow_size) +
                                                          " is out of range (1.." +
                                                          std::to_string(device.capabilities().max_texture_size) + ")");
    }
    std::unique_ptr<EngineFrame> frame(new EngineFrame(device, scene, std::move(settings)));
    LOOM_TRY(frame->upload());
    LOOM_TRY(frame->create_programs());
    LOOM_TRY(frame->build_graph());
    return frame;
}

fg::Extent2D EngineFrame::tile_count(fg::Extent2D size) {
    return {(size.width + kTileSize - 1) / kTileSize, (size.height + kTileSize - 1) / kTileSize};
}

fg::PlanOptions EngineFrame::plan_options(fg::Extent2D size) const {
    fg::PlanOptions options;
    options.frame = size;
    options.allocator = settings_.allocator;
    options.order = settings_.order;
    return options;
}

Status EngineFrame::upload() {
    auto gpu = renderer::GpuScene::create(*device_, scene_.prepared);
    if (!gpu) return gpu.take_error();
    gpu_ = std::move(*gpu);

    const std::span<const std::byte> light_bytes = std::as_bytes(std::span(scene_.lights));
    auto lights = device_->create_buffer({"engine lights", light_bytes.size(), rhi::BufferUsage::Storage});
    if (!lights) return lights.take_error();
    lights_ = *lights;
    LOOM_TRY(device_->write_buffer(lights_, 0, light_bytes));

    // Every draw item's uniforms, once: the scene does not move, the camera is in the frame's.
    const uint64_t alignment = std::max<uint64_t>(device_->capabilities().uniform_buffer_offset_alignment, 16);
    draw_stride_ = (sizeof(DrawUniforms) + alignment - 1) / alignment * alignment;
    const scene::Scene& scene = scene_.prepared->scene;
    std::vector<std::byte> bytes(std::max<std::size_t>(scene.draw_items.size(), 1) * draw_stride_);
    for (std::size_t i = 0; i < scene.draw_items.size(); ++i) {
        const scene::DrawItem& item = scene.draw_items[i];
        const scene::Material& m = scene.materials[item.material];
        DrawUniforms u{};
        u.model = item.world;
        u.normal_matrix = glm::mat4(item.normal_matrix);
        u.base_color = m.base_color_factor;
        u.emissive = glm::vec4(m.emissive_factor, 0.0f);
        u.factors = glm::vec4(m.metallic_factor, m.roughness_factor, m.normal_scale, m.occlusion_strength);
        u.alpha = glm::vec4(m.alpha_mode == scene::AlphaMode::Mask ? 1.0f : 0.0f, m.alpha_cutoff, 0.0f, 0.0f);
        const std::array<const std::optional<scene::TextureRef>*, 5> refs = {
            &m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture, &m.emissive_texture};
        std::array<int, 5> uv_sets{};
        int present = 0;
        for (std::size_t t = 0; t < refs.size(); ++t) {
            if (!refs[t]->has_value()) continue;
            present |= 1 << t;
            uv_sets[t] = static_cast<int>((*refs[t])->uv_set);
        }
        u.uv_sets = glm::ivec4(uv_sets[0], uv_sets[1], uv_sets[2], uv_sets[3]);
        u.textures = glm::ivec4(uv_sets[4], present, 0, 0);
        std::memcpy(bytes.data() + i * draw_stride_, &u, sizeof(u));
    }
    auto draws = device_->create_buffer({"engine draw uniforms", bytes.size(), rhi::BufferUsage::Uniform});
    if (!draws) return draws.take_error();
    draws_ = *draws;
    return device_->write_buffer(draws_, 0, bytes);
}

Status EngineFrame::create_programs() {
    Programs& p = *programs_;
    auto shader = [&](const std::string& name) -> Result<rhi::ShaderHandle> {
        if (auto it = p.shaders.find(name); it != p.shaders.end()) return it->second;
        for (const auto& embedded : embedded::embedded_shaders()) {
            if (embedded.name != name) continue;
            auto module = shader_compiler::ShaderCompiler::from_spirv(name, embedded.stage, embedded.spirv);
            if (!module) return module.take_error();
            auto handle = device_->create_shader(*module);
            if (!handle) return handle.take_error();
            p.shaders.emplace(name, *handle);
            return *handle;
        }
        return make_error(ErrorCode::InvalidArgument, "loom-engine: no embedded shader '" + name + "'");
    };
    auto compute = [&](const std::string& name, rhi::PipelineHandle& out) -> Status {
        auto module = shader(name);
        if (!module) return module.take_error();
        auto pipeline = device_->create_compute_pipeline({name, *module});
        if (!pipeline) return pipeline.take_error();
        out = *pipeline;
        return {};
    };
    auto graphics = [&](const std::string& name, const std::string& vertex, const std::string& fragment,
                        std::vector<rhi::VertexBufferLayout> layouts, rhi::RasterState raster, rhi::DepthState depth,
                        std::vector<rhi::Format> colors, rhi::Format depth_format) -> Result<rhi::PipelineHandle> {
        auto vs = shader(vertex);
        if (!vs) return vs.take_error();
        auto fs = shader(fragment);
        if (!fs) return fs.take_error();
        rhi::GraphicsPipelineDesc desc;
        desc.name = name;
        desc.vertex = *vs;
        desc.fragment = *fs;
        desc.vertex_buffers = std::move(layouts);
        desc.raster = raster;
        desc.depth = depth;
        desc.color_formats = std::move(colors);
        desc.depth_format = depth_format;
        return device_->create_graphics_pipeline(desc);
    };

    rhi::SamplerDesc point;
    point.name = "engine nearest";
    point.min_filter = rhi::Filter::Nearest;
    point.mag_filter = rhi::Filter::Nearest;
    auto nearest = device_->create_sampler(point);
    if (!nearest) return nearest.take_error();
    p.nearest = *nearest;
    rhi::SamplerDesc bilinear;
    bilinear.name = "engine linear";
    auto linear = device_->create_sampler(bilinear);
    if (!linear) return linear.take_error();
    p.linear = *linear;

    const std::vector<rhi::VertexBufferLayout> scene_layout{scene::vertex_buffer_layout()};
    // The prepass reads what it needs of the same vertices: position, UVs and colour.
    rhi::VertexBufferLayout prepass_vertices = scene::vertex_buffer_layout();
    std::erase_if(prepass_vertices.attributes, [](const rhi::VertexAttribute& a) {
        return a.location == scene::vertex_location::kNormal || a.location == scene::vertex_location::kTangent;
    });
    const std::vector<rhi::VertexBufferLayout> prepass_layout{prepass_vertices};
    for (rhi::CullMode cull : {rhi::CullMode::Back, rhi::CullMode::None}) {
        for (rhi::FrontFace front : {rhi::FrontFace::CounterClockwise, rhi::FrontFace::Clockwise}) {
            rhi::RasterState raster;
            raster.cull = cull;
            raster.front_face = front;
            auto prepass = graphics("depth prepass", "prepass.vert", "prepass.frag", prepass_layout, raster,
                                    {.test = true, .write = true, .compare = rhi::CompareOp::Less}, {}, rhi::Format::Depth32F);
            if (!prepass) return prepass.take_error();
            p.prepass[{cull, front}] = *prepass;
            auto shade = graphics("shade", "scene.vert", "shade.frag", scene_layout, raster,
                                  {.test = true, .write = false, .compare = rhi::CompareOp::Equal}, {rhi::Format::RGBA16Float},
                                  rhi::Format::Depth32F);
            if (!shade) return shade.take_error();
            p.shade[{cull, front}] = *shade;
        }
    }
    auto sky = graphics("sky", "sky.vert", "sky.frag", {}, {}, {.test = true, .write = false, .compare = rhi::CompareOp::Equal},
                        {rhi::Format::RGBA16Float}, rhi::Format::Depth32F);
    if (!sky) return sky.take_error();
    p.sky = *sky;
    // Shadow casters read only the position of the scene's vertices.
    rhi::VertexBufferLayout positions{static_cast<uint32_t>(sizeof(scene::Vertex)), rhi::VertexStepMode::PerVertex,
                                      {{scene::vertex_location::kPosition, rhi::VertexFormat::Float3, 0}}};
    auto shadow = graphics("shadow cascade", "shadow.vert", "depth_only.frag", {positions}, {},
                           {.test = true, .write = true, .compare = rhi::CompareOp::Less}, {}, rhi::Format::Depth32F);
    if (!shadow) return shadow.take_error();
    p.shadow = *shadow;
    auto tonemap = graphics("tonemap", "fullscreen.vert", "tonemap.frag", {}, {}, {}, {settings_.target_format}, rhi::Format::Undefined);
    if (!tonemap) return tonemap.take_error();
    p.tonemap = *tonemap;
    LOOM_TRY(compute("hzb_copy.comp", p.hzb_copy));
    LOOM_TRY(compute("hzb_reduce.comp", p.hzb_reduce));
    LOOM_TRY(compute("light_cull.comp", p.light_cull));
    LOOM_TRY(compute("ssao.comp", p.ssao));
    LOOM_TRY(compute("ssao_blur.comp", p.ssao_blur));
    LOOM_TRY(compute("bloom_prefilter.comp", p.bloom_prefilter));
    LOOM_TRY(compute("bloom_down.comp", p.bloom_down));
    LOOM_TRY(compute("bloom_up.comp", p.bloom_up));
    return {};
}

scene::CameraMatrices EngineFrame::camera(fg::Extent2D size) const {
    scene::CameraMatrices out;
    out.view = glm::lookAt(scene_.eye, scene_.target, glm::vec3(0.0f, 1.0f, 0.0f));
    out.projection = glm::perspective(scene_.yfov, static_cast<float>(size.width) / static_cast<float>(std::max(size.height, 1u)),
                                      scene_.znear, scene_.zfar);
    out.position = scene_.eye;
    return out;
}

Status EngineFrame::prepare_frame(fg::Extent2D size) {
    if (size.width < kMinFrameSide || size.height < kMinFrameSide) {
        return make_error(ErrorCode::InvalidArgument, "loom-engine: a " + std::to_string(size.width) + "x" +
                                                          std::to_string(size.height) + " frame is too small (at least " +
                                                          std::to_string(kMinFrameSide) + "x" + std::to_string(kMinFrameSide) +
                                                          ", so that every level of the Z and bloom pyramids has a texel)");
    }
    const float aspect = static_cast<float>(size.width) / static_cast<float>(size.height);
    FrameUniforms u{};
    const scene::CameraMatrices matrices = camera(size);
    u.view = matrices.view;
    u.projection = matrices.projection;
    u.view_projection = u.projection * u.view;
    u.inverse_projection = glm::inverse(u.projection);
    u.inverse_view_projection = glm::inverse(u.view_projection);

    // Cascades: the view distance up to kShadowDistance split between a logarithmic and a
    // uniform split; each cascade an orthographic view along the sun around the bounding sphere
    // of its slice of the view frustum, deep enough to hold every caster of the scene.
    const glm::mat4 inverse_view = glm::inverse(u.view);
    const float tan_y = std::tan(scene_.yfov * 0.5f);
    const float tan_x = tan_y * aspect;
    const float start = std::clamp(scene_.shadow_start, scene_.znear, scene_.zfar);
    const float reach = std::clamp(scene_.shadow_end, start, scene_.zfar);
    const scene::Bounds& bounds = scene_.prepared->scene.bounds;
    const float scene_radius = glm::length(bounds.size()) * 0.5f;
    float slice_near = start;
    for (uint32_t i = 0; i < kCascades; ++i) {
        const float t = static_cast<float>(i + 1) / kCascades;
        const float log_split = start * std::pow(reach / start, t);
        const float uniform_split = start + (reach - start) * t;
        const float slice_far = kSplitLambda * log_split + (1.0f - kSplitLambda) * uniform_split;
        glm::vec3 centre(0.0f);
        std::array<glm::vec3, 8> corners;
        for (int c = 0; c < 8; ++c) {
            const float z = (c & 4) ? slice_far : slice_near;
            const glm::vec4 view_point((c & 1 ? 1.0f : -1.0f) * tan_x * z, (c & 2 ? 1.0f : -1.0f) * tan_y * z, -z, 1.0f);
            corners[c] = glm::vec3(inverse_view * view_point);
            centre += corners[c] / 8.0f;
        }
        float radius = 0.0f;
        for (const glm::vec3& corner : corners) radius = std::max(radius, glm::length(corner - centre));
        radius = std::ceil(radius * 16.0f) / 16.0f;
        const glm::vec3 up = std::abs(scene_.towards_sun.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const float depth = radius + 2.0f * scene_radius;
        const glm::mat4 light_view = glm::lookAt(centre + scene_.towards_sun * depth, centre, up);
        const glm::mat4 light_projection = glm::ortho(-radius, radius, -radius, radius, 0.0f, depth + radius);
        u.cascade_view_projection[i] = light_projection * light_view;
        u.cascade_far[static_cast<int>(i)] = slice_far;
        u.cascade_texel[static_cast<int>(i)] = 2.0f * radius / static_cast<float>(settings_.shadow_size);
        slice_near = slice_far;
    }
    u.camera_position = glm::vec4(scene_.eye, 1.0f);
    u.sun_direction = glm::vec4(scene_.towards_sun, 0.0f);
    u.sun_color = glm::vec4(scene_.sun_color, 0.0f);
    u.sky_zenith = glm::vec4(scene_.sky_zenith, 0.0f);
    u.sky_horizon = glm::vec4(scene_.sky_horizon, 0.0f);
    u.ground_color = glm::vec4(scene_.ground_color, 0.0f);
    u.screen = glm::vec4(static_cast<float>(size.width), static_cast<float>(size.height), 1.0f / static_cast<float>(size.width),
                         1.0f / static_cast<float>(size.height));
    const fg::Extent2D tiles = tile_count(size);
    u.tiles = glm::uvec4(tiles.width, tiles.height, static_cast<uint32_t>(scene_.lights.size()), 0u);
    u.lighting = glm::vec4(kAmbient, kSsaoRadius, kSsaoStrength, 0.0f);
    u.post = glm::vec4(kBloomThreshold, kBloomStrength, kExposure,
                       rhi::format_info(settings_.target_format).features.srgb ? 0.0f : 1.0f);
    frame_uniforms_.resize(sizeof(u));
    std::memcpy(frame_uniforms_.data(), &u, sizeof(u));
    return {};
}

Status EngineFrame::render(fg::Extent2D size) {
    LOOM_TRY(prepare_frame(size));
    return executor_.run_frame(graph_, plan_options(size));
}

Status EngineFrame::record(rhi::CommandList& commands, rhi::TextureHandle target, fg::Extent2D size,
                           rhi::ResourceState final_state) {
    LOOM_TRY(prepare_frame(size));
    executor_.import_texture(fg::port("tonemap", "final"), target, final_state);
    return executor_.execute(graph_, commands, plan_options(size));
}

Status EngineFrame::replan(fg::AllocatorKind allocator, bool async_compute) {
    if (allocator == fg::AllocatorKind::Paper && async_compute) {
        return make_error(ErrorCode::InvalidArgument,
                          "the paper allocator refuses async compute passes: switch async compute off first");
    }
    settings_.allocator = allocator;
    if (async_compute == settings_.async_compute) return {};
    // The passes' queues are fixed when they are added: a new graph, the same programs.
    settings_.async_compute = async_compute;
    graph_ = fg::FrameGraph();
    return build_graph();
}

rhi::TextureHandle EngineFrame::final_texture() {
    for (const Intermediate& captured : captures_) {
        if (captured.name == "final") return captured.texture;
    }
    return executor_.texture("tonemap", "final");
}

Status EngineFrame::capture(fg::PassContext& ctx, const std::string& port, const std::string& name, rhi::ResourceState state) {
    if (!settings_.capture) return {};
    const fg::ResolvedSpec* spec = ctx.spec(port);
    const rhi::TextureHandle source = ctx.texture(port);
    if (spec == nullptr || !source) {
        return make_error(ErrorCode::InvalidState, "pass '" + ctx.pass_name() + "': port '" + port + "' has no texture to capture");
    }
    rhi::TextureDesc desc = fg::to_texture_desc(*spec, name + " (capture)");
    desc.usage = rhi::TextureUsage::CopyDst | rhi::TextureUsage::CopySrc;
    auto entry = std::find_if(captures_.begin(), captures_.end(), [&](const Intermediate& c) { return c.name == name; });
    if (entry != captures_.end() && (entry->width != desc.width || entry->height != desc.height || entry->format != desc.format)) {
        (void)device_->destroy(entry->texture);
        captures_.erase(entry);
        entry = captures_.end();
    }
    if (entry == captures_.end()) {
        auto texture = device_->create_texture(desc);
        if (!texture) return texture.take_error();
        captures_.push_back({name, *texture, desc.format, desc.width, desc.height, desc.mip_levels, desc.depth_or_layers});
        entry = captures_.end() - 1;
    }
    const rhi::TextureRange range = ctx.range(port);
    for (uint32_t mip = range.base_mip; mip < range.base_mip + range.mip_count; ++mip) {
        for (uint32_t layer = range.base_layer; layer < range.base_layer + range.layer_count; ++layer) {
            rhi::TextureCopy copy;
            copy.src = source;
            copy.src_region.mip = mip;
            copy.src_region.layer = layer;
            copy.dst = entry->texture;
            copy.dst_region.mip = mip;
            copy.dst_region.layer = layer;
            ctx.commands().copy_texture(copy);
        }
    }
    // The copy left the source in CopySrc: back to the state the pass left it in, which is the
    // state the executor planned from.
    ctx.commands().transition(source, state, range);
    return {};
}

Status EngineFrame::capture_buffer(fg::PassContext& ctx, const std::string& port) {
    if (!settings_.capture) return {};
    const rhi::BufferHandle source = ctx.buffer(port);
    const uint64_t size = ctx.buffer_size(port);
    if (light_list_capture_ && light_list_capture_bytes_ != size) {
        (void)device_->destroy(light_list_capture_);
        light_list_capture_ = {};
    }
    if (!light_list_capture_) {
        auto buffer = device_->create_buffer({"light list (capture)", size, rhi::BufferUsage::CopyDst | rhi::BufferUsage::CopySrc});
        if (!buffer) return buffer.take_error();
        light_list_capture_ = *buffer;
        light_list_capture_bytes_ = size;
    }
    ctx.commands().copy_buffer(source, 0, light_list_capture_, 0, size);
    ctx.commands().transition(source, rhi::ResourceState::Storage);
    return {};
}

Status EngineFrame::draw_scene(fg::PassContext& ctx, bool shading) {
    rhi::CommandList& cmd = ctx.commands();
    const scene::Scene& scene = scene_.prepared->scene;
    if (!gpu_->vertex_buffer()) return {};
    cmd.set_vertex_buffer(0, gpu_->vertex_buffer());
    cmd.set_index_buffer(gpu_->index_buffer(), rhi::IndexType::Uint32);
    rhi::PipelineHandle bound;
    for (std::size_t i = 0; i < scene.draw_items.size(); ++i) {
        const scene::DrawItem& item = scene.draw_items[i];
        const scene::Material& m = scene.materials[item.material];
        const scene::PrimitiveRange& range = scene_.prepared->geometry.range(item);
        if (range.index_count == 0) continue;
        const Programs::RasterKey key{m.double_sided ? rhi::CullMode::None : rhi::CullMode::Back,
                                      item.flips_winding ? rhi::FrontFace::Clockwise : rhi::FrontFace::CounterClockwise};
        const rhi::PipelineHandle pipeline = shading ? programs_->shade.at(key) : programs_->prepass.at(key);
        if (pipeline != bound) {
            cmd.set_pipeline(pipeline);
            bound = pipeline;
        }
        auto texture = [&](const std::optional<scene::TextureRef>& ref) {
            return ref ? gpu_->texture(ref->texture) : gpu_->fallback();
        };
        rhi::BindGroup set;
        set.buffer(0, draws_, i * draw_stride_, sizeof(DrawUniforms));
        const rhi::TextureBinding base = texture(m.base_color_texture);
        set.texture(1, base.texture, base.sampler);
        if (shading) {
            int binding = 2;
            for (const auto* ref : {&m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture, &m.emissive_texture}) {
                const rhi::TextureBinding t = texture(*ref);
                set.texture(binding++, t.texture, t.sampler);
            }
        }
        cmd.set_bind_group(1, set);
        cmd.draw_indexed(range.index_count, 1, range.first_index, range.base_vertex);
    }
    return {};
}

Status EngineFrame::build_graph() {
    using fg::Pass;
    using fg::TextureSpec;
    const rhi::TextureUsage copy = settings_.capture ? rhi::TextureUsage::CopySrc : rhi::TextureUsage::None;
    const fg::Queue async = settings_.async_compute ? fg::Queue::AsyncCompute : fg::Queue::Graphics;
    Programs& p = *programs_;
    auto frame_set = [this](fg::PassContext& ctx) {
        return rhi::BindGroup{}.buffer(0, ctx.commands().transient_uniforms(std::as_bytes(std::span(frame_uniforms_))));
    };
    // The graph is fixed, so an error here is loom-engine's bug; the first one is returned.
    Status status;
    auto keep_first = [&status](Status step) {
        if (status.ok() && !step.ok()) status = std::move(step);
    };
    auto add = [&](Pass pass) {
        auto added = graph_.add_pass(std::move(pass));
        if (!added) keep_first(added.take_error());
    };
    auto connect = [&](const std::string& from_pass, const std::string& from_port, const std::string& to_pass,
                       const std::string& to_port) { keep_first(graph_.connect(fg::port(from_pass, from_port), fg::port(to_pass, to_port))); };

    // Depth prepass: the depth of everything, so that later passes shade each pixel once.
    add(Pass("depth_prepass").output("depth", TextureSpec::of(rhi::Format::Depth32F).with_usage(copy)).on_execute(
        [this, frame_set](fg::PassContext& ctx) -> Status {
            ctx.begin_depth_pass(fg::DepthPort("depth", 1.0f));
            ctx.commands().set_bind_group(0, frame_set(ctx));
            Status drawn = draw_scene(ctx, false);
            ctx.end_render_pass();
            LOOM_TRY(drawn);
            return capture(ctx, "depth", "depth", ResourceState::DepthWrite);
        }));

    // SSAO and its blur on the async compute queue: they need only the depth, and run beside
    // the hierarchical Z, the light list and the shadow cascades.
    add(Pass("ssao").set_kind(fg::PassKind::Compute).set_queue(async).input("depth")
            .output("occlusion", TextureSpec::of(rhi::Format::R8Unorm).with_usage(copy))
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                const fg::Extent2D size = ctx.extent("occlusion");
                ctx.commands().set_pipeline(p.ssao);
                ctx.commands().set_bind_group(0, frame_set(ctx)
                                                     .texture(1, ctx.texture("depth"), p.nearest)
                                                     .storage_texture(2, ctx.texture("occlusion")));
                ctx.commands().dispatch(groups(size.width), groups(size.height));
                return capture(ctx, "occlusion", "ssao_raw", ResourceState::Storage);
            }));
    add(Pass("ssao_blur").set_kind(fg::PassKind::Compute).set_queue(async).input("depth").input("raw")
            .output("occlusion", TextureSpec::of(rhi::Format::R8Unorm).with_usage(copy))
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                const fg::Extent2D size = ctx.extent("occlusion");
                ctx.commands().set_pipeline(p.ssao_blur);
                ctx.commands().set_bind_group(0, frame_set(ctx)
                                                     .texture(1, ctx.texture("depth"), p.nearest)
                                                     .texture(2, ctx.texture("raw"), p.nearest)
                                                     .storage_texture(3, ctx.texture("occlusion")));
                ctx.commands().dispatch(groups(size.width), groups(size.height));
                return capture(ctx, "occlusion", "ssao", ResourceState::Storage);
            }));
    connect("depth_prepass", "depth", "ssao", "depth");
    connect("depth_prepass", "depth", "ssao_blur", "depth");
    connect("ssao", "occlusion", "ssao_blur", "raw");

    // Hierarchical Z, level by level: (nearest, farthest) depth pairs down to one texel per tile.
    const TextureSpec hzb_spec = TextureSpec::of(rhi::Format::RG32Float).with_mips(kHzbLevels).with_usage(copy);
    add(Pass("hzb_0").set_kind(fg::PassKind::Compute).input("depth").output("hzb", hzb_spec, fg::mip(0))
            .on_execute([this, &p](fg::PassContext& ctx) -> Status {
                const fg::Extent2D size = ctx.range_extent("hzb");
                ctx.commands().set_pipeline(p.hzb_copy);
                ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                     .texture(0, ctx.texture("depth"), p.nearest)
                                                     .storage_texture(1, ctx.texture("hzb"), 0));
                ctx.commands().dispatch(groups(size.width), groups(size.height));
                return capture(ctx, "hzb", "hzb", ResourceState::Storage);
            }));
    connect("depth_prepass", "depth", "hzb_0", "depth");
    for (uint32_t level = 1; level < kHzbLevels; ++level) {
        const std::string name = level_port("hzb", level);
        add(Pass(name).set_kind(fg::PassKind::Compute).input("finer", {}, fg::mip(level - 1)).inout("hzb", {}, fg::mip(level))
                .on_execute([this, &p, level](fg::PassContext& ctx) -> Status {
                    const fg::Extent2D size = ctx.range_extent("hzb");
                    ctx.commands().set_pipeline(p.hzb_reduce);
                    ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                         .texture(0, ctx.texture("finer"), p.nearest, ctx.range("finer"))
                                                         .storage_texture(1, ctx.texture("hzb"), level));
                    ctx.commands().dispatch(groups(size.width), groups(size.height));
                    return capture(ctx, "hzb", "hzb", ResourceState::Storage);
                }));
        const std::string previous = level_port("hzb", level - 1);
        connect(previous, "hzb", name, "finer");
        connect(previous, "hzb", name, "hzb");
    }

    // The light list: per 16x16 tile, the point lights that reach its depth range.
    fg::BufferSpec list_spec = fg::BufferSpec::sized(fg::BufferSize::per_tile(kTileSize, kTileSize, kTileStride * 4))
                                   .with_usage(rhi::BufferUsage::Storage);
    if (settings_.capture) list_spec = list_spec.with_usage(rhi::BufferUsage::CopySrc);
    add(Pass("light_cull").set_kind(fg::PassKind::Compute).input("hzb", {}, fg::mip(kHzbLevels - 1))
            .buffer_output("light_list", list_spec)
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                const fg::Extent2D tiles = tile_count(ctx.frame_size());
                ctx.commands().set_pipeline(p.light_cull);
                ctx.commands().set_bind_group(0, frame_set(ctx)
                                                     .texture(1, ctx.texture("hzb"), p.nearest, ctx.range("hzb"))
                                                     .buffer(2, lights_)
                                                     .buffer(3, ctx.buffer("light_list")));
                ctx.commands().dispatch(groups(tiles.width), groups(tiles.height));
                return capture_buffer(ctx, "light_list");
            }));
    connect(level_port("hzb", kHzbLevels - 1), "hzb", "light_cull", "hzb");

    // Shadow cascades: one layer of one array texture each.
    const TextureSpec cascade_spec = TextureSpec::of(rhi::Format::Depth32F)
                                         .with_size(settings_.shadow_size, settings_.shadow_size)
                                         .with_layers(kCascades)
                                         .with_usage(copy);
    for (uint32_t cascade = 0; cascade < kCascades; ++cascade) {
        const std::string name = level_port("shadow_cascade", cascade);
        Pass pass(name);
        if (cascade == 0) {
            pass.output("cascades", cascade_spec, fg::layer(0));
        } else {
            pass.inout("cascades", {}, fg::layer(cascade));
        }
        pass.on_execute([this, &p, frame_set, cascade](fg::PassContext& ctx) -> Status {
            // Each cascade clears its own layer: the layers written before hold other cascades,
            // and the plan's Load for an in-place port would otherwise keep undefined texels.
            rhi::RenderPassDesc desc = ctx.render_pass({}, fg::DepthPort("cascades", 1.0f));
            desc.depth->depth_load = rhi::LoadOp::Clear;
            desc.depth->clear_depth = 1.0f;
            rhi::CommandList& cmd = ctx.commands();
            cmd.begin_render_pass(desc);
            cmd.set_pipeline(p.shadow);
            cmd.set_bind_group(0, frame_set(ctx));
            const scene::Scene& scene = scene_.prepared->scene;
            if (gpu_->vertex_buffer()) {
                cmd.set_vertex_buffer(0, gpu_->vertex_buffer());
                cmd.set_index_buffer(gpu_->index_buffer(), rhi::IndexType::Uint32);
                for (const scene::DrawItem& item : scene.draw_items) {
                    const scene::PrimitiveRange& range = scene_.prepared->geometry.range(item);
                    if (range.index_count == 0) continue;
                    cmd.push_constants_of(CasterConstants{item.world, glm::ivec4(static_cast<int>(cascade), 0, 0, 0)});
                    cmd.draw_indexed(range.index_count, 1, range.first_index, range.base_vertex);
                }
            }
            cmd.end_render_pass();
            return capture(ctx, "cascades", "shadow_cascades", ResourceState::DepthWrite);
        });
        add(std::move(pass));
        if (cascade > 0) connect(level_port("shadow_cascade", cascade - 1), "cascades", name, "cascades");
    }

    // Shading: forward+ on the prepass depth, then the sky where nothing was drawn.
    add(Pass("shade").inout("depth").input("cascades").input("occlusion").buffer_input("light_list")
            .output("hdr", TextureSpec::of(rhi::Format::RGBA16Float).with_usage(copy))
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                ctx.begin_render_pass({"hdr"}, fg::DepthPort("depth"));
                rhi::CommandList& cmd = ctx.commands();
                const rhi::BindGroup frame = frame_set(ctx);
                cmd.set_bind_group(0, rhi::BindGroup(frame)
                                          .texture(1, ctx.texture("cascades"), p.nearest)
                                          .texture(2, ctx.texture("occlusion"), p.nearest)
                                          .buffer(3, lights_)
                                          .buffer(4, ctx.buffer("light_list")));
                Status drawn = draw_scene(ctx, true);
                cmd.set_pipeline(p.sky);
                cmd.set_bind_group(0, frame);
                cmd.draw(3);
                ctx.end_render_pass();
                LOOM_TRY(drawn);
                return capture(ctx, "hdr", "hdr", ResourceState::RenderTarget);
            }));
    connect("depth_prepass", "depth", "shade", "depth");
    connect(level_port("shadow_cascade", kCascades - 1), "cascades", "shade", "cascades");
    connect("ssao_blur", "occlusion", "shade", "occlusion");
    connect("light_cull", "light_list", "shade", "light_list");

    // Bloom: a half-size pyramid down from the bright parts, then back up level by level.
    const TextureSpec bloom_spec = TextureSpec::of(rhi::Format::RGBA16Float).with_scale(0.5f).with_mips(kBloomLevels).with_usage(copy);
    add(Pass("bloom_prefilter").set_kind(fg::PassKind::Compute).input("hdr").output("bloom", bloom_spec, fg::mip(0))
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                const fg::Extent2D size = ctx.range_extent("bloom");
                ctx.commands().set_pipeline(p.bloom_prefilter);
                ctx.commands().set_bind_group(0, frame_set(ctx)
                                                     .texture(1, ctx.texture("hdr"), p.linear)
                                                     .storage_texture(2, ctx.texture("bloom"), 0));
                ctx.commands().dispatch(groups(size.width), groups(size.height));
                return capture(ctx, "bloom", "bloom_down", ResourceState::Storage);
            }));
    connect("shade", "hdr", "bloom_prefilter", "hdr");
    std::string previous = "bloom_prefilter";
    auto bloom_step = [&](const std::string& name, const char* source, uint32_t from, uint32_t to, rhi::PipelineHandle pipeline,
                          const char* capture_name) {
        add(Pass(name).set_kind(fg::PassKind::Compute).input(source, {}, fg::mip(from)).inout("bloom", {}, fg::mip(to))
                .on_execute([this, &p, source, to, pipeline, capture_name](fg::PassContext& ctx) -> Status {
                    const fg::Extent2D size = ctx.range_extent("bloom");
                    ctx.commands().set_pipeline(pipeline);
                    ctx.commands().set_bind_group(0, rhi::BindGroup{}
                                                         .texture(0, ctx.texture(source), p.linear, ctx.range(source))
                                                         .storage_texture(1, ctx.texture("bloom"), to));
                    ctx.commands().dispatch(groups(size.width), groups(size.height));
                    return capture(ctx, "bloom", capture_name, ResourceState::Storage);
                }));
        connect(previous, "bloom", name, source);
        connect(previous, "bloom", name, "bloom");
        previous = name;
    };
    for (uint32_t level = 1; level < kBloomLevels; ++level) bloom_step(level_port("bloom_down", level), "finer", level - 1, level, p.bloom_down, "bloom_down");
    for (uint32_t level = kBloomLevels - 1; level-- > 0;) bloom_step(level_port("bloom_up", level), "coarser", level + 1, level, p.bloom_up, "bloom_up");

    // Tone mapping into the picture.
    add(Pass("tonemap").input("hdr").input("bloom", {}, fg::mip(0))
            .output("final", TextureSpec::of(settings_.target_format).with_usage(copy))
            .on_execute([this, &p, frame_set](fg::PassContext& ctx) -> Status {
                ctx.begin_render_pass({"final"});
                ctx.commands().set_pipeline(p.tonemap);
                ctx.commands().set_bind_group(0, frame_set(ctx)
                                                     .texture(1, ctx.texture("hdr"), p.nearest)
                                                     .texture(2, ctx.texture("bloom"), p.linear, ctx.range("bloom")));
                ctx.commands().draw(3);
                ctx.end_render_pass();
                return capture(ctx, "final", "final", ResourceState::RenderTarget);
            }));
    connect("shade", "hdr", "tonemap", "hdr");
    connect(previous, "bloom", "tonemap", "bloom");
    keep_first(graph_.mark_output(fg::port("tonemap", "final")));
    return status;
}

}  // namespace loom::engine
