// Printable forms of the executor's figures and timings, for samples and tools.
#include <algorithm>
#include <cstdio>

#include "loom/framegraph/executor.hpp"

namespace loom::fg {

std::string describe_stats(const ExecutionStats& stats) {
    auto plural = [](uint64_t n, const char* word) { return std::to_string(n) + " " + word + (n == 1 ? "" : "s"); };
    // Buffers are named only where there are some, so texture-only reports read as before.
    const bool buffers = stats.plan_buffers != 0 || stats.buffers != 0;
    std::string out = "plan: " + plural(stats.plan_textures, "texture") + ", " +
                      (buffers ? plural(stats.plan_buffers, "buffer") + ", " : std::string()) +
                      plural(stats.plan_heaps, "heap") + " (" + std::to_string(stats.plan_heap_bytes) + " bytes), " +
                      std::to_string(stats.plan_bytes) + " bytes\n";
    out += "created: " + plural(stats.textures, "texture") + " (" + std::to_string(stats.placed_textures) + " placed), " +
           (buffers ? plural(stats.buffers, "buffer") + " (" + std::to_string(stats.placed_buffers) + " placed), " : std::string()) +
           plural(stats.history_textures, "history texture") + ", " + plural(stats.heaps, "heap") + " (" +
           std::to_string(stats.heap_bytes) + " bytes); device now: " + plural(stats.device.textures, "texture") + ", " +
           plural(stats.device.heaps, "heap") + ", " + std::to_string(stats.device.texture_bytes) + " texture bytes, " +
           std::to_string(stats.device.heap_bytes) + " heap bytes";
    return out;
}

std::string describe_timings(const std::vector<PassTiming>& timings) {
    std::size_t width = 5;
    for (const PassTiming& t : timings) width = std::max(width, t.pass.size());
    auto row = [&](const std::string& name, const std::string& cpu, const std::string& gpu) {
        std::string line = name + std::string(width - name.size() + 2, ' ');
        line += std::string(cpu.size() < 8 ? 8 - cpu.size() : 0, ' ') + cpu + "  ";
        line += std::string(gpu.size() < 8 ? 8 - gpu.size() : 0, ' ') + gpu + "\n";
        return line;
    };
    auto ms = [](double value) {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.3f", value);
        return std::string(buffer);
    };
    std::string out = row("pass", "cpu ms", "gpu ms");
    double cpu_total = 0.0;
    double gpu_total = 0.0;
    bool all_gpu = !timings.empty();
    for (const PassTiming& t : timings) {
        out += row(t.pass, ms(t.cpu_ms), t.gpu_ms ? ms(*t.gpu_ms) : "-");
        cpu_total += t.cpu_ms;
        if (t.gpu_ms) gpu_total += *t.gpu_ms;
        all_gpu = all_gpu && t.gpu_ms.has_value();
    }
    out += row("total", ms(cpu_total), all_gpu ? ms(gpu_total) : "-");
    return out;
}

}  // namespace loom::fg
