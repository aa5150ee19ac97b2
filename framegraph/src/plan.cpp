#include "loom/framegraph/plan.hpp"

#include <type_traits>

namespace loom::fg {
namespace {

// FNV-1a over every field, fed in a fixed order with explicit sizes, so the value is the same
// on every platform and run.
class Hasher {
public:
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            state_ ^= p[i];
            state_ *= 1099511628211ull;
        }
    }
    template <class T>
        requires std::is_integral_v<T> || std::is_enum_v<T>
    void add(T value) {
        const auto wide = static_cast<uint64_t>(value);
        unsigned char little_endian[8];
        for (int i = 0; i < 8; ++i) little_endian[i] = static_cast<unsigned char>(wide >> (8 * i));
        bytes(little_endian, sizeof little_endian);
    }
    void add(std::string_view text) {
        add(text.size());
        bytes(text.data(), text.size());
    }
    template <class T>
    void add(const std::optional<T>& value) {
        add(value.has_value());
        if (value) add(*value);
    }
    void add(const rhi::FormatFeatures& f) {
        for (const rhi::Channel& c : f.color) {
            add(c.bits);
            add(c.kind);
        }
        add(f.depth.bits);
        add(f.depth.kind);
        add(f.stencil_bits);
        add(f.shared_exponent_bits);
        add(f.srgb);
        add(f.compressed);
        add(f.bgra);
    }
    void add(const ResolvedSpec& s) {
        add(s.format);
        add(s.format_match);
        add(s.extent.width);
        add(s.extent.height);
        add(s.samples);
        add(s.mips);
        add(s.layers);
        add(s.usage);
        add(s.cube);
    }
    void add(const ResolvedBufferSpec& s) {
        add(s.size);
        add(s.usage);
        add(s.alignment);
    }
    void add(const HeapRange& r) {
        add(r.heap);
        add(r.offset);
    }
    [[nodiscard]] uint64_t value() const { return state_; }

private:
    uint64_t state_ = 14695981039346656037ull;
};

}  // namespace

std::string_view spec_sharing_name(SpecSharing sharing) {
    switch (sharing) {
        case SpecSharing::Equal: return "equal";
        case SpecSharing::Joinable: return "joinable";
    }
    return "unknown";
}

std::string_view pass_order_name(PassOrder order) {
    switch (order) {
        case PassOrder::Declared: return "declared";
        case PassOrder::Memory: return "memory";
    }
    return "unknown";
}

std::optional<PassOrder> parse_pass_order(std::string_view name) {
    if (name == "declared") return PassOrder::Declared;
    if (name == "memory") return PassOrder::Memory;
    return std::nullopt;
}

const PlanPass* Plan::find_pass(std::string_view name) const {
    for (const PlanPass& pass : order) {
        if (pass.name == name) return &pass;
    }
    return nullptr;
}

const PlanResource* Plan::resource_of(std::string_view pass_name, std::string_view port_name) const {
    const PlanPass* pass = find_pass(pass_name);
    if (!pass) return nullptr;
    for (const PlanPort& port : pass->ports) {
        if (port.name == port_name) return port.resource ? &resources[*port.resource] : nullptr;
    }
    return nullptr;
}

std::optional<uint32_t> Plan::texture_of(std::string_view pass_name, std::string_view port_name) const {
    const PlanResource* resource = resource_of(pass_name, port_name);
    if (!resource || resource->type != ResourceType::Texture) return std::nullopt;
    return resource->texture;
}

std::optional<uint32_t> Plan::buffer_of(std::string_view pass_name, std::string_view port_name) const {
    const PlanResource* resource = resource_of(pass_name, port_name);
    if (!resource || resource->type != ResourceType::Buffer) return std::nullopt;
    return resource->buffer;
}

std::string describe_port_range(const PlanResource& resource, const PlanPort& port) {
    if (resource.type == ResourceType::Buffer) {
        if (port.bytes.offset == 0 && port.bytes.size == resource.buffer_spec.size) return {};
        return "bytes " + std::to_string(port.bytes.offset) + "+" + std::to_string(port.bytes.size);
    }
    // The plan's counts are concrete: a part covering every level (layer) is left out.
    SubresourceRange shown = port.range;
    if (shown.base_mip == 0 && shown.mip_count == resource.spec.mips) shown.mip_count = rhi::kRemainingSubresources;
    if (shown.base_layer == 0 && shown.layer_count == resource.spec.layers) shown.layer_count = rhi::kRemainingSubresources;
    std::string text = describe_range(shown);
    return text == "whole" ? std::string() : text;
}

