#pragma once
// A plan: everything the planner decided about one graph for one frame size, as plain data.
// It can be printed, compared (==), hashed, and exported as JSON and DOT (export.hpp). The
// executor realises it on a device: one rhi texture per PlanTexture (placed at its heap
// offset where the plan has heaps), each pass's ports resolved through PlanPort::resource →
// PlanResource::texture.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/buffer_spec.hpp"
#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/resolved_spec.hpp"
#include "loom/framegraph/texture_spec.hpp"

namespace loom::fg {

/// Which logical resources may share a physical texture.
enum class SpecSharing : uint8_t {
    Equal,     ///< only resources with the same resolved format, size, samples, mips and layers
    Joinable,  ///< also resources whose specs join (§6.2 allows it); the texture gets the join
};

/// "equal" or "joinable".
std::string_view spec_sharing_name(SpecSharing sharing);

/// How the planner orders the passes that run (PlanOptions::order). Every order runs each pass
/// after the passes it depends on (docs/framegraph.md, "Pass order").
enum class PassOrder : uint8_t {
    /// The declaration order, as far as the dependencies allow: of the passes ready at once,
    /// the one declared first runs first.
    Declared,
    /// An order that lowers the peak of live bytes (PlanSummary::lower_bound_bytes, the heap
    /// allocator's target), keeping side-effect passes and passes pinned with
    /// Pass::keep_declared_order in their declared relative order. Never a higher peak nor a
    /// bigger allocation than Declared: the planner keeps the declared order unless another
    /// lowers the peak and the chosen allocator places it in no more bytes.
    Memory,
};

/// The order planning uses unless told otherwise (PlanOptions::order, a graph file's "order",
/// the renderer's and samples' settings): Memory, which never needs more memory than Declared
/// and costs at most half as much planning time again at 10,000 passes (docs/BENCHMARKS.md,
/// "Pass order").
inline constexpr PassOrder kDefaultPassOrder = PassOrder::Memory;

/// "declared" or "memory".
std::string_view pass_order_name(PassOrder order);
/// The order called `name` ("declared", "memory"), or nullopt.
std::optional<PassOrder> parse_pass_order(std::string_view name);

/// An inclusive range of positions in Plan::order during which a resource must exist.
struct Lifetime {
    uint32_t first = 0;
    uint32_t last = 0;

    /// True when the two ranges share a position.
    [[nodiscard]] bool overlaps(const Lifetime& other) const { return first <= other.last && other.first <= last; }
    friend bool operator==(const Lifetime&, const Lifetime&) = default;
};

/// QueueSync::signal_after and OwnershipTransfer::release_after of what happens at the start of
/// the frame on the graphics queue, before its first pass. (Their wait_before and
/// acquire_before use Plan::order.size() for the end of the frame.)
inline constexpr uint32_t kFrameStart = UINT32_MAX;

/// PlanResource::texture of a buffer, PlanResource::buffer of a texture.
inline constexpr uint32_t kNoPhysical = UINT32_MAX;

/// One port of a scheduled pass.
struct PlanPort {
    std::string name;
    PortKind kind = PortKind::Input;
    bool optional = false;
    /// Index into Plan::resources; empty for an unconnected optional input, or an optional
    /// output nobody reads (no texture is allocated for it).
    std::optional<uint32_t> resource;
    /// How this texture port uses the texture (Sampled, ColorAttachment, DepthStencilAttachment,
    /// Storage, CopySrc, CopyDst); None for buffer ports.
    rhi::TextureUsage usage = rhi::TextureUsage::None;
    ResourceType type = ResourceType::Texture;
    /// How this buffer port uses the buffer: one flag (Storage, Uniform, Vertex, Index,
    /// Indirect, CopySrc, CopyDst), also when no buffer is behind it; None for texture ports.
    rhi::BufferUsage buffer_usage = rhi::BufferUsage::None;
    /// Texture ports: the mip levels and layers it uses, with concrete counts.
    SubresourceRange range{};
    /// Buffer ports: the bytes it uses, with a concrete size.
    BufferRange bytes{};

    friend bool operator==(const PlanPort&, const PlanPort&) = default;
};

/// A pass that runs, in execution order.
struct PlanPass {
    std::string name;
    uint32_t declaration_index = 0;  ///< position among the graph's passes
    bool side_effect = false;
    std::vector<PlanPort> ports;     ///< in the pass's port order
    PassKind kind = PassKind::Graphics;
    Queue queue = Queue::Graphics;   ///< the queue it is submitted to

