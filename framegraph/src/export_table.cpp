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
        << ", sharing " << spec_sharing_name(plan.sharing) << "\n\n";

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
            ports += port.resource ? numbered("t", plan.resources[*port.resource].texture) : "-";
        }
        order.add({std::to_string(at), pass.name + (pass.side_effect ? " (side effect)" : ""), ports});
    }
    order.render(out, "  ");
    out << "\n";

    out << "resources\n";
    Table resources({"resource", "format", "size", "life", "texture", "bytes"});
    for (const PlanResource& r : plan.resources) {
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
                       std::to_string(r.lifetime.first) + "-" + std::to_string(r.lifetime.last),
                       numbered("t", r.texture), format_bytes(r.bytes)});
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

    const PlanSummary& s = plan.summary;
    out << "summary\n";
    Table summary({"", "textures", "bytes", "bytes / lower bound"});
    summary.add({"plan", std::to_string(s.textures), format_bytes(s.bytes), ratio(s.bytes, s.lower_bound_bytes)});
    summary.add({"naive", std::to_string(s.naive_textures), format_bytes(s.naive_bytes),
                 ratio(s.naive_bytes, s.lower_bound_bytes)});
    summary.add({"lower bound", std::to_string(s.lower_bound_textures), format_bytes(s.lower_bound_bytes), "1.000"});
    summary.render(out, "  ");
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
