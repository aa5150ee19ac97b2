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

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

#include "allocators.hpp"

namespace loom::fg::detail {
namespace {

constexpr uint32_t kNoColour = std::numeric_limits<uint32_t>::max();

// The colours of one spec: an array of availability flags, as in step 2.4.
class ColourArray {
public:
    explicit ColourArray(uint32_t count) : available_(count, true) {}

    /// The first available colour, now unavailable. There is always one: the array has a
    /// colour per output of the spec, and each output holds at most one at a time.
    uint32_t take_first_available() {
        uint32_t colour = 0;
        while (colour < available_.size() && !available_[colour]) ++colour;
        assert(colour < available_.size());
        available_[colour] = false;
        used_ = std::max(used_, colour + 1);
        return colour;
    }
    void make_available(uint32_t colour) { available_[colour] = true; }
    /// Colours ever taken: the number of textures this spec needs.
    [[nodiscard]] uint32_t used() const { return used_; }

private:
    std::vector<bool> available_;
    uint32_t used_ = 0;
};

class PaperAllocator final : public Allocator {
public:
    [[nodiscard]] std::string_view name() const override { return "paper"; }
    // It colours the ports of each class pass by pass; sizes play no part.
    [[nodiscard]] bool reads_bytes() const override { return false; }

    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem& problem) const override {
        const auto resource_count = static_cast<uint32_t>(problem.resources.size());
        Allocation out;
        out.texture_of_resource.assign(resource_count, kNoColour);
        std::vector<uint32_t> colour(resource_count, kNoColour);

        // Step 1: the unique specs are the planner's spec classes, in order of first use.
        for (uint32_t spec = 0; spec < problem.spec_class_count; ++spec) {
            auto of_spec = [&](uint32_t r) { return problem.resources[r].spec_class == spec; };
            // Steps 2.1-2.3: the nodes are in topological order; count the outputs of spec T
            // (every resource starts at exactly one output, or unconnected inout, port).
            uint32_t colour_count = 0;
            for (const AllocationPass& node : problem.passes) {
                for (uint32_t r : node.begins) colour_count += of_spec(r) ? 1 : 0;
            }
            ColourArray colours(colour_count);  // step 2.4
            auto assign = [&](uint32_t r) {
                if (of_spec(r) && colour[r] == kNoColour) colour[r] = colours.take_first_available();
            };

            for (uint32_t r : problem.graph_outputs) assign(r);  // read by the virtual last node
            // Step 2.5: the nodes in reverse order.
            for (auto node = problem.passes.rbegin(); node != problem.passes.rend(); ++node) {
                for (uint32_t r : node->inputs) assign(r);      // 2.5.1 neighbours of input ports
                for (uint32_t r : node->non_inputs) assign(r);  // 2.5.2 non-input ports
                for (uint32_t r : node->begins) {               // 2.5.3 the node's own ports
                    if (of_spec(r) && colour[r] != kNoColour) colours.make_available(colour[r]);
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
