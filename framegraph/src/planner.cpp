#include "loom/framegraph/planner.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <queue>
#include <tuple>

#include "graph_analysis.hpp"
#include "plan_phases.hpp"
#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/join.hpp"

namespace loom::fg {
namespace {

using rhi::TextureUsage;

constexpr uint32_t kNone = UINT32_MAX;

// Ports of one graph by flat index, so per-port data lives in plain vectors.
class PortIndex {
public:
    explicit PortIndex(const FrameGraph& graph) {
        offsets_.reserve(graph.pass_count() + 1);
        uint32_t total = 0;
        for (uint32_t p = 0; p < graph.pass_count(); ++p) {
            offsets_.push_back(total);
            total += static_cast<uint32_t>(graph.pass(PassId{p}).ports().size());
        }
        offsets_.push_back(total);
    }
    [[nodiscard]] uint32_t flat(PortAddress a) const { return offsets_[a.pass] + a.port; }
    [[nodiscard]] uint32_t size() const { return offsets_.back(); }

private:
    std::vector<uint32_t> offsets_;
};

// A connected group of ports: an output (or an unconnected inout) and everything it feeds,
// directly or through inouts. One logical resource when its producer runs.
struct Group {
    std::vector<PortAddress> ports;  // the starting port first, then breadth-first by connection order
};

std::vector<Group> collect_groups(const FrameGraph& graph) {
    std::vector<Group> groups;
    for (uint32_t p = 0; p < graph.pass_count(); ++p) {
        const Pass& pass = graph.pass(PassId{p});
        for (uint32_t i = 0; i < pass.ports().size(); ++i) {
            const PortAddress start{p, i};
            const Port& port = pass.ports()[i];
            const bool starts = port.kind == PortKind::Output || (port.kind == PortKind::InOut && !graph.source(start));
            if (!starts) continue;
            Group group;
            group.ports.push_back(start);
            for (std::size_t next = 0; next < group.ports.size(); ++next) {
                const PortAddress at = group.ports[next];
                if (!port_writes(graph.port_at(at).kind)) continue;
                for (const PortAddress& consumer : graph.consumers(at)) group.ports.push_back(consumer);
            }
            groups.push_back(std::move(group));
        }
    }
    return groups;
}

// The role of a port decides the usage it needs; an explicit Storage request turns an
// attachment write or a sampled read into a storage access.
TextureUsage port_usage(const Port& port, rhi::Format format) {
    TextureUsage usage = port.spec.usage;
    if (rhi::has_all(port.spec.usage, TextureUsage::Storage)) return usage;
    if (port_writes(port.kind)) {
        usage |= rhi::format_info(format).is_depth_stencil() ? TextureUsage::DepthStencilAttachment
                                                             : TextureUsage::ColorAttachment;
    } else {
        usage |= TextureUsage::Sampled;
    }
    return usage;
}

// A spec that asks for exactly what `resolved` is, to join resolved specs with each other.
TextureSpec as_spec(const ResolvedSpec& resolved) {
    TextureSpec spec = TextureSpec::of(resolved.format).with_size(resolved.extent.width, resolved.extent.height);
    spec.samples = resolved.samples;
    spec.mips = resolved.mips;
    spec.layers = resolved.layers;
    spec.usage = resolved.usage;
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

// A spec with only one of the properties format, size, samples, mips, layers (by index) of `spec`.
TextureSpec only_property(const TextureSpec& spec, std::size_t property) {
    TextureSpec out;
    switch (property) {
        case 0: out.format = spec.format; break;
        case 1: out.size = spec.size; break;
        case 2: out.samples = spec.samples; break;
        case 3: out.mips = spec.mips; break;
        default: out.layers = spec.layers; break;
    }
    return out;
}

// Joins the specs of a group's ports in group order. On a conflict the error names the port
// that first constrained the conflicting property and the port that contradicts it.
Result<TextureSpec> join_group(const FrameGraph& graph, const Group& group, Extent2D frame) {
    TextureSpec joined;
    // First port to constrain each property: format, size, samples, mips, layers.
    std::array<std::optional<PortAddress>, 5> origin{};
    for (const PortAddress& address : group.ports) {
        const TextureSpec& spec = graph.port_at(address).spec;
        JoinContext context;
        context.frame = frame;
        auto result = join(joined, spec, context);
        if (!result) {
            // Find the property at fault and name the port it came from.
            for (std::size_t i = 0; i < origin.size(); ++i) {
                if (!origin[i]) continue;
                const std::string a_name = graph.port_name(*origin[i]);
                const std::string b_name = graph.port_name(address);
                JoinContext named;
                named.frame = frame;
                named.a_name = a_name;
                named.b_name = b_name;
                auto single = join(only_property(joined, i), only_property(spec, i), named);
                if (!single) {
                    Error error = single.take_error();
                    error.subjects = {b_name, a_name};
                    return error;
                }
            }
            Error error = result.take_error();
            error.subjects = {graph.port_name(address)};
            return error;
        }
        if (spec.format && !origin[0]) origin[0] = address;
        if (spec.size && !origin[1]) origin[1] = address;
        if (spec.samples && !origin[2]) origin[2] = address;
        if (spec.mips && !origin[3]) origin[3] = address;
        if (spec.layers && !origin[4]) origin[4] = address;
        joined = std::move(*result);
    }
    return joined;
}

// Most members of each class alive at once, and the peak of live bytes, over the order.
struct Peaks {
    std::vector<uint32_t> live_per_class;
    uint64_t bytes = 0;
};

Peaks measure_peaks(const std::vector<PlanResource>& resources, uint32_t pass_count, uint32_t class_count) {
    // Sweep: +1 at first, -1 after last.
    std::vector<std::vector<uint32_t>> starting(pass_count + 1);
    std::vector<std::vector<uint32_t>> ending(pass_count + 1);
    for (uint32_t r = 0; r < resources.size(); ++r) {
        starting[resources[r].lifetime.first].push_back(r);
        ending[resources[r].lifetime.last + 1].push_back(r);
    }
    Peaks peaks;
    peaks.live_per_class.assign(class_count, 0);
    std::vector<uint32_t> live(class_count, 0);
    uint64_t live_bytes = 0;
    for (uint32_t position = 0; position < pass_count; ++position) {
        for (uint32_t r : ending[position]) {
            --live[resources[r].spec_class];
            live_bytes -= resources[r].bytes;
        }
        for (uint32_t r : starting[position]) {
            const uint32_t c = resources[r].spec_class;
            peaks.live_per_class[c] = std::max(peaks.live_per_class[c], ++live[c]);
            live_bytes += resources[r].bytes;
        }
        peaks.bytes = std::max(peaks.bytes, live_bytes);
    }
    return peaks;
}

}  // namespace

Result<Plan> build_plan(const FrameGraph& graph, const PlanOptions& options) {
    if (options.frame.width == 0 || options.frame.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "plan: frame size " + std::to_string(options.frame.width) + "x" +
                                                          std::to_string(options.frame.height) + " is empty");
    }
    auto allocator = make_allocator(options.allocator);
    if (!allocator) return allocator.take_error();
    std::shared_ptr<MemoryModel> memory = options.memory_model;
    if (!memory) memory = std::make_shared<DefaultMemoryModel>();

