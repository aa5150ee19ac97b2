#pragma once
// The retained object layer (after the LPSG manual's renderer): the application submits shapes
// once and retracts them when they go; every pass attached to the scene draws every submitted
// shape (or those naming it), frame after frame, from structures made for drawing fast instead
// of walking the application's objects:
//
//   - render bundles in render queues: per attached pass, one bundle per shape (its geometry
//     range, its object's record slot, the pass's program for its kind, its material). A
//     Sorted queue orders bundles by state key — program and raster state, vertex buffers,
//     material — so that every key is bound once; a Submission queue keeps submission order
//     (for blending) and binds again whenever the key changes. Bundles with one key become
//     one batch, drawn with one draw_indexed_indirect (a multi-draw; one draw_indexed per
//     command where the device has no indirect draws), bundles of one key and one geometry
//     one instanced command.
//   - shared buffers (geometry_buffers.hpp): every geometry's vertices and indices in a few
//     large buffers, drawn by base vertex and first index; ranges of retracted geometries are
//     reused.
//   - uniform sets by frequency (uniform_set.hpp): per object an ObjectRecord in one storage
//     buffer addressed by the object's slot, per material a MaterialUniforms block in one
//     uniform buffer bound at the material's offset; only sets whose parameters changed are
//     recomputed, and only those whose bytes changed are uploaded.
//   - finalize and upload queues: submit() and retract() touch no GPU object. At the start of
//     the next frame that draws (prepare(), called by the first attached pass to draw), new
//     geometries are placed in the shared buffers, then stale uniform sets are refreshed and
//     uploaded (grouped per buffer, adjacent slots in one write), then the render queues that
//     changed are rebuilt and their draw lists uploaded.
//
//   RetainedScene scene;
//   scene.attach(*gbuffer);                                  // a GeometryPass, before add_pass
//   auto model = std::make_shared<InputParam<glm::mat4>>(transform);
//   scene.submit(std::make_shared<Shape>("crate", retained_pbr_mesh_kind(), crate_geometry,
//                                        wood, model));
//   ... executor.run_frame(graph, options) every frame; model->set(m) to move the crate ...
//
// A shape's kind must follow the retained convention (retained_mesh.hpp). One scene draws on
// one device; destroy it (or release_gpu()) before the device. A shape or material is
// submitted to one scene at a time.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "loom/passes/draw_source.hpp"
#include "loom/passes/geometry_buffers.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/passes/shape.hpp"
#include "loom/passes/uniform_set.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::passes {

/// How a render queue orders its bundles.
enum class QueueOrder : uint8_t {
    Sorted,      ///< by state key, every key bound once (opaque geometry)
    Submission,  ///< in submission order (blending); consecutive bundles of one key still batch
};

/// Sizes the shared buffers start with (they double when full) and how batches are drawn.
struct RetainedConfig {
    uint32_t initial_vertices = 1u << 16;  ///< per vertex layout
    uint32_t initial_indices = 1u << 18;
    uint32_t initial_objects = 1024;       ///< object record slots
    uint32_t initial_materials = 64;
    /// Draw every batch with one draw_indexed_indirect where the device has indirect draws
    /// (Capabilities::draw_indirect); false, or a device without them: one draw_indexed per
    /// command of the batch.
    bool indirect = true;
};

/// One batch of a render queue: bundles that share a state key, drawn together.
struct DrawBatch {
    std::string kind;
    rhi::CullMode cull = rhi::CullMode::Back;
    rhi::FrontFace front_face = rhi::FrontFace::CounterClockwise;
    uint32_t vertex_pool = 0;
    /// The material bound for the batch; 0 when the pass's program reads no material (the
    /// shadow map), which then plays no part in the key.
    uint64_t material = 0;
    uint32_t first_command = 0;  ///< into commands()
    uint32_t command_count = 0;
    uint32_t bundles = 0;
};

/// Work of the scene, counted since reset_stats().
struct RetainedStats {
    // prepare(): the finalize and upload queues.
    uint64_t geometries_placed = 0;
    UploadStats geometry_uploads;   ///< vertices and indices into the shared buffers
    UploadStats object_uploads;     ///< per-object sets (ObjectRecord)
    UploadStats material_uploads;   ///< per-material sets
    UploadStats queue_uploads;      ///< instance lists and indirect commands of rebuilt queues
    uint64_t object_sets_refreshed = 0;  ///< stale per-object sets recomputed
    uint64_t queue_rebuilds = 0;
    // draw(): per pass and frame, summed.
    uint64_t bundles_drawn = 0;
    uint64_t batches_drawn = 0;
    uint64_t draw_calls = 0;        ///< draw_indexed_indirect or draw_indexed commands recorded
    uint64_t commands_drawn = 0;    ///< indirect commands (one per run of instances)
    uint64_t state_changes = 0;     ///< batches whose state key differs from the batch before
    uint64_t pipeline_changes = 0;
    uint64_t material_changes = 0;  ///< set-1 bind groups (material and record buffer)
    uint64_t buffer_changes = 0;    ///< vertex/index buffer bindings changed
    uint64_t distinct_keys = 0;     ///< distinct state keys of the queues drawn

    /// Bytes the scene wrote with Device::write_buffer.
    [[nodiscard]] uint64_t uploaded_bytes() const {
        return geometry_uploads.bytes + object_uploads.bytes + material_uploads.bytes + queue_uploads.bytes;
    }
};

