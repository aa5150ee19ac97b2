#include "loom/framegraph/executor.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include "frame_state.hpp"
#include "loom/rhi/checked_math.hpp"
#include "text.hpp"

namespace loom::fg {
namespace {

std::string in_quotes(std::string_view name) { return detail::concat("'", name, "'"); }

// "t3 [gbuffer.albedo, blur.out]", "b0 [cull.lights]": a plan object's name and the resources
// it holds.
std::string object_label(const Plan& plan, const std::string& name, const std::vector<uint32_t>& resources) {
    std::string label = name + " [";
    for (std::size_t i = 0; i < resources.size(); ++i) label += (i ? ", " : "") + plan.resources[resources[i]].name;
    return label + "]";
}

// The plan's heap offsets must hold on this device: `needs` (the device's size and alignment for
// the object called `what`) must fit the bytes and the offset the plan gave it.
Status check_placement(const std::string& what, const Result<rhi::MemoryRequirements>& needs, uint64_t planned_bytes,
                       const HeapRange& range, const std::vector<uint64_t>& heap_sizes) {
    if (!needs) return make_error(needs.error().code, "executor: " + what + ": " + needs.error().message);
    if (range.offset % std::max<uint64_t>(needs->alignment, 1) != 0 || needs->size > planned_bytes ||
        !checked::range_fits(range.offset, needs->size, heap_sizes[range.heap])) {
        return make_error(ErrorCode::InvalidArgument,
                          "executor: " + what + " needs " + std::to_string(needs->size) + " bytes aligned to " +
                              std::to_string(needs->alignment) + " on this device, but the plan gives it " +
                              std::to_string(planned_bytes) + " bytes at offset " + std::to_string(range.offset) +
                              " of heap " + std::to_string(range.heap) +
                              "; plan with the executor's memory model (Executor::effective_options)");
    }
    return {};
}

ResolvedSpec spec_from_desc(const rhi::TextureDesc& desc) {
    ResolvedSpec spec;
    spec.format = desc.format;
    spec.format_match = FormatMatch::Exact;
    spec.extent = {desc.width, desc.height};
    spec.samples = desc.samples;
    spec.mips = desc.mip_levels;
    spec.layers = desc.depth_or_layers;
    spec.usage = desc.usage;
    spec.cube = desc.dimension == rhi::TextureDimension::Cube;
    return spec;
}

}  // namespace

struct Executor::Impl {
    // An application texture or buffer bound to a port.
    template <class Handle>
    struct Bound {
        ImportBinding binding;
        Handle handle;
    };
    using Import = Bound<rhi::TextureHandle>;
    using BufferImport = Bound<rhi::BufferHandle>;

    // Binds `handle` to `port` in `bound` (re-binding costs nothing unless the final state changes).
    template <class Handle>
    void bind(std::vector<Bound<Handle>>& bound, const PortRef& port, Handle handle, rhi::ResourceState final_state) {
        for (Bound<Handle>& import : bound) {
            if (import.binding.port == port) {
                import.handle = handle;
                if (import.binding.final_state != final_state) {
                    import.binding.final_state = final_state;
                    ++bindings_revision;
                }
                return;
            }
        }
        bound.push_back({ImportBinding{port, final_state}, handle});
        ++bindings_revision;
    }
    template <class Handle>
    bool unbind(std::vector<Bound<Handle>>& bound, const PortRef& port) {
        auto it = std::find_if(bound.begin(), bound.end(), [&](const Bound<Handle>& i) { return i.binding.port == port; });
        if (it == bound.end()) return false;
        bound.erase(it);
        ++bindings_revision;
        return true;
    }
    // Textures carrying a source into the next frame.
    struct History {
        HistoryTexture layout;
        std::array<rhi::TextureHandle, 2> textures{};
        bool cleared = false;                     // zero-filled since created
        std::optional<uint64_t> last_copy_frame;  // frame whose copy it holds
    };

    explicit Impl(rhi::Device& d) : device(d), memory(std::make_shared<DeviceMemoryModel>(d)) {}