    auto dependencies = detail::analyze(graph);
    if (!dependencies) return dependencies.take_error();

    auto kept = detail::cull_passes(graph, *dependencies);
    if (!kept) return kept.take_error();
    const detail::Schedule schedule = detail::schedule_passes(*dependencies, *kept);
    const std::vector<uint32_t>& order = schedule.order;
    const std::vector<uint32_t>& position = schedule.position;
    const auto scheduled = static_cast<uint32_t>(order.size());
    const uint32_t last_position = scheduled - 1;

    // ---- resources: join each group, resolve, measure its lifetime ------------------------
    const PortIndex ports(graph);
    std::vector<uint32_t> resource_of_port(ports.size(), kNone);
    std::vector<bool> is_graph_output(ports.size(), false);
    for (const PortAddress& out : graph.outputs()) is_graph_output[ports.flat(out)] = true;

    struct PendingResource {
        PlanResource resource;
        PortAddress start;
        std::vector<PortAddress> kept_ports;
    };
    std::vector<PendingResource> pending;
    for (const Group& group : collect_groups(graph)) {
        // Join every port, even those of culled passes: a bad connection is an error either way.
        auto joined = join_group(graph, group, options.frame);
        if (!joined) return joined.take_error();

        const PortAddress start = group.ports.front();
        if (!(*kept)[start.pass]) continue;
        PendingResource item;
        item.start = start;
        bool graph_output = false;
        uint32_t last = position[start.pass];
        for (const PortAddress& address : group.ports) {
            if (!(*kept)[address.pass]) continue;
            item.kept_ports.push_back(address);
            graph_output = graph_output || is_graph_output[ports.flat(address)];
            last = std::max(last, position[address.pass]);
        }
        // An optional output nobody reads gets no texture.
        if (item.kept_ports.size() == 1 && !graph_output && graph.port_at(start).optional) continue;

        const std::string name = graph.port_name(start);
        auto resolved = resolve(*joined, options.frame, name);
        if (!resolved) {
            Error error = resolved.take_error();
            for (const PortAddress& address : item.kept_ports) error.subjects.push_back(graph.port_name(address));
            return error;
        }
        TextureUsage usage = TextureUsage::None;
        for (const PortAddress& address : item.kept_ports) usage |= port_usage(graph.port_at(address), resolved->format);
        if (graph_output) usage |= TextureUsage::CopySrc;
        resolved->usage = usage;

        PlanResource& r = item.resource;
        r.name = name;
        for (const PortAddress& address : item.kept_ports) r.ports.push_back(graph.port_name(address));
        r.requested_format = joined->format;
        r.spec = *resolved;
        r.graph_output = graph_output;
        r.lifetime = {position[start.pass], graph_output ? last_position : last};
        auto requirements = memory->requirements(to_texture_desc(r.spec, r.name));
        if (!requirements) return requirements.take_error();
        r.bytes = requirements->size;
        r.alignment = std::max<uint64_t>(requirements->alignment, 1);
        pending.push_back(std::move(item));
    }
    // Resources in order of their producers' positions, then by port.
    std::stable_sort(pending.begin(), pending.end(), [&](const PendingResource& a, const PendingResource& b) {
        return std::pair(position[a.start.pass], a.start.port) < std::pair(position[b.start.pass], b.start.port);
    });

