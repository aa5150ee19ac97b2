#pragma once
// Everything of the frame graph in one include.

#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/buffer_spec.hpp"
#include "loom/framegraph/execution_schedule.hpp"
#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/export.hpp"
#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/graph_file.hpp"
#include "loom/framegraph/join.hpp"
#include "loom/framegraph/memory_model.hpp"
#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/pass_context.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/framegraph/resolved_spec.hpp"
#include "loom/framegraph/texture_spec.hpp"
