// Fuzz harness: the command lines of loom-plan (plan_arguments.hpp), loom-compare
// (compare_options.hpp) and the options every sample shares (sample_common/options.hpp). One
// input is one argv without the program name, its words separated by NUL bytes (as the kernel
// hands them over, so no word can hold a NUL). Any input must give options or an
// InvalidArgument error, and parsed options must keep the limits the parsers promise: no
// crash, hang, leak or undefined behaviour (docs/fuzzing.md).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "compare_options.hpp"
#include "loom/sample_common/options.hpp"
#include "plan_arguments.hpp"

namespace {

// A broken promise counts as a finding like a crash.
void require(bool condition, const char* what) {
    if (!condition) {
        std::fprintf(stderr, "command_line fuzzer: %s\n", what);
        std::abort();
    }
}

void require_usage_error(const loom::Error& error, const char* tool) {
    if (error.code != loom::ErrorCode::InvalidArgument || error.message.empty()) {
        std::fprintf(stderr, "command_line fuzzer: %s: not an InvalidArgument error with a message: %s\n", tool,
                     error.to_string().c_str());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> words;
    if (!input.empty()) {
        std::size_t start = 0;
        while (true) {
            const std::size_t end = input.find('\0', start);
            words.emplace_back(input.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
            if (end == std::string_view::npos) break;
            start = end + 1;
        }
    }

    if (auto plan = loom::plan::parse_arguments(words)) {
        require(!plan->graph.empty() || plan->help, "loom-plan: parsed without a graph file or --help");
        if (plan->frame) {
            require(plan->frame->width >= 1 && plan->frame->width <= loom::fg::kMaxTextureExtent &&
                        plan->frame->height >= 1 && plan->frame->height <= loom::fg::kMaxTextureExtent,
                    "loom-plan: --frame outside 1..kMaxTextureExtent");
        }
    } else {
        require_usage_error(plan.error(), "loom-plan");
    }

    if (auto compare = loom::compare::parse_options(words)) {
        require(!compare->pipelines.empty(), "loom-compare: no pipeline");
        require(compare->width > 0 && compare->height > 0, "loom-compare: an empty --size");
        require(std::isfinite(compare->threshold) && compare->threshold >= 0.0 && compare->threshold <= 255.0,
                "loom-compare: --threshold outside 0..255");
        require(std::isfinite(compare->max_differing) && compare->max_differing >= 0.0 && compare->max_differing <= 1.0,
                "loom-compare: --max-differing outside 0..1");
        require(!compare->out.empty(), "loom-compare: an empty --out");
    } else {
        require_usage_error(compare.error(), "loom-compare");
    }

    if (auto common = loom::samples::parse_common_options(words)) {
        require(common->width > 0 && common->height > 0, "samples: an empty --size");
        require(common->rest.size() <= words.size(), "samples: more arguments passed on than given");
    } else {
        require_usage_error(common.error(), "samples");
    }
    return 0;
}
