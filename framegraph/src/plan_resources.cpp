// The logical resources of a plan: the join and resolve phases of build_plan, and the ports of
// the scheduled passes with the resource and usage of each.
#include <algorithm>
#include <array>
#include <numeric>
#include <optional>
#include <span>
#include <utility>

#include "loom/framegraph/join.hpp"
#include "loom/rhi/checked_math.hpp"
#include "plan_phases.hpp"

namespace loom::fg::detail {
namespace {

using rhi::TextureUsage;

// True when the port at `address` starts a group: an output, or an inout nothing feeds.
bool starts_group(const FrameGraph& graph, const PortFacts& port, PortAddress address) {
    return port.kind == PortKind::Output || (port.kind == PortKind::InOut && !graph.source(address));
}

// The group `start` begins, into `group` (cleared first): `start`, then breadth-first the
// ports each port feeds, in connection order. Only outputs and inouts feed ports (connect and
// Pass::read refuse anything else), so an input's consumers are empty and its kind need not be
// looked up.
void collect_group(const FrameGraph& graph, PortAddress start, std::vector<PortAddress>& group) {
    group.clear();
    group.push_back(start);
    for (std::size_t next = 0; next < group.size(); ++next) {
        const std::span<const PortAddress> consumers = graph.consumers(group[next]);
        group.insert(group.end(), consumers.begin(), consumers.end());
    }
}

// Calls visit(group ports) for every group of the graph in declaration order of their starting
// ports, reusing one array for the ports; stops at the first error visit returns.
template <class Visit>
Status for_each_group(const FrameGraph& graph, Visit visit) {
    std::vector<PortAddress> group;
    for (uint32_t p = 0; p < graph.pass_count(); ++p) {
        const std::span<const PortFacts> ports = graph.port_facts(PassId{p});
        for (uint32_t i = 0; i < ports.size(); ++i) {
            const PortAddress start{p, i};
            if (!starts_group(graph, ports[i], start)) continue;
            collect_group(graph, start, group);
            LOOM_TRY(visit(std::span<const PortAddress>(group)));
        }
    }
    return {};
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
// that first constrained the conflicting property and the port that contradicts it. Sets
// `sizes_compared` when two ports declare sizes differently (an absolute and a relative one):
// the join then holds for this frame size only.
Result<TextureSpec> join_group(const FrameGraph& graph, std::span<const PortAddress> group, Extent2D frame,
                               bool& sizes_compared) {
    TextureSpec joined;
    // First port to constrain each property: format, size, samples, mips, layers.
    std::array<std::optional<PortAddress>, 5> origin{};
    bool first = true;
    for (const PortAddress& address : group) {
        // Joining with an unconstrained spec changes nothing, and the first spec joined with the
        // empty start is itself: most ports of a graph (reads) constrain nothing, so most joins
        // need not run, and their Port is not read. No property is constrained by such a port,
        // so `origin` stays as it is.
        if (graph.facts(address).unconstrained) {
            first = false;
            continue;
        }
        const TextureSpec& spec = graph.port_at(address).spec;
        if (first) {
            first = false;
            joined = spec;
            if (spec.format) origin[0] = address;
            if (spec.size) origin[1] = address;
            if (spec.samples) origin[2] = address;
            if (spec.mips) origin[3] = address;
            if (spec.layers) origin[4] = address;
            continue;
        }
        if (joined.size && spec.size && *joined.size != *spec.size) sizes_compared = true;
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

// A buffer group's join in group order; on a size conflict the error names the port that first
// gave a size and the port that contradicts it. Names are written only for the error. Sets
// `sizes_compared` as join_group does.
Result<BufferSpec> join_buffer_group(const FrameGraph& graph, std::span<const PortAddress> group, Extent2D frame,
                                     bool& sizes_compared) {
    BufferSpec joined;
    std::optional<PortAddress> sized;
    JoinContext context;
    context.frame = frame;
    for (const PortAddress& address : group) {
        const BufferSpec& spec = graph.port_at(address).buffer;
        if (joined.size && spec.size && *joined.size != *spec.size) sizes_compared = true;
        auto result = join_buffer_specs(joined, spec, context);
        if (!result) {
            // Only sizes conflict, so a port gave one before: name it and this port.
            const std::string a_name = graph.port_name(*sized);
            const std::string b_name = graph.port_name(address);
            JoinContext named = context;
            named.a_name = a_name;
            named.b_name = b_name;
            Error error = join_buffer_specs(joined, spec, named).take_error();
            error.subjects = {b_name, a_name};
            return error;
        }
        if (spec.size && !sized) sized = address;
        joined = std::move(*result);
    }
    return joined;
}

// A resource being resolved, before its index is known (resources are numbered once sorted by
// producer position): the resource made in place, the port that starts it, and the group's
// ports whose passes run, the starting port first.
struct PendingResource {
    PlanResource& resource;
    PortAddress start;
    std::span<const PortAddress> kept_ports;
};

// The running part of a group whose producer runs: its running ports, appended to `kept`,
// whether one is a graph output, and the positions they span (a graph output lives to the last
// position).
void running_part(const FrameGraph& graph, std::span<const PortAddress> group, const Schedule& schedule,
                  std::vector<PortAddress>& kept, PlanResource& resource) {
    const std::vector<uint32_t>& position = schedule.position;
    const PortAddress start = group.front();
    bool graph_output = false;
    uint32_t last = position[start.pass];
    for (const PortAddress& address : group) {
        if (position[address.pass] == kNotScheduled) continue;
        kept.push_back(address);
        graph_output = graph_output || graph.is_output(address);
        last = std::max(last, position[address.pass]);
    }
    const auto last_position = static_cast<uint32_t>(schedule.order.size() - 1);
    resource.graph_output = graph_output;
    resource.lifetime = {position[start.pass], graph_output ? last_position : last};
    resource.occupancy = resource.lifetime;
}

// Fills in what a buffer group's joined spec decides: the resolved spec with the usage of the
// running ports, the port names, and the bytes the memory model asks for.
Status resolve_pending_buffer(const FrameGraph& graph, const BufferSpec& joined, Extent2D frame, MemoryModel& memory,
                              PendingResource& item) {
    PlanResource& r = item.resource;
    r.name = graph.port_name(item.start);
    r.type = ResourceType::Buffer;
    r.texture = kNoPhysical;
    auto subjects = [&](Error error) {
        for (const PortAddress& address : item.kept_ports) error.subjects.push_back(graph.port_name(address));
        return error;
    };
    auto resolved = resolve_buffer(joined, frame, r.name);
    if (!resolved) return subjects(resolved.take_error());
    for (const PortAddress& address : item.kept_ports) {
        auto role = port_buffer_usage(graph, address);
        if (!role) return role.take_error();
        resolved->usage |= *role;
    }
    if (r.graph_output) resolved->usage |= rhi::BufferUsage::CopySrc;
    for (const PortAddress& address : item.kept_ports) {
        const BufferRange& bytes = graph.port_at(address).bytes;
        if (!resolve_bytes(bytes, resolved->size)) {
            Error error = make_error(ErrorCode::Graph, "port " + graph.port_name(address) + " uses bytes " +
                                                           std::to_string(bytes.offset) + "+" + std::to_string(bytes.size) +
                                                           " of buffer " + r.name + ", which has " +
                                                           std::to_string(resolved->size) + " bytes");
            error.subjects = {graph.port_name(address)};
            return error;
        }
    }
    r.buffer_spec = *resolved;
    Status measured = measure_resource(r, memory);
    if (!measured) return subjects(measured.error());
    return {};
}

// Fills in what the joined spec decides: the resolved spec with the usage of the running
// ports, the port names, and the bytes the memory model asks for.
Status resolve_pending(const FrameGraph& graph, const TextureSpec& joined, Extent2D frame, MemoryModel& memory,
                       PendingResource& item) {
    PlanResource& r = item.resource;
    r.name = graph.port_name(item.start);
    auto resolved = resolve(joined, frame, r.name);
    if (!resolved) {
        Error error = resolved.take_error();
        for (const PortAddress& address : item.kept_ports) error.subjects.push_back(graph.port_name(address));
        return error;
    }
    TextureUsage usage = TextureUsage::None;
    for (const PortAddress& address : item.kept_ports) usage |= port_texture_usage(graph.facts(address), resolved->format);
    if (r.graph_output) usage |= TextureUsage::CopySrc;
    resolved->usage = usage;
    for (const PortAddress& address : item.kept_ports) {
        if (graph.facts(address).whole) continue;  // the default range fits any texture
        const SubresourceRange& range = graph.port_at(address).range;
        if (!resolve_range(range, resolved->mips, resolved->layers)) {
            Error error = make_error(ErrorCode::Graph, "port " + graph.port_name(address) + " uses " + describe_range(range) +
                                                           " of texture " + r.name + ", which has " +
                                                           std::to_string(resolved->mips) + " mips and " +
                                                           std::to_string(resolved->layers) + " layers");
            error.subjects = {graph.port_name(address)};
            return error;
        }
    }

    r.requested_format = joined.format;
    r.spec = *resolved;
    return measure_resource(r, memory);
}

// The running ports of resources put in another order into `out`: its resource k's are
// resource by[k]'s of (`first`, `ports`) (laid out as ResolvedResources::running_ports).
void permute_running_ports(std::span<const uint32_t> by, const std::vector<uint32_t>& first,
                           const std::vector<PortAddress>& ports, ResolvedResources& out) {
    out.running_ports.resize(ports.size());
    out.first_running_port.assign(by.size() + 1, 0);
    for (std::size_t k = 0; k < by.size(); ++k) {
        const uint32_t i = by[k];
        const uint32_t begin = out.first_running_port[k];
        std::copy(ports.begin() + first[i], ports.begin() + first[i + 1], out.running_ports.begin() + begin);
        out.first_running_port[k + 1] = begin + first[i + 1] - first[i];
    }
}

// The buffers' joined sizes of resources put in another order: resource by[k]'s becomes
// resource k's; by resource index.
std::vector<std::pair<uint32_t, BufferSize>> renumber_buffer_sizes(
    const std::vector<std::pair<uint32_t, BufferSize>>& sizes, std::span<const uint32_t> by) {
    if (sizes.empty()) return {};
    std::vector<uint32_t> renumbered(by.size());
    for (uint32_t k = 0; k < by.size(); ++k) renumbered[by[k]] = k;
    std::vector<std::pair<uint32_t, BufferSize>> out;
    out.reserve(sizes.size());
    for (const auto& [r, size] : sizes) out.emplace_back(renumbered[r], size);
    std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    return out;
}

// The resources of the groups given one by one in group order (resolve_resources): each made
// in place in one array, with its starting port and its running ports one after another in
// `kept_` (resource i's are kept_[first_kept_[i], first_kept_[i + 1])), then numbered in order
// of their producers' positions.
class ResourceBuilder {
public:
    ResourceBuilder(const FrameGraph& graph, const Schedule& schedule, Extent2D frame, MemoryModel& memory,
                    std::size_t group_count)
        : graph_(graph), schedule_(schedule), frame_(frame), memory_(memory) {
        resources_.reserve(group_count);
        joined_sizes_.reserve(group_count);
        starts_.reserve(group_count);
        first_kept_.reserve(group_count + 1);
        first_kept_.push_back(0);
    }

    // The resource of a group whose ports join to `spec` (a texture group) or `buffer` (a
    // buffer group), if its producer runs.
    Status add(std::span<const PortAddress> group, ResourceType type, const TextureSpec& spec, const BufferSpec& buffer) {
        const PortAddress start = group.front();
        if (schedule_.position[start.pass] == kNotScheduled) return {};
        const std::size_t first = kept_.size();
        PlanResource& resource = resources_.emplace_back();
        running_part(graph_, group, schedule_, kept_, resource);
        const std::span<const PortAddress> kept_ports(kept_.data() + first, kept_.size() - first);
        // An optional output nobody reads gets no texture.
        if (kept_ports.size() == 1 && !resource.graph_output && graph_.facts(start).optional) {
            resources_.pop_back();
            kept_.resize(first);
            return {};
        }
        PendingResource item{resource, start, kept_ports};
        if (type == ResourceType::Buffer) {
            LOOM_TRY(resolve_pending_buffer(graph_, buffer, frame_, memory_, item));
            // A buffer resolves only with a size.
            joined_buffer_sizes_.emplace_back(static_cast<uint32_t>(resources_.size() - 1), *buffer.size);
            joined_sizes_.emplace_back();
        } else {
            LOOM_TRY(resolve_pending(graph_, spec, frame_, memory_, item));
            joined_sizes_.push_back(spec.size);
        }
        starts_.push_back(start);
        first_kept_.push_back(static_cast<uint32_t>(kept_.size()));
        return {};
    }

    // Set by the joins of the groups (a culled one's included) when one compared differently
    // declared sizes against the frame (ResolvedResources::joins_compared_sizes).
    bool joins_compared_sizes = false;

    // The resources in order of their producers' positions, then by port. Groups come in
    // declaration order, which is mostly that order already: then no resource moves.
    ResolvedResources finish() {
        const std::vector<uint32_t>& position = schedule_.position;
        const auto count = static_cast<uint32_t>(resources_.size());
        auto starts_earlier = [&](uint32_t a, uint32_t b) {
            return std::pair(position[starts_[a].pass], starts_[a].port) <
                   std::pair(position[starts_[b].pass], starts_[b].port);
        };
        std::vector<uint32_t> by_start(count);
        std::iota(by_start.begin(), by_start.end(), 0u);
        const bool in_order = std::is_sorted(by_start.begin(), by_start.end(), starts_earlier);
        if (!in_order) std::stable_sort(by_start.begin(), by_start.end(), starts_earlier);

        ResolvedResources resolved;
        resolved.resource_of_port = PortTable(graph_, kNoResource);
        resolved.joins_compared_sizes = joins_compared_sizes;
        if (in_order) {
            resolved.resources = std::move(resources_);
            resolved.joined_sizes = std::move(joined_sizes_);
            resolved.joined_buffer_sizes = std::move(joined_buffer_sizes_);
            resolved.starts = std::move(starts_);
            resolved.running_ports = std::move(kept_);
            resolved.first_running_port = std::move(first_kept_);
        } else {
            resolved.resources.reserve(count);
            resolved.joined_sizes.reserve(count);
            resolved.starts.reserve(count);
            for (uint32_t i : by_start) {
                resolved.resources.push_back(std::move(resources_[i]));
                resolved.joined_sizes.push_back(joined_sizes_[i]);
                resolved.starts.push_back(starts_[i]);
            }
            permute_running_ports(by_start, first_kept_, kept_, resolved);
            resolved.joined_buffer_sizes = renumber_buffer_sizes(joined_buffer_sizes_, by_start);
        }
        for (uint32_t r = 0; r < count; ++r) {
            for (const PortAddress& address : resolved.running_ports_of(r)) {
                resolved.resource_of_port[address.pass][address.port] = r;
            }
        }
        std::vector<bool> listed(count, false);
        for (const PortAddress& out : graph_.outputs()) {
            const uint32_t r = resolved.resource_of_port[out.pass][out.port];
            if (r != kNoResource && !listed[r]) {
                listed[r] = true;
                resolved.graph_output_resources.push_back(r);
            }
        }
        return resolved;
    }

private:
    const FrameGraph& graph_;
    const Schedule& schedule_;
    Extent2D frame_;
    MemoryModel& memory_;
    std::vector<PlanResource> resources_;
    std::vector<std::optional<SizeSpec>> joined_sizes_;
    std::vector<std::pair<uint32_t, BufferSize>> joined_buffer_sizes_;
    std::vector<PortAddress> starts_;
    std::vector<PortAddress> kept_;
    std::vector<uint32_t> first_kept_;
};

}  // namespace

Status measure_resource(PlanResource& resource, MemoryModel& memory) {
    if (resource.type == ResourceType::Texture) {
        auto requirements = memory.requirements(to_texture_desc(resource.spec, resource.name));
        if (!requirements) return requirements.take_error();
        resource.bytes = requirements->size;
        resource.alignment = std::max<uint64_t>(requirements->alignment, 1);
        return {};
    }
    const ResolvedBufferSpec& spec = resource.buffer_spec;
    auto requirements = memory.buffer_requirements(to_buffer_desc(spec, resource.name));
    if (!requirements) return requirements.take_error();
    resource.alignment = std::max({requirements->alignment, spec.alignment, uint64_t{1}});
    auto bytes = checked::align_up(std::max(requirements->size, spec.size), resource.alignment);
    if (!bytes) return make_error(ErrorCode::Graph, "buffer " + resource.name + ": its size overflows when aligned");
    resource.bytes = *bytes;
    return {};
}

PortTable::PortTable(const FrameGraph& graph, uint32_t value) {
    first_.reserve(graph.pass_count() + 1);
    first_.push_back(0);
    for (uint32_t p = 0; p < graph.pass_count(); ++p) {
        first_.push_back(first_.back() + static_cast<uint32_t>(graph.port_facts(PassId{p}).size()));
    }
    values_.assign(first_.back(), value);
}

bool operator==(const PortTable& table, const std::vector<std::vector<uint32_t>>& per_pass) {
    if (table.size() != per_pass.size()) return false;
    for (uint32_t p = 0; p < table.size(); ++p) {
        if (!std::equal(table[p].begin(), table[p].end(), per_pass[p].begin(), per_pass[p].end())) return false;
    }
    return true;
}

std::optional<SubresourceRange> resolve_range(const SubresourceRange& range, uint32_t mips, uint32_t layers) {
    auto resolve_part = [](uint32_t base, uint32_t count, uint32_t total) -> std::optional<uint32_t> {
        if (base >= total) return std::nullopt;
        if (count == rhi::kRemainingSubresources) return total - base;
        if (count == 0 || count > total - base) return std::nullopt;
        return count;
    };
    auto mip_count = resolve_part(range.base_mip, range.mip_count, mips);
    auto layer_count = resolve_part(range.base_layer, range.layer_count, layers);
    if (!mip_count || !layer_count) return std::nullopt;
    return SubresourceRange{range.base_mip, *mip_count, range.base_layer, *layer_count};
}

std::optional<BufferRange> resolve_bytes(const BufferRange& bytes, uint64_t size) {
    if (bytes.offset >= size) return std::nullopt;
    if (bytes.size == 0) return BufferRange{bytes.offset, size - bytes.offset};
    if (bytes.size > size - bytes.offset) return std::nullopt;
    return bytes;
}

Status JoinedGroup::status() const {
    if (!spec) return spec.error();
    if (!buffer) return buffer.error();
    return {};
}

TextureUsage port_texture_usage(const PortFacts& port, rhi::Format format) {
    TextureUsage usage = port.requested_usage;
    switch (port.pass_kind) {
        case PassKind::Copy:
            return usage | (port_writes(port.kind) ? TextureUsage::CopyDst : TextureUsage::CopySrc);
        case PassKind::Compute:
            return usage | (port_writes(port.kind) ? TextureUsage::Storage : TextureUsage::Sampled);
        case PassKind::Graphics: break;
    }
    if (rhi::has_all(port.requested_usage, TextureUsage::Storage)) return usage;
    if (port_writes(port.kind)) {
        usage |= rhi::format_info(format).is_depth_stencil() ? TextureUsage::DepthStencilAttachment
                                                             : TextureUsage::ColorAttachment;
    } else {
        usage |= TextureUsage::Sampled;
    }
    return usage;
}

rhi::BufferUsage default_buffer_use(PortKind kind, PassKind pass_kind) {
    const bool copy = pass_kind == PassKind::Copy;
    if (port_writes(kind)) return copy ? rhi::BufferUsage::CopyDst : rhi::BufferUsage::Storage;
    return copy ? rhi::BufferUsage::CopySrc : rhi::BufferUsage::Storage;
}

Result<rhi::BufferUsage> port_buffer_usage(const FrameGraph& graph, PortAddress address) {
    using rhi::BufferUsage;
    const Port& port = graph.port_at(address);
    const PassKind pass_kind = graph.pass(PassId{address.pass}).kind();
    if (port_writes(port.kind)) return default_buffer_use(port.kind, pass_kind);
    static constexpr BufferUsage kReads[] = {BufferUsage::Vertex, BufferUsage::Index, BufferUsage::Uniform,
                                             BufferUsage::Storage, BufferUsage::Indirect, BufferUsage::CopySrc};
    BufferUsage read = BufferUsage::None;
    for (BufferUsage flag : kReads) {
        if (!rhi::has_all(port.buffer.usage, flag)) continue;
        if (read != BufferUsage::None) {
            const std::string port_name = graph.port_name(address);
            Error error = make_error(ErrorCode::Graph,
                                     "port " + port_name + " reads its buffer in several ways (" +
                                         describe_buffer_usage(read | flag) +
                                         "); a port reads a buffer one way: declare one input port per use");
            error.subjects = {port_name};
            return error;
        }
        read = flag;
    }
    if (read != BufferUsage::None) return read;
    return default_buffer_use(port.kind, pass_kind);
}

std::vector<JoinedGroup> join_port_groups(const FrameGraph& graph, Extent2D frame) {
    std::vector<JoinedGroup> joined;
    // Join errors are kept in their groups, so visiting never stops.
    (void)for_each_group(graph, [&](std::span<const PortAddress> group) -> Status {
        std::vector<PortAddress> ports(group.begin(), group.end());
        bool sizes_compared = false;
        if (graph.facts(group.front()).type == ResourceType::Buffer) {
            Result<BufferSpec> buffer = join_buffer_group(graph, group, frame, sizes_compared);
            joined.push_back(
                JoinedGroup{std::move(ports), TextureSpec{}, ResourceType::Buffer, std::move(buffer), sizes_compared});
        } else {
            Result<TextureSpec> spec = join_group(graph, group, frame, sizes_compared);
            joined.push_back(JoinedGroup{std::move(ports), std::move(spec), ResourceType::Texture, BufferSpec{},
                                         sizes_compared});
        }
        return {};
    });
    return joined;
}

Result<ResolvedResources> resolve_resources(const FrameGraph& graph, const std::vector<JoinedGroup>& groups,
                                            const Schedule& schedule, Extent2D frame, MemoryModel& memory) {
    ResourceBuilder builder(graph, schedule, frame, memory, groups.size());
    for (const JoinedGroup& group : groups) {
        // A join error is reported only when its group is reached: the first group at fault (in
        // declaration order) gives the error, whether its ports do not join or its spec does not
        // resolve.
        LOOM_TRY(group.status());
        builder.joins_compared_sizes = builder.joins_compared_sizes || group.sizes_compared;
        LOOM_TRY(builder.add(group.ports, group.type, *group.spec, *group.buffer));
    }
    return builder.finish();
}

Result<ResolvedResources> resolve_resources(const FrameGraph& graph, const Schedule& schedule, Extent2D frame,
                                            MemoryModel& memory) {
    std::size_t group_count = 0;
    for (uint32_t p = 0; p < graph.pass_count(); ++p) {
        const std::span<const PortFacts> ports = graph.port_facts(PassId{p});
        for (uint32_t i = 0; i < ports.size(); ++i) group_count += starts_group(graph, ports[i], {p, i}) ? 1 : 0;
    }
    ResourceBuilder builder(graph, schedule, frame, memory, group_count);
    // Each group joined and resolved before the next is collected: the first group at fault
    // gives the error, as when every group is joined first (join_port_groups).
    LOOM_TRY(for_each_group(graph, [&](std::span<const PortAddress> group) -> Status {
        if (graph.facts(group.front()).type == ResourceType::Buffer) {
            Result<BufferSpec> buffer = join_buffer_group(graph, group, frame, builder.joins_compared_sizes);
            if (!buffer) return buffer.take_error();
            return builder.add(group, ResourceType::Buffer, TextureSpec{}, *buffer);
        }
        Result<TextureSpec> spec = join_group(graph, group, frame, builder.joins_compared_sizes);
        if (!spec) return spec.take_error();
        return builder.add(group, ResourceType::Texture, *spec, BufferSpec{});
    }));
    return builder.finish();
}

Status rejoin_resource(const FrameGraph& graph, PortAddress start, std::span<const uint32_t> position, Extent2D frame,
                       MemoryModel& memory, PlanResource& resource, std::optional<SizeSpec>& joined_size,
                       std::vector<PortAddress>& running) {
    std::vector<PortAddress> group;
    collect_group(graph, start, group);
    bool sizes_compared = false;
    Result<TextureSpec> joined = join_group(graph, group, frame, sizes_compared);
    if (!joined) return joined.take_error();
    if (sizes_compared) {
        return make_error(ErrorCode::Join, "resource " + resource.name + ": its sizes join for this frame size only");
    }
    running.clear();
    for (const PortAddress& address : group) {
        if (position[address.pass] != kNotScheduled) running.push_back(address);
    }
    PendingResource item{resource, start, running};
    LOOM_TRY(resolve_pending(graph, *joined, frame, memory, item));
    joined_size = joined->size;
    return {};
}

void name_resource_ports(const std::vector<PlanPass>& order, ResolvedResources& resolved) {
    // Each running port's place in its resource's list; the first, the starting port, which
    // runs with its producer, is named by the resource's own name.
    PortTable place = resolved.resource_of_port;
    std::fill(place.values().begin(), place.values().end(), 0u);
    for (uint32_t r = 0; r < resolved.resources.size(); ++r) {
        const std::span<const PortAddress> running = resolved.running_ports_of(r);
        std::vector<std::string>& ports = resolved.resources[r].ports;
        ports.clear();
        ports.resize(running.size());
        ports[0] = resolved.resources[r].name;
        for (uint32_t k = 1; k < running.size(); ++k) place[running[k].pass][running[k].port] = k;
    }
    // The others from the plan's passes, pass by pass: just made, they are still in cache, where
    // the graph's passes and ports are scattered in memory (on big graphs, reading those for
    // every port was most of the cost of naming them).
    for (const PlanPass& pass : order) {
        const std::span<const uint32_t> places = place[pass.declaration_index];
        for (uint32_t i = 0; i < places.size(); ++i) {
            if (places[i] == 0) continue;
            const std::string& port = pass.ports[i].name;
            std::string& name = resolved.resources[*pass.ports[i].resource].ports[places[i]];
            name.reserve(pass.name.size() + 1 + port.size());
            name.append(pass.name).append(1, '.').append(port);
        }
    }
}

ResolvedResources reorder_resources(const ResolvedResources& resolved, const Schedule& schedule) {
    const std::vector<uint32_t>& position = schedule.position;
    const auto resource_count = static_cast<uint32_t>(resolved.resources.size());
    const auto position_count = static_cast<uint32_t>(schedule.order.size());
    std::vector<uint32_t> last(resource_count, 0);
    for (uint32_t pass = 0; pass < resolved.resource_of_port.size(); ++pass) {
        if (position[pass] == kNotScheduled) continue;
        for (uint32_t r : resolved.resource_of_port[pass]) {
            if (r != kNoResource) last[r] = std::max(last[r], position[pass]);
        }
    }
    // By their producers' new positions (a counting sort): a pass's resources keep their order,
    // which is by port already.
    std::vector<uint32_t> first_at(position_count + 1, 0);
    for (const PortAddress& start : resolved.starts) ++first_at[position[start.pass] + 1];
    for (uint32_t k = 0; k < position_count; ++k) first_at[k + 1] += first_at[k];
    std::vector<uint32_t> renumbered(resource_count);
    for (uint32_t r = 0; r < resource_count; ++r) renumbered[r] = first_at[position[resolved.starts[r].pass]]++;
    std::vector<uint32_t> by_start(resource_count);
    for (uint32_t r = 0; r < resource_count; ++r) by_start[renumbered[r]] = r;

    const uint32_t last_position = position_count - 1;
    ResolvedResources out;
    out.resources.reserve(resource_count);
    out.joined_sizes.reserve(resource_count);
    out.starts.reserve(resource_count);
    out.joins_compared_sizes = resolved.joins_compared_sizes;
    for (uint32_t r : by_start) {
        // PlanResource::ports is not named yet (name_resource_ports), so no string but the
        // resource's name is copied.
        PlanResource& resource = out.resources.emplace_back(resolved.resources[r]);
        resource.lifetime = {position[resolved.starts[r].pass], resource.graph_output ? last_position : last[r]};
        resource.occupancy = resource.lifetime;
        out.joined_sizes.push_back(resolved.joined_sizes[r]);
        out.starts.push_back(resolved.starts[r]);
    }
    permute_running_ports(by_start, resolved.first_running_port, resolved.running_ports, out);
    out.joined_buffer_sizes = renumber_buffer_sizes(resolved.joined_buffer_sizes, by_start);
    out.resource_of_port = resolved.resource_of_port;
    for (uint32_t& r : out.resource_of_port.values()) {
        if (r != kNoResource) r = renumbered[r];
    }
    for (uint32_t r : resolved.graph_output_resources) out.graph_output_resources.push_back(renumbered[r]);
    return out;
}

std::vector<PlanPass> plan_passes(const FrameGraph& graph, const Schedule& schedule,
                                  const ResolvedResources& resolved) {
    std::vector<PlanPass> passes;
    passes.reserve(schedule.order.size());
    for (uint32_t p : schedule.order) {
        const Pass& pass = graph.pass(PassId{p});
        PlanPass planned{pass.name(), p, pass.side_effect(), {}, pass.kind(), pass.queue()};
        planned.ports.reserve(pass.ports().size());
        for (uint32_t i = 0; i < pass.ports().size(); ++i) {
            const Port& port = pass.ports()[i];
            PlanPort planned_port{port.name, port.kind, port.optional, std::nullopt, TextureUsage::None, port.type};
            // A buffer port's use is its role's with or without a buffer behind it (an imported
            // buffer may stand in). Ports with a resource were checked when it was resolved.
            if (port.type == ResourceType::Buffer) {
                planned_port.buffer_usage =
                    port_buffer_usage(graph, {p, i}).value_or(default_buffer_use(port.kind, pass.kind()));
            }
            const uint32_t r = resolved.resource_of_port[p][i];
            if (r != kNoResource) {
                planned_port.resource = r;
                // Usages and ranges were checked when the resource was resolved.
                const PlanResource& resource = resolved.resources[r];
                if (port.type == ResourceType::Buffer) {
                    planned_port.bytes = resolve_bytes(port.bytes, resource.buffer_spec.size).value_or(BufferRange{});
                } else {
                    planned_port.usage = port_texture_usage(graph.facts({p, i}), resource.spec.format);
                    planned_port.range =
                        resolve_range(port.range, resource.spec.mips, resource.spec.layers).value_or(SubresourceRange{});
                }
            }
            planned.ports.push_back(std::move(planned_port));
        }
        passes.push_back(std::move(planned));
    }
    return passes;
}

std::vector<PlanEdge> plan_edges(const FrameGraph& graph, const Schedule& schedule,
                                 const PortTable& resource_of_port) {
    const std::vector<uint32_t>& position = schedule.position;
    std::vector<PlanEdge> edges;
    edges.reserve(graph.connections().size());
    for (const Connection& c : graph.connections()) {
        if (position[c.from.pass] == kNotScheduled || position[c.to.pass] == kNotScheduled) continue;
        const uint32_t r = resource_of_port[c.to.pass][c.to.port];
        edges.push_back(PlanEdge{position[c.from.pass], c.from.port, position[c.to.pass], c.to.port, r});
    }
    return edges;
}

}  // namespace loom::fg::detail
