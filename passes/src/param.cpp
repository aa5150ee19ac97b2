#include "loom/passes/param.hpp"

#include <algorithm>

namespace loom::passes {
namespace {

void remove_one(std::vector<ParamNode*>& nodes, ParamNode* node) {
    auto it = std::find(nodes.begin(), nodes.end(), node);
    if (it == nodes.end()) return;
    *it = nodes.back();
    nodes.pop_back();
}

}  // namespace

ParamNode::~ParamNode() {
    for (ParamNode* source : sources_) remove_one(source->sinks_, this);
    // Sinks normally keep their sources alive; one that did not must not call a dead node.
    for (ParamNode* sink : sinks_) remove_one(sink->sources_, this);
}

void ParamNode::invalidate() {
    if (!valid_) return;
    valid_ = false;
    on_invalidated();
    invalidate_sinks();
}

void ParamNode::invalidate_sinks() {
    // A sink's on_invalidated() may add or remove nodes elsewhere; walk a copy.
    const std::vector<ParamNode*> sinks = sinks_;
    for (ParamNode* sink : sinks) sink->invalidate();
}

void ParamNode::depend_on(ParamNode& source) {
    sources_.push_back(&source);
    source.sinks_.push_back(this);
}

}  // namespace loom::passes
