#include "loom/framegraph/graph.hpp"

#include <algorithm>

#include "graph_analysis.hpp"
#include "plan_resize.hpp"
#include "quoted_name.hpp"

namespace loom::fg {
namespace {

using detail::printable_name;

Error graph_error(std::string message) { return make_error(ErrorCode::Graph, std::move(message)); }

std::string port_list(const Pass& pass) {
    std::string out;
    for (const Port& p : pass.ports()) {
        if (!out.empty()) out += ", ";
        out += p.name;
    }
    return out.empty() ? "none" : out;
}

}  // namespace

std::optional<PortRef> parse_port_ref(std::string_view text) {
    const auto dot = text.rfind('.');
    if (dot == std::string_view::npos || dot == 0 || dot + 1 == text.size()) return std::nullopt;
    return PortRef{std::string(text.substr(0, dot)), std::string(text.substr(dot + 1))};
}

// A pass of the previous graph as planning saw it.
struct PreviousPass {
    std::string name;
    std::vector<Port> ports;
    PassKind kind = PassKind::Graphics;
    Queue queue = Queue::Graphics;
    bool side_effect = false;
    bool keep_declared_order = false;
};

struct FrameGraph::PreviousGraph {
    std::vector<PreviousPass> passes;
    std::vector<Connection> connections;
    std::vector<PortAddress> outputs;
    std::vector<std::pair<PassId, PassId>> order_requirements;
};

FrameGraph::FrameGraph() = default;
FrameGraph::~FrameGraph() = default;
FrameGraph::FrameGraph(FrameGraph&&) noexcept = default;
FrameGraph& FrameGraph::operator=(FrameGraph&&) noexcept = default;

Result<PassId> FrameGraph::add_pass(std::unique_ptr<Pass> pass) {
    if (!pass) return make_error(ErrorCode::InvalidArgument, "add_pass: null pass");
    // Names first: a bad name is the error to report, rather than a declaration error of the
    // pass (status()) that merely contains it.
    if (pass->name().empty()) return graph_error("add_pass: a pass needs a name");
    if (auto problem = name_problem(pass->name())) {
        return graph_error("add_pass: the pass name " + quoted_name(pass->name()) + " " + *problem);
    }
    for (const Port& port : pass->ports()) {
        if (auto problem = name_problem(port.name)) {
            return graph_error("add_pass: pass '" + pass->name() + "': the port name " + quoted_name(port.name) + " " +
                               *problem);
        }
    }
    // Bad port set names were refused by Pass::add (its status).
    LOOM_TRY(pass->status());
    if (find_pass(pass->name())) {
        return graph_error("add_pass: a pass called '" + pass->name() + "' already exists");
    }
    // Reads (Pass::read) are checked before the pass is added, so that a refused pass leaves
    // the graph as it was; the input they connect is new, so no other check can fail.
    for (const auto& [input, source] : pass->reads()) {
        const Port& port = pass->ports()[input];
        auto what = [&] { return "add_pass: pass '" + pass->name() + "': " + port.name + " reads "; };
        if (auto problem = address_problem(source)) return graph_error(what() + *problem);
        const Port& written = port_at(source);
        if (!port_writes(written.kind)) {
            return graph_error(what() + port_name(source) + ", an input; a read takes an output or inout");
        }
        if (written.type != port.type) {
            return graph_error(what() + port_name(source) + ", a " + std::string(resource_type_name(written.type)) +
                               " port; read() reads textures");
        }
    }
    const auto index = static_cast<uint32_t>(passes_.size());
    const auto first_port = static_cast<uint32_t>(sources_.size());
    port_offset_.push_back(first_port);
    port_data_.push_back(pass->ports().data());
    for (const Port& port : pass->ports()) port_facts_.push_back(PortFacts::of(port, pass->kind()));
    sources_.resize(first_port + pass->ports().size());
    consumer_lists_.resize(first_port + pass->ports().size());
    marked_output_.resize(first_port + pass->ports().size());
    passes_.push_back(std::move(pass));
    index_name(index);
    for (const auto& [input, source] : passes_.back()->reads()) link(source, PortAddress{index, input});
    if (same_as_previous_) {
        const PreviousMatch match = compare_with_previous(index);
        if (match != PreviousMatch::Different) {
            if (match == PreviousMatch::TextureSpecsDiffer) respecified_passes_.push_back(index);
            if (passes_[index]->side_effect() != previous_->passes[index].side_effect) ++side_effect_differences_;
            // Compared: the previous pass's ports are not needed again, and the passes declared
            // next reuse their memory while it is warm.
            std::vector<Port>().swap(previous_->passes[index].ports);
        } else {
            release_previous();
        }
    }
    ++revision_;
    return PassId{index};
}

void FrameGraph::reserve(uint32_t passes, uint32_t ports) {
    passes_.reserve(passes);
    name_hashes_.reserve(passes);
    if (std::size_t{passes} * 2 > name_slots_.size()) grow_name_index(std::size_t{passes} * 2);
    port_offset_.reserve(passes);
    port_data_.reserve(passes);
    port_facts_.reserve(ports);
    sources_.reserve(ports);
    consumer_lists_.reserve(ports);
    // Each list starts with room for two (see link).
    consumer_pool_.reserve(std::size_t{ports} * 2);
    marked_output_.reserve(ports);
    connections_.reserve(ports);
}

void FrameGraph::clear() {
    remove_declarations();
    cached_plan_.reset();
    resize_basis_.reset();
    release_previous();
    ++revision_;
}

void FrameGraph::redeclare() {
    // Only a graph that the cached plan was made from is worth comparing with: the one planned
    // last, or one declared again as it was and not planned since.
    if (cached_plan_ && cached_revision_ != revision_ && is_previous_graph()) cached_revision_ = revision_;
    if (!cached_plan_ || cached_revision_ != revision_) {
        clear();
        return;
    }
    if (!previous_) previous_ = std::make_unique<PreviousGraph>();
    PreviousGraph& previous = *previous_;
    previous.passes.clear();
    previous.passes.reserve(passes_.size());
    for (const std::unique_ptr<Pass>& pass : passes_) {
        previous.passes.push_back({pass->name_, std::move(pass->ports_), pass->kind_, pass->queue_,
                                   pass->side_effect_, pass->keep_declared_order_});
    }
    // The arrays trade places, so that neither graph allocates them anew.
    previous.connections.swap(connections_);
    previous.outputs.swap(outputs_);
    previous.order_requirements.swap(order_requirements_);
    remove_declarations();
    same_as_previous_ = true;
    side_effect_differences_ = 0;
    respecified_passes_.clear();
    ++revision_;
}

FrameGraph::PreviousMatch FrameGraph::compare_with_previous(uint32_t index) const {
    if (index >= previous_->passes.size()) return PreviousMatch::Different;
    const PreviousPass& before = previous_->passes[index];
    const Pass& pass = *passes_[index];
    if (pass.name() != before.name || pass.kind() != before.kind || pass.queue() != before.queue ||
        pass.keeps_declared_order() != before.keep_declared_order || pass.ports().size() != before.ports.size()) {
        return PreviousMatch::Different;
    }
    if (pass.ports() == before.ports) return PreviousMatch::Same;
    // Each port compared whole but for its spec, so that a field added to Port is compared too
    // (a copy: only passes that differ get here).
    for (std::size_t i = 0; i < before.ports.size(); ++i) {
        Port port = pass.ports()[i];
        port.spec = before.ports[i].spec;
        if (!(port == before.ports[i])) return PreviousMatch::Different;
    }
    return PreviousMatch::TextureSpecsDiffer;
}

bool FrameGraph::is_previous_structure() const {
    return previous_ && same_as_previous_ && side_effect_differences_ == 0 &&
           passes_.size() == previous_->passes.size() &&
           connections_ == previous_->connections && outputs_ == previous_->outputs &&
           order_requirements_ == previous_->order_requirements;
}

void FrameGraph::release_previous() {
    same_as_previous_ = false;
    respecified_passes_.clear();
    if (!previous_) return;
    previous_->passes.clear();
    previous_->connections.clear();
    previous_->outputs.clear();
    previous_->order_requirements.clear();
}

void FrameGraph::remove_declarations() {
    passes_.clear();
    std::fill(name_slots_.begin(), name_slots_.end(), 0u);
    name_hashes_.clear();
    port_offset_.clear();
    port_data_.clear();
    port_facts_.clear();
    sources_.clear();
    consumer_lists_.clear();
    consumer_pool_.clear();
    connections_.clear();
    outputs_.clear();
    marked_output_.clear();
    order_requirements_.clear();
}

std::optional<std::string> FrameGraph::address_problem(PortAddress address) const {
    if (address.pass >= passes_.size()) {
        return "pass #" + std::to_string(address.pass) + ", which is not in the graph (it has " +
               std::to_string(passes_.size()) + " passes)";
    }
    const Pass& p = *passes_[address.pass];
    if (address.port >= p.ports().size()) {
        return "port #" + std::to_string(address.port) + " of pass '" + p.name() + "', which has " +
               std::to_string(p.ports().size()) + " ports (" + port_list(p) + ")";
    }
    return std::nullopt;
}

void FrameGraph::link(PortAddress from, PortAddress to) {
    sources_[flat(to)] = from;
    ConsumerList& list = consumer_lists_[flat(from)];
    if (list.count == list.capacity) {
        // Outputs are mostly read once or twice: room for two at the first, doubled when full,
        // the list moving to the end of the pool (its old slots stay unused).
        const uint32_t capacity = list.capacity == 0 ? 2 : list.capacity * 2;
        const auto offset = static_cast<uint32_t>(consumer_pool_.size());
        consumer_pool_.resize(consumer_pool_.size() + capacity);
        std::copy_n(consumer_pool_.begin() + list.offset, list.count, consumer_pool_.begin() + offset);
        list.offset = offset;
        list.capacity = capacity;
    }
    consumer_pool_[list.offset + list.count++] = to;
    connections_.push_back({from, to});
}

std::optional<PassId> FrameGraph::find_pass(std::string_view name) const {
    if (name_slots_.empty()) return std::nullopt;
    const std::size_t hash = std::hash<std::string_view>{}(name);
    const std::size_t mask = name_slots_.size() - 1;
    for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
        const uint32_t entry = name_slots_[slot];
        if (entry == 0) return std::nullopt;
        if (name_hashes_[entry - 1] == hash && passes_[entry - 1]->name() == name) return PassId{entry - 1};
    }
}