    Status prepare(const std::shared_ptr<const Plan>& next);
    Status create_plan_resources();
    Status destroy_plan_resources();
    Status reconcile_histories();
    Status destroy_history(History& history);
    Status check_imports(FrameState& frame);
    void clear_new_histories(rhi::CommandList& commands);
    Status run_passes(FrameGraph& graph, rhi::CommandList& commands, FrameState& frame);

    std::vector<ImportBinding> import_bindings() const {
        std::vector<ImportBinding> out;
        for (const Import& i : imports) out.push_back(i.binding);
        return out;
    }
    std::vector<ImportBinding> buffer_import_bindings() const {
        std::vector<ImportBinding> out;
        for (const BufferImport& i : buffer_imports) out.push_back(i.binding);
        return out;
    }
    Status create_plan_buffers();
    // The schedule of `pass`.`port` in the latest plan; null when there is none.
    const PortSchedule* find_port(std::string_view pass, std::string_view port) const {
        if (!plan || !schedule) return nullptr;
        for (uint32_t p = 0; p < plan->order.size(); ++p) {
            if (plan->order[p].name != pass) continue;
            for (const PortSchedule& ps : schedule->passes[p].ports) {
                if (ps.name == port) return &ps;
            }
        }
        return nullptr;
    }
    Status check_buffer_imports(FrameState& frame);

    rhi::Device& device;
    std::shared_ptr<DeviceMemoryModel> memory;

    std::vector<Import> imports;
    std::vector<BufferImport> buffer_imports;
    std::vector<HistoryBinding> history_bindings;
    uint64_t bindings_revision = 0;

    // Realised state.
    std::shared_ptr<const Plan> plan;
    uint64_t realised_bindings_revision = 0;
    std::optional<ExecutionSchedule> schedule;
    std::vector<rhi::HeapHandle> heaps;
    std::vector<uint64_t> heap_sizes;
    std::vector<rhi::TextureHandle> textures;  // per Plan::textures
    std::vector<bool> created_for;             // texture_needed the textures were created for
    std::vector<rhi::BufferHandle> buffers;    // per Plan::buffers
    std::vector<bool> buffers_created_for;     // buffer_needed the buffers were created for
    std::vector<History> histories;            // per schedule->histories
    uint64_t realisations = 0;

