#pragma once
// The frame graph: passes, the connections between their ports, the ports whose textures
// leave the graph (graph outputs), and a cache of the last plan. Declaration and connection
// happen here; planning is in planner.hpp; nothing here touches a GPU.
//
//   FrameGraph graph;
//   graph.add_pass(Pass("geometry").output("albedo", TextureSpec::of(rhi::Format::RGBA8Unorm)));
//   graph.add_pass(Pass("composite").input("color").output("final"));
//   graph.connect(port("geometry", "albedo"), port("composite", "color"));
//   graph.mark_output(port("composite", "final"));
//   PlanOptions options;
//   options.frame = {1280, 720};
//   auto plan = graph.plan(options);

#include <concepts>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "loom/framegraph/pass.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/framegraph/planner.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

namespace detail {
struct ResizeBasis;
}  // namespace detail

/// Names a port by pass name and port name, as `connect` and `mark_output` take it.
struct PortRef {
    std::string pass;
    std::string port;

    /// "pass.port"
    [[nodiscard]] std::string to_string() const { return pass + "." + port; }
    friend bool operator==(const PortRef&, const PortRef&) = default;
};

/// The port `name` of `pass` (the paper's `(port pass 'name)`).
inline PortRef port(const Pass& pass, std::string_view name) { return {pass.name(), std::string(name)}; }
/// A reference to port `name` of pass `pass`, e.g. port("blur", "out").
inline PortRef port(std::string_view pass, std::string_view name) { return {std::string(pass), std::string(name)}; }

/// "pass.port" split at the last dot; nullopt when there is no dot or a side is empty.
std::optional<PortRef> parse_port_ref(std::string_view text);

/// An edge from an output/inout port to an input/inout port.
struct Connection {
    PortAddress from;
    PortAddress to;
    friend bool operator==(const Connection&, const Connection&) = default;
};

/// What planning reads of most ports, kept by the graph in one flat array (FrameGraph::port_facts)
/// so that the planner reads 12 bytes per port instead of walking to each Pass and its Port.
/// Written when the pass is added, and again for a port set_texture_spec changes.
struct PortFacts {
    rhi::TextureUsage requested_usage = rhi::TextureUsage::None;  ///< the texture spec's usage
    PortKind kind = PortKind::Input;
    ResourceType type = ResourceType::Texture;
    PassKind pass_kind = PassKind::Graphics;  ///< the kind of the port's pass
    bool optional = false;
    /// The port's spec (Port::spec of a texture port, Port::buffer of a buffer port) constrains
    /// nothing: joining it changes nothing.
    bool unconstrained = true;
    /// The port uses the whole resource: Port::range (textures) or Port::bytes (buffers) is the
    /// default.
    bool whole = true;

    /// The facts of `port`, a port of a pass of kind `pass_kind`.
    static PortFacts of(const Port& port, PassKind pass_kind);
};

// Inline: built where it is stored, rather than returned through the stack, which made GCC
// store the fields one by one and load them back whole (a stalled load for every port declared).
inline PortFacts PortFacts::of(const Port& port, PassKind pass_kind) {
    PortFacts facts;
    facts.requested_usage = port.spec.usage;
    facts.kind = port.kind;
    facts.type = port.type;
    facts.pass_kind = pass_kind;
    facts.optional = port.optional;
    if (port.type == ResourceType::Buffer) {
        facts.unconstrained = port.buffer.unconstrained();
        facts.whole = port.bytes == BufferRange{};
    } else {
        facts.unconstrained = port.spec.unconstrained();
        facts.whole = port.range == SubresourceRange{};
    }
    return facts;
}

/// Passes and their connections, with the graph outputs: what is planned (plan()) and executed (Executor).
class FrameGraph {
public:
    FrameGraph();
    ~FrameGraph();
    FrameGraph(FrameGraph&&) noexcept;
    FrameGraph& operator=(FrameGraph&&) noexcept;
    FrameGraph(const FrameGraph&) = delete;
    FrameGraph& operator=(const FrameGraph&) = delete;

