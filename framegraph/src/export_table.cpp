#include <algorithm>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <vector>

#include "loom/framegraph/export.hpp"
#include "text.hpp"

namespace loom::fg {
namespace {

// Left-aligned columns separated by two spaces.
class Table {
public:
    explicit Table(std::vector<std::string> header) { rows_.push_back(std::move(header)); }
    void add(std::vector<std::string> row) { rows_.push_back(std::move(row)); }

    // Columns are as wide as their widest cell, so a table is written only once it is complete.
    void render(std::ostream& out, std::string_view indent) const {
        std::vector<std::size_t> width;
        for (const auto& row : rows_) {
            width.resize(std::max(width.size(), row.size()), 0);
            for (std::size_t i = 0; i < row.size(); ++i) width[i] = std::max(width[i], row[i].size());
        }
        for (const auto& row : rows_) {
            std::string line(indent);
            for (std::size_t i = 0; i < row.size(); ++i) {
                line += row[i];
                if (i + 1 < row.size()) line += std::string(width[i] - row[i].size() + 2, ' ');
            }
            out << line << '\n';
        }
    }

private:
    std::vector<std::vector<std::string>> rows_;
};

std::string numbered(std::string_view prefix, uint64_t number) { return detail::concat(prefix, number); }

std::string ratio(uint64_t value, uint64_t bound) {
    if (bound == 0) return "-";
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3f", static_cast<double>(value) / static_cast<double>(bound));
    return buffer;
}

// "t3" or "b1": the physical texture or buffer behind a resource.
std::string physical_name(const PlanResource& resource) {
    return resource.type == ResourceType::Buffer ? numbered("b", resource.buffer) : numbered("t", resource.texture);
}

// The part of its resource a port uses, in parentheses, or "" when it is all of it.
std::string range_suffix(const PlanResource& resource, const PlanPort& port) {
    const std::string range = describe_port_range(resource, port);
    return range.empty() ? range : "(" + range + ")";
}

// "3-7", and where async compute widened it the positions its memory is held, and "shared"
// when both queues read it: "3-7 held 1-9 shared".
std::string life_text(const PlanResource& r) {
    std::string text = std::to_string(r.lifetime.first) + "-" + std::to_string(r.lifetime.last);
    if (r.occupancy != r.lifetime) {
        text += " held " + std::to_string(r.occupancy.first) + "-" + std::to_string(r.occupancy.last);
    }
    if (r.queue_shared) text += " shared";
    return text;
}

// A position a sync or transfer refers to: "2 ssao", or the frame's start or end.
std::string position_text(const Plan& plan, uint32_t position) {
    if (position == kFrameStart) return "frame start";
    if (position >= plan.order.size()) return "frame end";
    return std::to_string(position) + " " + plan.order[position].name;
}

// The semaphores and ownership transfers between the queues; nothing without async passes.
void write_queue_tables(std::ostream& out, const Plan& plan) {
    if (plan.queue_syncs.empty()) return;
    out << "queue syncs\n";
    Table syncs({"signal", "after", "wait", "before"});
    for (const QueueSync& sync : plan.queue_syncs) {
        syncs.add({std::string(queue_name(sync.from)), position_text(plan, sync.signal_after),
                   std::string(queue_name(sync.to)), position_text(plan, sync.wait_before)});
    }
    syncs.render(out, "  ");
    out << "\n";
    if (plan.ownership_transfers.empty()) return;
    out << "ownership transfers\n";
    Table transfers({"resource", "from", "release after", "to", "acquire before"});
    for (const OwnershipTransfer& t : plan.ownership_transfers) {
        transfers.add({plan.resources[t.resource].name, std::string(queue_name(t.from)),
                       position_text(plan, t.release_after), std::string(queue_name(t.to)),
                       position_text(plan, t.acquire_before)});
    }
    transfers.render(out, "  ");
    out << "\n";
}

}  // namespace

std::string format_bytes(uint64_t bytes) {
    char buffer[32];
    if (bytes >= 1024ull * 1024) {
        std::snprintf(buffer, sizeof buffer, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    } else if (bytes >= 1024) {
        std::snprintf(buffer, sizeof buffer, "%.1f KiB", static_cast<double>(bytes) / 1024.0);
    } else {
        std::snprintf(buffer, sizeof buffer, "%llu B", static_cast<unsigned long long>(bytes));
    }
    return buffer;
}

void write_plan_table(std::ostream& out, const Plan& plan) {
    out << "plan: allocator " << plan.allocator << ", frame " << plan.frame.width << "x" << plan.frame.height
        << ", sharing " << spec_sharing_name(plan.sharing) << ", order " << pass_order_name(plan.pass_order) << "\n\n";

    out << numbered("order (", plan.order.size()) + " passes";
    if (!plan.culled.empty()) {
        out << "; culled:";
        for (const std::string& name : plan.culled) out << " " << name;
    }
    out << ")\n";
    Table order({"#", "pass", "ports"});
    for (uint32_t at = 0; at < plan.order.size(); ++at) {
        const PlanPass& pass = plan.order[at];
        std::string ports;
        for (const PlanPort& port : pass.ports) {
            if (!ports.empty()) ports += "  ";
            ports += std::string(port.kind == PortKind::Input ? "<" : port.kind == PortKind::Output ? ">" : "<>") +
                     port.name + "=";
            if (port.resource) {
                const PlanResource& resource = plan.resources[*port.resource];
                ports += physical_name(resource) + range_suffix(resource, port);
            } else {
                ports += "-";
            }
        }
        // Graphics is the default kind and queue and goes unsaid.
        std::string name = pass.name;
        if (pass.kind != PassKind::Graphics) {
            name += " [" + std::string(pass_kind_name(pass.kind)) + (pass.queue == Queue::AsyncCompute ? ", async]" : "]");
        }
        if (pass.side_effect) name += " (side effect)";
        order.add({std::to_string(at), name, ports});
    }
    order.render(out, "  ");
    out << "\n";
    write_queue_tables(out, plan);

    out << "resources\n";
    Table resources({"resource", "format", "size", "life", "texture", "bytes"});
    for (const PlanResource& r : plan.resources) {
        if (r.type != ResourceType::Texture) continue;  // in the buffer table below
        std::string format(rhi::format_name(r.spec.format));
        if (r.spec.format_match == FormatMatch::Covering && r.requested_format) {
            format += " (covers " + describe_features(*r.requested_format) + ")";
        } else if (r.spec.format_match == FormatMatch::Default) {
            format += " (default)";
        }
        std::string size = std::to_string(r.spec.extent.width) + "x" + std::to_string(r.spec.extent.height);
        if (r.spec.samples != 1) size += numbered(" x", r.spec.samples);
        if (r.spec.mips != 1) size += numbered(" m", r.spec.mips);
        if (r.spec.layers != 1) size += numbered(" l", r.spec.layers);
        resources.add({r.name + (r.graph_output ? " (output)" : ""), format, size,
                       life_text(r), numbered("t", r.texture), format_bytes(r.bytes)});
    }
    resources.render(out, "  ");
    out << "\n";

    out << "textures\n";
    Table textures({"texture", "spec", "holds", "bytes", "placement"});
    for (const PlanTexture& t : plan.textures) {
        std::string holds;
        for (uint32_t r : t.resources) {
            if (!holds.empty()) holds += ", ";
            holds += plan.resources[r].name;
        }
        std::string placement = "-";
        if (t.placement) {
            placement = numbered("heap ", t.placement->heap) + numbered(" @ ", t.placement->offset);
        }
        textures.add({t.name, describe_resolved(t.spec), holds, format_bytes(t.bytes), placement});
    }
    textures.render(out, "  ");
    out << "\n";

    // Buffer tables and columns appear only in plans with buffers: a texture-only plan prints
    // what it printed before buffers existed.
    const PlanSummary& s = plan.summary;
    const bool buffers = s.naive_buffers > 0;
    if (buffers) {
        out << "buffer resources\n";
        Table buffer_resources({"resource", "size", "usage", "life", "buffer", "bytes"});
        for (const PlanResource& r : plan.resources) {
            if (r.type != ResourceType::Buffer) continue;
            std::string size = std::to_string(r.buffer_spec.size) + " B";
            if (r.buffer_spec.alignment > 1) size += numbered(" aligned ", r.buffer_spec.alignment);
            buffer_resources.add({r.name + (r.graph_output ? " (output)" : ""), size,
                                  describe_buffer_usage(r.buffer_spec.usage),
                                  life_text(r), physical_name(r), format_bytes(r.bytes)});
        }
        buffer_resources.render(out, "  ");
        out << "\n";

        out << "buffers\n";
        Table physical({"buffer", "spec", "holds", "bytes", "placement"});
        for (const PlanBuffer& b : plan.buffers) {
            std::string holds;
            for (uint32_t r : b.resources) {
                if (!holds.empty()) holds += ", ";
                holds += plan.resources[r].name;
            }
            std::string placement = "-";
            if (b.placement) placement = numbered("heap ", b.placement->heap) + numbered(" @ ", b.placement->offset);
            physical.add({b.name, describe_resolved_buffer(b.spec), holds, format_bytes(b.bytes), placement});
        }
        physical.render(out, "  ");
        out << "\n";
    }

    out << "summary\n";
    std::vector<std::string> header{"", "textures", "bytes", "bytes / lower bound"};
    std::vector<std::string> plan_row{"plan", std::to_string(s.textures), format_bytes(s.bytes),
                                      ratio(s.bytes, s.lower_bound_bytes)};
    std::vector<std::string> naive_row{"naive", std::to_string(s.naive_textures), format_bytes(s.naive_bytes),
                                       ratio(s.naive_bytes, s.lower_bound_bytes)};
    std::vector<std::string> bound_row{"lower bound", std::to_string(s.lower_bound_textures),
                                       format_bytes(s.lower_bound_bytes), "1.000"};
    if (buffers) {
        header.insert(header.begin() + 2, "buffers");
        plan_row.insert(plan_row.begin() + 2, std::to_string(s.buffers));
        naive_row.insert(naive_row.begin() + 2, std::to_string(s.naive_buffers));
        bound_row.insert(bound_row.begin() + 2, std::to_string(s.lower_bound_buffers));
    }
    Table summary(std::move(header));
    summary.add(std::move(plan_row));
    summary.add(std::move(naive_row));
    summary.add(std::move(bound_row));
    summary.render(out, "  ");
    // The physical buffers' bytes, counted in the plan's bytes (placed ones within the heaps).
    if (buffers) out << "  buffer bytes: " << format_bytes(s.buffer_bytes) << "\n";
    if (!plan.heaps.empty()) {
        out << "  heaps:";
        for (uint64_t size : plan.heaps) {
            out << ' ' << format_bytes(size);
        }
        out << "\n";
    }
}

std::string plan_to_table(const Plan& plan) {
    std::ostringstream out;
    write_plan_table(out, plan);
    return std::move(out).str();
}

}  // namespace loom::fg