/// The scene is the draw source (draw_source.hpp) of every pass attached to it.
class RetainedScene final : public DrawSource {
public:
    explicit RetainedScene(RetainedConfig config = {});
    /// Detaches every pass and destroys the scene's buffers (its device must still be alive).
    ~RetainedScene() override;
    RetainedScene(const RetainedScene&) = delete;
    RetainedScene& operator=(const RetainedScene&) = delete;

    /// Makes `pass` draw the scene's shapes (a render queue for it, filled with the shapes
    /// submitted so far), in draw_objects() after its registered objects. Errors: the pass is
    /// attached to another scene, a shape's kind does not compile for the pass.
    Status attach(ShaderPass& pass, QueueOrder order = QueueOrder::Sorted);
    /// Drops the pass's render queue (a pass that is destroyed detaches itself).
    void detach(ShaderPass& pass) override;

    /// Submits `shape`: a bundle in the queue of every attached pass it names (all of them when
    /// it names none), drawn from the next frame on. Composes and compiles the programs of a
    /// kind new to a pass. Errors (InvalidArgument, naming the shape): a missing part, a kind
    /// that does not follow the retained convention, geometry whose layouts differ from the
    /// kind's, a shape already submitted; the kind's compile errors.
    Status submit(std::shared_ptr<Shape> shape);
    /// Removes `shape` from every queue and releases what only it used: its record slot, and
    /// its geometry's ranges and material's slot when no other shape uses them. InvalidArgument
    /// when it was not submitted.
    Status retract(const Shape& shape);
    [[nodiscard]] bool submitted(const Shape& shape) const;
    /// Shapes submitted now.
    [[nodiscard]] std::size_t size() const { return objects_.size(); }

    /// Runs the finalize and upload queues on `device` and rebuilds the render queues that
    /// changed (see the top of this file). Attached passes call it before drawing; with nothing
    /// queued it costs nothing, so calling it again in a frame is free. The first call binds
    /// the scene to `device`; another device is an InvalidState error.
    Status prepare(rhi::Device& device);
    /// Records the render queue of `context.pass()` (ShaderPass::draw_objects calls it): per
    /// batch the pipeline (the pass's state with the batch's raster state; the pass's set 0
    /// bound after each pipeline change), the shared buffers, the material's set, and the draw.
    /// Runs prepare() first.
    Status draw(DrawSourceContext& context) override;

    /// The batches, indirect commands and instance list (object slots) of `pass`'s queue as of
    /// the latest prepare(); empty for a pass that is not attached.
    [[nodiscard]] std::vector<DrawBatch> batches(const ShaderPass& pass) const;
    [[nodiscard]] std::vector<rhi::DrawIndexedIndirectCommand> commands(const ShaderPass& pass) const;
    [[nodiscard]] std::vector<uint32_t> instances(const ShaderPass& pass) const;
    /// A buffer the shapes' programs may read besides their records and materials (e.g. a skin's
    /// joint palette): bound in set 1 under `name` for every batch whose program declares a
    /// resource of that name. The caller keeps it alive and writes it; setting a name again
    /// replaces the binding, an empty buffer removes it.
    void set_shared_buffer(const std::string& name, const rhi::BufferBinding& binding);
    /// The record slot of a submitted shape; nullopt when it is not submitted.
    [[nodiscard]] std::optional<uint32_t> object_slot(const Shape& shape) const;

    [[nodiscard]] const RetainedStats& stats() const { return stats_; }
    void reset_stats() { stats_ = {}; }
    /// The shared vertex and index buffers.
    [[nodiscard]] const GeometryBuffers& geometry_buffers() const { return geometry_; }
    /// Geometries and materials in use now.
    [[nodiscard]] std::size_t geometry_count() const { return geometries_.size(); }
    [[nodiscard]] std::size_t material_count() const { return materials_.size(); }

    /// Destroys every GPU object of the scene; the next prepare() makes them again (on any device).
    void release_gpu();

private:
    struct GeometryEntry;
    struct MaterialEntry;
    struct ObjectEntry;
    struct BatchState;
    struct Queue;

    Queue* find_queue(const ShaderPass& pass) const;
    Status add_to_queue(Queue& queue, ObjectEntry& object);
    void remove_from_queue(Queue& queue, ObjectEntry& object);
    Status rebuild(Queue& queue);
    Status upload_queue(Queue& queue);
    void mark_all_queues_dirty();

    RetainedConfig config_;
    rhi::Device* device_ = nullptr;
    GeometryBuffers geometry_;
    UniformSetPool object_records_;
    std::map<uint32_t, std::unique_ptr<UniformSetPool>> material_pools_;  ///< by set size
    std::vector<std::unique_ptr<Queue>> queues_;
    std::map<const Shape*, std::unique_ptr<ObjectEntry>> objects_;
    std::map<const Geometry*, std::unique_ptr<GeometryEntry>> geometries_;
    std::map<const GpuMaterial*, std::unique_ptr<MaterialEntry>> materials_;
    std::map<std::string, uint32_t> kind_ranks_;  ///< kinds in order of first submission
    std::map<std::string, rhi::BufferBinding> shared_buffers_;
    // The finalize queue (geometries to place) and the upload queue (stale sets).
    std::vector<GeometryEntry*> to_place_;
    std::vector<ObjectEntry*> stale_objects_;
    std::vector<MaterialEntry*> stale_materials_;
    uint64_t next_sequence_ = 0;
    RetainedStats stats_;
};

}  // namespace loom::passes
