#include "case_result.hpp"

#include <cinttypes>
#include <cstdio>

namespace loom::compare {

RunSummary summarize(const std::vector<CaseResult>& cases, double seconds) {
    RunSummary summary;
    summary.cases = static_cast<uint32_t>(cases.size());
    for (const CaseResult& c : cases) (c.passed() ? summary.passed : summary.failed) += 1;
    summary.seconds = seconds;
    return summary;
}

uint64_t plan_texture_bytes(const fg::Plan& plan) {
    uint64_t bytes = 0;
    for (const fg::PlanTexture& texture : plan.textures) bytes += texture.bytes;
    return bytes;
}

std::string plan_hash_text(const fg::Plan& plan) {
    char text[17];
    std::snprintf(text, sizeof(text), "%016" PRIx64, fg::plan_hash(plan));
    return text;
}

}  // namespace loom::compare
