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

}  // namespace

void write_plan_dot(std::ostream& out, const Plan& plan) {
    out << "digraph plan {\n";
    out << "  rankdir=LR;\n";
    out << "  node [shape=record, fontname=\"Helvetica\", fontsize=10];\n";
    out << "  edge [fontname=\"Helvetica\", fontsize=9];\n";
    out << "  label=" << quoted(plan.allocator + " allocator: " + std::to_string(plan.summary.textures) +
                              " textures, " + format_bytes(plan.summary.bytes) + " (naive " +
                              std::to_string(plan.summary.naive_textures) + ", " +
                              format_bytes(plan.summary.naive_bytes) + ")") << ";\n";

    for (uint32_t at = 0; at < plan.order.size(); ++at) {
        const PlanPass& pass = plan.order[at];
        std::string inputs;
        std::string outputs;
        for (uint32_t i = 0; i < pass.ports.size(); ++i) {
            const PlanPort& port = pass.ports[i];
            std::string field = numbered("<f", i) + "> " + record_escape(port.name);
            if (port.resource) field += numbered(" (t", plan.resources[*port.resource].texture) + ")";
            std::string& side = port.kind == PortKind::Input ? inputs : outputs;
            if (!side.empty()) side += '|';
            side += field;
        }
        std::string label = "{";
        if (!inputs.empty()) label += "{" + inputs + "}|";
        label += std::to_string(at) + ": " + record_escape(pass.name);
        if (pass.side_effect) label += " (side effect)";
        if (!outputs.empty()) label += "|{" + outputs + "}";
        label += "}";
        out << "  " << pass_node(at) << " [label=\"" << label << "\"];\n";
    }
    for (std::size_t i = 0; i < plan.culled.size(); ++i) {
        out << numbered("  c", i) << " [label=" << quoted(plan.culled[i] + " (culled)")
            << ", style=dashed, color=gray, fontcolor=gray];\n";
    }
    for (const PlanEdge& e : plan.edges) {
        const PlanResource& resource = plan.resources[e.resource];
        const std::string colour(kPalette[resource.texture % kPalette.size()]);
        out << "  " << pass_node(e.from_pass) << numbered(":f", e.from_port) << ":e -> " << pass_node(e.to_pass)
            << numbered(":f", e.to_port) << ":w [color=" << quoted(colour) << ", fontcolor=" << quoted(colour)
            << ", label=" << quoted(numbered("t", resource.texture)) << "];\n";
    }
    if (!plan.graph_outputs.empty()) {
        out << "  output [shape=doublecircle, label=\"output\"];\n";
        const std::unordered_set<std::string> marked_outputs(plan.graph_outputs.begin(), plan.graph_outputs.end());
        for (uint32_t at = 0; at < plan.order.size(); ++at) {
            const PlanPass& pass = plan.order[at];
            for (uint32_t i = 0; i < pass.ports.size(); ++i) {
                const std::string name = pass.name + "." + pass.ports[i].name;
                if (!marked_outputs.contains(name) || !pass.ports[i].resource) continue;
                const uint32_t texture = plan.resources[*pass.ports[i].resource].texture;
                const std::string colour(kPalette[texture % kPalette.size()]);
                out << "  " << pass_node(at) << numbered(":f", i) << ":e -> output [color=" << quoted(colour)
                    << ", label=" << quoted(numbered("t", texture)) << "];\n";
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
