#include "loom/framegraph/graph.hpp"

#include <algorithm>

#include "graph_analysis.hpp"
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
    if (pass_index_.contains(pass->name())) {
        return graph_error("add_pass: a pass called '" + pass->name() + "' already exists");
    }
    const auto index = static_cast<uint32_t>(passes_.size());
    pass_index_.emplace(pass->name(), index);
    const auto first_port = static_cast<uint32_t>(sources_.size());
    port_offset_.push_back(first_port);
    sources_.resize(first_port + pass->ports().size());
    consumers_.resize(first_port + pass->ports().size());
    marked_output_.resize(first_port + pass->ports().size());
    passes_.push_back(std::move(pass));
    ++revision_;
    return PassId{index};
}

std::optional<PassId> FrameGraph::find_pass(std::string_view name) const {
    auto it = pass_index_.find(std::string(name));
    if (it == pass_index_.end()) return std::nullopt;
    return PassId{it->second};
}

const Port& FrameGraph::port_at(PortAddress address) const { return passes_[address.pass]->ports()[address.port]; }

std::optional<PortAddress> FrameGraph::source(PortAddress address) const { return sources_[flat(address)]; }

std::span<const PortAddress> FrameGraph::consumers(PortAddress address) const { return consumers_[flat(address)]; }

std::string FrameGraph::port_name(PortAddress address) const {
    return passes_[address.pass]->name() + "." + port_at(address).name;
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
    const std::string what = "connect " + printable_name(from.to_string()) + " -> " + printable_name(to.to_string()) + ": ";
    auto from_address = resolve(from);
    if (!from_address) return graph_error(what + from_address.error().message);
    auto to_address = resolve(to);
    if (!to_address) return graph_error(what + to_address.error().message);

    const Port& from_port = port_at(*from_address);
    const Port& to_port = port_at(*to_address);
    if (!port_writes(from_port.kind)) {
        return graph_error(what + from.to_string() + " is an input; a connection starts at an output or inout");
    }
    if (!port_reads(to_port.kind)) {
        return graph_error(what + to.to_string() + " is an output; a connection ends at an input or inout");
    }
    if (from_port.type != to_port.type) {
        return graph_error(what + from.to_string() + " is a " + std::string(resource_type_name(from_port.type)) +
                           " port but " + to.to_string() + " is a " + std::string(resource_type_name(to_port.type)) +
                           " port");
    }
    if (auto existing = sources_[flat(*to_address)]) {
        return graph_error(what + to.to_string() + " is already connected to " + port_name(*existing) + "; an " +
                           std::string(port_kind_name(to_port.kind)) + " takes one source");
    }
    if (to_port.kind == PortKind::InOut) {
        for (const PortAddress& consumer : consumers_[flat(*from_address)]) {
            if (port_at(consumer).kind == PortKind::InOut) {
                return graph_error(what + from.to_string() + " is already modified in place by " +
                                   port_name(consumer) + "; one texture has one in-place writer at a time (chain " +
                                   "the inouts: connect " + port_name(consumer) + " -> " + to.to_string() + ")");
            }
        }
    }
    sources_[flat(*to_address)] = *from_address;
    consumers_[flat(*from_address)].push_back(*to_address);
    connections_.push_back({*from_address, *to_address});
    ++revision_;
    return {};
}

Status FrameGraph::mark_output(const PortRef& ref) {
    auto address = resolve(ref);
    if (!address) return graph_error("mark_output " + printable_name(ref.to_string()) + ": " + address.error().message);
    if (!port_writes(port_at(*address).kind)) {
        return graph_error("mark_output " + ref.to_string() + ": an input cannot be a graph output; mark the port "
                           "that produces the texture");
    }
    if (!marked_output_[flat(*address)]) {
        marked_output_[flat(*address)] = true;
        outputs_.push_back(*address);
        ++revision_;
    }
    return {};
}

Status FrameGraph::set_side_effect(std::string_view name, bool side_effect) {
    auto id = find_pass(name);
    if (!id) return graph_error("set_side_effect: unknown pass " + quoted_name(name));
    if (passes_[id->index]->side_effect() != side_effect) {
        passes_[id->index]->set_side_effect(side_effect);
        ++revision_;
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
    if (cached_plan_ && cached_revision_ == revision_ && cached_options_ == options) return cached_plan_;
    auto fresh = build_plan(*this, options);
    if (!fresh) return fresh.take_error();
    ++plans_built_;
    cached_plan_ = std::make_shared<const Plan>(std::move(*fresh));
    cached_revision_ = revision_;
    cached_options_ = options;
    return cached_plan_;
}

}  // namespace loom::fg
