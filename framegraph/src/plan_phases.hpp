#pragma once
// Internal: the phases of build_plan (planner.cpp), each a function from plain data to plain
// data so that each can be tested on its own (tests/framegraph/plan_phases_test.cpp). In order:
//   cull          which passes run                                     plan_schedule.cpp
//   schedule      their order, and each pass's position in it          plan_schedule.cpp
//   join          the port groups, each with the join of its specs     plan_resources.cpp
//   resolve       the logical resources: resolved specs, usages,       plan_resources.cpp
//                 lifetimes, bytes; each running pass's ports, edges
//                 (build_plan joins and resolves each group in turn, keeping no group)
//   order         under PassOrder::Memory, another order of the same   plan_order.cpp,
//                 passes for a lower peak; the resources renumbered    planner.cpp
//   queues        semaphores and ownership transfers between the       plan_queues.cpp
//                 graphics and async compute queues; occupancies
//   spec classes  which resources may share a texture; the peaks       plan_allocation.cpp
//   allocate      the allocation problem, the allocator's checked      plan_allocation.cpp
//                 answer, textures numbered by first use, heaps
//   summary       the figures that make allocators comparable          plan_allocation.cpp
// The barriers are not a phase of planning: build_execution_schedule (execution_schedule.cpp)
// derives them from a finished plan, once per plan and set of bindings.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "graph_analysis.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg::detail {

/// Schedule::position of a pass that does not run.
inline constexpr uint32_t kNotScheduled = UINT32_MAX;
/// ResolvedResources::resource_of_port of a port without a resource.
inline constexpr uint32_t kNoResource = UINT32_MAX;

/// Cull: per pass (declaration order), whether it runs: a pass runs when it has side effects,
/// produces a graph output, or produces a texture a running pass reads. ErrorCode::Graph when
/// nothing would run.
Result<std::vector<bool>> cull_passes(const FrameGraph& graph, const Dependencies& dependencies);

/// The names of the passes that do not run, in declaration order (Plan::culled).
std::vector<std::string> culled_pass_names(const FrameGraph& graph, const std::vector<bool>& kept);

/// The execution order of the passes that run.
struct Schedule {
    std::vector<uint32_t> order;     ///< passes by declaration index, in execution order
    std::vector<uint32_t> position;  ///< per pass, its index in `order`; kNotScheduled when culled
};

/// Schedule: Kahn's algorithm over the kept passes; of the passes ready at once, the one
/// declared first runs first.
Schedule schedule_passes(const Dependencies& dependencies, const std::vector<bool>& kept);

/// The schedule that runs `declared`'s passes in `order` (indices into declared.order).
Schedule reorder_schedule(const Schedule& declared, const std::vector<uint32_t>& order);

/// A connected group of ports: an output (or an unconnected inout) and everything it feeds,
/// directly or through inouts. One logical resource when its producer runs.
struct JoinedGroup {
    std::vector<PortAddress> ports;  ///< the starting port first, then breadth-first by connection order
    /// The join of the ports' specs in group order; on a conflict, the error naming the port that
    /// first constrained the property and the port that contradicts it. For a buffer group the
    /// empty spec.
    Result<TextureSpec> spec;
    ResourceType type = ResourceType::Texture;
    /// A buffer group's join, as `spec` is a texture group's; the empty spec for textures.
    Result<BufferSpec> buffer = BufferSpec{};
    /// Two of its ports declare sizes differently (an absolute and a relative one), which only
    /// a frame size can compare: the join holds for this frame size only.
    bool sizes_compared = false;

    /// The group's join error, if any.
    [[nodiscard]] Status status() const;
};

/// How a port uses its texture given its role and its pass's kind (both in its facts): a
/// graphics pass writes attachments (an explicit Storage request turns an attachment write or a
/// sampled read into a storage access) and samples; a compute pass writes storage images and
/// samples; a copy pass writes copy destinations and reads copy sources.
rhi::TextureUsage port_texture_usage(const PortFacts& port, rhi::Format format);

