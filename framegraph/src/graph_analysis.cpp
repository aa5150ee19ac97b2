#include "graph_analysis.hpp"

#include <algorithm>
#include <functional>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace loom::fg::detail {
namespace {

Error graph_error(std::string message) { return make_error(ErrorCode::Graph, std::move(message)); }


// Why one pass must run before another: the connection between them, the texture the first
// reads before the second modifies it in place, or the application's require_order. Indexed
// once, so that naming every edge of a long cycle does not scan every connection per edge.
class EdgeReasons {
public:
    explicit EdgeReasons(const FrameGraph& graph) : graph_(graph), into_(graph.pass_count()) {
        const auto& connections = graph.connections();
        for (uint32_t i = 0; i < connections.size(); ++i) {
            const Connection& c = connections[i];
            first_feeding_.try_emplace(pair_key(c.from.pass, c.to.pass), i);
            into_[c.to.pass].push_back(i);
        }
        for (const auto& [earlier, later] : graph.order_requirements()) {
            required_.insert(pair_key(earlier.index, later.index));
        }
    }

    [[nodiscard]] std::string operator()(uint32_t from, uint32_t to) const {
        const auto& connections = graph_.connections();
        if (auto it = first_feeding_.find(pair_key(from, to)); it != first_feeding_.end()) {
            const Connection& c = connections[it->second];
            return graph_.port_name(c.from) + " feeds " + graph_.port_name(c.to);
        }
        for (uint32_t i : into_[to]) {
            const Connection& c = connections[i];
            if (graph_.port_at(c.to).kind != PortKind::InOut) continue;
            for (const PortAddress& reader : graph_.consumers(c.from)) {
                if (reader.pass == from) {
                    return graph_.port_name(reader) + " reads " + graph_.port_name(c.from) + " before " +
                           graph_.port_name(c.to) + " modifies it in place";
                }
            }
        }
        if (required_.contains(pair_key(from, to))) {
            return "require_order puts " + graph_.pass(PassId{from}).name() + " before " + graph_.pass(PassId{to}).name();
        }
        return "dependency";
    }

private:
    static uint64_t pair_key(uint32_t from, uint32_t to) { return (uint64_t{from} << 32) | to; }

    const FrameGraph& graph_;
    std::unordered_map<uint64_t, uint32_t> first_feeding_;  // (from, to) -> first connection between them
    std::vector<std::vector<uint32_t>> into_;               // per pass, the connections into it, in order
    std::unordered_set<uint64_t> required_;                 // (earlier, later) of require_order
};

// Finds a cycle among the passes Kahn's algorithm could not order (each has a predecessor
// among them) and names it in order, starting at the first declared pass on it.
Error cycle_error(const FrameGraph& graph, const Dependencies& dependencies, const std::vector<uint32_t>& in_degree) {
    const uint32_t count = graph.pass_count();
    std::vector<std::vector<uint32_t>> predecessors(count);
    for (uint32_t from = 0; from < count; ++from) {
        for (uint32_t to : dependencies.successors[from]) predecessors[to].push_back(from);
    }
    auto stuck = [&](uint32_t pass) { return in_degree[pass] > 0; };
    uint32_t start = 0;
    while (!stuck(start)) ++start;

    // Walk backwards through stuck predecessors until a pass repeats.
    std::vector<int64_t> seen_at(count, -1);
    std::vector<uint32_t> walk;
    uint32_t current = start;
    while (seen_at[current] < 0) {
        seen_at[current] = static_cast<int64_t>(walk.size());
        walk.push_back(current);
        for (uint32_t p : predecessors[current]) {
            if (stuck(p)) {
                current = p;
                break;
            }
        }
    }
    std::vector<uint32_t> cycle(walk.begin() + seen_at[current], walk.end());
    std::reverse(cycle.begin(), cycle.end());  // the walk went against the edges
    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());

    const EdgeReasons edge_reason(graph);
    std::string names;
    std::string reasons;
    for (std::size_t i = 0; i < cycle.size(); ++i) {
        const uint32_t from = cycle[i];
        const uint32_t to = cycle[(i + 1) % cycle.size()];
        names += graph.pass(PassId{from}).name() + " -> ";
        if (!reasons.empty()) reasons += "; ";
        reasons += edge_reason(from, to);
    }
    names += graph.pass(PassId{cycle.front()}).name();
    Error error = graph_error("cycle: " + names + " (" + reasons + ")");
    for (uint32_t pass : cycle) error.subjects.push_back(graph.pass(PassId{pass}).name());
    return error;
}

}  // namespace

IndexLists::IndexLists(uint32_t count, const std::vector<std::pair<uint32_t, uint32_t>>& pairs) : first_(count + 1, 0) {
    // A counting sort by index, then each list sorted and made unique in place.
    for (const auto& [index, value] : pairs) ++first_[index + 1];
    for (uint32_t i = 1; i <= count; ++i) first_[i] += first_[i - 1];
    // assign, not resize: GCC 12 at -O3 warns falsely (-Wnull-dereference) about resize growing an empty vector.
    values_.assign(pairs.size(), 0u);
    {
        std::vector<uint32_t> cursor(first_.begin(), first_.end() - 1);
        for (const auto& [index, value] : pairs) values_[cursor[index]++] = value;
    }
    sort_and_deduplicate();
}

IndexLists::IndexLists(std::vector<uint32_t> first, std::vector<uint32_t> values)
    : first_(std::move(first)), values_(std::move(values)) {
    sort_and_deduplicate();
}