uint64_t plan_hash(const Plan& plan) {
    Hasher h;
    h.add(plan.allocator);
    h.add(plan.frame.width);
    h.add(plan.frame.height);
    h.add(plan.sharing);
    // Only the memory order's mode is hashed, so that declared-order plans keep the hashes they
    // had before the mode existed (logs and documents quote them).
    if (plan.pass_order != PassOrder::Declared) h.add(plan.pass_order);
    h.add(plan.order.size());
    for (const PlanPass& pass : plan.order) {
        h.add(pass.name);
        h.add(pass.declaration_index);
        h.add(pass.side_effect);
        h.add(pass.kind);
        h.add(pass.queue);
        h.add(pass.ports.size());
        for (const PlanPort& port : pass.ports) {
            h.add(port.name);
            h.add(port.kind);
            h.add(port.optional);
            h.add(port.resource);
            h.add(port.usage);
            h.add(port.type);
            h.add(port.buffer_usage);
            h.add(port.range.base_mip);
            h.add(port.range.mip_count);
            h.add(port.range.base_layer);
            h.add(port.range.layer_count);
            h.add(port.bytes.offset);
            h.add(port.bytes.size);
        }
    }
    h.add(plan.culled.size());
    for (const std::string& name : plan.culled) h.add(name);
    h.add(plan.edges.size());
    for (const PlanEdge& e : plan.edges) {
        h.add(e.from_pass);
        h.add(e.from_port);
        h.add(e.to_pass);
        h.add(e.to_port);
        h.add(e.resource);
    }
    h.add(plan.graph_outputs.size());
    for (const std::string& name : plan.graph_outputs) h.add(name);
    h.add(plan.resources.size());
    for (const PlanResource& r : plan.resources) {
        h.add(r.name);
        h.add(r.ports.size());
        for (const std::string& p : r.ports) h.add(p);
        h.add(r.requested_format);
        h.add(r.spec);
        h.add(r.lifetime.first);
        h.add(r.lifetime.last);
        h.add(r.occupancy.first);
        h.add(r.occupancy.last);
        h.add(r.queue_shared);
        h.add(r.graph_output);
        h.add(r.spec_class);
        h.add(r.bytes);
        h.add(r.alignment);
        h.add(r.texture);
        h.add(r.type);
        h.add(r.buffer_spec);
        h.add(r.buffer);
    }
    h.add(plan.spec_classes.size());
    for (const SpecClass& c : plan.spec_classes) {
        h.add(c.spec);
        h.add(c.resources.size());
        for (uint32_t r : c.resources) h.add(r);
        h.add(c.peak_live);
        h.add(c.type);
        h.add(c.buffer_spec);
    }
    h.add(plan.textures.size());
    for (const PlanTexture& t : plan.textures) {
        h.add(t.name);
        h.add(t.spec);
        h.add(t.resources.size());
        for (uint32_t r : t.resources) h.add(r);
        h.add(t.bytes);
        h.add(t.alignment);
        h.add(t.placement);
    }
    h.add(plan.buffers.size());
    for (const PlanBuffer& b : plan.buffers) {
        h.add(b.name);
        h.add(b.spec);
        h.add(b.resources.size());
        for (uint32_t r : b.resources) h.add(r);
        h.add(b.bytes);
        h.add(b.alignment);
        h.add(b.placement);
    }
    h.add(plan.heaps.size());
    for (uint64_t size : plan.heaps) h.add(size);
    const PlanSummary& s = plan.summary;
    h.add(s.textures);
    h.add(s.bytes);
    h.add(s.naive_textures);
    h.add(s.naive_bytes);
    h.add(s.lower_bound_textures);
    h.add(s.lower_bound_bytes);
    h.add(s.buffers);
    h.add(s.buffer_bytes);
    h.add(s.naive_buffers);
    h.add(s.lower_bound_buffers);
    h.add(plan.queue_syncs.size());
    for (const QueueSync& sync : plan.queue_syncs) {
        h.add(sync.from);
        h.add(sync.to);
        h.add(sync.signal_after);
        h.add(sync.wait_before);
    }
    h.add(plan.ownership_transfers.size());
    for (const OwnershipTransfer& t : plan.ownership_transfers) {
        h.add(t.resource);
        h.add(t.from);
        h.add(t.to);
        h.add(t.release_after);
        h.add(t.acquire_before);
    }
    return h.value();
}

}  // namespace loom::fg
