#include "inspect_input.hpp"

#include <fstream>
#include <ostream>

#include <nlohmann/json.hpp>

namespace loom::inspect {
namespace {

using nlohmann::json;

std::string_view load_name(rhi::LoadOp op) {
    switch (op) {
        case rhi::LoadOp::Load: return "load";
        case rhi::LoadOp::Clear: return "clear";
        case rhi::LoadOp::DontCare: return "dont-care";
    }
    return "?";
}

std::string_view store_name(rhi::StoreOp op) { return op == rhi::StoreOp::Store ? "store" : "dont-care"; }

// Null for the whole texture (the default range), else the mips and layers it covers; "all"
// for a count that runs to the end.
json range_json(const rhi::TextureRange& range) {
    if (range == rhi::TextureRange{}) return nullptr;
    auto count = [](uint32_t n) -> json {
        if (n == rhi::kRemainingSubresources) return "all";
        return n;
    };
    return {{"base_mip", range.base_mip}, {"mip_count", count(range.mip_count)},
            {"base_layer", range.base_layer}, {"layer_count", count(range.layer_count)}};
}

json transitions_json(const std::vector<fg::Transition>& transitions) {
    json list = json::array();
    for (const fg::Transition& t : transitions) {
        list.push_back({{"slot", fg::describe_slot(t.texture)},
                        {"state", rhi::resource_state_name(t.state)},
                        {"range", range_json(t.range)}});
    }
    return list;
}

json buffer_transitions_json(const std::vector<fg::BufferTransition>& transitions) {
    json list = json::array();
    for (const fg::BufferTransition& t : transitions) {
        list.push_back({{"slot", fg::describe_slot(t.buffer)}, {"state", rhi::resource_state_name(t.state)}});
    }
    return list;
}

json schedule_json(const fg::ExecutionSchedule& schedule) {
    json passes = json::array();
    for (const fg::PassSchedule& pass : schedule.passes) {
        json ports = json::array();
        for (const fg::PortSchedule& port : pass.ports) {
            const bool buffer = !port.buffer.empty();
            ports.push_back({{"name", port.name},
                             {"slot", buffer ? fg::describe_slot(port.buffer) : fg::describe_slot(port.texture)},
                             {"first_write", port.first_write},
                             // Load and store actions mean something only for attachments.
                             {"load", load_name(port.load)},
                             {"store", store_name(port.store)}});
        }
        json copies = json::array();
        for (const fg::HistoryCopy& copy : pass.copies) {
            copies.push_back({{"history", copy.history}, {"source", fg::describe_slot(copy.source)}});
        }
        passes.push_back({{"pass", pass.name},
                          {"ports", std::move(ports)},
                          {"before", transitions_json(pass.before)},
                          {"after", transitions_json(pass.after)},
                          {"buffers_before", buffer_transitions_json(pass.buffers_before)},
                          {"buffers_after", buffer_transitions_json(pass.buffers_after)},
                          {"copies", std::move(copies)}});
    }
    return passes;
}

json timings_json(const std::vector<fg::PassTiming>& timings) {
    json list = json::array();
    for (const fg::PassTiming& t : timings) {
        json gpu = nullptr;
        if (t.gpu_ms) gpu = *t.gpu_ms;
        list.push_back({{"pass", t.pass}, {"cpu_ms", t.cpu_ms}, {"gpu_ms", gpu}});
    }
    return list;
}

json allocations_json(const fg::ExecutionStats& s) {
    return {{"textures", s.textures},
            {"placed_textures", s.placed_textures},
            {"history_textures", s.history_textures},
            {"heaps", s.heaps},
            {"heap_bytes", s.heap_bytes},
            {"texture_bytes", s.texture_bytes},
            {"buffers", s.buffers},
            {"placed_buffers", s.placed_buffers},
            {"buffer_bytes", s.buffer_bytes},
            {"device",
             {{"textures", s.device.textures},
              {"buffers", s.device.buffers},
              {"heaps", s.device.heaps},
              {"texture_bytes", s.device.texture_bytes},
              {"buffer_bytes", s.device.buffer_bytes},
              {"heap_bytes", s.device.heap_bytes}}}};
}

json allocators_json(const std::vector<AllocatorFigures>& rows) {
    json list = json::array();
    for (const AllocatorFigures& row : rows) {
        if (row.summary) {
            list.push_back({{"allocator", row.allocator},
                            {"bytes", row.summary->bytes},
                            {"textures", row.summary->textures},
                            {"buffers", row.summary->buffers}});
        } else {
            list.push_back({{"allocator", row.allocator}, {"refused", row.refused}});
        }
    }
    return list;
}

}  // namespace

Result<std::vector<AllocatorFigures>> compare_allocators(const fg::FrameGraph& graph, fg::PlanOptions options) {
    std::vector<AllocatorFigures> rows;
    for (const fg::AllocatorKind allocator : fg::allocator_kinds()) {
        options.allocator = allocator;
        const std::string name(fg::allocator_name(allocator));
        auto plan = fg::build_plan(graph, options);
        if (plan) {
            rows.push_back({name, plan->summary, {}});
        } else if (plan.error().code == ErrorCode::InvalidArgument) {
            rows.push_back({name, std::nullopt, plan.error().message});
        } else {
            return plan.take_error();
        }
    }
    return rows;
}

void write_input(std::ostream& out, const fg::Plan& plan, const RunRecord& run) {
    // Members in the order a reader wants them when looking at the file; the plan, by far the
    // largest, last but for nothing.
    out << "{\"format\": " << json(kInputFormat).dump() << ", \"version\": " << kInputVersion
        << ",\n\"source\": " << json(run.source).dump(-1, ' ', false, json::error_handler_t::replace);
    if (!run.allocators.empty()) out << ",\n\"allocators\": " << allocators_json(run.allocators).dump();
    if (run.allocations) out << ",\n\"allocations\": " << allocations_json(*run.allocations).dump();
    if (!run.timings.empty()) {
        out << ",\n\"timings\": " << timings_json(run.timings).dump(-1, ' ', false, json::error_handler_t::replace);
    }
    if (run.schedule) {
        out << ",\n\"schedule\": " << schedule_json(*run.schedule).dump(-1, ' ', false, json::error_handler_t::replace);
    }
    out << ",\n\"plan\": ";
    fg::write_plan_json(out, plan, -1);
    out << "}\n";
}

Status write_input_file(const std::filesystem::path& path, const fg::Plan& plan, const RunRecord& run) {
    std::ofstream file(path, std::ios::binary);
    if (file) write_input(file, plan, run);
    file.close();
    if (!file) return make_error(ErrorCode::Io, "cannot write the inspector input " + path.string());
    return {};
}

Result<RunRecord> executor_run_record(const fg::Executor& executor, const fg::FrameGraph& graph,
                                      const fg::PlanOptions& options, std::string source) {
    if (!executor.plan() || !executor.schedule()) {
        return make_error(ErrorCode::InvalidState, "no frame was executed: no inspector input to write");
    }
    RunRecord run;
    run.source = std::move(source);
    run.schedule = executor.schedule();
    run.timings = executor.timings();
    run.allocations = executor.stats();
    auto allocators = compare_allocators(graph, options);
    if (!allocators) return allocators.take_error();
    run.allocators = std::move(*allocators);
    return run;
}

Status write_executor_input(const std::filesystem::path& path, const fg::Executor& executor,
                            const fg::FrameGraph& graph, const fg::PlanOptions& options, std::string source) {
    auto run = executor_run_record(executor, graph, options, std::move(source));
    if (!run) return run.take_error();
    return write_input_file(path, *executor.plan(), *run);
}

}  // namespace loom::inspect