void FrameGraph::index_name(uint32_t index) {
    name_hashes_.push_back(std::hash<std::string_view>{}(passes_[index]->name()));
    // Half full at most, so that probes stay short and always find a free slot.
    if (name_hashes_.size() * 2 > name_slots_.size()) {
        grow_name_index(std::max<std::size_t>(16, name_slots_.size() * 2));
        return;  // growing put every pass in, this one too
    }
    const std::size_t mask = name_slots_.size() - 1;
    std::size_t slot = name_hashes_[index] & mask;
    while (name_slots_[slot] != 0) slot = (slot + 1) & mask;
    name_slots_[slot] = index + 1;
}

void FrameGraph::grow_name_index(std::size_t slots) {
    std::size_t size = 16;
    while (size < slots) size *= 2;
    name_slots_.assign(size, 0u);
    const std::size_t mask = size - 1;
    for (uint32_t index = 0; index < name_hashes_.size(); ++index) {
        std::size_t slot = name_hashes_[index] & mask;
        while (name_slots_[slot] != 0) slot = (slot + 1) & mask;
        name_slots_[slot] = index + 1;
    }
}

std::optional<PortAddress> FrameGraph::source(PortAddress address) const { return sources_[flat(address)]; }

std::span<const PortAddress> FrameGraph::consumers(PortAddress address) const {
    const ConsumerList& list = consumer_lists_[flat(address)];
    return {consumer_pool_.data() + list.offset, list.count};
}

