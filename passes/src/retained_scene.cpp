#include "loom/passes/retained_scene.hpp"

#include <algorithm>
#include <cstring>
#include <tuple>

#include "loom/passes/retained_mesh.hpp"

namespace loom::passes {
namespace {

std::string shape_name(const Shape& shape) { return "shape '" + shape.name() + "'"; }

/// The kind's per-instance slot (the object index), checked against the retained convention.
Result<uint32_t> object_index_slot(const ObjectKind& kind) {
    const auto& layouts = kind.vertex_buffers();
    const std::string what = "object kind '" + kind.name() + "' does not follow the retained convention: ";
    if (layouts.empty() || layouts.back().step != rhi::VertexStepMode::PerInstance) {
        return make_error(ErrorCode::InvalidArgument, what + "its last vertex buffer slot must be the per-instance object "
                                                             "index (object_index_layout())");
    }
    const rhi::VertexBufferLayout& last = layouts.back();
    if (last.attributes.size() != 1 || last.attributes[0].location != kObjectIndexLocation ||
        last.attributes[0].format != rhi::VertexFormat::Uint || last.stride != sizeof(uint32_t)) {
        return make_error(ErrorCode::InvalidArgument,
                          what + "its per-instance slot must hold one Uint at location " +
                              std::to_string(kObjectIndexLocation) + " with stride 4");
    }
    for (std::size_t i = 0; i + 1 < layouts.size(); ++i) {
        if (layouts[i].step != rhi::VertexStepMode::PerVertex) {
            return make_error(ErrorCode::InvalidArgument, what + "only its last vertex buffer slot may be per-instance");
        }
    }
    return static_cast<uint32_t>(layouts.size() - 1);
}

bool names_pass(const Shape& shape, const ShaderPass& pass) {
    return shape.passes.empty() || std::find(shape.passes.begin(), shape.passes.end(), pass.name()) != shape.passes.end();
}

/// Whether `program` reads `material`'s resources (a pass may leave the material parts out).
bool reads_material(const Program& program, const GpuMaterial& material) {
    if (material.uniforms() && program.find(material.uniforms()->block())) return true;
    return std::any_of(material.textures().begin(), material.textures().end(),
                       [&](const MaterialTexture& t) { return program.find(t.name).has_value(); });
}

/// Makes `buffer` hold `now`: a new buffer (everything written) when it is too small, else only
/// the span from the first to the last element that differs from `uploaded`.
template <class T>
Status sync_buffer(rhi::Device& device, rhi::BufferHandle& buffer, uint64_t& capacity, rhi::BufferUsage usage,
                   const std::string& name, const std::vector<T>& now, std::vector<T>& uploaded, UploadStats& stats) {
    if (now.empty()) {
        uploaded.clear();
        return {};
    }
    auto bytes = [](const T* data, std::size_t count) {
        return std::span<const std::byte>(reinterpret_cast<const std::byte*>(data), count * sizeof(T));
    };
    if (now.size() > capacity || !buffer) {
        const uint64_t elements = std::max<uint64_t>(now.size(), capacity * 2);
        rhi::BufferDesc desc;
        desc.name = name;
        desc.size = elements * sizeof(T);
        desc.usage = usage;
        auto made = device.create_buffer(desc);
        if (!made) return made.take_error();
        if (buffer) {
            (void)device.destroy(buffer);
            ++stats.growths;
        }
        buffer = *made;
        capacity = elements;
        uploaded.clear();
    }
    std::size_t first = 0;
    const std::size_t common = std::min(now.size(), uploaded.size());
    while (first < common && std::memcmp(&now[first], &uploaded[first], sizeof(T)) == 0) ++first;
    if (first == now.size()) {
        uploaded = now;
        return {};
    }
    std::size_t last = now.size();
    if (now.size() == uploaded.size()) {
        while (last > first + 1 && std::memcmp(&now[last - 1], &uploaded[last - 1], sizeof(T)) == 0) --last;
    }
    LOOM_TRY(device.write_buffer(buffer, first * sizeof(T), bytes(now.data() + first, last - first)));
    ++stats.writes;
    stats.bytes += (last - first) * sizeof(T);
    stats.sets += last - first;
    uploaded = now;
    return {};
}

}  // namespace

// ---- the scene's records ---------------------------------------------------------------------

struct RetainedScene::GeometryEntry {
    std::shared_ptr<const Geometry> geometry;
    uint32_t users = 0;
    std::optional<GeometryPlacement> placement;
};

struct RetainedScene::MaterialEntry {
    std::shared_ptr<GpuMaterial> material;
    uint32_t users = 0;
    UniformSetPool* pool = nullptr;  ///< of its uniform set's size; null without a set
    std::optional<uint32_t> slot;    ///< in `pool`
    bool queued = false;           ///< on stale_materials_
    bool fresh = true;             ///< its slot was never written
};

struct RetainedScene::ObjectEntry {
    std::shared_ptr<Shape> shape;
    uint64_t sequence = 0;
    uint32_t slot = 0;  ///< record slot
    uint32_t instance_slot = 0;
    std::unique_ptr<UniformSet> record;
    GeometryEntry* geometry = nullptr;
    MaterialEntry* material = nullptr;
    rhi::FrontFace front_face = rhi::FrontFace::CounterClockwise;
    bool queued = false;  ///< on stale_objects_
    bool fresh = true;    ///< its slot was never written
    /// The queues it is in, with its position in each one's members.
    std::vector<std::pair<Queue*, uint32_t>> positions;
};

/// How a batch is drawn (DrawBatch plus what draw() needs).
struct RetainedScene::BatchState {
    const Program* program = nullptr;
    const ObjectKind* kind = nullptr;
    const MaterialEntry* material = nullptr;  ///< null when the program reads no material
    uint32_t instance_slot = 0;
};

struct RetainedScene::Queue {
    ShaderPass* pass = nullptr;
    QueueOrder order = QueueOrder::Sorted;
    std::vector<ObjectEntry*> members;
    bool dirty = true;
    // Built by rebuild().
    std::vector<DrawBatch> batches;
    std::vector<BatchState> states;
    std::vector<rhi::DrawIndexedIndirectCommand> commands;
    std::vector<uint32_t> instances;
    uint64_t distinct_keys = 0;
    // On the GPU.
    std::vector<rhi::DrawIndexedIndirectCommand> uploaded_commands;
    std::vector<uint32_t> uploaded_instances;
    rhi::BufferHandle command_buffer;
    rhi::BufferHandle instance_buffer;
    uint64_t command_capacity = 0;
    uint64_t instance_capacity = 0;