    friend bool operator==(const PlanPass&, const PlanPass&) = default;
};

/// A logical texture or buffer: one output (or unconnected optional inout) with everything it
/// feeds, directly or through in-place modifications (inouts). Its ports share one physical
/// texture (or buffer).
struct PlanResource {
    std::string name;                ///< "pass.port" of the port that starts it
    std::vector<std::string> ports;  ///< every port on it that runs, "pass.port", the starting port first
    /// The joined format features before resolution; empty when no port constrained the format.
    std::optional<rhi::FormatFeatures> requested_format;
    ResolvedSpec spec;               ///< the joined spec made concrete; usage is what the ports need
    Lifetime lifetime;               ///< from its producer to its last reader, positions in Plan::order
    /// The positions during which its memory is reserved: its lifetime, widened over the passes
    /// of the other queue that may run while an async compute pass uses it (equal to `lifetime`
    /// in a plan without async passes). Allocators and lower bounds use it.
    Lifetime occupancy;
    /// Some of its contents are read on both queues (a depth buffer read by the graphics queue
    /// and by async compute): it is shared by both queue families rather than owned by one, and
    /// never appears in Plan::ownership_transfers.
    bool queue_shared = false;
    bool graph_output = false;       ///< read after the frame: lives until the last pass
    uint32_t spec_class = 0;         ///< index into Plan::spec_classes
    uint64_t bytes = 0;              ///< memory model size of a texture of `spec`
    uint64_t alignment = 0;
    uint32_t texture = 0;            ///< index into Plan::textures; kNoPhysical for a buffer
    ResourceType type = ResourceType::Texture;
    /// A buffer's joined spec made concrete (usage: what its ports need); empty for a texture,
    /// whose `spec` and `requested_format` are unused for a buffer.
    ResolvedBufferSpec buffer_spec;
    uint32_t buffer = kNoPhysical;   ///< index into Plan::buffers; kNoPhysical for a texture

    friend bool operator==(const PlanResource&, const PlanResource&) = default;
};

/// A connection between two scheduled ports, by position in Plan::order and port index.
struct PlanEdge {
    uint32_t from_pass = 0;
    uint32_t from_port = 0;
    uint32_t to_pass = 0;
    uint32_t to_port = 0;
    uint32_t resource = 0;  ///< the resource flowing along it

    friend bool operator==(const PlanEdge&, const PlanEdge&) = default;
};

/// A semaphore between the two queues: signalled on `from` after the pass at `signal_after`
/// (kFrameStart: at the start of the frame) and waited on `to` before the pass at
/// `wait_before` (Plan::order.size(): before the frame ends). Every later command of `to`
/// waits for every earlier command of `from`.
struct QueueSync {
    Queue from = Queue::Graphics;
    Queue to = Queue::AsyncCompute;
    uint32_t signal_after = 0;
    uint32_t wait_before = 0;

    friend bool operator==(const QueueSync&, const QueueSync&) = default;
};

/// A resource whose contents move between the queues: released on `from` after the pass at
/// `release_after` (kFrameStart: at the start of the frame), acquired on `to` before the pass
/// at `acquire_before` (Plan::order.size(): at the end of the frame, for a graph output last
/// used on the async queue). A QueueSync orders the two. On a device whose queues share one
/// queue family (or one queue), only the sync is needed.
struct OwnershipTransfer {
    uint32_t resource = 0;  ///< index into Plan::resources
    Queue from = Queue::Graphics;
    Queue to = Queue::AsyncCompute;
    uint32_t release_after = 0;
    uint32_t acquire_before = 0;

    friend bool operator==(const OwnershipTransfer&, const OwnershipTransfer&) = default;
};

/// Where a texture lives inside a heap.
struct HeapRange {
    uint32_t heap = 0;
    uint64_t offset = 0;

    friend bool operator==(const HeapRange&, const HeapRange&) = default;
};

/// A physical texture to create.
struct PlanTexture {
    std::string name;                 ///< "t0", "t1", ...
    ResolvedSpec spec;                ///< the join of its resources' specs; usage is their union
    std::vector<uint32_t> resources;  ///< resources it holds, in order of their lifetimes
    uint64_t bytes = 0;
    uint64_t alignment = 0;
    std::optional<HeapRange> placement;  ///< set by allocators that place textures in heaps

    friend bool operator==(const PlanTexture&, const PlanTexture&) = default;
};

/// A physical buffer to create.
struct PlanBuffer {
    std::string name;                 ///< "b0", "b1", ...
    ResolvedBufferSpec spec;          ///< its resources' size, the union of their usage, the largest alignment
    std::vector<uint32_t> resources;  ///< resources it holds, in order of their lifetimes
    uint64_t bytes = 0;               ///< the memory model's size for it (at least spec.size)
    uint64_t alignment = 0;
    std::optional<HeapRange> placement;  ///< set by allocators that place resources in heaps

