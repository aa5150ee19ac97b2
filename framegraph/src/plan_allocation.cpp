// Which resources share which texture: the spec classes, allocate and summary phases of
// build_plan.
#include <algorithm>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <tuple>

#include "loom/framegraph/join.hpp"
#include "plan_phases.hpp"
#include "text.hpp"

namespace loom::fg::detail {
namespace {

// A spec that asks for exactly what `resolved` is, to join resolved specs with each other.
TextureSpec as_spec(const ResolvedSpec& resolved) {
    TextureSpec spec = TextureSpec::of(resolved.format).with_size(resolved.extent.width, resolved.extent.height);
    spec.samples = resolved.samples;
    spec.mips = resolved.mips;
    spec.layers = resolved.layers;
    spec.usage = resolved.usage;
    spec.cube = resolved.cube;
    return spec;
}

// Join of two resolved specs; nullopt when they do not join.
std::optional<ResolvedSpec> join_resolved(const ResolvedSpec& a, const ResolvedSpec& b, Extent2D frame) {
    if (same_texture_shape(a, b)) {
        ResolvedSpec out = a;
        out.usage = a.usage | b.usage;
        return out;
    }
    JoinContext context;
    context.frame = frame;
    auto joined = join(as_spec(a), as_spec(b), context);
    if (!joined) return std::nullopt;
    auto resolved = resolve(*joined, frame, "joined texture");
    if (!resolved) return std::nullopt;
    return *resolved;
}

// The most bytes of resources alive at one position (within their occupancies, which async
// compute widens): each resource adds its bytes at its first position and takes them away after
// its last.
uint64_t peak_live_bytes(const std::vector<PlanResource>& resources, uint32_t position_count) {
    std::vector<uint64_t> change(position_count + 1, 0);
    std::vector<uint64_t> ending(position_count + 1, 0);
    for (const PlanResource& resource : resources) {
        change[resource.occupancy.first] += resource.bytes;
        ending[resource.occupancy.last + 1] += resource.bytes;
    }
    uint64_t live = 0;
    uint64_t peak = 0;
    for (uint32_t position = 0; position < position_count; ++position) {
        live = live + change[position] - ending[position];
        peak = std::max(peak, live);
    }
    return peak;
}

// Most members of each class alive at once, and the peak of live bytes, over the order
// (alive: within its occupancy, which async compute widens).
struct Peaks {
    std::vector<uint32_t> live_per_class;
    uint64_t bytes = 0;
};

Peaks measure_peaks(const std::vector<PlanResource>& resources, const std::vector<uint32_t>& class_of_resource,
                    uint32_t position_count, uint32_t class_count) {
    // Sweep: +1 at first, -1 after last. The resources starting and ending at each position are
    // listed one position after another in two flat arrays (a counting sort by position, each
    // position's resources in resource order), not in a vector per position.
    auto by_position = [&](auto position_of) {
        std::vector<uint32_t> first(position_count + 2, 0);
        for (const PlanResource& resource : resources) ++first[position_of(resource) + 1];
        for (uint32_t at = 1; at < first.size(); ++at) first[at] += first[at - 1];
        std::vector<uint32_t> listed(resources.size());
        std::vector<uint32_t> cursor(first.begin(), first.end() - 1);
        for (uint32_t r = 0; r < resources.size(); ++r) listed[cursor[position_of(resources[r])]++] = r;
        return std::pair(std::move(first), std::move(listed));
    };
    const auto [first_starting, starting] = by_position([](const PlanResource& r) { return r.occupancy.first; });
    const auto [first_ending, ending] = by_position([](const PlanResource& r) { return r.occupancy.last + 1; });
    Peaks peaks;
    peaks.live_per_class.assign(class_count, 0);
    std::vector<uint32_t> live(class_count, 0);
    for (uint32_t position = 0; position < position_count; ++position) {
        for (uint32_t k = first_ending[position]; k < first_ending[position + 1]; ++k) --live[class_of_resource[ending[k]]];
        for (uint32_t k = first_starting[position]; k < first_starting[position + 1]; ++k) {
            const uint32_t c = class_of_resource[starting[k]];
            peaks.live_per_class[c] = std::max(peaks.live_per_class[c], ++live[c]);
        }
    }
    peaks.bytes = peak_live_bytes(resources, position_count);
    return peaks;
}

constexpr uint32_t kNoClass = UINT32_MAX;

// What equal sharing puts in one class: textures of one shape (format, extent, samples, mips,
// layers, cube), buffers of one size and alignment.
using ShapeKey = std::tuple<rhi::Format, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, bool>;
ShapeKey shape_key(const ResolvedSpec& spec) {
    return ShapeKey{spec.format, spec.extent.width, spec.extent.height, spec.samples, spec.mips, spec.layers, spec.cube};
}
std::pair<uint64_t, uint64_t> buffer_key(const ResolvedBufferSpec& spec) { return {spec.size, spec.alignment}; }

// Whether equal sharing makes of `plan`'s resources, whose sizes may have changed since its
// classes were assigned, the classes it has: every member has the shape of its class's first
// member, and no two classes have one shape.
bool classes_still_hold(const Plan& plan) {
    std::set<ShapeKey> texture_shapes;
    std::set<std::pair<uint64_t, uint64_t>> buffer_shapes;
    for (const SpecClass& spec_class : plan.spec_classes) {
        const PlanResource& first = plan.resources[spec_class.resources.front()];
        const bool distinct = first.type == ResourceType::Buffer ? buffer_shapes.insert(buffer_key(first.buffer_spec)).second
                                                                 : texture_shapes.insert(shape_key(first.spec)).second;
        if (!distinct) return false;
    }
    return std::all_of(plan.resources.begin(), plan.resources.end(), [&](const PlanResource& resource) {
        const PlanResource& first = plan.resources[plan.spec_classes[resource.spec_class].resources.front()];
        return resource.type == ResourceType::Buffer ? buffer_key(resource.buffer_spec) == buffer_key(first.buffer_spec)
                                                     : shape_key(resource.spec) == shape_key(first.spec);
    });
}

// An allocator's answer can be trusted only this far: a texture below the count for every
// resource, and a placement for every texture when it places any.
bool well_formed(const Allocation& allocation, std::size_t resource_count) {
    const bool placed = !allocation.texture_placement.empty();
    return allocation.texture_of_resource.size() == resource_count &&
           std::all_of(allocation.texture_of_resource.begin(), allocation.texture_of_resource.end(),
                       [&](uint32_t t) { return t < allocation.texture_count; }) &&
           (!placed || allocation.texture_placement.size() == allocation.texture_count);
}

// The textures and buffers of a well-formed allocation, each kind numbered by first use, so
// plans read the same whatever an allocator's own numbering; an error when an object has no
// resource or holds both textures and buffers.
Result<TextureAssignment> number_by_first_use(const Allocation& allocation, const std::vector<PlanResource>& resources,
                                              const std::string& allocator_name) {
    std::vector<uint32_t> first_user(allocation.texture_count, kNoResource);
    for (uint32_t r = 0; r < allocation.texture_of_resource.size(); ++r) {
        uint32_t& first = first_user[allocation.texture_of_resource[r]];
        first = std::min(first, r);
    }
    if (std::find(first_user.begin(), first_user.end(), kNoResource) != first_user.end()) {
        return make_error(ErrorCode::Graph, "allocator '" + allocator_name + "' made a texture no resource uses");
    }
    for (uint32_t r = 0; r < allocation.texture_of_resource.size(); ++r) {
        const PlanResource& first = resources[first_user[allocation.texture_of_resource[r]]];
        if (first.type != resources[r].type) {
            return make_error(ErrorCode::Graph, "allocator '" + allocator_name + "' put " + resources[r].name + " (a " +
                                                    std::string(resource_type_name(resources[r].type)) + ") and " +
                                                    first.name + " (a " + std::string(resource_type_name(first.type)) +
                                                    ") into one object");
        }
    }
    std::vector<uint32_t> by_first_use(allocation.texture_count);
    std::iota(by_first_use.begin(), by_first_use.end(), 0u);
    std::sort(by_first_use.begin(), by_first_use.end(),
              [&](uint32_t a, uint32_t b) { return first_user[a] < first_user[b]; });
    // Allocator object -> index among the textures or among the buffers.
    std::vector<uint32_t> renumbered(allocation.texture_count);
    TextureAssignment out;
    // Sized first: one allocation each rather than one per doubling (a heap allocator makes an
    // object per resource, tens of thousands in a large graph).
    const auto buffer_objects = static_cast<std::size_t>(std::count_if(
        first_user.begin(), first_user.end(), [&](uint32_t r) { return resources[r].type == ResourceType::Buffer; }));
    out.buffers.reserve(buffer_objects);
    out.textures.reserve(allocation.texture_count - buffer_objects);
    const bool placed = !allocation.texture_placement.empty();
    for (uint32_t object : by_first_use) {
        std::optional<HeapRange> placement;
        if (placed) placement = allocation.texture_placement[object];
        if (resources[first_user[object]].type == ResourceType::Buffer) {
            renumbered[object] = static_cast<uint32_t>(out.buffers.size());
            PlanBuffer buffer;
            buffer.name = concat("b", out.buffers.size());
            buffer.placement = placement;
            out.buffers.push_back(std::move(buffer));
        } else {
            renumbered[object] = static_cast<uint32_t>(out.textures.size());
            PlanTexture texture;
            texture.name = concat("t", out.textures.size());
            texture.placement = placement;
            out.textures.push_back(std::move(texture));
        }
    }
    out.texture_of_resource.reserve(allocation.texture_of_resource.size());
    for (uint32_t r = 0; r < allocation.texture_of_resource.size(); ++r) {
        const uint32_t index = renumbered[allocation.texture_of_resource[r]];
        const bool buffer = resources[r].type == ResourceType::Buffer;
        out.texture_of_resource.push_back(buffer ? kNoPhysical : index);
        out.buffer_of_resource.push_back(buffer ? index : kNoPhysical);
    }
    out.heaps = allocation.heap_sizes;
    return out;
}

// Each texture's resources, its spec (the join of theirs) and its bytes; each buffer's likewise.
Status describe_objects(const std::string& allocator_name, const std::vector<PlanResource>& resources, Extent2D frame,
                        MemoryModel& memory, TextureAssignment& assignment) {
    for (uint32_t r = 0; r < resources.size(); ++r) {
        const PlanResource& resource = resources[r];
        if (resource.type == ResourceType::Buffer) {
            PlanBuffer& buffer = assignment.buffers[assignment.buffer_of_resource[r]];
            if (buffer.resources.empty()) {
                buffer.spec = resource.buffer_spec;
            } else if (buffer.spec.size == resource.buffer_spec.size) {
                buffer.spec.usage |= resource.buffer_spec.usage;
                buffer.spec.alignment = std::max(buffer.spec.alignment, resource.buffer_spec.alignment);
            } else {
                return make_error(ErrorCode::Graph, "allocator '" + allocator_name + "' put " + resource.name +
                                                        " into a buffer of another size");
            }
            buffer.resources.push_back(r);
            continue;
        }
        PlanTexture& texture = assignment.textures[assignment.texture_of_resource[r]];
        if (texture.resources.empty()) {
            texture.spec = resource.spec;
        } else if (auto joined = join_resolved(texture.spec, resource.spec, frame)) {
            texture.spec = *joined;
        } else {
            return make_error(ErrorCode::Graph, "allocator '" + allocator_name + "' put " + resource.name +
                                                    " into a texture of a spec it does not join with");
        }
        texture.resources.push_back(r);
    }
    for (PlanTexture& texture : assignment.textures) {
        if (texture.resources.size() == 1) {
            texture.bytes = resources[texture.resources.front()].bytes;
            texture.alignment = resources[texture.resources.front()].alignment;
        } else {
            auto requirements = memory.requirements(to_texture_desc(texture.spec, texture.name));
            if (!requirements) return requirements.take_error();
            texture.bytes = requirements->size;
            texture.alignment = std::max<uint64_t>(requirements->alignment, 1);
        }
    }
    for (PlanBuffer& buffer : assignment.buffers) {
        // Members share size and alignment (one spec class); the largest figures hold them all.
        for (uint32_t r : buffer.resources) {
            buffer.bytes = std::max(buffer.bytes, resources[r].bytes);
            buffer.alignment = std::max(buffer.alignment, resources[r].alignment);
        }
    }
    return {};
}

}  // namespace

SpecClassAssignment assign_spec_classes(const std::vector<PlanResource>& resources, SpecSharing sharing, Extent2D frame,
                                        uint32_t position_count) {
    SpecClassAssignment out;
    std::vector<SpecClass>& classes = out.classes;
    // Equal sharing: a class per texture shape (its shape never changes, only its usage
    // grows), found by key rather than by trying every class.
    std::map<ShapeKey, uint32_t> class_of_shape;
    // Buffers share only with buffers of the same size and alignment, under either sharing.
    std::map<std::pair<uint64_t, uint64_t>, uint32_t> class_of_buffer_shape;
    for (uint32_t r = 0; r < resources.size(); ++r) {
        const PlanResource& resource = resources[r];
        uint32_t chosen = kNoClass;
        if (resource.type == ResourceType::Buffer) {
            auto [it, inserted] =
                class_of_buffer_shape.try_emplace(buffer_key(resource.buffer_spec), static_cast<uint32_t>(classes.size()));
            if (inserted) {
                SpecClass fresh;
                fresh.type = ResourceType::Buffer;
                fresh.buffer_spec = resource.buffer_spec;
                classes.push_back(std::move(fresh));
            } else {
                classes[it->second].buffer_spec.usage |= resource.buffer_spec.usage;
            }
            out.class_of_resource.push_back(it->second);
            classes[it->second].resources.push_back(r);
            continue;
        }
        if (sharing == SpecSharing::Equal) {
            auto it = class_of_shape.find(shape_key(resource.spec));
            if (it != class_of_shape.end()) {
                chosen = it->second;
                classes[chosen].spec.usage |= resource.spec.usage;
            } else {
                class_of_shape.emplace(shape_key(resource.spec), static_cast<uint32_t>(classes.size()));
            }
        }
        for (uint32_t c = 0; sharing != SpecSharing::Equal && c < classes.size() && chosen == kNoClass; ++c) {
            if (classes[c].type != ResourceType::Texture) continue;
            if (auto joined = join_resolved(classes[c].spec, resource.spec, frame)) {
                classes[c].spec = *joined;
                chosen = c;
            }
        }
        if (chosen == kNoClass) {
            chosen = static_cast<uint32_t>(classes.size());
            classes.push_back(SpecClass{resource.spec, {}, 0, ResourceType::Texture, {}});
        }
        out.class_of_resource.push_back(chosen);
        classes[chosen].resources.push_back(r);
    }
    const auto class_count = static_cast<uint32_t>(classes.size());
    const Peaks peaks = measure_peaks(resources, out.class_of_resource, position_count, class_count);
    for (uint32_t c = 0; c < class_count; ++c) classes[c].peak_live = peaks.live_per_class[c];
    out.peak_live_bytes = peaks.bytes;
    return out;
}

AllocationProblem make_allocation_problem(const std::vector<PlanPass>& order,
                                          const std::vector<PlanResource>& resources,
                                          std::vector<uint32_t> graph_output_resources, uint32_t spec_class_count,
                                          uint64_t max_heap_bytes, bool with_pass_lists) {
    AllocationProblem problem;
    problem.spec_class_count = spec_class_count;
    problem.max_heap_bytes = max_heap_bytes;
    problem.passes.resize(order.size());
    problem.resources.reserve(resources.size());
    for (const PlanResource& resource : resources) {
        problem.resources.push_back(AllocationResource{resource.spec_class, resource.occupancy, resource.bytes,
                                                       resource.alignment, resource.name});
    }
    problem.graph_outputs = std::move(graph_output_resources);
    if (!with_pass_lists) return problem;

    // Each list sized first, so that it is one allocation rather than one per doubling.
    std::vector<uint32_t> begin_count(order.size(), 0);
    for (const PlanResource& resource : resources) ++begin_count[resource.lifetime.first];
    for (uint32_t at = 0; at < order.size(); ++at) {
        AllocationPass& step = problem.passes[at];
        uint32_t reads = 0;
        uint32_t writes = 0;
        for (const PlanPort& port : order[at].ports) {
            if (!port.resource) continue;
            reads += port_reads(port.kind) ? 1 : 0;
            writes += port_writes(port.kind) ? 1 : 0;
        }
        step.inputs.reserve(reads);
        step.non_inputs.reserve(writes);
        step.begins.reserve(begin_count[at]);
        for (const PlanPort& port : order[at].ports) {
            if (!port.resource) continue;
            if (port_reads(port.kind)) step.inputs.push_back(*port.resource);
            if (port_writes(port.kind)) step.non_inputs.push_back(*port.resource);
        }
    }
    for (uint32_t r = 0; r < resources.size(); ++r) problem.passes[resources[r].lifetime.first].begins.push_back(r);
    return problem;
}

Result<TextureAssignment> allocate_textures(const Allocator& allocator, const AllocationProblem& problem,
                                            const std::vector<PlanResource>& resources, Extent2D frame,
                                            MemoryModel& memory) {
    auto allocation = allocator.allocate(problem);
    if (!allocation) return allocation.take_error();
    const std::string name(allocator.name());
    if (!well_formed(*allocation, resources.size())) {
        return make_error(ErrorCode::Graph, "allocator '" + name + "' returned a malformed allocation");
    }
    auto assignment = number_by_first_use(*allocation, resources, name);
    if (!assignment) return assignment.take_error();
    LOOM_TRY(describe_objects(name, resources, frame, memory, *assignment));
    return std::move(*assignment);
}

Status allocate_plan(Plan& plan, const PlanOptions& options, const Allocator& allocator, MemoryModel& memory,
                     std::vector<uint32_t> graph_output_resources) {
    SpecClassAssignment classes = assign_spec_classes(plan.resources, options.sharing, options.frame,
                                                      static_cast<uint32_t>(plan.order.size()));
    for (uint32_t r = 0; r < plan.resources.size(); ++r) plan.resources[r].spec_class = classes.class_of_resource[r];
    plan.spec_classes = std::move(classes.classes);
    const AllocationProblem problem =
        make_allocation_problem(plan.order, plan.resources, std::move(graph_output_resources),
                                static_cast<uint32_t>(plan.spec_classes.size()), options.max_heap_bytes,
                                allocator.reads_pass_lists());
    auto textures = allocate_textures(allocator, problem, plan.resources, options.frame, memory);
    if (!textures) return textures.take_error();
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        plan.resources[r].texture = textures->texture_of_resource[r];
        plan.resources[r].buffer = textures->buffer_of_resource[r];
    }
    plan.textures = std::move(textures->textures);
    plan.buffers = std::move(textures->buffers);
    plan.heaps = std::move(textures->heaps);
    plan.summary = summarize_plan(plan, classes.peak_live_bytes);
    return {};
}