    void release(rhi::Device* device) {
        if (device) {
            if (command_buffer) (void)device->destroy(command_buffer);
            if (instance_buffer) (void)device->destroy(instance_buffer);
        }
        command_buffer = {};
        instance_buffer = {};
        command_capacity = 0;
        instance_capacity = 0;
        uploaded_commands.clear();
        uploaded_instances.clear();
        dirty = true;
    }
};

// ---- RetainedScene ---------------------------------------------------------------------------

RetainedScene::RetainedScene(RetainedConfig config)
    : config_(config), geometry_(config.initial_vertices, config.initial_indices),
      object_records_("object records", rhi::BufferUsage::Storage, sizeof(ObjectRecord), UniformSetPool::Layout::Array,
                      config.initial_objects) {}

RetainedScene::~RetainedScene() {
    while (!queues_.empty()) detach(*queues_.back()->pass);
    for (auto& [material, entry] : materials_) {
        if (entry->material->uniforms()) entry->material->uniforms()->on_stale(nullptr);
    }
    release_gpu();
}

RetainedScene::Queue* RetainedScene::find_queue(const ShaderPass& pass) const {
    for (const auto& queue : queues_) {
        if (queue->pass == &pass) return queue.get();
    }
    return nullptr;
}

Status RetainedScene::attach(ShaderPass& pass, QueueOrder order) {
    if (pass.draw_source() == this) return {};
    if (pass.draw_source() != nullptr) {
        return make_error(ErrorCode::InvalidState, "pass '" + pass.name() + "' is attached to another draw source");
    }
    // Every kind submitted so far must compile for the pass before anything changes.
    for (const auto& [shape, object] : objects_) {
        if (!names_pass(*shape, pass)) continue;
        auto program = pass.prepare_kind(shape->kind());
        if (!program) return program.take_error();
    }
    auto queue = std::make_unique<Queue>();
    queue->pass = &pass;
    queue->order = order;
    for (const auto& [shape, object] : objects_) {
        if (names_pass(*shape, pass)) LOOM_TRY(add_to_queue(*queue, *object));
    }
    LOOM_TRY(pass.attach_draw_source(*this));
    queues_.push_back(std::move(queue));
    return {};
}

void RetainedScene::detach(ShaderPass& pass) {
    auto it = std::find_if(queues_.begin(), queues_.end(), [&](const auto& q) { return q->pass == &pass; });
    if (it == queues_.end()) return;
    Queue* queue = it->get();
    for (ObjectEntry* member : queue->members) {
        std::erase_if(member->positions, [&](const auto& p) { return p.first == queue; });
    }
    queue->release(device_);
    pass.detach_draw_source(*this);
    queues_.erase(it);
}

Status RetainedScene::add_to_queue(Queue& queue, ObjectEntry& object) {
    object.positions.emplace_back(&queue, static_cast<uint32_t>(queue.members.size()));
    queue.members.push_back(&object);
    queue.dirty = true;
    return {};
}

void RetainedScene::remove_from_queue(Queue& queue, ObjectEntry& object) {
    auto position = std::find_if(object.positions.begin(), object.positions.end(),
                                 [&](const auto& p) { return p.first == &queue; });
    if (position == object.positions.end()) return;
    const uint32_t index = position->second;
    object.positions.erase(position);
    // Swap-remove: the order of members does not matter, rebuild() sorts them.
    ObjectEntry* moved = queue.members.back();
    queue.members[index] = moved;
    queue.members.pop_back();
    if (moved != &object) {
        for (auto& p : moved->positions) {
            if (p.first == &queue) p.second = index;
        }
    }
    queue.dirty = true;
}

void RetainedScene::mark_all_queues_dirty() {
    for (auto& queue : queues_) queue->dirty = true;
}

Status RetainedScene::submit(std::shared_ptr<Shape> shape) {
    if (!shape) return make_error(ErrorCode::InvalidArgument, "submit: no shape");
    const std::string what = shape_name(*shape) + ": ";
    if (!shape->kind() || !shape->geometry() || !shape->material() || !shape->model()) {
        return make_error(ErrorCode::InvalidArgument, what + "needs a kind, a geometry, a material and a model transform");
    }
    if (objects_.count(shape.get())) return make_error(ErrorCode::InvalidArgument, what + "is submitted already");
    auto instance_slot = object_index_slot(*shape->kind());
    if (!instance_slot) return make_error(ErrorCode::InvalidArgument, what + instance_slot.error().message);
    const auto& kind_layouts = shape->kind()->vertex_buffers();
    if (!same_vertex_layouts(std::span(kind_layouts.data(), *instance_slot), shape->geometry()->layouts())) {
        return make_error(ErrorCode::InvalidArgument, what + "geometry '" + shape->geometry()->name() +
                                                          "' has other vertex layouts than object kind '" +
                                                          shape->kind()->name() + "' reads");
    }
    if (const auto& set = shape->material()->uniforms();
        set && (set->size() == 0 || set->frequency() != UpdateFrequency::PerMaterial)) {
        return make_error(ErrorCode::InvalidArgument, what + "material '" + shape->material()->name() +
                                                          "' needs a non-empty per-material uniform set (or none)");
    }
    for (const auto& queue : queues_) {
        if (!names_pass(*shape, *queue->pass)) continue;
        auto program = queue->pass->prepare_kind(shape->kind());
        if (!program) return program.take_error();
    }

    kind_ranks_.emplace(shape->kind()->name(), static_cast<uint32_t>(kind_ranks_.size()));

    // Geometry: placed by the next prepare() unless already in the shared buffers.
    auto& geometry = geometries_[shape->geometry().get()];
    if (!geometry) {
        geometry = std::make_unique<GeometryEntry>();
        geometry->geometry = shape->geometry();
        to_place_.push_back(geometry.get());
    }
    ++geometry->users;

    // GpuMaterial: a slot for its uniform set, uploaded by the next prepare() and whenever its
    // parameters change.
    auto& material = materials_[shape->material().get()];
    if (!material) {
        material = std::make_unique<MaterialEntry>();
        material->material = shape->material();
        if (const auto& set = material->material->uniforms()) {
            auto& pool = material_pools_[set->size()];
            if (!pool) {
                pool = std::make_unique<UniformSetPool>("material sets (" + std::to_string(set->size()) + " bytes)",
                                                        rhi::BufferUsage::Uniform, set->size(),
                                                        UniformSetPool::Layout::Bindable, config_.initial_materials);
            }
            material->pool = pool.get();
            material->slot = pool->allocate();
            MaterialEntry* entry = material.get();
            set->on_stale([this, entry](UniformSet&) {
                if (!entry->queued) {
                    entry->queued = true;
                    stale_materials_.push_back(entry);
                }
            });
            material->queued = true;
            stale_materials_.push_back(material.get());
        }
    }
    ++material->users;

    // The object: a record slot and its per-object set, computed from the model transform.
    auto object = std::make_unique<ObjectEntry>();
    object->shape = shape;
    object->sequence = next_sequence_++;
    object->slot = object_records_.allocate();
    object->instance_slot = *instance_slot;
    object->geometry = geometry.get();
    object->material = material.get();
    std::shared_ptr<Param<glm::mat4>> model = shape->model();
    object->record = std::make_unique<UniformSet>(
        "ObjectRecords", UpdateFrequency::PerObject, static_cast<uint32_t>(sizeof(ObjectRecord)),
        [model](std::span<std::byte> block) {
            const ObjectRecord record = object_record(model->value());
            std::memcpy(block.data(), &record, sizeof(record));
        },
        std::vector<std::shared_ptr<ParamNode>>{model});
    ObjectEntry* entry = object.get();
    object->record->on_stale([this, entry](UniformSet&) {
        if (!entry->queued) {
            entry->queued = true;
            stale_objects_.push_back(entry);
        }
    });
    object->queued = true;
    stale_objects_.push_back(entry);
    for (auto& queue : queues_) {
        if (names_pass(*shape, *queue->pass)) LOOM_TRY(add_to_queue(*queue, *entry));
    }
    objects_.emplace(shape.get(), std::move(object));
    return {};
}

Status RetainedScene::retract(const Shape& shape) {
    auto it = objects_.find(&shape);
    if (it == objects_.end()) {
        return make_error(ErrorCode::InvalidArgument, "retract: " + shape_name(shape) + " is not submitted");
    }
    ObjectEntry& object = *it->second;
    while (!object.positions.empty()) remove_from_queue(*object.positions.back().first, object);
    if (object.queued) std::erase(stale_objects_, &object);
    object_records_.release(object.slot);

    GeometryEntry* geometry = object.geometry;
    if (--geometry->users == 0) {
        if (geometry->placement) {
            geometry_.free(*geometry->geometry, *geometry->placement);
        } else {
            std::erase(to_place_, geometry);
        }
        geometries_.erase(geometry->geometry.get());
    }
    MaterialEntry* material = object.material;
    if (--material->users == 0) {
        if (material->slot) material->pool->release(*material->slot);
        if (material->queued) std::erase(stale_materials_, material);
        if (material->material->uniforms()) material->material->uniforms()->on_stale(nullptr);
        materials_.erase(material->material.get());
    }
    objects_.erase(it);
    return {};
}

bool RetainedScene::submitted(const Shape& shape) const { return objects_.count(&shape) != 0; }

std::optional<uint32_t> RetainedScene::object_slot(const Shape& shape) const {
    auto it = objects_.find(&shape);
    if (it == objects_.end()) return std::nullopt;
    return it->second->slot;
}

Status RetainedScene::prepare(rhi::Device& device) {
    if (device_ && device_ != &device) {
        return make_error(ErrorCode::InvalidState, "retained scene: prepare on another device than its buffers' (release_gpu() first)");
    }
    device_ = &device;

    // The finalize queue: new geometries into the shared buffers.
    if (!to_place_.empty()) {
        std::vector<const Geometry*> geometries;
        for (GeometryEntry* entry : to_place_) geometries.push_back(entry->geometry.get());
        std::vector<std::pair<const Geometry*, GeometryPlacement>> live;
        for (const auto& [key, entry] : geometries_) {
            if (entry->placement) live.emplace_back(entry->geometry.get(), *entry->placement);
        }
        std::vector<GeometryPlacement> placed;
        LOOM_TRY(geometry_.place(device, geometries, placed, live, stats_.geometry_uploads));
        for (std::size_t i = 0; i < to_place_.size(); ++i) to_place_[i]->placement = placed[i];
        stats_.geometries_placed += to_place_.size();
        to_place_.clear();
        mark_all_queues_dirty();
    }

    // The upload queue: stale per-object and per-material sets, recomputed and written into
    // their pools when their bytes changed, then each pool's changed slots uploaded.
    for (ObjectEntry* object : stale_objects_) {
        object->queued = false;
        ++stats_.object_sets_refreshed;
        const bool changed = object->record->refresh();
        if (changed || object->fresh) (void)object_records_.write(object->slot, object->record->bytes(), object->fresh);
        object->fresh = false;
        // A mirroring transform turns the triangles' winding around: another pipeline.
        const glm::mat4& model = object->shape->model()->value();
        const rhi::FrontFace front = glm::determinant(glm::mat3(model)) < 0.0f ? rhi::FrontFace::Clockwise
                                                                              : rhi::FrontFace::CounterClockwise;
        if (front != object->front_face) {
            object->front_face = front;
            for (auto& [queue, position] : object->positions) queue->dirty = true;
        }
    }
    stale_objects_.clear();
    LOOM_TRY(object_records_.upload(device, stats_.object_uploads));
    for (MaterialEntry* material : stale_materials_) {
        material->queued = false;
        const auto& set = material->material->uniforms();
        const bool changed = set->refresh();
        if (changed || material->fresh) (void)material->pool->write(*material->slot, set->bytes(), material->fresh);
        material->fresh = false;
    }
    stale_materials_.clear();
    for (auto& [size, pool] : material_pools_) LOOM_TRY(pool->upload(device, stats_.material_uploads));

    // Render queues whose bundles changed.
    for (auto& queue : queues_) {
        if (!queue->dirty) continue;
        LOOM_TRY(rebuild(*queue));
        LOOM_TRY(upload_queue(*queue));
        ++stats_.queue_rebuilds;
        queue->dirty = false;
    }
    return {};
}

Status RetainedScene::rebuild(Queue& queue) {
    struct Item {
        uint32_t kind_rank;
        rhi::CullMode cull;
        rhi::FrontFace front_face;
        uint32_t vertex_pool;
        uint64_t material;  ///< 0 when the program reads none
        uint64_t geometry;
        uint64_t sequence;
        ObjectEntry* object;
        const Program* program;
        bool reads_material;

        [[nodiscard]] auto key() const { return std::tie(kind_rank, cull, front_face, vertex_pool, material); }
    };
    std::vector<Item> items;
    items.reserve(queue.members.size());
    for (ObjectEntry* object : queue.members) {
        const Shape& shape = *object->shape;
        const Program* program = queue.pass->program_for_kind(*shape.kind());
        if (!program || !object->geometry->placement) {
            return make_error(ErrorCode::InvalidState, "pass '" + queue.pass->name() + "': " + shape_name(shape) +
                                                           " has no program or no place in the shared buffers");
        }
        const GpuMaterial& material = *object->material->material;
        const bool reads = reads_material(*program, material);
        items.push_back(Item{kind_ranks_.at(shape.kind()->name()), material.cull(), object->front_face,
                             object->geometry->placement->vertex_pool, reads ? material.id() : 0,
                             object->geometry->geometry->id(), object->sequence, object, program, reads});
    }
    if (queue.order == QueueOrder::Sorted) {
        std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) {
            return std::tie(a.kind_rank, a.cull, a.front_face, a.vertex_pool, a.material, a.geometry, a.sequence) <
                   std::tie(b.kind_rank, b.cull, b.front_face, b.vertex_pool, b.material, b.geometry, b.sequence);
        });
    } else {
        std::sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.sequence < b.sequence; });
    }

    queue.batches.clear();
    queue.states.clear();
    queue.commands.clear();
    queue.instances.clear();
    for (std::size_t i = 0; i < items.size(); ++i) {
        const Item& item = items[i];
        const bool new_batch = i == 0 || item.key() != items[i - 1].key();
        if (new_batch) {
            DrawBatch batch;
            batch.kind = item.object->shape->kind()->name();
            batch.cull = item.cull;
            batch.front_face = item.front_face;
            batch.vertex_pool = item.vertex_pool;
            batch.material = item.material;
            batch.first_command = static_cast<uint32_t>(queue.commands.size());
            queue.batches.push_back(batch);
            queue.states.push_back(BatchState{item.program, item.object->shape->kind().get(),
                                              item.reads_material ? item.object->material : nullptr,
                                              item.object->instance_slot});
        }
        DrawBatch& batch = queue.batches.back();
        // Consecutive bundles of one geometry in a batch: one instanced command.
        if (!new_batch && item.geometry == items[i - 1].geometry) {
            ++queue.commands.back().instance_count;
        } else {
            const GeometryPlacement& placement = *item.object->geometry->placement;
            rhi::DrawIndexedIndirectCommand command;
            command.index_count = placement.index_count;
            command.instance_count = 1;
            command.first_index = placement.first_index;
            command.base_vertex = static_cast<int32_t>(placement.first_vertex);
            command.first_instance = static_cast<uint32_t>(queue.instances.size());
            queue.commands.push_back(command);
            ++batch.command_count;
        }
        queue.instances.push_back(item.object->slot);
        ++batch.bundles;
    }
    if (queue.order == QueueOrder::Sorted) {
        queue.distinct_keys = queue.batches.size();
    } else {
        std::vector<std::tuple<uint32_t, rhi::CullMode, rhi::FrontFace, uint32_t, uint64_t>> distinct;
        for (const Item& item : items) {
            distinct.emplace_back(item.kind_rank, item.cull, item.front_face, item.vertex_pool, item.material);
        }
        std::sort(distinct.begin(), distinct.end());
        queue.distinct_keys = static_cast<uint64_t>(std::unique(distinct.begin(), distinct.end()) - distinct.begin());
    }
    return {};
}

