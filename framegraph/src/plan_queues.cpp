// The queues phase of build_plan: the semaphores and queue-ownership transfers between the
// graphics and async compute queues, and how long each resource's memory stays reserved when
// passes of the two queues may run at the same time.
//
// The sync model (Vulkan's, which every other API's is weaker than): a semaphore signalled on
// one queue covers every command submitted before it there, and its wait holds back every
// command submitted after it on the waiting queue. So the passes of the other queue that
// happen before a pass form a prefix of that queue's order (up to the last signal it waited
// for), and those that happen after it form a suffix (from the first wait on a signal it
// precedes); the passes in between may run at the same time as it does.
#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include "plan_phases.hpp"

namespace loom::fg::detail {
namespace {

constexpr int64_t kNothingWaited = -2;  // below the frame start (-1)

uint32_t index_of(Queue queue) { return queue == Queue::Graphics ? 0 : 1; }
Queue other(Queue queue) { return queue == Queue::Graphics ? Queue::AsyncCompute : Queue::Graphics; }

// "The pass at `consumer` (on the other queue than `producer`'s) must not start before the
// pass at `producer` has finished"; producer -1 is the start of the frame on the graphics
// queue, consumer == pass count the end of the frame on the graphics queue.
struct Requirement {
    int64_t producer = 0;
    uint32_t consumer = 0;
    Queue to = Queue::Graphics;
};

// The uses of one resource, in order: the position of each pass using it, whether it reads
// the contents and whether it writes new ones.
struct Use {
    uint32_t position = 0;
    bool reads = false;
    bool writes = false;
};

std::vector<std::vector<Use>> uses_by_resource(const std::vector<PlanPass>& order, std::size_t resource_count) {
    std::vector<std::vector<Use>> uses(resource_count);
    for (uint32_t at = 0; at < order.size(); ++at) {
        for (const PlanPort& port : order[at].ports) {
            if (!port.resource) continue;
            std::vector<Use>& list = uses[*port.resource];
            if (list.empty() || list.back().position != at) list.push_back(Use{at, false});
            list.back().reads = list.back().reads || port_reads(port.kind);
            list.back().writes = list.back().writes || port_writes(port.kind);
        }
    }
    return uses;
}

// True when some contents of the resource (what one write leaves, until the next) are read on
// both queues: exclusive ownership would then bounce between the queues without a dependency
// to carry it, so such a resource is shared by both queues instead. The contents before the
// first use come from the graphics queue; a graph output is read after the frame there.
bool read_on_both_queues(const std::vector<PlanPass>& order, const std::vector<Use>& uses, bool graph_output) {
    bool read_by[2] = {false, false};
    for (const Use& use : uses) {
        if (use.reads) read_by[index_of(order[use.position].queue)] = true;
        if (read_by[0] && read_by[1]) return true;
        if (use.writes) read_by[0] = read_by[1] = false;  // new contents from here on
    }
    return graph_output && read_by[index_of(Queue::AsyncCompute)];
}

// Ownership follows the contents from the queue that wrote them to the one that reads them: a
// read on the other queue than the previous use's takes the resource over; a graph output last
// used on the async queue goes back to graphics at the end of the frame; a first use that reads
// (imported contents) on the async queue takes it from graphics at the start of the frame.
void plan_transfers(uint32_t resource, const std::vector<PlanPass>& order, const std::vector<Use>& uses,
                    bool graph_output, std::vector<OwnershipTransfer>& transfers) {
    Queue owner = Queue::Graphics;
    uint32_t last_use = kFrameStart;
    for (const Use& use : uses) {
        const Queue queue = order[use.position].queue;
        if (queue != owner && use.reads) {
            transfers.push_back(OwnershipTransfer{resource, owner, queue, last_use, use.position});
        }
        // Only the first use can write without reading (the producer): the contents it leaves
        // start on its queue, whatever was there before.
        owner = queue;
        last_use = use.position;
    }
    if (graph_output && owner != Queue::Graphics) {
        transfers.push_back(
            OwnershipTransfer{resource, owner, Queue::Graphics, last_use, static_cast<uint32_t>(order.size())});
    }
}

}  // namespace

QueuePlan plan_queues(const std::vector<PlanPass>& order, const std::vector<PlanResource>& resources,
                      const Dependencies& dependencies, const Schedule& schedule) {
    QueuePlan out;
    out.occupancy.reserve(resources.size());
    for (const PlanResource& resource : resources) out.occupancy.push_back(resource.lifetime);
    out.queue_shared.assign(resources.size(), false);
    const bool any_async = std::any_of(order.begin(), order.end(),
                                       [](const PlanPass& pass) { return pass.queue != Queue::Graphics; });
    if (!any_async) return out;

    const auto pass_count = static_cast<uint32_t>(order.size());
    const std::vector<std::vector<Use>> uses = uses_by_resource(order, resources.size());
    for (uint32_t r = 0; r < resources.size(); ++r) {
        if (uses[r].empty()) continue;
        if (read_on_both_queues(order, uses[r], resources[r].graph_output)) {
            out.queue_shared[r] = true;
        } else {
            plan_transfers(r, order, uses[r], resources[r].graph_output, out.transfers);
        }
    }
    std::sort(out.transfers.begin(), out.transfers.end(), [](const OwnershipTransfer& a, const OwnershipTransfer& b) {
        return std::tie(a.acquire_before, a.resource) < std::tie(b.acquire_before, b.resource);
    });

    // What must be ordered across the queues: dependencies between passes on different queues,
    // each ownership transfer's release before its acquire, and the end of the frame (on the
    // graphics queue) after the last async pass, so that the frame ends when both queues do.
    std::vector<Requirement> requirements;
    for (uint32_t at = 0; at < pass_count; ++at) {
        for (uint32_t successor : dependencies.successors[order[at].declaration_index]) {
            const uint32_t later = schedule.position[successor];
            if (later == kNotScheduled || order[later].queue == order[at].queue) continue;
            requirements.push_back(Requirement{at, later, order[later].queue});
        }
    }
    for (const OwnershipTransfer& t : out.transfers) {
        const int64_t producer = t.release_after == kFrameStart ? -1 : int64_t{t.release_after};
        requirements.push_back(Requirement{producer, t.acquire_before, t.to});
    }
    for (uint32_t at = pass_count; at-- > 0;) {
        if (order[at].queue == Queue::Graphics) continue;
        requirements.push_back(Requirement{at, pass_count, Queue::Graphics});
        break;
    }
    // And the first async pass after the start of the frame on the graphics queue: a signal
    // there covers every earlier frame's graphics work, whose resources this frame's async
    // passes reuse (the end of the frame covers the other way round).
    for (uint32_t at = 0; at < pass_count; ++at) {
        if (order[at].queue == Queue::Graphics) continue;
        requirements.push_back(Requirement{-1, at, order[at].queue});
        break;
    }
    std::sort(requirements.begin(), requirements.end(), [](const Requirement& a, const Requirement& b) {
        return std::tie(a.consumer, a.producer) < std::tie(b.consumer, b.producer);
    });

    // Per waiting queue, walk its consumers in order and wait only where what is needed is not
    // yet covered by an earlier wait: the latest producer a consumer needs is the one to wait for.
    int64_t waited[2] = {kNothingWaited, kNothingWaited};
    for (std::size_t i = 0; i < requirements.size();) {
        const Requirement& first = requirements[i];
        int64_t need[2] = {kNothingWaited, kNothingWaited};
        std::size_t j = i;
        for (; j < requirements.size() && requirements[j].consumer == first.consumer; ++j) {
            int64_t& n = need[index_of(requirements[j].to)];
            n = std::max(n, requirements[j].producer);
        }
        for (const Queue to : {Queue::Graphics, Queue::AsyncCompute}) {
            const uint32_t q = index_of(to);
            if (need[q] <= waited[q]) continue;
            const uint32_t signal = need[q] < 0 ? kFrameStart : static_cast<uint32_t>(need[q]);
            out.syncs.push_back(QueueSync{other(to), to, signal, first.consumer});
            waited[q] = need[q];
        }
        i = j;
    }

    // The other-queue passes an async pass may overlap run between the last signal it waited
    // for (before it) and the first wait on a signal after it: its resources keep their memory
    // over all of them, so nothing running at the same time can alias it.
    std::vector<int64_t> last_waited(pass_count, -1);  // per position on the async queue
    std::vector<uint32_t> first_waiting(pass_count, pass_count);
    for (const QueueSync& sync : out.syncs) {
        if (sync.to == Queue::AsyncCompute && sync.signal_after != kFrameStart && sync.wait_before < pass_count) {
            last_waited[sync.wait_before] = std::max<int64_t>(last_waited[sync.wait_before], sync.signal_after);
        }
        if (sync.from == Queue::AsyncCompute) {
            first_waiting[sync.signal_after] = std::min(first_waiting[sync.signal_after], sync.wait_before);
        }
    }
    int64_t running_waited = -1;
    for (uint32_t at = 0; at < pass_count; ++at) {
        running_waited = std::max(running_waited, last_waited[at]);
        last_waited[at] = running_waited;
    }
    uint32_t running_first = pass_count;
    for (uint32_t at = pass_count; at-- > 0;) {
        running_first = std::min(running_first, first_waiting[at]);
        first_waiting[at] = running_first;
    }
    for (uint32_t r = 0; r < resources.size(); ++r) {
        Lifetime& occupancy = out.occupancy[r];
        for (const Use& use : uses[r]) {
            if (order[use.position].queue == Queue::Graphics) continue;
            const auto from = static_cast<uint32_t>(last_waited[use.position] + 1);
            const uint32_t to = first_waiting[use.position] - 1;  // first_waiting > position >= 0
            occupancy.first = std::min(occupancy.first, from);
            occupancy.last = std::max(occupancy.last, to);
        }
    }
    return out;
}

}  // namespace loom::fg::detail