Status allocate_resized_plan(Plan& plan, const PlanOptions& options, const Allocator& allocator, MemoryModel& memory,
                             std::vector<uint32_t> graph_output_resources) {
    if (allocator.reads_bytes() || options.sharing != SpecSharing::Equal || !classes_still_hold(plan)) {
        return allocate_plan(plan, options, allocator, memory, std::move(graph_output_resources));
    }
    // The same classes with the same members and lifetimes: the same peaks of live members, and
    // the allocator's answer as before. What changed is each class's, texture's and buffer's
    // shape (its first member's) and usage (the union of its members').
    for (SpecClass& spec_class : plan.spec_classes) {
        const PlanResource& first = plan.resources[spec_class.resources.front()];
        if (spec_class.type == ResourceType::Buffer) {
            spec_class.buffer_spec = first.buffer_spec;
            for (uint32_t r : spec_class.resources) spec_class.buffer_spec.usage |= plan.resources[r].buffer_spec.usage;
        } else {
            spec_class.spec = first.spec;
            for (uint32_t r : spec_class.resources) spec_class.spec.usage |= plan.resources[r].spec.usage;
        }
    }
    TextureAssignment assignment;
    assignment.textures = std::move(plan.textures);
    assignment.buffers = std::move(plan.buffers);
    for (PlanTexture& texture : assignment.textures) texture.resources.clear();
    for (PlanBuffer& buffer : assignment.buffers) {
        buffer.resources.clear();
        buffer.bytes = 0;
        buffer.alignment = 0;
    }
    assignment.texture_of_resource.reserve(plan.resources.size());
    assignment.buffer_of_resource.reserve(plan.resources.size());
    for (const PlanResource& resource : plan.resources) {
        assignment.texture_of_resource.push_back(resource.texture);
        assignment.buffer_of_resource.push_back(resource.buffer);
    }
    LOOM_TRY(describe_objects(plan.allocator, plan.resources, options.frame, memory, assignment));
    plan.textures = std::move(assignment.textures);
    plan.buffers = std::move(assignment.buffers);
    plan.summary = summarize_plan(plan, peak_live_bytes(plan.resources, static_cast<uint32_t>(plan.order.size())));
    return {};
}

