#pragma once
// Plans as text: JSON (every field, for tools and tests), Graphviz DOT (passes as nodes with
// their ports, edges coloured by physical texture or buffer) and a readable table. Buffers and
// subresource ranges appear in all three; the DOT and the table mention buffers only in plans
// that have some, and ranges only where a port uses part of its resource.

#include <iosfwd>
#include <string>

#include "loom/framegraph/plan.hpp"

namespace loom::fg {

/// The plan as one JSON object. Top level: allocator, frame, sharing, hash, summary (every
/// PlanSummary field), order (pass names), culled, passes (kind, ports with their type, range,
/// resource and texture or buffer), edges, graph_outputs, resources (texture or buffer),
/// spec_classes, textures, buffers, heaps. See docs/framegraph.md.
std::string plan_to_json(const Plan& plan, int indent = 2);
/// The same text as plan_to_json, written to `out` piece by piece: memory stays proportional
/// to one pass or resource, not to the whole document (large plans, loom-plan --json).
void write_plan_json(std::ostream& out, const Plan& plan, int indent = 2);

/// The plan as a Graphviz digraph: one record node per scheduled pass (inputs left, outputs
/// right; a compute or copy pass says so), culled passes dashed and grey, one edge per
/// connection labelled and coloured by its physical texture or buffer (buffer edges dashed),
/// with the range its reader uses when not the whole resource ("t0 mip 2", "b1 bytes 0+512"),
/// graph outputs leading to an "output" node.
std::string plan_to_dot(const Plan& plan);
/// The same text as plan_to_dot, written to `out` line by line.
void write_plan_dot(std::ostream& out, const Plan& plan);

/// The plan as aligned text tables: order, resources, textures, buffer resources and buffers
/// (when the plan has buffers), summary.
std::string plan_to_table(const Plan& plan);
/// The same text as plan_to_table, written to `out` table by table.
void write_plan_table(std::ostream& out, const Plan& plan);

/// "12.0 MiB", "512 KiB", "100 B".
std::string format_bytes(uint64_t bytes);

}  // namespace loom::fg
