// The port colouring of Hafner (ELS 2019) §6.2, kept as the reference allocator.
//
// For each unique texture spec T (here: each spec class, in order of first use):
//   2.1 the nodes are in topological order (the planner's order);
//   2.2-2.4 one colour per output port of spec T is available;
//   2.5 walking the nodes in reverse order, for each node N:
//     2.5.1 every input port's neighbour (the port feeding it) of spec T without a colour
//           takes the first available colour, which becomes unavailable;
//     2.5.2 every non-input port of spec T without a colour does the same;
//     2.5.3 the colours of N's own ports become available again.
// Colours are textures. Two extensions the paper's graphs did not need:
//   - graph outputs are read after the frame, by a virtual last node, so they are coloured
//     before the walk starts and stay unavailable until their producer frees them;
//   - an inout port modifies the texture of its source in place: it carries the colour of
//     its source, and only the node that started the texture (its output port) frees it.

#include <cstdint>
#include <limits>

#include "allocators.hpp"

namespace loom::fg::detail {
namespace {

constexpr uint32_t kNoColour = std::numeric_limits<uint32_t>::max();

class PaperAllocator final : public Allocator {
public:
    [[nodiscard]] std::string_view name() const override { return "paper"; }

    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem& problem) const override {
        const auto resource_count = static_cast<uint32_t>(problem.resources.size());
        Allocation out;
        out.texture_of_resource.assign(resource_count, kNoColour);
        std::vector<uint32_t> colour(resource_count, kNoColour);

        for (uint32_t spec = 0; spec < problem.spec_class_count; ++spec) {
            auto of_spec = [&](uint32_t r) { return problem.resources[r].spec_class == spec; };
            LowestFreeNumber colours;
            auto assign = [&](uint32_t r) {
                if (of_spec(r) && colour[r] == kNoColour) colour[r] = colours.take();
            };

            for (uint32_t r : problem.graph_outputs) assign(r);
            for (auto node = problem.passes.rbegin(); node != problem.passes.rend(); ++node) {
                for (uint32_t r : node->inputs) assign(r);      // 2.5.1
                for (uint32_t r : node->non_inputs) assign(r);  // 2.5.2
                for (uint32_t r : node->begins) {               // 2.5.3
                    if (of_spec(r) && colour[r] != kNoColour) colours.release(colour[r]);
                }
            }
            for (uint32_t r = 0; r < resource_count; ++r) {
                if (of_spec(r)) out.texture_of_resource[r] = out.texture_count + colour[r];
            }
            out.texture_count += colours.used();
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Allocator> make_paper_allocator() { return std::make_unique<PaperAllocator>(); }

}  // namespace loom::fg::detail