/// `range` with concrete counts for a texture of `mips` levels and `layers` layers; nullopt
/// when it reaches past them or is empty.
std::optional<SubresourceRange> resolve_range(const SubresourceRange& range, uint32_t mips, uint32_t layers);
/// `bytes` with a concrete size for a buffer of `size` bytes; nullopt when it reaches past it.
std::optional<BufferRange> resolve_bytes(const BufferRange& bytes, uint64_t size);

/// How a port uses its buffer: a write is Storage (CopyDst in a copy pass); a read is the one
/// read usage the port declares (vertex, index, indirect, uniform, storage; copy in a copy pass),
/// Storage (CopySrc) when it declares none. ErrorCode::Graph naming the port (its name built
/// only then) when it declares several read usages.
Result<rhi::BufferUsage> port_buffer_usage(const FrameGraph& graph, PortAddress address);
/// What a buffer port does by its role alone: Storage, or in a copy pass CopyDst (writes) and
/// CopySrc (reads).
rhi::BufferUsage default_buffer_use(PortKind kind, PassKind pass_kind);

/// Join: every group of the graph, in declaration order of their starting ports, with its join.
/// Groups of culled passes are joined too: a bad connection is an error either way.
std::vector<JoinedGroup> join_port_groups(const FrameGraph& graph, Extent2D frame);

/// A value per port of a graph, stored flat (pass by pass, each pass's ports in order): one
/// array for the whole graph instead of a vector per pass. table[pass][port] reads and writes
/// as a vector of vectors would.
class PortTable {
public:
    PortTable() = default;
    /// `value` for every port of `graph`.
    PortTable(const FrameGraph& graph, uint32_t value);

    [[nodiscard]] std::span<uint32_t> operator[](uint32_t pass) {
        return {values_.data() + first_[pass], values_.data() + first_[pass + 1]};
    }
    [[nodiscard]] std::span<const uint32_t> operator[](uint32_t pass) const {
        return {values_.data() + first_[pass], values_.data() + first_[pass + 1]};
    }
    /// Number of passes.
    [[nodiscard]] uint32_t size() const { return first_.empty() ? 0 : static_cast<uint32_t>(first_.size() - 1); }
    /// Every value, pass by pass.
    [[nodiscard]] std::span<uint32_t> values() { return values_; }

    friend bool operator==(const PortTable&, const PortTable&) = default;
    /// Equal to the same values given per pass (tests write them so).
    friend bool operator==(const PortTable& table, const std::vector<std::vector<uint32_t>>& per_pass);

private:
    std::vector<uint32_t> first_;  // per pass, where its ports start in values_; one more at the end
    std::vector<uint32_t> values_;
};

/// The logical resources of the passes that run.
struct ResolvedResources {
    /// In order of their producers' positions, then by port; spec_class and texture are not
    /// assigned yet.
    std::vector<PlanResource> resources;
    /// Per pass, per port: the index of its resource, or kNoResource (culled passes, unconnected
    /// optional inputs, optional outputs nobody reads).
    PortTable resource_of_port;
    /// The resources of the graph outputs, in marking order, each once.
    std::vector<uint32_t> graph_output_resources;
    /// Per resource, the port that starts it.
    std::vector<PortAddress> starts;
    /// Per resource, its ports whose passes run, the starting port first (group order):
    /// resource r's are running_ports[first_running_port[r], first_running_port[r + 1]).
    /// PlanResource::ports is left empty until the plan names them (name_resource_ports): a
    /// reordered copy then moves no strings.
    std::vector<PortAddress> running_ports;
    std::vector<uint32_t> first_running_port{0};
    /// Per resource, the size its ports joined to: what re-planning for another frame size
    /// evaluates again (plan_resize.hpp). Nullopt for buffers and for textures no port sized
    /// (the frame's size).
    std::vector<std::optional<SizeSpec>> joined_sizes;
    /// The buffer resources' joined sizes, by resource index.
    std::vector<std::pair<uint32_t, BufferSize>> joined_buffer_sizes;
    /// Some group's join, a culled one's included, compared differently declared sizes against
    /// the frame (JoinedGroup::sizes_compared).
    bool joins_compared_sizes = false;

