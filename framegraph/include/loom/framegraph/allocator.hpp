#pragma once
// Allocators decide which logical resources share which physical texture (and, for APIs that
// can alias memory, where each texture lives inside a heap). They all see the same problem
// and are chosen by AllocatorKind in C++ (a name in graph files and on command lines):
//   "paper"    — the port colouring of Hafner (ELS 2019) §6.2, the reference;
//   "interval" — interval-graph colouring per spec class: for the given order, the fewest
//                textures (the peak number of live resources of each class);
//   "heap"     — one texture per resource, placed at byte offsets in heaps so that resources
//                alive at the same time never overlap in memory; aims for the peak live bytes.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/plan.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// The allocators loom has, as C++ chooses them (PlanOptions::allocator): a misspelt kind does
/// not compile, where a misspelt name is found only when it is parsed.
enum class AllocatorKind : uint8_t {
    Paper,     ///< "paper"
    Interval,  ///< "interval"
    Heap,      ///< "heap"
};

/// The name graph files, command lines and Plan::allocator use: "paper", "interval", "heap".
std::string_view allocator_name(AllocatorKind kind);

/// The kind called `name`; an InvalidArgument error quotes the value and lists the known names.
/// For names that come from users (command lines, settings files).
Result<AllocatorKind> parse_allocator(std::string_view name);

/// Every kind, in the order of allocator_names().
std::span<const AllocatorKind> allocator_kinds();

/// A scheduled pass as an allocator sees it: resource indices, each list in port order.
struct AllocationPass {
    std::vector<uint32_t> inputs;      ///< resources read (input and inout ports)
    std::vector<uint32_t> non_inputs;  ///< resources written (output and inout ports)
    std::vector<uint32_t> begins;      ///< resources that start at this pass (their producer)
};

/// A logical resource as an allocator sees it.
struct AllocationResource {
    uint32_t spec_class = 0;  ///< resources may share a texture only within one class
    /// Positions in the order during which it holds its memory (PlanResource::occupancy);
    /// graph outputs last until the end.
    Lifetime lifetime;
    uint64_t bytes = 0;
    uint64_t alignment = 1;
    /// The resource's name ("pass.port"), for error messages: the plan's (PlanResource::name),
    /// which outlives the allocation, so that a problem copies no names.
    std::string_view name;
};

/// What an allocator is given: the passes in order and the resources with their classes, lifetimes, sizes and alignments.
struct AllocationProblem {
    std::vector<AllocationPass> passes;          ///< in execution order
    std::vector<AllocationResource> resources;
    std::vector<uint32_t> graph_outputs;         ///< resources read after the frame, in marking order
    uint32_t spec_class_count = 0;
    uint64_t max_heap_bytes = 0;                 ///< heaps: 0 means one heap as large as needed
};

/// What an allocator decides: a texture for every resource, and where placed, heaps and offsets.
struct Allocation {
    std::vector<uint32_t> texture_of_resource;  ///< per resource, a texture index < texture_count
    uint32_t texture_count = 0;
    std::vector<HeapRange> texture_placement;   ///< per texture where the allocator places, else empty
    std::vector<uint64_t> heap_sizes;
};

/// Assigns physical textures (or heap offsets) to the resources of a plan; implementations are chosen by kind (make_allocator).
class Allocator {
public:
    /// Allocators are used through this interface.
    virtual ~Allocator() = default;
    /// The name it is chosen by ("paper", "interval", "heap").
    [[nodiscard]] virtual std::string_view name() const = 0;
    /// Assigns textures (and placements) to the problem's resources. Two resources whose
    /// lifetimes overlap never share a texture, nor overlapping heap bytes.
    [[nodiscard]] virtual Result<Allocation> allocate(const AllocationProblem& problem) const = 0;
    /// True when allocate() reads the lists of AllocationProblem::passes (inputs, non_inputs,
    /// begins). An allocator that works from the resources' lifetimes alone says false, and
    /// planning then leaves the lists empty (passes still has one entry per position), which
    /// saves three lists per pass.
    [[nodiscard]] virtual bool reads_pass_lists() const { return true; }
    /// True when allocate() reads the resources' bytes or alignments. An allocator that says
    /// false answers a problem that differs only in them as it answered before: re-planning for
    /// another frame size (FrameGraph::plan) then keeps its allocation when the spec classes
    /// stay as they were.
    [[nodiscard]] virtual bool reads_bytes() const { return true; }
};

/// "paper", "interval", "heap".
std::span<const std::string_view> allocator_names();

/// The allocator of that kind.
std::unique_ptr<Allocator> make_allocator(AllocatorKind kind);

/// The allocator called `name`; an InvalidArgument error lists the known names (parse_allocator).
Result<std::unique_ptr<Allocator>> make_allocator(std::string_view name);

}  // namespace loom::fg