    friend bool operator==(const PlanBuffer&, const PlanBuffer&) = default;
};

/// The resources that may share textures (or buffers) with each other (see SpecSharing).
/// Buffers share only with buffers of the same size and alignment.
struct SpecClass {
    ResolvedSpec spec;                ///< the join of its members (usage: union); textures
    std::vector<uint32_t> resources;
    uint32_t peak_live = 0;           ///< most members alive at once over the order
    ResourceType type = ResourceType::Texture;
    ResolvedBufferSpec buffer_spec;   ///< buffers: the members' size and alignment, usage the union

    friend bool operator==(const SpecClass&, const SpecClass&) = default;
};

/// The figures that make allocators comparable. Byte figures count textures and buffers.
struct PlanSummary {
    uint32_t textures = 0;              ///< physical textures allocated
    uint64_t bytes = 0;                 ///< their memory and the buffers' (for heaps: the heap sizes)
    uint32_t naive_textures = 0;        ///< one texture per texture resource (per output)
    uint64_t naive_bytes = 0;           ///< one texture or buffer per resource
    uint32_t lower_bound_textures = 0;  ///< sum over texture spec classes of the peak live count
    uint64_t lower_bound_bytes = 0;     ///< peak over the order of the bytes of live resources
    uint32_t buffers = 0;               ///< physical buffers allocated
    uint64_t buffer_bytes = 0;          ///< their bytes (placed or not), part of `bytes` unless placed
    uint32_t naive_buffers = 0;         ///< buffer resources
    uint32_t lower_bound_buffers = 0;   ///< sum over buffer spec classes of the peak live count

    friend bool operator==(const PlanSummary&, const PlanSummary&) = default;
};

/// A compiled frame graph, as plain data: order, culled passes, resources, textures, heaps and their summary.
struct Plan {
    std::string allocator;            ///< name of the allocator that made it
    Extent2D frame{};
    SpecSharing sharing = SpecSharing::Equal;
    /// How `order` was chosen (PlanOptions::order). Under PassOrder::Memory the order may still
    /// be the declared one: when no other lowers the peak, or when the declared order's
    /// allocation needs fewer bytes.
    PassOrder pass_order = kDefaultPassOrder;
    std::vector<PlanPass> order;      ///< passes that run, in execution order
    std::vector<std::string> culled;  ///< passes that do not run, in declaration order
    std::vector<PlanEdge> edges;      ///< connections between passes that run, in connection order
    std::vector<std::string> graph_outputs;  ///< "pass.port" of each graph output, in marking order
    std::vector<PlanResource> resources;  ///< ordered by (first use, starting port)
    std::vector<SpecClass> spec_classes;
    std::vector<PlanTexture> textures;
    std::vector<PlanBuffer> buffers;
    std::vector<uint64_t> heaps;      ///< heap sizes in bytes; empty unless the allocator places
    PlanSummary summary;
    /// Semaphores between the graphics and async compute queues, by wait position; empty when
    /// every pass runs on the graphics queue.
    std::vector<QueueSync> queue_syncs;
    /// Resources moving between the queues, by acquire position, then resource.
    std::vector<OwnershipTransfer> ownership_transfers;

    /// The scheduled pass called `name`, or nullptr (also for culled passes).
    [[nodiscard]] const PlanPass* find_pass(std::string_view name) const;
    /// The resource behind `pass`.`port`, or nullptr.
    [[nodiscard]] const PlanResource* resource_of(std::string_view pass, std::string_view port) const;
    /// The physical texture behind `pass`.`port` (nullopt for a buffer port).
    [[nodiscard]] std::optional<uint32_t> texture_of(std::string_view pass, std::string_view port) const;
    /// The physical buffer behind `pass`.`port` (nullopt for a texture port).
    [[nodiscard]] std::optional<uint32_t> buffer_of(std::string_view pass, std::string_view port) const;

    friend bool operator==(const Plan&, const Plan&) = default;
};

/// The part of `resource` that `port` uses, or "" when it is all of it: "mip 2", "mips 1..3
/// layer 0", "layers 2..5" (describe_range), "bytes 512+512" (offset+size).
std::string describe_port_range(const PlanResource& resource, const PlanPort& port);

/// A 64-bit hash of every field of the plan; equal plans hash equal, on every platform.
uint64_t plan_hash(const Plan& plan);

}  // namespace loom::fg