    /// Adds a pass; its ports are fixed from now on. Errors: the pass's own declaration error
    /// (Pass::status), an empty name, or a name already used (ErrorCode::Graph).
    Result<PassId> add_pass(std::unique_ptr<Pass> pass);
    /// Adds a pass given by value (a Pass or a class derived from it).
    template <std::derived_from<Pass> P>
    Result<PassId> add_pass(P pass) {
        return add_pass(std::make_unique<P>(std::move(pass)));
    }

    /// Feeds `to` (an input or inout) from `from` (an output or inout). An output feeds any
    /// number of inputs, but at most one inout (a texture is modified in place by one pass;
    /// chain inouts to modify it again); an input or inout takes one source. Errors
    /// (ErrorCode::Graph) name both ports: unknown pass or port, wrong direction, a second
    /// source, a second in-place modification.
    Status connect(const PortRef& from, const PortRef& to);
    /// connect by the handles add_pass and port_of give: no name is looked up, and an error's
    /// text (the same as connect by names gives) is built only when a check fails. An address
    /// outside the graph is an error too.
    Status connect(PortAddress from, PortAddress to);

    /// Marks an output or inout port as a graph output: its texture is read after the frame
    /// (presented, read back), so its pass is never culled and it lives until the last pass.
    Status mark_output(const PortRef& port);
    /// mark_output by handle.
    Status mark_output(PortAddress port);

    /// Marks a pass as having side effects (never culled), or clears the mark.
    Status set_side_effect(std::string_view pass, bool side_effect = true);
    /// set_side_effect by handle.
    Status set_side_effect(PassId pass, bool side_effect = true);

    /// Gives texture port `port` another spec, as if its pass had been declared with it (a
    /// quality setting that changes a format or a scale, say), without declaring the graph again.
    /// When every change to the graph since the current plan was such a respecification and the
    /// plan is in the declared order, the next plan() makes the new plan from the previous one
    /// (see plan()); whether the specs still join is planning's to say. Setting the spec the port
    /// has changes nothing. Errors (ErrorCode::Graph): an address outside the graph, a buffer port.
    Status set_texture_spec(PortAddress port, TextureSpec spec);

    /// Makes room for `passes` passes with `ports` ports in all (and as many connections), so
    /// that declaring a graph of a known size does not grow its arrays pass by pass.
    void reserve(uint32_t passes, uint32_t ports);
    /// Removes every pass, connection, graph output and order requirement, keeping the arrays'
    /// memory: a graph declared anew every frame reuses it (reserve once, clear every frame).
    /// The next plan() plans afresh.
    void clear();
    /// Removes every pass, connection, graph output and order requirement as clear() does, for a
    /// graph declared anew every frame: when what is declared next equals the graph the current
    /// plan was made from (the same passes with the same ports, kinds, queues and side effects,
    /// the same connections, graph outputs and order requirements, each in the same order), the
    /// next plan() with the same options returns that plan again, the same object, without
    /// planning. Each pass is compared as it is added. When passes differ only in the texture
    /// specs of their ports and the plan is in the declared order, the next plan() makes the new
    /// plan from the previous one (see plan()); any other difference (a side effect set after
    /// add_pass included) makes it plan afresh. Until that plan() the graph keeps the ports of
    /// the passes removed here.
    void redeclare();

    /// Requires `earlier` to run before `later` in every order although no texture connects
    /// them (both write what the application presents, say). It orders them like a connection
    /// does: across queues with a semaphore; a requirement that closes a cycle is an error of
    /// planning naming it. It does not keep a pass from being culled; a requirement on a culled
    /// pass is dropped. Errors (ErrorCode::Graph): an unknown pass, the same pass twice.
    Status require_order(std::string_view earlier, std::string_view later);
    /// The pairs (earlier, later) given to require_order, in the order given, each once.
    [[nodiscard]] const std::vector<std::pair<PassId, PassId>>& order_requirements() const { return order_requirements_; }