    [[nodiscard]] std::span<const PortAddress> running_ports_of(uint32_t r) const {
        return {running_ports.data() + first_running_port[r], running_ports.data() + first_running_port[r + 1]};
    }
};

/// Resolve: a resource for each group whose producer runs, except an optional output no running
/// pass reads: its joined spec resolved for `frame`, with the usage its running ports' roles
/// need (and CopySrc when it is a graph output); the positions from its producer to its last
/// running reader (a graph output lives to the last position); bytes and alignment from
/// `memory`. The first group at fault in group order gives the error: its join error, or its
/// resolve error naming its running ports, or the memory model's.
Result<ResolvedResources> resolve_resources(const FrameGraph& graph, const std::vector<JoinedGroup>& groups,
                                            const Schedule& schedule, Extent2D frame, MemoryModel& memory);
/// The bytes and alignment of `resource`, a texture (its `spec`) or a buffer (its
/// `buffer_spec`), from `memory`. Errors: the memory model's, or ErrorCode::Graph for a buffer
/// whose size overflows when aligned.
Status measure_resource(PlanResource& resource, MemoryModel& memory);

/// Join and resolve in one: the same resources and the same first error as
/// resolve_resources(graph, join_port_groups(graph, frame), ...), with each group joined and
/// resolved as it is collected, so that no group's ports or join are kept (what build_plan runs).
Result<ResolvedResources> resolve_resources(const FrameGraph& graph, const Schedule& schedule, Extent2D frame,
                                            MemoryModel& memory);

/// Join and resolve again for one texture resource whose group starts at `start`, after texture
/// specs of its ports changed (position: per pass, its position in the order or
/// kNotScheduled): `resource`'s spec (usage: its running ports'), requested format and bytes,
/// the size its ports joined to, and in `running` its ports that run. Errors: the join's or
/// resolve's; also ErrorCode::Join when the join compared differently declared sizes against the
/// frame (JoinedGroup::sizes_compared), which a plan made from the previous one cannot keep.
Status rejoin_resource(const FrameGraph& graph, PortAddress start, std::span<const uint32_t> position, Extent2D frame,
                       MemoryModel& memory, PlanResource& resource, std::optional<SizeSpec>& joined_size,
                       std::vector<PortAddress>& running);

/// Fills in every resource's PlanResource::ports: the names of its running ports, taken from
/// `order`, the plan's passes (plan_passes of the same resources), which the planner has in cache
/// when it names them.
void name_resource_ports(const std::vector<PlanPass>& order, ResolvedResources& resolved);

/// The same resources for another order of the same passes: lifetimes (and occupancies) from
/// `schedule`, renumbered in order of their producers' positions, then by port, as
/// resolve_resources numbers them.
ResolvedResources reorder_resources(const ResolvedResources& resolved, const Schedule& schedule);

/// The passes that run, in order, each port with its resource and the usage its role needs
/// (Plan::order). The resources come from resolve_resources, which checked every port's usage.
std::vector<PlanPass> plan_passes(const FrameGraph& graph, const Schedule& schedule, const ResolvedResources& resolved);

/// The connections between passes that run, by position, each with its resource (Plan::edges).
std::vector<PlanEdge> plan_edges(const FrameGraph& graph, const Schedule& schedule,
                                 const PortTable& resource_of_port);

/// What running passes on two queues decides (Plan::queue_syncs, Plan::ownership_transfers,
/// PlanResource::occupancy).
struct QueuePlan {
    std::vector<QueueSync> syncs;
    std::vector<OwnershipTransfer> transfers;
    std::vector<Lifetime> occupancy;  ///< per resource
    std::vector<bool> queue_shared;   ///< per resource (PlanResource::queue_shared)
};

/// Queues: without async passes, no syncs or transfers and every occupancy is the lifetime.
/// Otherwise the transfers (a read on the other queue than the previous use's; a graph output
/// last used on the async queue goes back to graphics at the end of the frame; a first use
/// that reads on the async queue starts from graphics at the start of the frame), then the
/// fewest semaphores that order every cross-queue dependency, every transfer, the start of the
/// frame before the first async pass and the end of the frame after the last (a wait is left
/// out when an earlier wait on that queue already covers it), then the occupancies: each async use widened over the positions between
/// the last signal its queue waited for and the first wait on a signal after it.
QueuePlan plan_queues(const std::vector<PlanPass>& order, const std::vector<PlanResource>& resources,
                      const Dependencies& dependencies, const Schedule& schedule);

