#pragma once
// Runs frame-graph plans on a rhi::Device.
//
//   fg::FrameGraph graph;
//   graph.add_pass(fg::Pass("gbuffer").output("albedo", spec).output("depth", depth_spec)
//                      .on_execute([&](fg::PassContext& ctx) {
//                          ctx.begin_render_pass({{"albedo", {0, 0, 0, 1}}}, "depth");
//                          ...draw...
//                          ctx.end_render_pass();
//                          return Status{};
//                      }));
//   ... more passes (or subclasses of fg::Pass overriding execute) ...
//   graph.mark_output(fg::port("composite", "final"));
//
//   fg::Executor executor(device);
//   fg::PlanOptions options;
//   options.frame = {1280, 720};
//   executor.run_frame(graph, options);              // begin_frame + every pass + end_frame
//   device.read_texture(executor.texture("composite", "final"));
//
//   // or inside a frame the application records itself (e.g. into the window's back buffer):
//   rhi::CommandList& cmd = device.begin_frame();
//   executor.import_texture(fg::port("composite", "final"), device.backbuffer(), rhi::ResourceState::Present);
//   executor.execute(graph, cmd, options);
//   device.end_frame();
//
// The executor plans the graph every frame (FrameGraph::plan returns the cached plan when
// nothing changed) and realises a plan once: one texture per plan texture and one buffer per
// plan buffer, placed at the plan's heap offsets where the plan has heaps and the device
// supports placed resources, otherwise one each. Resources persist across frames and are rebuilt only when the plan changes
// (a new frame size re-evaluates relative sizes: the old resources are released first).
// Transitions and load/store actions come from the ExecutionSchedule (execution_schedule.hpp),
// computed once per plan. Every pass is timed (CPU recording time, and GPU time through the
// RHI timers where the device has them).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/execution_schedule.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/framegraph/pass_context.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// A MemoryModel asking the device (rhi::Device::texture_memory_requirements), so that the
/// heap allocator's sizes, alignments and offsets are the device's.
class DeviceMemoryModel final : public MemoryModel {
public:
    /// A model asking `device` (which must outlive it).
    explicit DeviceMemoryModel(rhi::Device& device) : device_(&device) {}
    /// The device's size and alignment for `desc` (Device::texture_memory_requirements).
    Result<rhi::MemoryRequirements> requirements(const rhi::TextureDesc& desc) override;
    /// The device's size and alignment for `desc` (Device::buffer_memory_requirements).
    Result<rhi::MemoryRequirements> buffer_requirements(const rhi::BufferDesc& desc) override;

private:
    rhi::Device* device_;
};

/// Timings of one pass.
struct PassTiming {
    std::string pass;
    /// CPU time of the latest frame spent recording the pass (its execute() and the executor's
    /// transitions around it), in milliseconds.
    double cpu_ms = 0.0;
    /// GPU time from the latest frame whose results the device has (Device::timer_results may
    /// lag a frame or two); empty when the device has no timestamps or no result yet.
    std::optional<double> gpu_ms;
};

/// The resources the executor created next to the plan's figures.
struct ExecutionStats {
    // The plan.
    uint32_t plan_textures = 0;   ///< Plan::textures.size()
    uint32_t plan_heaps = 0;      ///< Plan::heaps.size()
    uint64_t plan_heap_bytes = 0; ///< sum of Plan::heaps
    uint64_t plan_bytes = 0;      ///< PlanSummary::bytes
    uint32_t plan_buffers = 0;    ///< Plan::buffers.size()
    // What the executor created for it (live now).
    uint32_t textures = 0;          ///< plan textures created (those all of whose resources are imported are not)
    uint32_t placed_textures = 0;   ///< of those, placed in heaps
    uint32_t history_textures = 0;  ///< textures keeping history (not in the plan)
    uint32_t heaps = 0;
    uint64_t heap_bytes = 0;        ///< sum of the created heaps' sizes
    uint64_t texture_bytes = 0;     ///< unplaced plan textures, by the plan's byte figures
    uint32_t buffers = 0;           ///< plan buffers created (those all of whose resources are imported are not)
    uint32_t placed_buffers = 0;    ///< of those, placed in heaps
    uint64_t buffer_bytes = 0;      ///< unplaced plan buffers, by the plan's byte figures
    /// How many times resources were (re)built; an unchanged plan builds nothing.
    uint64_t realisations = 0;
    /// What the device reports now (all objects on it, not only the executor's).
    rhi::ResourceStats device{};
};

/// Two lines: the plan's figures and what was created, e.g.
/// "plan: 6 textures, 1 heap (393216 bytes), 393216 bytes\ncreated: 6 textures (6 placed), ...".
std::string describe_stats(const ExecutionStats& stats);

/// A table of per-pass timings ("pass  cpu ms  gpu ms"), with a total line.
std::string describe_timings(const std::vector<PassTiming>& timings);

/// Realises plans on one device and records their passes (see the top of this file). Destroy
/// it before the device: it destroys what it created.
class Executor {
public:
    /// An executor creating its resources on `device`, which must outlive it.
    explicit Executor(rhi::Device& device);
    /// Releases every resource the executor created (textures before their heaps).
    ~Executor();
    Executor(const Executor&) = delete;
    Executor& operator=(const Executor&) = delete;