    /// Number of passes added.
    [[nodiscard]] uint32_t pass_count() const { return static_cast<uint32_t>(passes_.size()); }
    /// The pass with id `id`.
    [[nodiscard]] const Pass& pass(PassId id) const { return *passes_[id.index]; }
    /// Runs the execute step of a pass (the executor calls it; ports stay fixed, which is why
    /// the graph hands out no mutable Pass).
    Status execute_pass(PassId id, PassContext& context) { return passes_[id.index]->execute(context); }
    /// The id of the pass called `name`, if any.
    [[nodiscard]] std::optional<PassId> find_pass(std::string_view name) const;
    /// Every connection, in the order made.
    [[nodiscard]] const std::vector<Connection>& connections() const { return connections_; }
    /// The ports marked as graph outputs.
    [[nodiscard]] const std::vector<PortAddress>& outputs() const { return outputs_; }
    /// True when the port at `address` is marked as a graph output (one of outputs()).
    [[nodiscard]] bool is_output(PortAddress address) const { return marked_output_[flat(address)]; }
    /// The port at `address`.
    [[nodiscard]] const Port& port_at(PortAddress address) const { return port_data_[address.pass][address.port]; }
    /// The facts of the port at `address`.
    [[nodiscard]] const PortFacts& facts(PortAddress address) const { return port_facts_[flat(address)]; }
    /// The facts of every port of `pass`, in port order.
    [[nodiscard]] std::span<const PortFacts> port_facts(PassId pass) const {
        const uint32_t first = port_offset_[pass.index];
        const uint32_t end = pass.index + 1 < port_offset_.size() ? port_offset_[pass.index + 1]
                                                                  : static_cast<uint32_t>(port_facts_.size());
        return {port_facts_.data() + first, end - first};
    }
    /// The port feeding `address` (an input or inout), if connected.
    [[nodiscard]] std::optional<PortAddress> source(PortAddress address) const;
    /// The ports `address` feeds, in connection order (valid until the graph changes).
    [[nodiscard]] std::span<const PortAddress> consumers(PortAddress address) const;
    /// "pass.port"
    [[nodiscard]] std::string port_name(PortAddress address) const;
    /// The address of a port by names; ErrorCode::Graph naming the unknown pass or port.
    [[nodiscard]] Result<PortAddress> resolve(const PortRef& ref) const;

    /// Checks that need no frame size: required inputs connected, no cycle (named in order),
    /// no pass reading a texture it modifies in place. Planning runs them too.
    [[nodiscard]] Status validate() const;

    /// Plans the graph (build_plan), or returns the previous plan when neither the graph nor
    /// the options changed since: the same shared object, not a copy. When the previous plan is
    /// in the declared order (PassOrder::Declared) and only the frame size changed, or the graph
    /// was redeclared with other texture specs on some ports of passes that run, the new plan is
    /// made from the previous one: what changed joined and resolved again, the resources
    /// allocated again, the rest kept (the same plan build_plan gives, for a fraction of the
    /// time). The previous plan is changed in place when nothing else holds it, else copied.
    Result<std::shared_ptr<const Plan>> plan(const PlanOptions& options = {});
    /// How many times plan() planned from scratch (for tests of the reuse).
    [[nodiscard]] uint64_t plans_built() const { return plans_built_; }
    /// How many times plan() made the plan of another frame size, or of other texture specs,
    /// from the previous plan.
    [[nodiscard]] uint64_t plans_resized() const { return plans_resized_; }
    /// Increases with every change to the graph.
    [[nodiscard]] uint64_t revision() const { return revision_; }

private:
    uint32_t flat(PortAddress address) const { return port_offset_[address.pass] + address.port; }
    // Why `address` names no port of this graph, or nullopt.
    [[nodiscard]] std::optional<std::string> address_problem(PortAddress address) const;
    // Records a connection that passed every check.
    void link(PortAddress from, PortAddress to);

    // Records pass `index` (already in passes_) in the name index.
    void index_name(uint32_t index);
    // Makes the name index at least `slots` slots (a power of two) and puts every pass back.
    void grow_name_index(std::size_t slots);