/// Which resources may share a texture.
struct SpecClassAssignment {
    std::vector<SpecClass> classes;           ///< with their members and peak live counts (Plan::spec_classes)
    std::vector<uint32_t> class_of_resource;  ///< per resource, an index into `classes`
    uint64_t peak_live_bytes = 0;             ///< most bytes of resources alive at one position
};

/// Spec classes: under SpecSharing::Equal a class per texture shape (its spec's usage the union
/// of its members'); under Joinable each resource joins the first class whose spec joins with
/// its own, widening that spec, or starts a class. Then the peaks over `position_count`
/// positions: the most members of each class alive at once, and the most live bytes.
SpecClassAssignment assign_spec_classes(const std::vector<PlanResource>& resources, SpecSharing sharing, Extent2D frame,
                                        uint32_t position_count);

/// The problem an allocator is given: per position of `order` the resources its ports read and
/// write and the resources that start there, and every resource (spec_class assigned) with its
/// class, lifetime, bytes and alignment. Without `with_pass_lists` (Allocator::reads_pass_lists)
/// the per-position lists stay empty.
AllocationProblem make_allocation_problem(const std::vector<PlanPass>& order,
                                          const std::vector<PlanResource>& resources,
                                          std::vector<uint32_t> graph_output_resources, uint32_t spec_class_count,
                                          uint64_t max_heap_bytes, bool with_pass_lists = true);

/// The textures and buffers an allocation makes.
struct TextureAssignment {
    std::vector<uint32_t> texture_of_resource;  ///< per resource, an index into `textures` (kNoPhysical: a buffer)
    std::vector<PlanTexture> textures;          ///< numbered by first use (Plan::textures)
    std::vector<uint64_t> heaps;                ///< Plan::heaps
    std::vector<uint32_t> buffer_of_resource;   ///< per resource, an index into `buffers` (kNoPhysical: a texture)
    std::vector<PlanBuffer> buffers;            ///< numbered by first use (Plan::buffers)
};

/// Allocate: runs `allocator` on `problem` and checks its answer (ErrorCode::Graph naming the
/// allocator: a texture index per resource below the texture count, a placement per texture if
/// any, no texture without a resource, only resources whose specs join in one texture, never a
/// texture and a buffer in one object). Textures and buffers are each numbered by their first
/// resource; each has the join of its resources' specs and, when
/// shared, the bytes `memory` gives for that join (else its resource's bytes).
Result<TextureAssignment> allocate_textures(const Allocator& allocator, const AllocationProblem& problem,
                                            const std::vector<PlanResource>& resources, Extent2D frame,
                                            MemoryModel& memory);

/// Spec classes, allocate and summary for `plan`, whose order and resources (occupancies
/// included) are final: fills in the resources' classes, textures and buffers, and the plan's
/// spec classes, textures, buffers, heaps and summary.
Status allocate_plan(Plan& plan, const PlanOptions& options, const Allocator& allocator, MemoryModel& memory,
                     std::vector<uint32_t> graph_output_resources);

/// allocate_plan for `plan`, allocated before, whose resources changed in shape or usage only
/// (FrameGraph::plan for another frame size or other texture specs): when `allocator` does not
/// read bytes (Allocator::reads_bytes) and equal sharing keeps the classes as they are, the
/// allocation is the one the plan has, and only the shapes and usages of its classes, textures
/// and buffers and its summary are made anew; else allocate_plan.
Status allocate_resized_plan(Plan& plan, const PlanOptions& options, const Allocator& allocator, MemoryModel& memory,
                             std::vector<uint32_t> graph_output_resources);

/// Summary: the figures of a plan whose other fields are filled (Plan::summary); the lower bound
/// of bytes is `peak_live_bytes` (SpecClassAssignment).
PlanSummary summarize_plan(const Plan& plan, uint64_t peak_live_bytes);

}  // namespace loom::fg::detail
