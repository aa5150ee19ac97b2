#include "loom/passes/shader_pass.hpp"

#include <algorithm>

#include "loom/framegraph/resolved_spec.hpp"
#include "loom/passes/geometry_buffers.hpp"

namespace loom::passes {
namespace {

bool same_kind(const ObjectKind& a, const ObjectKind& b) {
    return &a == &b || (a.name() == b.name() && a.parts() == b.parts() && same_vertex_layouts(a.vertex_buffers(), b.vertex_buffers()));
}

bool same_sampler(const rhi::SamplerDesc& a, const rhi::SamplerDesc& b) {
    return a.min_filter == b.min_filter && a.mag_filter == b.mag_filter && a.mipmap_filter == b.mipmap_filter &&
           a.address_u == b.address_u && a.address_v == b.address_v && a.address_w == b.address_w &&
           a.min_lod == b.min_lod && a.max_lod == b.max_lod && a.max_anisotropy == b.max_anisotropy &&
           a.compare == b.compare && a.border == b.border;
}

/// The kind's vertex buffers with only the attributes the vertex stage reads.
std::vector<rhi::VertexBufferLayout> vertex_inputs(const ObjectKind& kind, const Program& program) {
    std::vector<rhi::VertexBufferLayout> layouts = kind.vertex_buffers();
    const auto& inputs = program.vertex().reflection.inputs;
    for (rhi::VertexBufferLayout& layout : layouts) {
        std::erase_if(layout.attributes, [&](const rhi::VertexAttribute& attribute) {
            return std::none_of(inputs.begin(), inputs.end(),
                                [&](const rhi::StageVariable& input) { return input.location == attribute.location; });
        });
    }
    return layouts;
}

}  // namespace

bool operator==(const PipelineState& a, const PipelineState& b) {
    auto same_raster = [](const rhi::RasterState& x, const rhi::RasterState& y) {
        return x.cull == y.cull && x.front_face == y.front_face && x.polygon == y.polygon &&
               x.depth_clamp == y.depth_clamp && x.depth_bias_constant == y.depth_bias_constant &&
               x.depth_bias_slope == y.depth_bias_slope;
    };
    auto same_blend = [](const rhi::BlendState& x, const rhi::BlendState& y) {
        return x.enabled == y.enabled && x.src_color == y.src_color && x.dst_color == y.dst_color &&
               x.color_op == y.color_op && x.src_alpha == y.src_alpha && x.dst_alpha == y.dst_alpha &&
               x.alpha_op == y.alpha_op && x.write_mask == y.write_mask;
    };
    return a.color_formats == b.color_formats && a.depth_format == b.depth_format && a.depth.test == b.depth.test &&
           a.depth.write == b.depth.write && a.depth.compare == b.depth.compare && same_raster(a.raster, b.raster) &&
           std::equal(a.blend.begin(), a.blend.end(), b.blend.begin(), b.blend.end(), same_blend);
}

// ---- Bindings ------------------------------------------------------------------------------------

Bindings::Bindings(const Program& program, rhi::CommandList& commands, uint32_t set)
    : program_(program), commands_(commands), set_(set) {}

Result<ResourceSlot> Bindings::find(std::string_view name) {
    auto slot = program_.slot(name);
    if (slot && slot->set != set_) {
        return make_error(ErrorCode::InvalidArgument, "program '" + program_.name() + "': resource '" +
                                                          std::string(name) + "' is in set " +
                                                          std::to_string(slot->set) + ", not " + std::to_string(set_));
    }
    return slot;
}

Bindings& Bindings::uniform_bytes(std::string_view block, std::span<const std::byte> data) {
    if (error_) return *this;
    auto slot = find(block);
    if (slot && slot->size != data.size()) slot = program_.uniform_slot(block, static_cast<uint32_t>(data.size()));
    if (!slot) {
        error_ = slot.take_error();
        return *this;
    }
    group_.buffer(slot->binding, commands_.transient_uniforms(data));
    return *this;
}

Bindings& Bindings::buffer(std::string_view name, const rhi::BufferBinding& range) {
    if (error_) return *this;
    auto slot = find(name);
    if (slot && !slot->storage_buffer && range.size != 0 && slot->size != range.size) {
        slot = program_.uniform_slot(name, static_cast<uint32_t>(range.size));
    }
    if (!slot) {
        error_ = slot.take_error();
        return *this;
    }
    group_.buffer(slot->binding, range);
    return *this;
}

Bindings& Bindings::texture(std::string_view name, rhi::TextureHandle texture, rhi::SamplerHandle sampler) {
    if (error_) return *this;
    auto slot = find(name);
    if (!slot) {
        error_ = slot.take_error();
        return *this;
    }
    group_.texture(slot->binding, texture, sampler);
    return *this;
}

Status Bindings::status() const {
    if (error_) return *error_;
    return {};
}

Status Bindings::bind() {
    if (error_) return *error_;
    // A set the program declares nothing in is left alone.
    if (!group_.entries.empty()) commands_.set_bind_group(set_, group_);
    return {};
}

// ---- PassConfig ------------------------------------------------------------------------------------

fg::TextureSpec color_spec(const PassConfig& config) {
    fg::TextureSpec spec = fg::TextureSpec::of(config.color_format).with_scale(1.0f);
    if (config.capturable) spec = spec.with_usage(rhi::TextureUsage::CopySrc);
    return spec;
}

// ---- ShaderPass ------------------------------------------------------------------------------------

ShaderPass::ShaderPass(std::string name, std::shared_ptr<ShaderLibrary> library)
    : fg::Pass(std::move(name)), library_(library ? std::move(library) : std::make_shared<ShaderLibrary>()) {}

ShaderPass::~ShaderPass() {
    if (draw_source_) draw_source_->detach(*this);
    release_gpu();
}

Status ShaderPass::attach_draw_source(DrawSource& source) {
    if (draw_source_ == &source) return {};
    if (draw_source_ != nullptr) {
        return make_error(ErrorCode::InvalidState, "pass '" + name() + "' is attached to another draw source");
    }
    draw_source_ = &source;
    return {};
}

void ShaderPass::detach_draw_source(const DrawSource& source) {
    if (draw_source_ == &source) draw_source_ = nullptr;
}

ShaderPass& ShaderPass::add(const PassPart& part) {
    fg::Pass::add(part.ports);
    parts_.push_back(part.shader);
    return *this;
}

ShaderPass& ShaderPass::add_shader(ShaderPart part) {
    parts_.push_back(std::move(part));
    return *this;
}

ShaderPass& ShaderPass::define(std::string name, std::string value) {
    defines_.emplace_back(std::move(name), std::move(value));
    return *this;
}

Status ShaderPass::register_object(std::shared_ptr<const Object> object) {
    if (!object) return make_error(ErrorCode::InvalidArgument, "pass '" + name() + "': register_object with no object");
    const std::shared_ptr<const ObjectKind>& kind = object->kind();
    if (!kind || kind->name().empty()) {
        return make_error(ErrorCode::InvalidArgument,
                          "pass '" + name() + "': object '" + object->name() + "' has no (named) kind");
    }
    auto program = prepare_kind(kind);
    if (!program) return program.take_error();
    objects_.push_back(std::move(object));
    return {};
}

Result<const Program*> ShaderPass::prepare_kind(const std::shared_ptr<const ObjectKind>& kind) {
    if (!kind || kind->name().empty()) {
        return make_error(ErrorCode::InvalidArgument, "pass '" + name() + "': an object kind needs a name");
    }
    if (auto it = programs_.find(kind->name()); it != programs_.end()) {
        if (!same_kind(*it->second.first, *kind)) {
            return make_error(ErrorCode::InvalidArgument,
                              "pass '" + name() + "': object kind '" + kind->name() +
                                  "' was registered before with other shader parts or vertex buffers; kinds "
                                  "are told apart by name");
        }
        return it->second.second.get();
    }
    auto program = make_program(kind.get());
    if (!program) return program.take_error();
    const Program* raw = program->get();
    programs_.emplace(kind->name(), std::make_pair(kind, std::move(*program)));
    return raw;
}

const Program* ShaderPass::program_for_kind(const ObjectKind& kind) const {
    auto it = programs_.find(kind.name());
    return it == programs_.end() ? nullptr : it->second.second.get();
}

const Program* ShaderPass::program_for(const Object& object) const {
    const auto& kind = object.kind();
    if (!kind) return nullptr;
    auto it = programs_.find(kind->name());
    return it == programs_.end() ? nullptr : it->second.second.get();
}

Result<shader_compiler::ShaderSource> ShaderPass::coerce_shader(const ObjectKind* kind, rhi::ShaderStage stage) const {
    Composition composition;
    composition.pass = name();
    for (const ShaderPart& part : parts_) composition.pass_parts.push_back(&part);
    composition.object = kind;
    composition.use_object_parts = uses_object_parts(stage);
    composition.defines = defines_;
    return compose_stage(composition, stage);
}

Result<std::shared_ptr<const Program>> ShaderPass::make_program(const ObjectKind* kind) {
    rhi::ShaderModule modules[2];
    const rhi::ShaderStage stages[2] = {rhi::ShaderStage::Vertex, rhi::ShaderStage::Fragment};
    for (int i = 0; i < 2; ++i) {
        auto source = coerce_shader(kind, stages[i]);
        if (!source) return source.take_error();
        const std::string context = "pass '" + name() + "', object kind '" + (kind ? kind->name() : "none") + "', " +
                                    std::string(rhi::shader_stage_name(stages[i])) + " stage";
        auto module = library_->compile(*source, context);
        if (!module) return module.take_error();
        modules[i] = std::move(*module);
    }
    return std::make_shared<const Program>(name(), kind ? kind->name() : std::string(), std::move(modules[0]),
                                           std::move(modules[1]));
}

Status ShaderPass::render_with(DrawContext& context, const Object& object) { return object.render(context); }

Result<const Program*> ShaderPass::own_program() {
    if (auto it = programs_.find(std::string_view{}); it != programs_.end()) return it->second.second.get();
    auto program = make_program(nullptr);
    if (!program) return program.take_error();
    const Program* raw = program->get();
    programs_.emplace(std::string(), std::make_pair(nullptr, std::move(*program)));
    return raw;
}

std::vector<CapturedTexture> ShaderPass::captured() const {
    std::vector<CapturedTexture> out;
    for (const CaptureEntry& entry : captures_) out.push_back({entry.port, entry.texture});
    return out;
}

void ShaderPass::release_gpu() {
    if (!device_) return;
    // Errors here would mean stale handles of our own; nothing a caller could act on.
    for (PipelineEntry& entry : pipelines_) (void)device_->destroy(entry.handle);
    for (auto& [program, handles] : shaders_) {
        (void)device_->destroy(handles.first);
        (void)device_->destroy(handles.second);
    }
    for (SamplerEntry& entry : samplers_) (void)device_->destroy(entry.handle);
    for (CaptureEntry& entry : captures_) (void)device_->destroy(entry.texture);
    for (auto& [block, pool] : pass_sets_) pool->release_gpu();
    pipelines_.clear();
    shaders_.clear();
    samplers_.clear();
    captures_.clear();
    device_ = nullptr;
}

bool ShaderPass::uses_object_parts(rhi::ShaderStage) const { return true; }

Status ShaderPass::use_device(rhi::Device& device) {
    if (device_ == nullptr) device_ = &device;
    if (device_ != &device) {
        return make_error(ErrorCode::InvalidState, "pass '" + name() +
                                                       "' holds GPU objects of another device (release_gpu() first)");
    }
    return {};
}

Result<std::pair<rhi::ShaderHandle, rhi::ShaderHandle>> ShaderPass::shaders_of(const Program& program) {
    if (auto it = shaders_.find(&program); it != shaders_.end()) return it->second;
    auto vertex = device_->create_shader(program.vertex());
    if (!vertex) return vertex.take_error();
    auto fragment = device_->create_shader(program.fragment());
    if (!fragment) {
        (void)device_->destroy(*vertex);
        return fragment.take_error();
    }
    auto handles = std::make_pair(*vertex, *fragment);
    shaders_.emplace(&program, handles);
    return handles;
}

Result<rhi::PipelineHandle> ShaderPass::pipeline(rhi::Device& device, const Program& program,
                                                 const PipelineState& state, const ObjectKind* kind) {
    LOOM_TRY(use_device(device));
    const std::string kind_name = kind ? kind->name() : std::string();
    for (const PipelineEntry& entry : pipelines_) {
        if (entry.program == &program && entry.kind == kind_name && entry.state == state) return entry.handle;
    }
    auto shaders = shaders_of(program);
    if (!shaders) return shaders.take_error();
    rhi::GraphicsPipelineDesc desc;
    desc.name = program.name();
    desc.vertex = shaders->first;
    desc.fragment = shaders->second;
    if (kind) desc.vertex_buffers = vertex_inputs(*kind, program);
    desc.raster = state.raster;
    desc.depth = state.depth;
    desc.color_formats = state.color_formats;
    desc.blend = state.blend;
    desc.depth_format = state.depth_format;
    auto handle = device.create_graphics_pipeline(desc);
    if (!handle) return handle.take_error();
    pipelines_.push_back(PipelineEntry{&program, state, kind_name, *handle});
    return *handle;
}

Result<rhi::SamplerHandle> ShaderPass::sampler(rhi::Device& device, const rhi::SamplerDesc& desc) {
    LOOM_TRY(use_device(device));
    for (const SamplerEntry& entry : samplers_) {
        if (same_sampler(entry.desc, desc)) return entry.handle;
    }
    auto handle = device.create_sampler(desc);
    if (!handle) return handle.take_error();
    samplers_.push_back(SamplerEntry{desc, *handle});
    return *handle;
}

Result<rhi::SamplerHandle> ShaderPass::nearest_sampler(rhi::Device& device) {
    rhi::SamplerDesc desc;
    desc.name = name() + " nearest";
    desc.min_filter = rhi::Filter::Nearest;
    desc.mag_filter = rhi::Filter::Nearest;
    desc.max_lod = 0.0f;
    return sampler(device, desc);
}

Status ShaderPass::draw_objects(fg::PassContext& context, const PipelineState& state, const PassBinder& bind_pass) {
    rhi::CommandList& commands = context.commands();
    // Objects of one kind share a program: draw them together (stable, so registration order
    // is kept within a kind).
    std::vector<const Object*> order;
    order.reserve(objects_.size());
    for (const auto& object : objects_) order.push_back(object.get());
    std::stable_sort(order.begin(), order.end(),
                     [](const Object* a, const Object* b) { return a->kind()->name() < b->kind()->name(); });

    rhi::PipelineHandle bound;
    for (const Object* object : order) {
        const Program* program = program_for(*object);
        if (!program) {
            return make_error(ErrorCode::InvalidState,
                              "pass '" + name() + "': object '" + object->name() + "' has no program");
        }
        PipelineState object_state = state;
        const rhi::RasterState raster = object->raster();
        object_state.raster.cull = raster.cull;
        object_state.raster.front_face = raster.front_face;
        auto handle = pipeline(context.device(), *program, object_state, object->kind().get());
        if (!handle) return handle.take_error();
        if (*handle != bound) {
            commands.set_pipeline(*handle);
            bound = *handle;
            // Re-bound with every pipeline: the pass's set follows the pipeline's layout.
            Bindings pass_set(*program, commands, kPassSet);
            LOOM_TRY(bind_pass(pass_set));
            LOOM_TRY(pass_set.bind());
        }
        DrawContext draw{commands, *program};
        LOOM_TRY(render_with(draw, *object));
    }
    if (!draw_source_) return {};

    // The pass's side of DrawSource::draw. A local class of this member function, so that it
    // may hand the source the pass's pipeline and sampler caches without the pass naming the
    // source's type or befriending it.
    class PassSide final : public DrawSourceContext {
    public:
        PassSide(ShaderPass& pass, fg::PassContext& context, const PipelineState& state, const PassBinder& bind_pass)
            : pass_(pass), context_(context), state_(state), bind_pass_(bind_pass) {}

        const ShaderPass& pass() const override { return pass_; }
        fg::PassContext& pass_context() override { return context_; }
        const PipelineState& state() const override { return state_; }
        Result<rhi::PipelineHandle> pipeline(const Program& program, const PipelineState& state,
                                             const ObjectKind& kind) override {
            return pass_.pipeline(context_.device(), program, state, &kind);
        }
        Result<rhi::SamplerHandle> sampler(const rhi::SamplerDesc& desc) override {
            return pass_.sampler(context_.device(), desc);
        }
        Status bind_pass_set(const Program& program) override {
            Bindings pass_set(program, context_.commands(), kPassSet);
            LOOM_TRY(bind_pass_(pass_set));
            return pass_set.bind();
        }

    private:
        ShaderPass& pass_;
        fg::PassContext& context_;
        const PipelineState& state_;
        const PassBinder& bind_pass_;
    };
    PassSide side(*this, context, state, bind_pass);
    return draw_source_->draw(side);
}

Status ShaderPass::draw_fullscreen(fg::PassContext& context, const PipelineState& state, const PassBinder& bind_pass) {
    auto program = own_program();
    if (!program) return program.take_error();
    auto handle = pipeline(context.device(), **program, state, nullptr);
    if (!handle) return handle.take_error();
    rhi::CommandList& commands = context.commands();
    commands.set_pipeline(*handle);
    Bindings pass_set(**program, commands, kPassSet);
    LOOM_TRY(bind_pass(pass_set));
    LOOM_TRY(pass_set.bind());
    commands.draw(3);
    return {};
}

Result<PipelineState> ShaderPass::attachment_state(fg::PassContext& context, std::span<const std::string> colors,
                                                   std::string_view depth) {
    PipelineState state;
    for (const std::string& port : colors) {
        const fg::ResolvedSpec* spec = context.spec(port);
        if (!spec) {
            return make_error(ErrorCode::InvalidState,
                              "pass '" + context.pass_name() + "': port '" + port + "' has no texture to render to");
        }
        state.color_formats.push_back(spec->format);
    }
    if (!depth.empty()) {
        const fg::ResolvedSpec* spec = context.spec(depth);
        if (!spec) {
            return make_error(ErrorCode::InvalidState, "pass '" + context.pass_name() + "': port '" +
                                                           std::string(depth) + "' has no texture to render to");
        }
        state.depth_format = spec->format;
    }
    return state;
}

Status ShaderPass::bind_pass_uniforms(Bindings& set, std::string_view block, std::span<const std::byte> bytes) {
    if (!device_) {
        return make_error(ErrorCode::InvalidState,
                          "pass '" + name() + "': pass uniforms '" + std::string(block) + "' bound before the pass has a device");
    }
    auto it = pass_sets_.find(block);
    if (it == pass_sets_.end()) {
        auto pool = std::make_unique<UniformSetPool>(name() + "." + std::string(block), rhi::BufferUsage::Uniform,
                                                     static_cast<uint32_t>(bytes.size()),
                                                     UniformSetPool::Layout::Bindable, 1);
        // The slot starts as zeros, so the first write always differs unless the value is zero:
        // upload() writes a new buffer whole in any case.
        (void)pool->allocate();
        it = pass_sets_.emplace(std::string(block), std::move(pool)).first;
    }
    UniformSetPool& pool = *it->second;
    if (pool.set_size() != bytes.size()) {
        return make_error(ErrorCode::InvalidArgument, "pass '" + name() + "': pass uniforms '" + std::string(block) +
                                                          "' changed size from " + std::to_string(pool.set_size()) +
                                                          " to " + std::to_string(bytes.size()) + " bytes");
    }
    (void)pool.write(0, bytes);
    LOOM_TRY(pool.upload(*device_, pass_uniform_stats_));
    set.buffer(block, pool.binding(0));
    return set.status();
}

Status ShaderPass::record_capture(fg::PassContext& context) {
    if (!capture_) return {};
    LOOM_TRY(use_device(context.device()));
    for (const fg::Port& port : ports()) {
        if (!fg::port_writes(port.kind) || !context.has_texture(port.name)) continue;
        const fg::ResolvedSpec* spec = context.spec(port.name);
        if (!rhi::has_all(spec->usage, rhi::TextureUsage::CopySrc)) {
            return make_error(ErrorCode::InvalidState, "pass '" + name() + "': capturing port '" + port.name +
                                                           "' needs CopySrc usage (PassConfig::capturable)");
        }
        rhi::TextureDesc desc = fg::to_texture_desc(*spec, name() + "." + port.name + " (capture)");
        desc.usage = rhi::TextureUsage::CopyDst | rhi::TextureUsage::CopySrc;
        auto entry = std::find_if(captures_.begin(), captures_.end(),
                                  [&](const CaptureEntry& e) { return e.port == port.name; });
        if (entry != captures_.end() &&
            (entry->desc.format != desc.format || entry->desc.width != desc.width || entry->desc.height != desc.height)) {
            (void)device_->destroy(entry->texture);
            captures_.erase(entry);
            entry = captures_.end();
        }
        if (entry == captures_.end()) {
            auto texture = device_->create_texture(desc);
            if (!texture) return texture.take_error();
            captures_.push_back(CaptureEntry{port.name, desc, *texture});
            entry = captures_.end() - 1;
        }
        rhi::TextureCopy copy;
        copy.src = context.texture(port.name);
        copy.dst = entry->texture;
        context.commands().copy_texture(copy);
        // The copy moved the output into CopySrc; hand it back to the executor in the state the
        // pass left it in (an attachment's), so that capturing changes nothing it planned.
        context.commands().transition(copy.src, rhi::format_info(spec->format).is_depth_stencil()
                                                    ? rhi::ResourceState::DepthWrite
                                                    : rhi::ResourceState::RenderTarget);
    }
    return {};
}

}  // namespace loom::passes