    uint64_t frame_index = 0;
    std::vector<double> cpu_ms;  // per Plan::order, latest frame
};

// ---- realisation ---------------------------------------------------------------------------------

Status Executor::Impl::destroy_plan_resources() {
    Status first;
    auto keep_first = [&](Status s) {
        if (!s && first.ok()) first = std::move(s);
    };
    // Placed textures and buffers go before their heaps.
    for (rhi::TextureHandle& t : textures) {
        if (t) keep_first(device.destroy(t));
        t = {};
    }
    for (rhi::BufferHandle& b : buffers) {
        if (b) keep_first(device.destroy(b));
        b = {};
    }
    buffers.clear();
    buffers_created_for.clear();
    for (rhi::HeapHandle& h : heaps) {
        if (h) keep_first(device.destroy(h));
    }
    textures.clear();
    heaps.clear();
    heap_sizes.clear();
    created_for.clear();
    return first;
}

Status Executor::Impl::create_plan_resources() {
    const Plan& p = *plan;
    const bool placed = !p.heaps.empty() && device.capabilities().placed_resources;
    if (placed) {
        for (uint32_t h = 0; h < p.heaps.size(); ++h) {
            auto heap = device.create_heap(rhi::HeapDesc{"frame graph heap " + std::to_string(h), p.heaps[h]});
            if (!heap) return make_error(heap.error().code, "executor: heap " + std::to_string(h) + ": " + heap.error().message);
            heaps.push_back(*heap);
            heap_sizes.push_back(p.heaps[h]);
        }
    }
    textures.assign(p.textures.size(), {});
    created_for = schedule->texture_needed;
    for (uint32_t t = 0; t < p.textures.size(); ++t) {
        if (!schedule->texture_needed[t]) continue;
        const PlanTexture& planned = p.textures[t];
        rhi::TextureDesc desc = to_texture_desc(planned.spec, object_label(p, planned.name, planned.resources));
        // Plans stay within loom's limits (texture_spec.hpp), which a device may not reach:
        // say so naming the ports, before the backend refuses a texture nobody asked for by name.
        const rhi::Capabilities& caps = device.capabilities();
        auto beyond = [&](const std::string& what) {
            std::vector<std::string> ports;
            for (uint32_t r : planned.resources) {
                for (const std::string& port : p.resources[r].ports) ports.push_back(port);
            }
            std::string listed;
            for (const std::string& port : ports) listed += (listed.empty() ? "" : ", ") + port;
            Error error = make_error(ErrorCode::Unsupported, "executor: texture " + in_quotes(desc.name) + " (" +
                                                                 describe_resolved(planned.spec) + ", for " + listed + ") " + what);
            error.subjects = std::move(ports);
            return error;
        };
        if (caps.max_texture_size != 0 && (desc.width > caps.max_texture_size || desc.height > caps.max_texture_size)) {
            return beyond("is larger than this device's limit of " + std::to_string(caps.max_texture_size) +
                          " texels per side");
        }
        if (caps.max_texture_layers != 0 && planned.spec.layers > caps.max_texture_layers) {
            return beyond("has more layers than this device's limit of " + std::to_string(caps.max_texture_layers));
        }
        if (caps.max_samples != 0 && planned.spec.samples > caps.max_samples) {
            return beyond("has more samples than this device's limit of " + std::to_string(caps.max_samples));
        }
        for (const HistoryTexture& history : schedule->histories) {
            if (p.resources[history.resource].texture == t) desc.usage |= rhi::TextureUsage::CopySrc;
        }
        if (placed && planned.placement) {
            LOOM_TRY(check_placement("texture " + in_quotes(desc.name), device.texture_memory_requirements(desc),
                                     planned.bytes, *planned.placement, p.heaps));
            desc.placement = rhi::TexturePlacement{heaps[planned.placement->heap], planned.placement->offset};
        }
        auto texture = device.create_texture(desc);
        if (!texture) return make_error(texture.error().code, "executor: texture " + in_quotes(desc.name) + ": " + texture.error().message);
        textures[t] = *texture;
    }
    return create_plan_buffers();
}

Status Executor::Impl::create_plan_buffers() {
    const Plan& p = *plan;
    buffers.assign(p.buffers.size(), {});
    buffers_created_for = schedule->buffer_needed;
    for (uint32_t b = 0; b < p.buffers.size(); ++b) {
        if (!schedule->buffer_needed[b]) continue;
        const PlanBuffer& planned = p.buffers[b];
        rhi::BufferDesc desc = to_buffer_desc(planned.spec, object_label(p, planned.name, planned.resources));
        if (!heaps.empty() && planned.placement) {
            LOOM_TRY(check_placement("buffer " + in_quotes(desc.name), device.buffer_memory_requirements(desc), planned.bytes,
                                     *planned.placement, p.heaps));
            desc.placement = rhi::BufferPlacement{heaps[planned.placement->heap], planned.placement->offset};
        }
        auto buffer = device.create_buffer(desc);
        if (!buffer) return make_error(buffer.error().code, "executor: buffer " + in_quotes(desc.name) + ": " + buffer.error().message);
        buffers[b] = *buffer;
    }
    return {};
}

Status Executor::Impl::destroy_history(History& history) {
    Status first;
    for (rhi::TextureHandle& t : history.textures) {
        if (t) {
            Status s = device.destroy(t);
            if (!s && first.ok()) first = std::move(s);
        }
        t = {};
    }
    return first;
}

Status Executor::Impl::reconcile_histories() {
    // Keep a history whose source and spec did not change (its contents stay valid), create
    // the others, release the ones no longer bound.
    std::vector<History> next;
    for (const HistoryTexture& layout : schedule->histories) {
        auto same = std::find_if(histories.begin(), histories.end(), [&](const History& h) {
            return h.layout.source == layout.source && h.layout.spec == layout.spec && h.layout.textures == layout.textures &&
                   h.textures[0];
        });
        History history;
        if (same != histories.end()) {
            history = std::move(*same);
            same->textures = {};
        }
        history.layout = layout;
        if (!history.textures[0]) {
            history.cleared = false;
            history.last_copy_frame.reset();
            for (uint32_t i = 0; i < layout.textures; ++i) {
                rhi::TextureDesc desc = to_texture_desc(layout.spec, "history of " + layout.source + (layout.textures > 1 ? " #" + std::to_string(i) : ""));
                const bool depth = rhi::format_info(layout.spec.format).is_depth_stencil();
                desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst |
                             (depth ? rhi::TextureUsage::DepthStencilAttachment : rhi::TextureUsage::ColorAttachment);
                auto texture = device.create_texture(desc);
                if (!texture) {
                    (void)destroy_history(history);
                    return make_error(texture.error().code, "executor: " + desc.name + ": " + texture.error().message);
                }
                history.textures[i] = *texture;
            }
        }
        next.push_back(std::move(history));
    }
    Status first;
    for (History& old : histories) {
        Status s = destroy_history(old);
        if (!s && first.ok()) first = std::move(s);
    }
    histories = std::move(next);
    return first;
}

Status Executor::Impl::prepare(const std::shared_ptr<const Plan>& next) {
    if (next == plan && realised_bindings_revision == bindings_revision && schedule) return {};
    auto built = build_execution_schedule(*next, import_bindings(), history_bindings, buffer_import_bindings());
    if (!built) return built.take_error();
    // A plan equal to the realised one (e.g. from a graph rebuilt every frame) reuses its resources.
    const bool plan_changed = next != plan && !(plan && *next == *plan);
    const bool needed_changed = built->texture_needed != created_for || built->buffer_needed != buffers_created_for;
    schedule = std::move(*built);
    if (plan_changed || needed_changed) {
        LOOM_TRY(destroy_plan_resources());
        plan = next;
        ++realisations;
        Status created = create_plan_resources();
        if (!created) {
            (void)destroy_plan_resources();
            plan.reset();
            schedule.reset();
            return created;
        }
    }
    plan = next;
    realised_bindings_revision = bindings_revision;
    Status histories_ok = reconcile_histories();
    if (!histories_ok) {
        schedule.reset();  // realise again next time
        return histories_ok;
    }
    cpu_ms.assign(plan->order.size(), 0.0);
    return {};
}

// ---- one frame -----------------------------------------------------------------------------------

Status Executor::Impl::check_imports(FrameState& frame) {
    frame.imports.resize(imports.size());
    frame.import_specs.resize(imports.size());
    for (uint32_t i = 0; i < imports.size(); ++i) {
        const Import& import = imports[i];
        const std::string what = "import " + import.binding.port.to_string();
        if (!import.handle) return make_error(ErrorCode::InvalidHandle, what + ": no texture bound (null handle)");
        auto desc = device.texture_desc(import.handle);
        if (!desc) return make_error(desc.error().code, what + ": " + desc.error().message);
        frame.imports[i] = import.handle;
        frame.import_specs[i] = spec_from_desc(*desc);
        // A texture standing in for a plan resource must have the resource's shape.
        for (uint32_t r = 0; r < plan->resources.size(); ++r) {
            // resource_import of a buffer resource counts buffer imports, not these.
            if (plan->resources[r].type != ResourceType::Texture || schedule->resource_import[r] != i) continue;
            const ResolvedSpec& wanted = plan->resources[r].spec;
            const ResolvedSpec& got = frame.import_specs[i];
            if (got.format != wanted.format || got.extent != wanted.extent || got.samples != wanted.samples ||
                got.mips < wanted.mips || got.layers < wanted.layers) {
                return make_error(ErrorCode::InvalidArgument, what + ": texture " + in_quotes(desc->name) + " is " +
                                                                  describe_resolved(got) + " but the port's texture is " +
                                                                  describe_resolved(wanted));
            }
        }
    }
    return {};
}

Status Executor::Impl::check_buffer_imports(FrameState& frame) {
    frame.buffer_imports.resize(buffer_imports.size());
    frame.buffer_import_sizes.resize(buffer_imports.size());
    for (uint32_t i = 0; i < buffer_imports.size(); ++i) {
        const BufferImport& import = buffer_imports[i];
        const std::string what = "buffer import " + import.binding.port.to_string();
        if (!import.handle) return make_error(ErrorCode::InvalidHandle, what + ": no buffer bound (null handle)");
        auto desc = device.buffer_desc(import.handle);
        if (!desc) return make_error(desc.error().code, what + ": " + desc.error().message);
        frame.buffer_imports[i] = import.handle;
        frame.buffer_import_sizes[i] = desc->size;
        // A buffer standing in for a plan resource must hold it and allow what its ports do.
        for (uint32_t r = 0; r < plan->resources.size(); ++r) {
            if (plan->resources[r].type != ResourceType::Buffer || schedule->resource_import[r] != i) continue;
            const ResolvedBufferSpec& wanted = plan->resources[r].buffer_spec;
            // Copy usage is always allowed on rhi buffers; the graph adds CopySrc for graph outputs.
            const auto copy_bits = static_cast<uint32_t>(rhi::BufferUsage::CopySrc | rhi::BufferUsage::CopyDst);
            const auto needed = static_cast<rhi::BufferUsage>(static_cast<uint32_t>(wanted.usage) & ~copy_bits);
            if (desc->size < wanted.size || (desc->usage & needed) != needed) {
                return make_error(ErrorCode::InvalidArgument,
                                  what + ": buffer " + in_quotes(desc->name) + " is " + std::to_string(desc->size) +
                                      " bytes " + describe_buffer_usage(desc->usage) + " but the port's buffer is " +
                                      describe_resolved_buffer(wanted));
            }
        }
    }
    return {};
}

void Executor::Impl::clear_new_histories(rhi::CommandList& commands) {
    for (History& history : histories) {
        if (history.cleared) continue;
        const bool depth = rhi::format_info(history.layout.spec.format).is_depth_stencil();
        for (uint32_t i = 0; i < history.layout.textures; ++i) {
            rhi::RenderPassDesc clear;
            clear.label = "clear " + history.layout.source + " history";
            if (depth) {
                rhi::DepthAttachment d;
                d.texture = history.textures[i];
                d.depth_load = rhi::LoadOp::Clear;
                d.clear_depth = 1.0f;
                d.stencil_load = rhi::LoadOp::Clear;
                d.stencil_store = rhi::StoreOp::Store;
                clear.depth = d;
            } else {
                rhi::ColorAttachment c;
                c.texture = history.textures[i];
                c.load = rhi::LoadOp::Clear;
                clear.colors.push_back(c);
            }
            commands.begin_render_pass(clear);
            commands.end_render_pass();
        }
        history.cleared = true;
    }
}

Status Executor::Impl::run_passes(FrameGraph& graph, rhi::CommandList& commands, FrameState& frame) {
    const bool timed = device.capabilities().timestamps;
    auto state_for = [&](const Transition& t) {
        // Imported inputs: the format is known only now.
        if (t.texture.kind == TextureSlot::Kind::Import && t.state == rhi::ResourceState::ShaderRead) {
            return sampled_state(frame.import_specs[t.texture.index].format);
        }
        return t.state;
    };
    // Plans with async compute passes: each pass on its queue, the plan's semaphores between
    // them (positions of signals and waits; kFrameStart and the order's length for the frame's
    // start and end, both on the graphics queue).
    const auto pass_count = static_cast<uint32_t>(plan->order.size());
    const std::vector<QueueSync>& syncs = plan->queue_syncs;
    std::vector<rhi::QueueSignal> signals(syncs.size());
    // Per position + 1 (0: the frame's start), the syncs signalled there; per position (the
    // order's length: the frame's end), the syncs waited there.
    std::vector<std::vector<uint32_t>> signalled(syncs.empty() ? 0 : pass_count + 1);
    std::vector<std::vector<uint32_t>> waited(syncs.empty() ? 0 : pass_count + 1);
    for (uint32_t i = 0; i < syncs.size(); ++i) {
        signalled[syncs[i].signal_after == kFrameStart ? 0 : syncs[i].signal_after + 1].push_back(i);
        waited[syncs[i].wait_before].push_back(i);
    }
    auto to_rhi = [](Queue queue) { return queue == Queue::Graphics ? rhi::QueueType::Graphics : rhi::QueueType::Compute; };
    auto signal_after = [&](uint32_t position) {
        for (uint32_t i : signalled[position == kFrameStart ? 0 : position + 1]) signals[i] = commands.signal_queue();
    };
    auto wait_before = [&](uint32_t position) {
        for (uint32_t i : waited[position]) commands.wait_queue(signals[i]);
    };
    if (!syncs.empty()) {
        commands.set_queue(rhi::QueueType::Graphics);
        signal_after(kFrameStart);
    }
    for (uint32_t p = 0; p < pass_count; ++p) {
        const PlanPass& planned = plan->order[p];
        const PassSchedule& around = schedule->passes[p];
        const auto start = std::chrono::steady_clock::now();
        frame.position = p;
        if (!syncs.empty()) {
            commands.set_queue(to_rhi(planned.queue));
            wait_before(p);
        }
        if (timed) commands.begin_timer(planned.name);
        commands.push_debug_group(planned.name);
        for (const Transition& t : around.before) commands.transition(frame.resolve(t.texture), state_for(t), t.range);
        for (const BufferTransition& t : around.buffers_before) commands.transition(frame.resolve(t.buffer), t.state);

        frame.pass_commands.begin_pass(commands);
        PassContext context(frame, p);
        Status status = graph.execute_pass(PassId{planned.declaration_index}, context);
        if (auto left_open = frame.pass_commands.end_pass()) {
            frame.fail(make_error(ErrorCode::InvalidState, "execute() returned with " + *left_open + " still open"));
        }
        if (!status && !frame.pass_error) frame.fail(status.take_error());

        if (!frame.pass_error) {
            for (const Transition& t : around.after) commands.transition(frame.resolve(t.texture), t.state, t.range);
            for (const BufferTransition& t : around.buffers_after) commands.transition(frame.resolve(t.buffer), t.state);
            for (const HistoryCopy& copy : around.copies) {
                History& history = histories[copy.history];
                const rhi::TextureHandle target = history.textures[frame.frame_index % history.layout.textures];
                for (uint32_t layer = 0; layer < history.layout.spec.layers; ++layer) {
                    rhi::TextureCopy c;
                    c.src = frame.resolve(copy.source);
                    c.src_region.layer = layer;
                    c.dst = target;
                    c.dst_region.layer = layer;
                    commands.copy_texture(c);
                }
                history.last_copy_frame = frame.frame_index;
            }
        }
        commands.pop_debug_group();
        if (timed) commands.end_timer();
        if (!syncs.empty()) signal_after(p);
        cpu_ms[p] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (frame.pass_error) return *frame.pass_error;
    }
    if (!syncs.empty()) {
        // The frame goes on (and ends) on the graphics queue, after the async passes it waits for.
        commands.set_queue(rhi::QueueType::Graphics);
        wait_before(pass_count);
    }
    return {};
}

// ---- Executor ------------------------------------------------------------------------------------

Executor::Executor(rhi::Device& device) : impl_(std::make_unique<Impl>(device)) {}

Executor::~Executor() { (void)release(); }

rhi::Device& Executor::device() const { return impl_->device; }

std::shared_ptr<MemoryModel> Executor::memory_model() const { return impl_->memory; }

PlanOptions Executor::effective_options(PlanOptions options) const {
    if (!options.memory_model && options.allocator == AllocatorKind::Heap && impl_->device.capabilities().placed_resources) {
        options.memory_model = impl_->memory;
    }
    return options;
}

Result<AllocatorKind> Executor::cheapest_allocator(const FrameGraph& graph, PlanOptions options) const {
    options.memory_model = nullptr;
    options.allocator = AllocatorKind::Interval;
    auto interval = build_plan(graph, options);
    if (!interval) return interval.take_error();
    if (!impl_->device.capabilities().placed_resources) return AllocatorKind::Interval;
    options.allocator = AllocatorKind::Heap;
    auto heap = build_plan(graph, effective_options(options));
    if (!heap) return heap.take_error();
    return heap->summary.bytes < interval->summary.bytes ? AllocatorKind::Heap : AllocatorKind::Interval;
}

void Executor::import_texture(const PortRef& port, rhi::TextureHandle texture, rhi::ResourceState final_state) {
    impl_->bind(impl_->imports, port, texture, final_state);
}

bool Executor::remove_import(const PortRef& port) { return impl_->unbind(impl_->imports, port); }

void Executor::import_buffer(const PortRef& port, rhi::BufferHandle buffer, rhi::ResourceState final_state) {
    impl_->bind(impl_->buffer_imports, port, buffer, final_state);
}

bool Executor::remove_buffer_import(const PortRef& port) { return impl_->unbind(impl_->buffer_imports, port); }

void Executor::bind_history(const PortRef& reader, const PortRef& source) {
    for (HistoryBinding& binding : impl_->history_bindings) {
        if (binding.reader == reader) {
            if (binding.source != source) {
                binding.source = source;
                ++impl_->bindings_revision;
            }
            return;
        }
    }
    impl_->history_bindings.push_back({reader, source});
    ++impl_->bindings_revision;
}

bool Executor::remove_history(const PortRef& reader) {
    auto& bindings = impl_->history_bindings;
    auto it = std::find_if(bindings.begin(), bindings.end(), [&](const HistoryBinding& b) { return b.reader == reader; });
    if (it == bindings.end()) return false;
    bindings.erase(it);
    ++impl_->bindings_revision;
    return true;
}

Status Executor::execute(FrameGraph& graph, rhi::CommandList& commands, const PlanOptions& options) {
    Impl& s = *impl_;
    auto planned = graph.plan(effective_options(options));
    if (!planned) return planned.take_error();
    LOOM_TRY(s.prepare(*planned));

    FrameState frame(s.device, *s.plan, *s.schedule);
    frame.frame_index = s.frame_index;
    frame.plan_textures = s.textures;
    frame.plan_buffers = s.buffers;
    LOOM_TRY(s.check_imports(frame));
    LOOM_TRY(s.check_buffer_imports(frame));
    for (const Impl::History& history : s.histories) {
        const uint32_t count = history.layout.textures;
        // One texture: readers run before this frame's copy. Two: readers read last frame's.
        frame.history_read.push_back(history.textures[count == 1 ? 0 : (s.frame_index + 1) % 2]);
        frame.history_valid.push_back(history.last_copy_frame.has_value() && *history.last_copy_frame < s.frame_index);
    }
    s.clear_new_histories(commands);
    Status status = s.run_passes(graph, commands, frame);
    ++s.frame_index;
    return status;
}

Status Executor::run_frame(FrameGraph& graph, const PlanOptions& options) {
    const uint64_t frame = impl_->frame_index;
    rhi::CommandList& commands = impl_->device.begin_frame();
    Status executed = execute(graph, commands, options);
    Status ended = impl_->device.end_frame();
    if (!executed) return executed;
    if (!ended) {
        return make_error(ended.error().code, "frame " + std::to_string(frame) + ": " + ended.error().message);
    }
    return {};
}

std::shared_ptr<const Plan> Executor::plan() const { return impl_->plan; }

const ExecutionSchedule* Executor::schedule() const { return impl_->schedule ? &*impl_->schedule : nullptr; }

rhi::TextureHandle Executor::texture(std::string_view pass, std::string_view port) const {
    const Impl& s = *impl_;
    const PortSchedule* ps = s.find_port(pass, port);
    if (!ps) return {};
    switch (ps->texture.kind) {
        case TextureSlot::Kind::None: return {};
        case TextureSlot::Kind::Plan: return plan_texture(ps->texture.index);
        case TextureSlot::Kind::Import: return s.imports[ps->texture.index].handle;
        case TextureSlot::Kind::History: {
            // What the port will read in the next frame.
            const Impl::History& h = s.histories[ps->texture.index];
            return h.textures[h.layout.textures == 1 ? 0 : (s.frame_index + 1) % 2];
        }
    }
    return {};
}

rhi::TextureHandle Executor::plan_texture(uint32_t index) const {
    return index < impl_->textures.size() ? impl_->textures[index] : rhi::TextureHandle{};
}

rhi::BufferHandle Executor::buffer(std::string_view pass, std::string_view port) const {
    const Impl& s = *impl_;
    const PortSchedule* ps = s.find_port(pass, port);
    if (!ps) return {};
    switch (ps->buffer.kind) {
        case BufferSlot::Kind::None: return {};
        case BufferSlot::Kind::Plan: return plan_buffer(ps->buffer.index);
        case BufferSlot::Kind::Import: return s.buffer_imports[ps->buffer.index].handle;
    }
    return {};
}

rhi::BufferHandle Executor::plan_buffer(uint32_t index) const {
    return index < impl_->buffers.size() ? impl_->buffers[index] : rhi::BufferHandle{};
}

std::vector<PassTiming> Executor::timings() const {
    const Impl& s = *impl_;
    std::vector<PassTiming> out;
    if (!s.plan) return out;
    const std::vector<rhi::TimerResult> gpu = s.device.timer_results();
    for (uint32_t p = 0; p < s.plan->order.size(); ++p) {
        PassTiming timing;
        timing.pass = s.plan->order[p].name;
        timing.cpu_ms = p < s.cpu_ms.size() ? s.cpu_ms[p] : 0.0;
        for (const rhi::TimerResult& r : gpu) {
            if (r.label == timing.pass) timing.gpu_ms = r.gpu_ms;
        }
        out.push_back(std::move(timing));
    }
    return out;
}

ExecutionStats Executor::stats() const {
    const Impl& s = *impl_;
    ExecutionStats stats;
    stats.realisations = s.realisations;
    stats.device = s.device.resource_stats();
    if (!s.plan) return stats;
    stats.plan_textures = static_cast<uint32_t>(s.plan->textures.size());
    stats.plan_heaps = static_cast<uint32_t>(s.plan->heaps.size());
    for (uint64_t h : s.plan->heaps) stats.plan_heap_bytes += h;
    stats.plan_bytes = s.plan->summary.bytes;
    for (uint32_t t = 0; t < s.textures.size(); ++t) {
        if (!s.textures[t]) continue;
        ++stats.textures;
        if (!s.heaps.empty() && s.plan->textures[t].placement) {
            ++stats.placed_textures;
        } else {
            stats.texture_bytes += s.plan->textures[t].bytes;
        }
    }
    stats.plan_buffers = static_cast<uint32_t>(s.plan->buffers.size());
    for (uint32_t b = 0; b < s.buffers.size(); ++b) {
        if (!s.buffers[b]) continue;
        ++stats.buffers;
        if (!s.heaps.empty() && s.plan->buffers[b].placement) {
            ++stats.placed_buffers;
        } else {
            stats.buffer_bytes += s.plan->buffers[b].bytes;
        }
    }
    for (const Impl::History& h : s.histories) stats.history_textures += h.layout.textures;
    stats.heaps = static_cast<uint32_t>(s.heaps.size());
    for (uint64_t size : s.heap_sizes) stats.heap_bytes += size;
    return stats;
}

uint64_t Executor::frame_index() const { return impl_->frame_index; }

Status Executor::release() {
    Impl& s = *impl_;
    Status first = s.destroy_plan_resources();
    for (Impl::History& h : s.histories) {
        Status d = s.destroy_history(h);
        if (!d && first.ok()) first = std::move(d);
    }
    s.histories.clear();
    s.plan.reset();
    s.schedule.reset();
    return first;
}

}  // namespace loom::fg