    Plan plan;
    plan.allocator = std::string((*allocator)->name());
    plan.frame = options.frame;
    plan.sharing = options.sharing;
    plan.resources.reserve(pending.size());
    for (uint32_t r = 0; r < pending.size(); ++r) {
        for (const PortAddress& address : pending[r].kept_ports) resource_of_port[ports.flat(address)] = r;
        plan.resources.push_back(std::move(pending[r].resource));
    }

    // ---- spec classes: which resources may share a texture -------------------------------
    // Equal sharing: a class per texture shape (its shape never changes, only its usage
    // grows), found by key rather than by trying every class.
    using ShapeKey = std::tuple<rhi::Format, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t>;
    auto shape_key = [](const ResolvedSpec& spec) {
        return ShapeKey{spec.format, spec.extent.width, spec.extent.height, spec.samples, spec.mips, spec.layers};
    };
    std::map<ShapeKey, uint32_t> class_of_shape;
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        PlanResource& resource = plan.resources[r];
        uint32_t chosen = kNone;
        if (options.sharing == SpecSharing::Equal) {
            auto it = class_of_shape.find(shape_key(resource.spec));
            if (it != class_of_shape.end()) {
                chosen = it->second;
                plan.spec_classes[chosen].spec.usage |= resource.spec.usage;
            } else {
                class_of_shape.emplace(shape_key(resource.spec), static_cast<uint32_t>(plan.spec_classes.size()));
            }
        }
        for (uint32_t c = 0; options.sharing != SpecSharing::Equal && c < plan.spec_classes.size() && chosen == kNone;
             ++c) {
            SpecClass& spec_class = plan.spec_classes[c];
            if (auto joined = join_resolved(spec_class.spec, resource.spec, options.frame)) {
                spec_class.spec = *joined;
                chosen = c;
            }
        }
        if (chosen == kNone) {
            chosen = static_cast<uint32_t>(plan.spec_classes.size());
            plan.spec_classes.push_back(SpecClass{resource.spec, {}, 0});
        }
        resource.spec_class = chosen;
        plan.spec_classes[chosen].resources.push_back(r);
    }
    const auto class_count = static_cast<uint32_t>(plan.spec_classes.size());
    const Peaks peaks = measure_peaks(plan.resources, scheduled, class_count);
    for (uint32_t c = 0; c < class_count; ++c) plan.spec_classes[c].peak_live = peaks.live_per_class[c];