    std::vector<std::unique_ptr<Pass>> passes_;
    // Pass name -> index, by open addressing with linear probing over one array (a slot holds
    // a pass index + 1; 0 is free; at most half the slots used), with each pass's name hash kept
    // beside: no node per pass as a std::unordered_map allocates, and a probe compares hashes
    // before names.
    std::vector<uint32_t> name_slots_;
    std::vector<std::size_t> name_hashes_;  // per pass
    std::vector<uint32_t> port_offset_;                 // first flat port index of each pass
    // Each pass's ports (Pass::ports().data(), fixed once added): port_at without a walk
    // through the Pass.
    std::vector<const Port*> port_data_;
    std::vector<PortFacts> port_facts_;                 // per flat port
    std::vector<std::optional<PortAddress>> sources_;   // per flat port
    // The ports each flat port feeds: a range of consumer_pool_ per port, so that no port
    // allocates a list of its own.
    struct ConsumerList {
        uint32_t offset = 0;
        uint32_t count = 0;
        uint32_t capacity = 0;
    };
    std::vector<ConsumerList> consumer_lists_;          // per flat port
    std::vector<PortAddress> consumer_pool_;
    std::vector<Connection> connections_;
    std::vector<PortAddress> outputs_;
    std::vector<bool> marked_output_;                  // per flat port: in outputs_
    std::vector<std::pair<PassId, PassId>> order_requirements_;  // (earlier, later)

    // Empties every declaration, keeping the arrays' memory (clear, redeclare).
    void remove_declarations();
    // How pass `index` (just added) compares with the previous graph's pass `index`, side
    // effects aside (they may change after add_pass; side_effect_differences_ counts them).
    enum class PreviousMatch : uint8_t { Same, TextureSpecsDiffer, Different };
    [[nodiscard]] PreviousMatch compare_with_previous(uint32_t index) const;
    // Whether the graph now declared is the previous graph (redeclare) but for the texture specs
    // of the passes in respecified_passes_...
    [[nodiscard]] bool is_previous_structure() const;
    // ... and whether it is the previous graph.
    [[nodiscard]] bool is_previous_graph() const { return is_previous_structure() && respecified_passes_.empty(); }
    // Whether the graph is the cached plan's graph (not redeclared since) but for the texture
    // specs set_texture_spec changed: it is unchanged, or every change since was one of its.
    [[nodiscard]] bool is_plan_graph_respecified() const {
        return cached_plan_ && !same_as_previous_ && (cached_revision_ == revision_ || respecified_revision_ == revision_);
    }
    // Forgets the previous graph, keeping its arrays' memory for the next redeclare.
    void release_previous();

    // What redeclare() keeps of the graph the cached plan was made from (graph.cpp).
    struct PreviousGraph;
    std::unique_ptr<PreviousGraph> previous_;
    // Every pass added since redeclare() matched the previous graph's pass at its index.
    bool same_as_previous_ = false;
    // How many passes added since redeclare() differ from the previous graph's in their side effect.
    uint32_t side_effect_differences_ = 0;
    // The passes added since redeclare() that differ from the previous graph's in texture specs
    // only, or whose texture specs set_texture_spec changed since then, or since the cached plan.
    std::vector<uint32_t> respecified_passes_;
    // The revision set_texture_spec left when every change since the cached plan was one of its:
    // equal to revision_ while that holds (any other change increases revision_ past it).
    uint64_t respecified_revision_ = 0;

    // The cached plan made the plan of `options`, which differ from its options in the frame size
    // at most, for the graph declared now, which differs from its graph in the texture specs of
    // the passes `respecified` at most (plan_resize.cpp): true when made.
    bool replan_cached_plan(const PlanOptions& options, std::span<const uint32_t> respecified);

    uint64_t revision_ = 0;
    uint64_t plans_built_ = 0;
    uint64_t plans_resized_ = 0;
    // Made as a (non-const) Plan, so that replan_cached_plan may change it when nobody else holds it.
    std::shared_ptr<const Plan> cached_plan_;
    // What re-planning the cached plan for another frame size needs; null when it cannot be.
    std::unique_ptr<detail::ResizeBasis> resize_basis_;
    uint64_t cached_revision_ = 0;
    PlanOptions cached_options_;
};

}  // namespace loom::fg