std::string FrameGraph::port_name(PortAddress address) const {
    // Sized once: plans name every port of every resource this way.
    const std::string& pass = passes_[address.pass]->name();
    const std::string& port = port_at(address).name;
    std::string name;
    name.reserve(pass.size() + 1 + port.size());
    name.append(pass).append(1, '.').append(port);
    return name;
}

Result<PortAddress> FrameGraph::resolve(const PortRef& ref) const {
    auto pass_id = find_pass(ref.pass);
    // The reference is the caller's and may hold any bytes; names in the graph are checked.
    if (!pass_id) return graph_error("unknown pass " + quoted_name(ref.pass));
    const Pass& p = pass(*pass_id);
    auto port_index = p.port_index(ref.port);
    if (!port_index) {
        return graph_error("unknown port " + quoted_name(ref.port) + " on pass '" + ref.pass + "' (its ports: " +
                           port_list(p) + ")");
    }
    return PortAddress{pass_id->index, *port_index};
}

Status FrameGraph::connect(const PortRef& from, const PortRef& to) {
    // The text is built only for an error.
    auto what = [&] { return "connect " + printable_name(from.to_string()) + " -> " + printable_name(to.to_string()) + ": "; };
    auto from_address = resolve(from);
    if (!from_address) return graph_error(what() + from_address.error().message);
    auto to_address = resolve(to);
    if (!to_address) return graph_error(what() + to_address.error().message);
    // Resolved names are the graph's, so the messages by address read as those by name.
    return connect(*from_address, *to_address);
}