Status RetainedScene::upload_queue(Queue& queue) {
    const std::string name = "render queue '" + queue.pass->name() + "'";
    LOOM_TRY(sync_buffer(*device_, queue.instance_buffer, queue.instance_capacity, rhi::BufferUsage::Vertex,
                         name + " instances", queue.instances, queue.uploaded_instances, stats_.queue_uploads));
    if (config_.indirect && device_->capabilities().draw_indirect) {
        LOOM_TRY(sync_buffer(*device_, queue.command_buffer, queue.command_capacity, rhi::BufferUsage::Indirect,
                             name + " commands", queue.commands, queue.uploaded_commands, stats_.queue_uploads));
    }
    return {};
}

Status RetainedScene::draw(DrawSourceContext& context) {
    fg::PassContext& frame = context.pass_context();
    LOOM_TRY(prepare(frame.device()));
    Queue* queue = find_queue(context.pass());
    if (!queue || queue->batches.empty()) return {};
    rhi::Device& device = frame.device();
    rhi::CommandList& commands = frame.commands();
    const bool indirect = config_.indirect && device.capabilities().draw_indirect;

    rhi::PipelineHandle bound_pipeline;
    const Program* bound_program = nullptr;
    const MaterialEntry* bound_material = nullptr;
    std::optional<std::pair<uint32_t, uint32_t>> bound_vertices;  // vertex pool, instance slot
    bool index_bound = false;
    for (std::size_t i = 0; i < queue->batches.size(); ++i) {
        const DrawBatch& batch = queue->batches[i];
        const BatchState& batch_state = queue->states[i];
        const Program& program = *batch_state.program;
        bool changed = false;

        PipelineState batch_pipeline = context.state();
        batch_pipeline.raster.cull = batch.cull;
        batch_pipeline.raster.front_face = batch.front_face;
        auto pipeline = context.pipeline(program, batch_pipeline, *batch_state.kind);
        if (!pipeline) return pipeline.take_error();
        if (*pipeline != bound_pipeline) {
            commands.set_pipeline(*pipeline);
            LOOM_TRY(context.bind_pass_set(program));
            bound_pipeline = *pipeline;
            ++stats_.pipeline_changes;
            changed = true;
        }
        // Set 1: the record buffer and the material, bound again for another program (its
        // binding numbers may differ) or another material.
        if (&program != bound_program || batch_state.material != bound_material) {
            Bindings object_set(program, commands, kObjectSet);
            if (program.find("ObjectRecords")) object_set.buffer("ObjectRecords", object_records_.whole());
            for (const auto& [name, binding] : shared_buffers_) {
                if (program.find(name)) object_set.buffer(name, binding);
            }
            if (const MaterialEntry* material = batch_state.material) {
                const GpuMaterial& m = *material->material;
                if (material->slot && program.find(m.uniforms()->block())) {
                    object_set.buffer(m.uniforms()->block(), material->pool->binding(*material->slot));
                }
                for (const MaterialTexture& texture : m.textures()) {
                    if (!program.find(texture.name)) continue;
                    auto sampler = context.sampler(texture.sampler);
                    if (!sampler) return sampler.take_error();
                    object_set.texture(texture.name, texture.texture, *sampler);
                }
            }
            LOOM_TRY(object_set.bind());
            bound_program = &program;
            bound_material = batch_state.material;
            ++stats_.material_changes;
            changed = true;
        }
        const std::pair<uint32_t, uint32_t> vertices{batch.vertex_pool, batch_state.instance_slot};
        if (bound_vertices != vertices) {
            const VertexPool& pool = geometry_.vertex_pools()[batch.vertex_pool];
            for (uint32_t slot = 0; slot < pool.buffers.size(); ++slot) commands.set_vertex_buffer(slot, pool.buffers[slot]);
            commands.set_vertex_buffer(batch_state.instance_slot, queue->instance_buffer);
            bound_vertices = vertices;
            ++stats_.buffer_changes;
            changed = true;
        }
        if (!index_bound) {
            commands.set_index_buffer(geometry_.index_buffer(), rhi::IndexType::Uint32);
            index_bound = true;
        }
        if (changed) ++stats_.state_changes;

        if (indirect) {
            commands.draw_indexed_indirect(queue->command_buffer,
                                           uint64_t{batch.first_command} * sizeof(rhi::DrawIndexedIndirectCommand),
                                           batch.command_count);
            ++stats_.draw_calls;
        } else {
            for (uint32_t c = 0; c < batch.command_count; ++c) {
                const rhi::DrawIndexedIndirectCommand& command = queue->commands[batch.first_command + c];
                commands.draw_indexed(command.index_count, command.instance_count, command.first_index,
                                      command.base_vertex, command.first_instance);
            }
            stats_.draw_calls += batch.command_count;
        }
        stats_.commands_drawn += batch.command_count;
        stats_.bundles_drawn += batch.bundles;
        ++stats_.batches_drawn;
    }
    stats_.distinct_keys += queue->distinct_keys;
    return {};
}

