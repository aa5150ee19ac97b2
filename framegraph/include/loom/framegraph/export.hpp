#pragma once
// Plans as text: JSON (every field, for tools and tests), Graphviz DOT (passes as nodes with
// their ports, edges coloured by physical texture) and a readable table.

#include <string>

#include "loom/framegraph/plan.hpp"

namespace loom::fg {

/// The plan as one JSON object. Top level: allocator, frame, sharing, hash, summary (the six
/// PlanSummary fields), order (pass names), culled, passes (ports with their resource and
/// texture), edges, graph_outputs, resources, spec_classes, textures, heaps. See docs/framegraph.md.
std::string plan_to_json(const Plan& plan, int indent = 2);

/// The plan as a Graphviz digraph: one record node per scheduled pass (inputs left, outputs
/// right), culled passes dashed and grey, one edge per connection labelled and coloured by
/// its physical texture, graph outputs leading to an "output" node.
std::string plan_to_dot(const Plan& plan);

/// The plan as aligned text tables: order, resources, textures, summary.
std::string plan_to_table(const Plan& plan);

/// "12.0 MiB", "512 KiB", "100 B".
std::string format_bytes(uint64_t bytes);

}  // namespace loom::fg