Status FrameGraph::connect(PortAddress from, PortAddress to) {
    auto from_problem = address_problem(from);
    auto to_problem = address_problem(to);
    if (from_problem || to_problem) {
        auto describe = [&](PortAddress a, const std::optional<std::string>& problem) {
            return problem ? "pass #" + std::to_string(a.pass) + " port #" + std::to_string(a.port) : port_name(a);
        };
        return graph_error("connect " + describe(from, from_problem) + " -> " + describe(to, to_problem) + ": no " +
                           (from_problem ? *from_problem : *to_problem));
    }
    auto what = [&] { return "connect " + port_name(from) + " -> " + port_name(to) + ": "; };
    const Port& from_port = port_at(from);
    const Port& to_port = port_at(to);
    if (!port_writes(from_port.kind)) {
        return graph_error(what() + port_name(from) + " is an input; a connection starts at an output or inout");
    }
    if (!port_reads(to_port.kind)) {
        return graph_error(what() + port_name(to) + " is an output; a connection ends at an input or inout");
    }
    if (from_port.type != to_port.type) {
        return graph_error(what() + port_name(from) + " is a " + std::string(resource_type_name(from_port.type)) +
                           " port but " + port_name(to) + " is a " + std::string(resource_type_name(to_port.type)) +
                           " port");
    }
    if (auto existing = sources_[flat(to)]) {
        return graph_error(what() + port_name(to) + " is already connected to " + port_name(*existing) + "; an " +
                           std::string(port_kind_name(to_port.kind)) + " takes one source");
    }
    if (to_port.kind == PortKind::InOut) {
        for (const PortAddress& consumer : consumers(from)) {
            if (port_at(consumer).kind == PortKind::InOut) {
                return graph_error(what() + port_name(from) + " is already modified in place by " +
                                   port_name(consumer) + "; one texture has one in-place writer at a time (chain " +
                                   "the inouts: connect " + port_name(consumer) + " -> " + port_name(to) + ")");
            }
        }
    }
    link(from, to);
    ++revision_;
    return {};
}

Status FrameGraph::mark_output(const PortRef& ref) {
    auto address = resolve(ref);
    if (!address) return graph_error("mark_output " + printable_name(ref.to_string()) + ": " + address.error().message);
    return mark_output(*address);
}

Status FrameGraph::mark_output(PortAddress address) {
    if (auto problem = address_problem(address)) return graph_error("mark_output: no " + *problem);
    if (!port_writes(port_at(address).kind)) {
        return graph_error("mark_output " + port_name(address) + ": an input cannot be a graph output; mark the port "
                           "that produces the texture");
    }
    if (!marked_output_[flat(address)]) {
        marked_output_[flat(address)] = true;
        outputs_.push_back(address);
        ++revision_;
    }
    return {};
}

Status FrameGraph::set_side_effect(std::string_view name, bool side_effect) {
    auto id = find_pass(name);
    if (!id) return graph_error("set_side_effect: unknown pass " + quoted_name(name));
    return set_side_effect(*id, side_effect);
}

Status FrameGraph::set_side_effect(PassId id, bool side_effect) {
    if (id.index >= passes_.size()) {
        return graph_error("set_side_effect: no pass #" + std::to_string(id.index) + " (the graph has " +
                           std::to_string(passes_.size()) + " passes)");
    }
    if (passes_[id.index]->side_effect() != side_effect) {
        passes_[id.index]->set_side_effect(side_effect);
        // While every pass so far matches the previous graph's but for side effects, this pass
        // now differs from its previous one where it did not, or the other way round.
        if (same_as_previous_) {
            const bool now_differs = side_effect != previous_->passes[id.index].side_effect;
            if (now_differs) {
                ++side_effect_differences_;
            } else {
                --side_effect_differences_;
            }
        }
        ++revision_;
    }
    return {};
}