    // ---- scheduled passes with their ports -------------------------------------------------
    AllocationProblem problem;
    problem.spec_class_count = class_count;
    problem.max_heap_bytes = options.max_heap_bytes;
    problem.passes.resize(scheduled);
    plan.order.reserve(scheduled);
    for (uint32_t at = 0; at < scheduled; ++at) {
        const uint32_t p = order[at];
        const Pass& pass = graph.pass(PassId{p});
        PlanPass planned{pass.name(), p, pass.side_effect(), {}};
        AllocationPass& step = problem.passes[at];
        for (uint32_t i = 0; i < pass.ports().size(); ++i) {
            const Port& port = pass.ports()[i];
            PlanPort planned_port{port.name, port.kind, port.optional, std::nullopt, TextureUsage::None};
            const uint32_t r = resource_of_port[ports.flat({p, i})];
            if (r != kNone) {
                planned_port.resource = r;
                planned_port.usage = port_usage(port, plan.resources[r].spec.format);
                if (port_reads(port.kind)) step.inputs.push_back(r);
                if (port_writes(port.kind)) step.non_inputs.push_back(r);
            }
            planned.ports.push_back(std::move(planned_port));
        }
        plan.order.push_back(std::move(planned));
    }
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        const PlanResource& resource = plan.resources[r];
        problem.passes[resource.lifetime.first].begins.push_back(r);
        problem.resources.push_back(
            AllocationResource{resource.spec_class, resource.lifetime, resource.bytes, resource.alignment, resource.name});
    }
    std::vector<bool> listed_output(plan.resources.size(), false);
    for (const PortAddress& out : graph.outputs()) {
        const uint32_t r = resource_of_port[ports.flat(out)];
        if (r != kNone && !listed_output[r]) {
            listed_output[r] = true;
            problem.graph_outputs.push_back(r);
        }
    }
    plan.culled = detail::culled_pass_names(graph, *kept);
    for (const Connection& c : graph.connections()) {
        if (!(*kept)[c.from.pass] || !(*kept)[c.to.pass]) continue;
        const uint32_t r = resource_of_port[ports.flat(c.to)];
        plan.edges.push_back(PlanEdge{position[c.from.pass], c.from.port, position[c.to.pass], c.to.port, r});
    }
    for (const PortAddress& out : graph.outputs()) plan.graph_outputs.push_back(graph.port_name(out));

    // ---- allocation -----------------------------------------------------------------------
    auto allocation = (*allocator)->allocate(problem);
    if (!allocation) return allocation.take_error();
    const bool placed = !allocation->texture_placement.empty();
    const bool well_formed =
        allocation->texture_of_resource.size() == plan.resources.size() &&
        std::all_of(allocation->texture_of_resource.begin(), allocation->texture_of_resource.end(),
                    [&](uint32_t t) { return t < allocation->texture_count; }) &&
        (!placed || allocation->texture_placement.size() == allocation->texture_count);
    if (!well_formed) return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' returned a malformed allocation");
    // Number textures by first use, so plans read the same whatever an allocator's own numbering.
    std::vector<uint32_t> first_user(allocation->texture_count, kNone);
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        uint32_t& first = first_user[allocation->texture_of_resource[r]];
        first = std::min(first, r);
    }
    if (std::find(first_user.begin(), first_user.end(), kNone) != first_user.end()) {
        return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' made a texture no resource uses");
    }
    std::vector<uint32_t> by_first_use(allocation->texture_count);
    std::iota(by_first_use.begin(), by_first_use.end(), 0u);
    std::sort(by_first_use.begin(), by_first_use.end(),
              [&](uint32_t a, uint32_t b) { return first_user[a] < first_user[b]; });
    std::vector<uint32_t> renumbered(allocation->texture_count);
    for (uint32_t t = 0; t < by_first_use.size(); ++t) renumbered[by_first_use[t]] = t;

    plan.textures.resize(allocation->texture_count);
    for (uint32_t t = 0; t < allocation->texture_count; ++t) {
        plan.textures[t].name = "t" + std::to_string(t);
        if (placed) plan.textures[t].placement = allocation->texture_placement[by_first_use[t]];
    }
    for (uint32_t r = 0; r < plan.resources.size(); ++r) {
        const uint32_t t = renumbered[allocation->texture_of_resource[r]];
        PlanResource& resource = plan.resources[r];
        PlanTexture& texture = plan.textures[t];
        resource.texture = t;
        if (texture.resources.empty()) {
            texture.spec = resource.spec;
        } else if (auto joined = join_resolved(texture.spec, resource.spec, options.frame)) {
            texture.spec = *joined;
        } else {
            return make_error(ErrorCode::Graph, "allocator '" + plan.allocator + "' put " + resource.name +
                                                    " into a texture of a spec it does not join with");
        }
        texture.resources.push_back(r);
    }
    for (uint32_t t = 0; t < plan.textures.size(); ++t) {
        PlanTexture& texture = plan.textures[t];
        if (texture.resources.size() == 1) {
            texture.bytes = plan.resources[texture.resources.front()].bytes;
            texture.alignment = plan.resources[texture.resources.front()].alignment;
        } else {
            auto requirements = memory->requirements(to_texture_desc(texture.spec, texture.name));
            if (!requirements) return requirements.take_error();
            texture.bytes = requirements->size;
            texture.alignment = std::max<uint64_t>(requirements->alignment, 1);
        }
    }
    plan.heaps = allocation->heap_sizes;

    // ---- summary --------------------------------------------------------------------------
    PlanSummary& summary = plan.summary;
    summary.textures = static_cast<uint32_t>(plan.textures.size());
    if (placed) {
        summary.bytes = std::accumulate(plan.heaps.begin(), plan.heaps.end(), uint64_t{0});
    } else {
        for (const PlanTexture& texture : plan.textures) summary.bytes += texture.bytes;
    }
    summary.naive_textures = static_cast<uint32_t>(plan.resources.size());
    for (const PlanResource& resource : plan.resources) summary.naive_bytes += resource.bytes;
    for (const SpecClass& spec_class : plan.spec_classes) summary.lower_bound_textures += spec_class.peak_live;
    summary.lower_bound_bytes = peaks.bytes;
    return plan;
}

}  // namespace loom::fg