    /// The device the executor runs on.
    [[nodiscard]] rhi::Device& device() const;

    /// The device-backed memory model. execute() uses it by itself for the "heap" allocator on
    /// a device with placed resources when PlanOptions::memory_model is null.
    [[nodiscard]] std::shared_ptr<MemoryModel> memory_model() const;
    /// `options` as execute() plans with them (memory model filled in as described above).
    [[nodiscard]] PlanOptions effective_options(PlanOptions options) const;
    /// The allocator that needs the fewest bytes for `graph` on this device: "heap" where the
    /// device places resources (Capabilities::placed_resources) and its plan, with the
    /// device's memory model, needs fewer bytes than the "interval" allocator's; "interval"
    /// otherwise (a device without placed resources cannot alias a heap plan's textures).
    /// Plans the graph with both (`options` gives the frame, order and limits; its allocator is
    /// ignored). Errors: the graph's, as build_plan returns them.
    [[nodiscard]] Result<AllocatorKind> cheapest_allocator(const FrameGraph& graph, PlanOptions options) const;

    /// Binds an application texture to `port` (see ImportBinding): the executor writes or reads
    /// it in place of a plan texture and leaves it in `final_state` after its last use in the
    /// frame. Binding another texture to the same port (e.g. each frame's back buffer) costs
    /// nothing; its format and size are checked against the port's spec at execute(). Errors
    /// (checked at execute(), naming the port): unknown port, a mismatching texture.
    void import_texture(const PortRef& port, rhi::TextureHandle texture,
                        rhi::ResourceState final_state = rhi::ResourceState::ShaderRead);
    /// Removes the import of `port`; false when it had none.
    bool remove_import(const PortRef& port);

    /// Binds an application buffer to buffer port `port`, as import_texture does a texture (e.g.
    /// a scene's persistent light buffer that a compute pass fills and a lighting pass reads);
    /// it is left in `final_state` after its last use in the frame. Errors (checked at
    /// execute(), naming the port): unknown port, a texture port, a buffer smaller than the
    /// port's buffer or without the usage the ports need.
    void import_buffer(const PortRef& port, rhi::BufferHandle buffer,
                       rhi::ResourceState final_state = rhi::ResourceState::ShaderRead);
    /// Removes the buffer import of `port`; false when it had none.
    bool remove_buffer_import(const PortRef& port);

    /// Lets `reader` (an input port left unconnected; declare it optional) read the contents
    /// `source` had at the end of the previous frame. The executor keeps a history texture
    /// alive across frames and copies `source` into it once `source` is final in the frame (the
    /// source's texture gets CopySrc usage; an imported source must have it). Errors (checked
    /// at execute(), naming the port): see build_execution_schedule.
    void bind_history(const PortRef& reader, const PortRef& source);
    /// Removes the history binding of `reader`; false when it had none.
    bool remove_history(const PortRef& reader);

    /// Plans `graph` with `options` (effective_options) and records every pass that runs into
    /// `commands`, a frame the caller began (Device::begin_frame) and will end. Errors name the
    /// pass (or the texture, import, or planning step) at fault; after one, the remaining
    /// passes are not recorded and the command list is left balanced. A plan with async compute
    /// passes records each pass on its queue (CommandList::set_queue) with the plan's
    /// semaphores (Plan::queue_syncs) between them, and leaves `commands` on the graphics
    /// queue; no timer or debug group of the caller may then be open around the call.
    Status execute(FrameGraph& graph, rhi::CommandList& commands, const PlanOptions& options);
    /// begin_frame, execute, end_frame. An error end_frame reports is returned with the frame.
    Status run_frame(FrameGraph& graph, const PlanOptions& options);

    /// The plan of the latest execute(); null before the first.
    [[nodiscard]] std::shared_ptr<const Plan> plan() const;
    /// The schedule of the latest execute(); null before the first.
    [[nodiscard]] const ExecutionSchedule* schedule() const;
    /// The texture behind `pass`.`port` in the latest plan (a plan texture, an import, or for a
    /// history port the history texture the next frame will read); null when it has none.
    [[nodiscard]] rhi::TextureHandle texture(std::string_view pass, std::string_view port) const;
    /// The texture created for Plan::textures[index]; null when not created.
    [[nodiscard]] rhi::TextureHandle plan_texture(uint32_t index) const;
    /// The buffer behind buffer port `pass`.`port` in the latest plan (a plan buffer or an
    /// import); null when it has none.
    [[nodiscard]] rhi::BufferHandle buffer(std::string_view pass, std::string_view port) const;
    /// The buffer created for Plan::buffers[index]; null when not created.
    [[nodiscard]] rhi::BufferHandle plan_buffer(uint32_t index) const;

    /// Per-pass timings of the latest frame, in Plan::order.
    [[nodiscard]] std::vector<PassTiming> timings() const;
    /// The plan's figures next to what the executor created (see ExecutionStats).
    [[nodiscard]] ExecutionStats stats() const;
    /// Frames executed so far.
    [[nodiscard]] uint64_t frame_index() const;

    /// Destroys every resource now (the next execute() realises the plan again).
    Status release();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace loom::fg
