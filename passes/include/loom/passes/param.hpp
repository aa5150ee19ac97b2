#pragma once
// Lazy parameter nodes (the LPSG manual's "incremental nodes"): values such as a model matrix
// computed from inputs (a parent transform, the animation time). Nodes form a dependency graph:
// setting an input marks every node that depends on it invalid, at once and transitively; a
// node recomputes its value only when it is read and only if it is invalid. Sinks at the end of
// a chain (uniform sets, uniform_set.hpp) hear of the invalidation through on_invalidated() and
// schedule their upload, which reads the values and so recomputes only what changed.
//
//   auto time = std::make_shared<InputParam<float>>(0.0f);
//   auto parent = std::make_shared<InputParam<glm::mat4>>(glm::mat4(1.0f));
//   auto model = compute<glm::mat4>([](const glm::mat4& p, const float& t) { return p * spin(t); },
//                                   parent, time);
//   time->set(0.5f);        // model is invalid now; nothing is computed yet
//   model->value();         // computed once here, cached until time or parent change
//
// Nodes are used from one thread. A dependant keeps its inputs alive (shared_ptr); inputs know
// their dependants by pointer, and a node that dies leaves the graph cleanly.

#include <cstdint>
#include <functional>
#include <memory>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace loom::passes {

/// A node of the dependency graph: validity, its sources (what it reads) and its sinks (what
/// reads it).
class ParamNode {
public:
    ParamNode() = default;
    /// Leaves the graph: forgets its sources and tells its sinks it is gone.
    virtual ~ParamNode();
    ParamNode(const ParamNode&) = delete;
    ParamNode& operator=(const ParamNode&) = delete;

    /// False after an input changed and until the value is read (recomputed) again.
    [[nodiscard]] bool valid() const { return valid_; }
    /// Marks the node invalid and, if it was valid, every node that depends on it (a node that
    /// is already invalid has told its dependants before).
    void invalidate();
    /// Nodes that read this one.
    [[nodiscard]] std::size_t sink_count() const { return sinks_.size(); }

protected:
    /// Registers this node as a dependant of `source`.
    void depend_on(ParamNode& source);
    void mark_valid() { valid_ = true; }
    /// Invalidates every dependant, whatever this node's own state (an input's new value).
    void invalidate_sinks();
    /// Called when the node turns invalid (after being valid): sinks schedule work here.
    virtual void on_invalidated() {}

private:
    std::vector<ParamNode*> sources_;
    std::vector<ParamNode*> sinks_;
    bool valid_ = false;
};

/// A node with a value of type T.
template <class T>
class Param : public ParamNode {
public:
    /// The current value, recomputed first if the node is invalid.
    virtual const T& value() = 0;
};

/// A value set from outside (the roots of the graph: a transform, the time, a material's
/// factors). Setting it invalidates its dependants; reading it never computes anything.
template <class T>
class InputParam final : public Param<T> {
public:
    explicit InputParam(T value = T{}) : value_(std::move(value)) {}

    const T& value() override {
        this->mark_valid();
        return value_;
    }
    /// Replaces the value and invalidates every node that depends on it.
    void set(T value) {
        value_ = std::move(value);
        ++changes_;
        this->invalidate_sinks();
    }
    /// set() calls so far.
    [[nodiscard]] uint64_t changes() const { return changes_; }

private:
    T value_;
    uint64_t changes_ = 0;
};

/// A value computed from other nodes by a function, cached until one of them changes.
template <class T, class... In>
class ComputedParam final : public Param<T> {
public:
    using Function = std::function<T(const In&...)>;

    explicit ComputedParam(Function function, std::shared_ptr<Param<In>>... inputs)
        : function_(std::move(function)), inputs_(std::move(inputs)...) {
        std::apply([this](auto&... input) { (this->depend_on(*input), ...); }, inputs_);
    }

    const T& value() override {
        if (!this->valid()) {
            value_ = std::apply([this](auto&... input) { return function_(input->value()...); }, inputs_);
            ++computations_;
            this->mark_valid();
        }
        return value_;
    }
    /// How many times the function ran (tests use it to check laziness).
    [[nodiscard]] uint64_t computations() const { return computations_; }

private:
    Function function_;
    std::tuple<std::shared_ptr<Param<In>>...> inputs_;
    T value_{};
    uint64_t computations_ = 0;
};

/// The value type of a parameter node type (InputParam<float> -> float).
template <class Node>
using param_value_t = std::remove_cvref_t<decltype(std::declval<Node&>().value())>;

/// A ComputedParam<T, ...> of `function` over `inputs` (shared pointers to any Param nodes):
/// compute<glm::mat4>([](const glm::mat4& parent, const float& t) { ... }, parent, time).
template <class T, class F, class... Nodes>
auto compute(F function, std::shared_ptr<Nodes>... inputs) {
    using Node = ComputedParam<T, param_value_t<Nodes>...>;
    return std::make_shared<Node>(typename Node::Function(std::move(function)),
                                  std::shared_ptr<Param<param_value_t<Nodes>>>(std::move(inputs))...);
}

}  // namespace loom::passes