std::vector<DrawBatch> RetainedScene::batches(const ShaderPass& pass) const {
    const Queue* queue = find_queue(pass);
    return queue ? queue->batches : std::vector<DrawBatch>{};
}

std::vector<rhi::DrawIndexedIndirectCommand> RetainedScene::commands(const ShaderPass& pass) const {
    const Queue* queue = find_queue(pass);
    return queue ? queue->commands : std::vector<rhi::DrawIndexedIndirectCommand>{};
}

std::vector<uint32_t> RetainedScene::instances(const ShaderPass& pass) const {
    const Queue* queue = find_queue(pass);
    return queue ? queue->instances : std::vector<uint32_t>{};
}

void RetainedScene::set_shared_buffer(const std::string& name, const rhi::BufferBinding& binding) {
    if (!binding.buffer) {
        shared_buffers_.erase(name);
    } else {
        shared_buffers_[name] = binding;
    }
}

void RetainedScene::release_gpu() {
    for (auto& queue : queues_) queue->release(device_);
    geometry_.release_gpu();
    object_records_.release_gpu();
    for (auto& [size, pool] : material_pools_) pool->release_gpu();
    // Everything is placed and written again by the next prepare().
    to_place_.clear();
    for (auto& [key, entry] : geometries_) {
        entry->placement.reset();
        to_place_.push_back(entry.get());
    }
    device_ = nullptr;
}

}  // namespace loom::passes
