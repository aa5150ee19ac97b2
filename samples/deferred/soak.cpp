#include "soak.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <unistd.h>

#include "loom/framegraph/export.hpp"

namespace loom::deferred {
namespace {

fg::Extent2D three_quarters(fg::Extent2D size) {
    return {std::max<uint32_t>(1, size.width / 4 * 3), std::max<uint32_t>(1, size.height / 4 * 3)};
}

std::string describe_live(const rhi::ResourceStats& s) {
    return std::to_string(s.textures) + " textures, " + std::to_string(s.buffers) + " buffers, " +
           std::to_string(s.heaps) + " heaps, " + std::to_string(s.samplers) + " samplers, " +
           std::to_string(s.shaders) + " shaders, " + std::to_string(s.pipelines) + " pipelines, " +
           std::to_string(s.total_bytes()) + " bytes";
}

}  // namespace

uint64_t soak_period(const SoakSettings& settings) {
    const uint64_t resize = 2 * uint64_t{std::max<uint32_t>(settings.resize_every, 1)};
    const uint64_t rebuild = 2 * uint64_t{std::max<uint32_t>(settings.rebuild_every, 1)};
    return std::lcm(resize, rebuild);
}

Result<std::vector<SoakSample>> run_soak(rhi::Device& device, renderer::DeferredPipeline& pipeline, const SoakSettings& settings,
                                         const std::function<void(const SoakSample&)>& on_frame) {
    if (settings.size.width == 0 || settings.size.height == 0) {
        return make_error(ErrorCode::InvalidArgument, "soak: empty frame size");
    }
    const fg::Extent2D sizes[2] = {settings.size, settings.alternate_size.value_or(three_quarters(settings.size))};
    if (sizes[1].width == 0 || sizes[1].height == 0) {
        return make_error(ErrorCode::InvalidArgument, "soak: empty alternate frame size");
    }
    const bool first_forward = pipeline.settings().forward;
    std::vector<SoakSample> samples;
    samples.reserve(static_cast<std::size_t>(std::min<uint64_t>(settings.frames, uint64_t{1} << 20)));
    for (uint64_t frame = 0; frame < settings.frames; ++frame) {
        const auto start = std::chrono::steady_clock::now();
        SoakSample sample;
        sample.frame = frame;
        const uint64_t size_index = settings.resize_every == 0 ? 0 : (frame / settings.resize_every) % 2;
        sample.size = sizes[size_index];
        const bool toggled = settings.rebuild_every != 0 && (frame / settings.rebuild_every) % 2 == 1;
        sample.forward = first_forward != toggled;
        // A rebuild at every multiple of rebuild_every, whether or not the lit pass changes
        // (frame 0 keeps the graph the pipeline was created with).
        if (frame != 0 && settings.rebuild_every != 0 && frame % settings.rebuild_every == 0) {
            renderer::PipelineSettings next = pipeline.settings();
            next.forward = sample.forward;
            if (Status rebuilt = pipeline.rebuild(next); !rebuilt) {
                return make_error(rebuilt.error().code,
                                  "soak frame " + std::to_string(frame) + ": rebuild: " + rebuilt.error().message);
            }
        }
        if (Status rendered = pipeline.render(sample.size); !rendered) {
            return make_error(rendered.error().code,
                              "soak frame " + std::to_string(frame) + ": " + rendered.error().message);
        }
        // Idle before counting, so that objects whose destruction waits for the GPU are gone.
        LOOM_TRY(device.wait_idle());
        sample.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        sample.live = device.resource_stats();
        sample.resident_bytes = resident_bytes();
        if (on_frame) on_frame(sample);
        samples.push_back(sample);
    }
    return samples;
}

std::string SoakVerdict::describe() const {
    std::string line = steady ? "steady" : "NOT steady";
    line += ": " + std::to_string(compared) + " frames compared with the same frame one period (" +
            std::to_string(period) + " frames) earlier, after " + std::to_string(warm_up_frames) + " warm-up frames";
    if (!first_difference.empty()) line += "; " + first_difference;
    if (resident_after_warm_up != 0) {
        line += "; resident memory " + fg::format_bytes(resident_after_warm_up) + " after the warm-up, " +
                fg::format_bytes(resident_at_end) + " at the end, peak " + fg::format_bytes(resident_peak);
    }
    return line;
}

SoakVerdict check_soak(const std::vector<SoakSample>& samples, uint64_t period) {
    SoakVerdict verdict;
    verdict.period = period;
    verdict.warm_up_frames = period;
    if (period == 0 || samples.size() <= 2 * period) {
        verdict.first_difference = "too short: " + std::to_string(samples.size()) + " frames, the check needs more than " +
                                   std::to_string(2 * period) + " (two periods)";
        return verdict;
    }
    verdict.resident_after_warm_up = samples[period - 1].resident_bytes;
    verdict.resident_at_end = samples.back().resident_bytes;
    for (std::size_t i = period; i < samples.size(); ++i) {
        verdict.resident_peak = std::max(verdict.resident_peak, samples[i].resident_bytes);
    }
    for (std::size_t i = 2 * period; i < samples.size(); ++i) {
        const SoakSample& now = samples[i];
        const SoakSample& before = samples[i - period];
        ++verdict.compared;
        if (verdict.first_difference.empty() && now.live != before.live) {
            verdict.first_difference = "frame " + std::to_string(now.frame) + " has " + describe_live(now.live) +
                                       ", frame " + std::to_string(before.frame) + " had " + describe_live(before.live);
        }
    }
    verdict.steady = verdict.first_difference.empty();
    return verdict;
}

std::string soak_csv_header() {
    return "frame,width,height,lit,textures,buffers,heaps,samplers,shaders,pipelines,texture_bytes,buffer_bytes,"
           "heap_bytes,resident_bytes,frame_ms\n";
}

std::string soak_csv_row(const SoakSample& s) {
    char line[384];
    std::snprintf(line, sizeof(line), "%llu,%u,%u,%s,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%llu,%.3f\n",
                  static_cast<unsigned long long>(s.frame), s.size.width, s.size.height,
                  s.forward ? "forward" : "deferred", static_cast<unsigned long long>(s.live.textures),
                  static_cast<unsigned long long>(s.live.buffers), static_cast<unsigned long long>(s.live.heaps),
                  static_cast<unsigned long long>(s.live.samplers), static_cast<unsigned long long>(s.live.shaders),
                  static_cast<unsigned long long>(s.live.pipelines), static_cast<unsigned long long>(s.live.texture_bytes),
                  static_cast<unsigned long long>(s.live.buffer_bytes), static_cast<unsigned long long>(s.live.heap_bytes),
                  static_cast<unsigned long long>(s.resident_bytes), s.frame_ms);
    return line;
}

uint64_t resident_bytes() {
    // statm: size resident shared text lib data dt, in pages.
    std::ifstream statm("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    if (!(statm >> size >> resident)) return 0;
    const long page = sysconf(_SC_PAGESIZE);
    return page > 0 ? resident * static_cast<uint64_t>(page) : 0;
}

}  // namespace loom::deferred
