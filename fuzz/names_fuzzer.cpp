// Fuzz harness: names given to the frame graph through its C++ API (pass, port set and port
// names, and the pass.port references of connect and mark_output) -> FrameGraph -> build_plan -> the
// plan's exports. Any input must give a plan or an error, errors must be one line (they name
// the user's names, which may hold newlines), and a graph must hold only names that
// name_problem() accepts: no crash, hang, leak or undefined behaviour (docs/fuzzing.md).
//
// Input: words separated by NUL bytes; a word's first byte says what it does, the rest is a
// name (or references):
//   P<name>  starts a pass (the one before is added to the graph)
//   p<name>  starts a port set of the current pass (added to the pass when the next port set
//            or pass starts); ports declared before any port set are the pass's own
//   i/o/x/q/u<name>  declares an input / output / inout / optional input / optional output
//   s        makes the current pass a side-effect pass
//   c<from>><to>     connects two references, each split at its last '.' into pass and port
//   g<ref>   marks a graph output
// Other words are ignored.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>

#include "loom/framegraph/framegraph.hpp"

namespace {

using loom::fg::FrameGraph;
using loom::fg::Pass;
using loom::fg::PortKind;
using loom::fg::PortRef;
using loom::fg::PortSet;

void require_one_line(const loom::Error& error, const char* step) {
    if (error.message.find('\n') != std::string::npos || error.message.find('\r') != std::string::npos) {
        std::fprintf(stderr, "names fuzzer: the error of %s is not one line: %s\n", step, error.message.c_str());
        std::abort();
    }
}

// Unlike parse_port_ref, keeps empty sides and words without a '.', so that connect and
// mark_output meet every kind of name.
PortRef reference(std::string_view text) {
    const std::size_t dot = text.rfind('.');
    if (dot == std::string_view::npos) return PortRef{std::string(text), std::string()};
    return PortRef{std::string(text.substr(0, dot)), std::string(text.substr(dot + 1))};
}

// Every name of an accepted pass passes name_problem(); otherwise a bad name got in.
void require_valid_names(const Pass& pass) {
    bool valid = !loom::fg::name_problem(pass.name());
    for (const loom::fg::Port& port : pass.ports()) {
        valid = valid && !loom::fg::name_problem(port.name);
        for (std::string_view set : port.port_sets) valid = valid && (set == pass.name() || !loom::fg::name_problem(set));
    }
    if (!valid) {
        std::fprintf(stderr, "names fuzzer: add_pass accepted a pass with a name name_problem() refuses\n");
        std::abort();
    }
}

class Builder {
public:
    void word(std::string_view word) {
        if (word.empty()) return;
        const char op = word.front();
        const std::string_view name = word.substr(1);
        switch (op) {
            case 'P':
                finish_pass();
                pass_.emplace(std::string(name));
                break;
            case 'p':
                finish_port_set();
                if (pass_) port_set_.emplace(std::string(name));
                break;
            case 'i': declare(name, PortKind::Input, false); break;
            case 'o': declare(name, PortKind::Output, false); break;
            case 'x': declare(name, PortKind::InOut, false); break;
            case 'q': declare(name, PortKind::Input, true); break;
            case 'u': declare(name, PortKind::Output, true); break;
            case 's':
                if (pass_) pass_->set_side_effect();
                break;
            case 'c': {
                finish_pass();
                const std::size_t arrow = name.find('>');
                if (arrow == std::string_view::npos) break;
                auto status = graph_.connect(reference(name.substr(0, arrow)), reference(name.substr(arrow + 1)));
                if (!status) require_one_line(status.error(), "connect");
                break;
            }
            case 'g': {
                finish_pass();
                auto status = graph_.mark_output(reference(name));
                if (!status) require_one_line(status.error(), "mark_output");
                break;
            }
            default: break;
        }
    }

    FrameGraph& finish() {
        finish_pass();
        return graph_;
    }

private:
    void declare(std::string_view name, PortKind kind, bool optional) {
        if (port_set_) {
            port_set_->declare(std::string(name), kind, {}, optional);
        } else if (pass_) {
            pass_->declare(std::string(name), kind, {}, optional);
        }
    }

    void finish_port_set() {
        if (port_set_ && pass_) pass_->add(*port_set_);
        port_set_.reset();
    }

    void finish_pass() {
        finish_port_set();
        if (!pass_) return;
        if (auto status = pass_->status(); !status) require_one_line(status.error(), "a pass's declarations");
        auto added = graph_.add_pass(std::move(*pass_));
        pass_.reset();
        if (!added) {
            require_one_line(added.error(), "add_pass");
            return;
        }
        require_valid_names(graph_.pass(*added));
    }

    FrameGraph graph_;
    std::optional<Pass> pass_;
    std::optional<PortSet> port_set_;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    Builder builder;
    std::size_t start = 0;
    while (start <= input.size()) {
        const std::size_t end = input.find('\0', start);
        builder.word(input.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    FrameGraph& graph = builder.finish();

    loom::fg::PlanOptions options;
    options.frame = {64, 64};
    auto plan = loom::fg::build_plan(graph, options);
    if (!plan) {
        require_one_line(plan.error(), "build_plan");
        return 0;
    }
    (void)loom::fg::plan_to_json(*plan);
    (void)loom::fg::plan_to_table(*plan);
    (void)loom::fg::plan_to_dot(*plan);
    return 0;
}
