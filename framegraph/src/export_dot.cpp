#include <array>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_set>

#include "loom/framegraph/export.hpp"
#include "text.hpp"

namespace loom::fg {
namespace {

// Distinct colours for textures; texture t uses kPalette[t % size].
constexpr std::array<std::string_view, 12> kPalette{
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b",
    "#e377c2", "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939",
};

// Escapes text for a record label, where { } | < > and quotes are syntax.
std::string record_escape(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '{' || c == '}' || c == '|' || c == '<' || c == '>' || c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out;
}

std::string quoted(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    return out + "\"";
}

std::string numbered(std::string_view prefix, uint64_t number) { return detail::concat(prefix, number); }

std::string pass_node(uint32_t position) { return numbered("p", position); }

// "t3" or "b1": the physical texture or buffer behind a resource.
std::string physical_name(const PlanResource& resource) {
    return resource.type == ResourceType::Buffer ? numbered("b", resource.buffer) : numbered("t", resource.texture);
}

// Textures take the palette from its start, buffers from its end, so that in a small plan t0
// and b0 differ in colour too (buffer edges are also dashed).
std::string colour_of(const PlanResource& resource) {
    if (resource.type == ResourceType::Buffer) {
        return std::string(kPalette[kPalette.size() - 1 - resource.buffer % kPalette.size()]);
    }
    return std::string(kPalette[resource.texture % kPalette.size()]);
}

}  // namespace

void write_plan_dot(std::ostream& out, const Plan& plan) {
    out << "digraph plan {\n";
    out << "  rankdir=LR;\n";
    out << "  node [shape=record, fontname=\"Helvetica\", fontsize=10];\n";
    out << "  edge [fontname=\"Helvetica\", fontsize=9];\n";
    // Buffers are counted only in plans that have them, so a texture-only plan's picture is
    // what it was before buffers existed.
    const PlanSummary& s = plan.summary;
    std::string title = detail::concat(plan.allocator, " allocator: ", s.textures, " textures, ");
    if (s.naive_buffers > 0) detail::append(title, s.buffers, " buffers, ");
    detail::append(title, format_bytes(s.bytes), " (naive ", s.naive_textures);
    if (s.naive_buffers > 0) detail::append(title, " + ", s.naive_buffers, " buffers");
    detail::append(title, ", ", format_bytes(s.naive_bytes), ")");
    detail::append(title, ", ", pass_order_name(plan.pass_order), " order");
    out << "  label=" << quoted(title) << ";\n";

    for (uint32_t at = 0; at < plan.order.size(); ++at) {
        const PlanPass& pass = plan.order[at];
        std::string inputs;
        std::string outputs;
        for (uint32_t i = 0; i < pass.ports.size(); ++i) {
            const PlanPort& port = pass.ports[i];
            std::string field = numbered("<f", i) + "> " + record_escape(port.name);
            if (port.resource) {
                const PlanResource& resource = plan.resources[*port.resource];
                const std::string range = describe_port_range(resource, port);
                field += " (" + physical_name(resource) + (range.empty() ? "" : " " + range) + ")";
            }
            std::string& side = port.kind == PortKind::Input ? inputs : outputs;
            if (!side.empty()) side += '|';
            side += field;
        }
        std::string label = "{";
        if (!inputs.empty()) label += "{" + inputs + "}|";
        label += std::to_string(at) + ": " + record_escape(pass.name);
        if (pass.kind != PassKind::Graphics) {
            label += " [" + std::string(pass_kind_name(pass.kind)) + (pass.queue == Queue::AsyncCompute ? ", async]" : "]");
        }
        if (pass.side_effect) label += " (side effect)";
        if (!outputs.empty()) label += "|{" + outputs + "}";
        label += "}";
        // Async compute passes are filled, so the two queues read apart at a glance.
        out << "  " << pass_node(at) << " [label=\"" << label << "\""
            << (pass.queue == Queue::AsyncCompute ? ", style=filled, fillcolor=\"#e8f0ff\"" : "") << "];\n";
    }
    for (std::size_t i = 0; i < plan.culled.size(); ++i) {
        out << numbered("  c", i) << " [label=" << quoted(plan.culled[i] + " (culled)")
            << ", style=dashed, color=gray, fontcolor=gray];\n";
    }
    for (const PlanEdge& e : plan.edges) {
        const PlanResource& resource = plan.resources[e.resource];
        const std::string colour = colour_of(resource);
        // The edge says what its reader uses: the resource, and the part of it when not all.
        const std::string range = describe_port_range(resource, plan.order[e.to_pass].ports[e.to_port]);
        out << "  " << pass_node(e.from_pass) << numbered(":f", e.from_port) << ":e -> " << pass_node(e.to_pass)
            << numbered(":f", e.to_port) << ":w [color=" << quoted(colour) << ", fontcolor=" << quoted(colour)
            << (resource.type == ResourceType::Buffer ? ", style=dashed" : "")
            << ", label=" << quoted(physical_name(resource) + (range.empty() ? "" : " " + range)) << "];\n";
    }
    // Semaphores between the queues: dotted, from the signalling pass to the waiting one (the
    // frame's start and end are left out: they have no node).
    for (const QueueSync& sync : plan.queue_syncs) {
        if (sync.signal_after == kFrameStart || sync.wait_before >= plan.order.size()) continue;
        out << "  " << pass_node(sync.signal_after) << " -> " << pass_node(sync.wait_before)
            << " [style=dotted, color=\"#3050c0\", label=\"sync\"];\n";
    }
    if (!plan.graph_outputs.empty()) {
        out << "  output [shape=doublecircle, label=\"output\"];\n";
        const std::unordered_set<std::string> marked_outputs(plan.graph_outputs.begin(), plan.graph_outputs.end());
        for (uint32_t at = 0; at < plan.order.size(); ++at) {
            const PlanPass& pass = plan.order[at];
            for (uint32_t i = 0; i < pass.ports.size(); ++i) {
                const std::string name = pass.name + "." + pass.ports[i].name;
                if (!marked_outputs.contains(name) || !pass.ports[i].resource) continue;
                const PlanResource& resource = plan.resources[*pass.ports[i].resource];
                out << "  " << pass_node(at) << numbered(":f", i) << ":e -> output [color=" << quoted(colour_of(resource))
                    << (resource.type == ResourceType::Buffer ? ", style=dashed" : "")
                    << ", label=" << quoted(physical_name(resource)) << "];\n";
            }
        }
    }
    out << "}\n";
}

std::string plan_to_dot(const Plan& plan) {
    std::ostringstream out;
    write_plan_dot(out, plan);
    return std::move(out).str();
}

}  // namespace loom::fg