Status FrameGraph::set_texture_spec(PortAddress address, TextureSpec spec) {
    if (auto problem = address_problem(address)) return graph_error("set_texture_spec: no " + *problem);
    Pass& pass = *passes_[address.pass];
    Port& port = pass.ports_[address.port];
    if (port.type != ResourceType::Texture) {
        return graph_error("set_texture_spec " + port_name(address) + ": a buffer port; its spec is a BufferSpec");
    }
    if (port.spec == spec) return {};
    const bool respecified_since_plan = is_plan_graph_respecified();
    port.spec = std::move(spec);
    port_facts_[flat(address)] = PortFacts::of(port, pass.kind());
    ++revision_;
    // Redeclared passes are compared as they are added: one changed after its comparison is
    // listed with the respecified ones, so that plan() does not take it for the previous pass.
    if (same_as_previous_ || respecified_since_plan) {
        // Listed twice is harmless; ports of one pass are mostly respecified one after another.
        if (respecified_passes_.empty() || respecified_passes_.back() != address.pass) {
            respecified_passes_.push_back(address.pass);
        }
        if (respecified_since_plan) respecified_revision_ = revision_;
    }
    return {};
}

Status FrameGraph::require_order(std::string_view earlier, std::string_view later) {
    const std::string what = "require_order " + quoted_name(earlier) + " before " + quoted_name(later) + ": ";
    auto first = find_pass(earlier);
    if (!first) return graph_error(what + "unknown pass " + quoted_name(earlier));
    auto second = find_pass(later);
    if (!second) return graph_error(what + "unknown pass " + quoted_name(later));
    if (*first == *second) return graph_error(what + "a pass cannot run before itself");
    const std::pair<PassId, PassId> requirement{*first, *second};
    if (std::find(order_requirements_.begin(), order_requirements_.end(), requirement) == order_requirements_.end()) {
        order_requirements_.push_back(requirement);
        ++revision_;
    }
    return {};
}

Status FrameGraph::validate() const {
    auto dependencies = detail::analyze(*this);
    if (!dependencies) return dependencies.take_error();
    return {};
}

Result<std::shared_ptr<const Plan>> FrameGraph::plan(const PlanOptions& options) {
    // The cached plan's graph, declared again (redeclare) or respecified (set_texture_spec) at most.
    const bool same_structure =
        cached_plan_ && (cached_revision_ == revision_ || is_previous_structure() || is_plan_graph_respecified());
    // The passes declared again with other texture specs (none when the graph was not redeclared),
    // taken before release_previous forgets them.
    std::vector<uint32_t> respecified;
    if (same_structure && cached_revision_ != revision_) respecified.swap(respecified_passes_);
    release_previous();
    if (same_structure) {
        cached_revision_ = revision_;
        if (cached_options_ == options && respecified.empty()) return cached_plan_;
        PlanOptions resized = cached_options_;
        resized.frame = options.frame;
        if (resize_basis_ && resized == options && replan_cached_plan(options, respecified)) return cached_plan_;
    }
    // The cached plan is replaced either way: when nobody else holds it, its memory is free for
    // the new one (a large plan's allocations are otherwise served around it).
    cached_plan_.reset();
    auto fresh = detail::build_plan(*this, options, resize_basis_);
    if (!fresh) return fresh.take_error();
    ++plans_built_;
    cached_plan_ = std::make_shared<Plan>(std::move(*fresh));
    cached_revision_ = revision_;
    cached_options_ = options;
    return cached_plan_;
}

bool FrameGraph::replan_cached_plan(const PlanOptions& options, std::span<const uint32_t> respecified) {
    // Nobody else can see a plan only the graph holds: it is changed in place, which saves
    // copying its passes, ports and names.
    std::shared_ptr<Plan> next = cached_plan_.use_count() == 1 ? std::const_pointer_cast<Plan>(cached_plan_)
                                                                : std::make_shared<Plan>(*cached_plan_);
    cached_plan_.reset();
    if (!detail::replan(*this, *resize_basis_, options, respecified, *next)) return false;
    ++plans_resized_;
    cached_plan_ = std::move(next);
    cached_options_ = options;
    return true;
}

}  // namespace loom::fg
