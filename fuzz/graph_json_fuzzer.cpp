// Fuzz harness: graph JSON -> load -> join -> plan with every allocator and sharing mode (in the
// file's pass order, and in memory order), and every export of the plan. Any input must give a plan or a clean error: no crash, hang, leak
// or undefined behaviour (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "loom/framegraph/framegraph.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    auto file = loom::fg::parse_graph_json(text, "fuzz.json");
    if (!file) return 0;
    using loom::fg::AllocatorKind;
    using loom::fg::SpecSharing;
    struct Variant {
        AllocatorKind allocator;
        loom::fg::SpecSharing sharing;
        uint64_t max_heap_bytes;
        bool memory_order;
    };
    static constexpr Variant kVariants[] = {
        {AllocatorKind::Paper, SpecSharing::Equal, 0, false},        {AllocatorKind::Paper, SpecSharing::Joinable, 0, false},
        {AllocatorKind::Interval, SpecSharing::Equal, 0, false},     {AllocatorKind::Interval, SpecSharing::Joinable, 0, false},
        {AllocatorKind::Heap, SpecSharing::Equal, 0, false},         {AllocatorKind::Heap, SpecSharing::Joinable, 1, false},
        {AllocatorKind::Heap, SpecSharing::Equal, 1 << 20, false},   {AllocatorKind::Interval, SpecSharing::Equal, 0, true},
        {AllocatorKind::Heap, SpecSharing::Equal, 0, true},
    };
    for (const Variant& variant : kVariants) {
        loom::fg::PlanOptions options;
        options.allocator = variant.allocator;
        options.sharing = variant.sharing;
        options.max_heap_bytes = variant.max_heap_bytes;
        options.frame = file->frame;
        options.order = variant.memory_order ? loom::fg::PassOrder::Memory : file->order;
        auto plan = loom::fg::build_plan(file->graph, options);
        if (!plan) continue;
        (void)loom::fg::plan_to_json(*plan);
        (void)loom::fg::plan_to_table(*plan);
        (void)loom::fg::plan_to_dot(*plan);
    }
    return 0;
}
