// Interval-graph colouring per spec class. For a fixed order every resource is an interval of
// positions; taking resources by start and giving each the lowest-numbered texture whose
// previous tenant has ended uses exactly as many textures as the largest number of resources
// of the class alive at one position, which no allocation can beat (interval graphs are
// perfect).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <utility>

#include "allocators.hpp"

namespace loom::fg::detail {
namespace {

class IntervalAllocator final : public Allocator {
public:
    [[nodiscard]] std::string_view name() const override { return "interval"; }
    // Lifetimes and classes are all it needs.
    [[nodiscard]] bool reads_pass_lists() const override { return false; }
    [[nodiscard]] bool reads_bytes() const override { return false; }

    [[nodiscard]] Result<Allocation> allocate(const AllocationProblem& problem) const override {
        const auto resource_count = static_cast<uint32_t>(problem.resources.size());
        Allocation out;
        out.texture_of_resource.assign(resource_count, 0);

        std::vector<std::vector<uint32_t>> members(problem.spec_class_count);
        for (uint32_t r = 0; r < resource_count; ++r) members[problem.resources[r].spec_class].push_back(r);

        for (std::vector<uint32_t>& spec : members) {
            const auto starts_before = [&](uint32_t a, uint32_t b) {
                return problem.resources[a].lifetime.first < problem.resources[b].lifetime.first;
            };
            // Plans number resources by their producers' positions: mostly sorted already.
            if (!std::is_sorted(spec.begin(), spec.end(), starts_before)) {
                std::stable_sort(spec.begin(), spec.end(), starts_before);
            }
            LowestFreeNumber textures;
            // (last position, texture) of the resources holding a texture, earliest end on top.
            using Tenant = std::pair<uint32_t, uint32_t>;
            std::priority_queue<Tenant, std::vector<Tenant>, std::greater<>> active;
            for (uint32_t r : spec) {
                const Lifetime& life = problem.resources[r].lifetime;
                while (!active.empty() && active.top().first < life.first) {
                    textures.release(active.top().second);
                    active.pop();
                }
                const uint32_t texture = textures.take();
                active.emplace(life.last, texture);
                out.texture_of_resource[r] = out.texture_count + texture;
            }
            out.texture_count += textures.used();
        }
        return out;
    }
};

}  // namespace

std::unique_ptr<Allocator> make_interval_allocator() { return std::make_unique<IntervalAllocator>(); }

}  // namespace loom::fg::detail