PlanSummary summarize_plan(const Plan& plan, uint64_t peak_live_bytes) {
    PlanSummary summary;
    summary.textures = static_cast<uint32_t>(plan.textures.size());
    summary.buffers = static_cast<uint32_t>(plan.buffers.size());
    for (const PlanBuffer& buffer : plan.buffers) summary.buffer_bytes += buffer.bytes;
    // An allocator that places resources places every one of them (allocate_textures checks it).
    const bool placed = !plan.heaps.empty();
    if (placed) {
        summary.bytes = std::accumulate(plan.heaps.begin(), plan.heaps.end(), uint64_t{0});
    } else {
        for (const PlanTexture& texture : plan.textures) summary.bytes += texture.bytes;
        summary.bytes += summary.buffer_bytes;
    }
    for (const PlanResource& resource : plan.resources) {
        summary.naive_bytes += resource.bytes;
        if (resource.type == ResourceType::Buffer) {
            ++summary.naive_buffers;
        } else {
            ++summary.naive_textures;
        }
    }
    for (const SpecClass& spec_class : plan.spec_classes) {
        (spec_class.type == ResourceType::Buffer ? summary.lower_bound_buffers : summary.lower_bound_textures) +=
            spec_class.peak_live;
    }
    summary.lower_bound_bytes = peak_live_bytes;
    return summary;
}

}  // namespace loom::fg::detail