void IndexLists::sort_and_deduplicate() {
    if (first_.empty()) return;
    const uint32_t count = size();
    uint32_t kept = 0;
    for (uint32_t i = 0; i < count; ++i) {
        const auto begin = values_.begin() + first_[i];
        const auto end = values_.begin() + first_[i + 1];
        std::sort(begin, end);
        const auto length = static_cast<uint32_t>(std::unique(begin, end) - begin);
        // Moved down over the duplicates dropped before it (never up: kept <= first_[i]).
        if (kept != first_[i]) std::move(begin, begin + length, values_.begin() + kept);
        first_[i] = kept;
        kept += length;
    }
    first_[count] = kept;
    values_.erase(values_.begin() + kept, values_.end());
}

IndexLists IndexLists::transposed(uint32_t count) const {
    IndexLists out;
    out.first_.assign(count + 1, 0);
    for (uint32_t value : values_) ++out.first_[value + 1];
    for (uint32_t j = 1; j <= count; ++j) out.first_[j] += out.first_[j - 1];
    out.values_.assign(values_.size(), 0u);
    std::vector<uint32_t> cursor(out.first_.begin(), out.first_.end() - 1);
    // Lists visited in ascending index: each transposed list comes out sorted.
    for (uint32_t i = 0; i < size(); ++i) {
        for (uint32_t value : (*this)[i]) out.values_[cursor[value]++] = i;
    }
    return out;
}

IndexLists::IndexLists(std::initializer_list<std::vector<uint32_t>> lists) {
    first_.reserve(lists.size() + 1);
    first_.push_back(0);
    for (const std::vector<uint32_t>& list : lists) {
        values_.insert(values_.end(), list.begin(), list.end());
        first_.push_back(static_cast<uint32_t>(values_.size()));
    }
}

Result<Dependencies> analyze(const FrameGraph& graph) {
    const uint32_t count = graph.pass_count();
    Dependencies out;
    // (pass, successor) and (pass, producer), made into the lists at the end.
    std::vector<std::pair<uint32_t, uint32_t>> successor_pairs;
    std::vector<std::pair<uint32_t, uint32_t>> producer_pairs;
    successor_pairs.reserve(graph.connections().size() + graph.order_requirements().size());
    producer_pairs.reserve(graph.connections().size());

    for (uint32_t pass_index = 0; pass_index < count; ++pass_index) {
        const Pass& pass = graph.pass(PassId{pass_index});
        if (pass.queue() == Queue::AsyncCompute && pass.kind() == PassKind::Graphics) {
            Error error = graph_error("pass '" + pass.name() +
                                      "' is a graphics pass: only compute and copy passes run on the async compute "
                                      "queue (set_kind, or \"kind\" in a graph file)");
            error.subjects = {pass.name()};
            return error;
        }
        const std::span<const PortFacts> ports = graph.port_facts(PassId{pass_index});
        for (uint32_t port_index = 0; port_index < ports.size(); ++port_index) {
            const PortAddress address{pass_index, port_index};
            const PortFacts& port = ports[port_index];
            if (!port_reads(port.kind)) continue;
            auto source = graph.source(address);
            if (!source) {
                if (port.optional) continue;
                Error error = graph_error("required " + std::string(port_kind_name(port.kind)) + " " +
                                          graph.port_name(address) + " is not connected");
                error.subjects = {graph.port_name(address)};
                return error;
            }
            successor_pairs.emplace_back(source->pass, pass_index);
            producer_pairs.emplace_back(pass_index, source->pass);
            if (port.kind != PortKind::InOut) continue;
            // Every other reader of the texture before this in-place modification runs first.
            for (const PortAddress& reader : graph.consumers(*source)) {
                if (reader == address) continue;
                if (reader.pass == pass_index) {
                    // Reading one part of a texture while writing another (mip k-1 into mip k,
                    // one cube face into the next) is no hazard.
                    const Port& read = graph.port_at(reader);
                    const Port& written = graph.port_at(address);
                    const bool disjoint = port.type == ResourceType::Buffer ? !overlaps(read.bytes, written.bytes)
                                                                            : !overlaps(read.range, written.range);
                    if (disjoint) continue;
                    Error error = graph_error("pass '" + pass.name() + "' reads " + graph.port_name(*source) +
                                              " through " + graph.port_name(reader) +
                                              " while modifying it in place through " + graph.port_name(address) +
                                              " (one pass may read and modify one resource only in disjoint ranges)");
                    error.subjects = {graph.port_name(address), graph.port_name(reader), graph.port_name(*source)};
                    return error;
                }
                successor_pairs.emplace_back(reader.pass, pass_index);
            }
        }
    }
    // The application's order requirements order like connections, without feeding anything.
    for (const auto& [earlier, later] : graph.order_requirements()) successor_pairs.emplace_back(earlier.index, later.index);
    out.successors = IndexLists(count, successor_pairs);
    out.producers = IndexLists(count, producer_pairs);

    // Kahn's algorithm over every pass; whatever it cannot order lies on or behind a cycle.
    std::vector<uint32_t> in_degree(count, 0);
    for (uint32_t from = 0; from < count; ++from) {
        for (uint32_t to : out.successors[from]) ++in_degree[to];
    }
    std::vector<uint32_t> ready;
    for (uint32_t i = 0; i < count; ++i) {
        if (in_degree[i] == 0) ready.push_back(i);
    }
    uint32_t ordered = 0;
    while (!ready.empty()) {
        const uint32_t pass = ready.back();
        ready.pop_back();
        ++ordered;
        for (uint32_t next : out.successors[pass]) {
            if (--in_degree[next] == 0) ready.push_back(next);
        }
    }
    if (ordered != count) return cycle_error(graph, out, in_degree);
    return out;
}

}  // namespace loom::fg::detail
