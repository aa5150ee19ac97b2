#include "soak_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

#include "loom/sample_common/html.hpp"

namespace loom::deferred {
namespace {

constexpr double kWidth = 900, kChartHeight = 220, kLeft = 70, kRight = 170, kTop = 40, kGap = 60;
constexpr double kPlotWidth = kWidth - kLeft - kRight;

struct Series {
    const char* name;
    const char* colour;
    std::function<double(const SoakSample&)> value;
};

std::string number(double v) {
    char text[32];
    std::snprintf(text, sizeof(text), "%.1f", v);
    return text;
}

std::string label(double v) {
    char text[32];
    if (std::fabs(v - std::round(v)) < 1e-9) {
        std::snprintf(text, sizeof(text), "%.0f", v);
    } else {
        std::snprintf(text, sizeof(text), "%.1f", v);
    }
    return text;
}

/// A "nice" upper bound for an axis (1, 2 or 5 times a power of ten, at least `max`).
double axis_top(double max) {
    if (max <= 0) return 1;
    const double power = std::pow(10.0, std::floor(std::log10(max)));
    for (double step : {1.0, 2.0, 5.0, 10.0}) {
        if (step * power >= max) return step * power;
    }
    return 10 * power;
}

void chart(std::ostringstream& svg, const std::vector<SoakSample>& samples, double top, const std::string& heading,
           const std::string& unit, const std::vector<Series>& series, uint64_t warm_up_frames) {
    const double frames = static_cast<double>(std::max<std::size_t>(samples.size(), 2) - 1);
    double max = 0;
    for (const Series& s : series) {
        for (const SoakSample& sample : samples) max = std::max(max, s.value(sample));
    }
    const double y_top = axis_top(max * 1.1);
    auto x_of = [&](double frame) { return kLeft + kPlotWidth * frame / frames; };
    auto y_of = [&](double v) { return top + kChartHeight * (1.0 - v / y_top); };

    svg << "<text x=\"" << kLeft << "\" y=\"" << number(top - 10) << "\" font-weight=\"bold\">" << samples::escape_html(heading)
        << "</text>\n";
    if (warm_up_frames > 0) {
        const double w = std::min(static_cast<double>(warm_up_frames), frames);
        svg << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << number(x_of(w) - kLeft) << "\" height=\""
            << kChartHeight << "\" fill=\"#eeeeee\"/>\n";
        svg << "<text x=\"" << number(kLeft + 4) << "\" y=\"" << number(top + 14) << "\" fill=\"#777\" font-size=\"11\">"
            << "warm-up</text>\n";
    }
    for (int i = 0; i <= 4; ++i) {
        const double v = y_top * i / 4;
        const double y = y_of(v);
        svg << "<line x1=\"" << kLeft << "\" x2=\"" << kLeft + kPlotWidth << "\" y1=\"" << number(y) << "\" y2=\""
            << number(y) << "\" stroke=\"#dddddd\"/>\n";
        svg << "<text x=\"" << kLeft - 6 << "\" y=\"" << number(y + 4) << "\" text-anchor=\"end\" font-size=\"11\">"
            << label(v) << "</text>\n";
    }
    svg << "<text x=\"14\" y=\"" << number(top + kChartHeight / 2) << "\" font-size=\"11\" transform=\"rotate(-90 14 "
        << number(top + kChartHeight / 2) << ")\" text-anchor=\"middle\">" << samples::escape_html(unit) << "</text>\n";
    // Frame numbers at round steps (0, 2000, 4000...), not at fifths of the run (1999, 3999...).
    const double step = std::max(1.0, axis_top(frames / 5));
    for (double frame = 0; frame <= frames; frame += step) {
        svg << "<text x=\"" << number(x_of(frame)) << "\" y=\"" << number(top + kChartHeight + 16)
            << "\" text-anchor=\"middle\" font-size=\"11\">" << label(frame) << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << top << "\" width=\"" << kPlotWidth << "\" height=\"" << kChartHeight
        << "\" fill=\"none\" stroke=\"#444444\"/>\n";

    // One point per sample for short runs; otherwise each pixel column's min and max.
    const std::size_t columns = static_cast<std::size_t>(kPlotWidth);
    for (std::size_t k = 0; k < series.size(); ++k) {
        const Series& s = series[k];
        svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.5\" points=\"";
        if (samples.size() <= 2 * columns) {
            for (const SoakSample& sample : samples) {
                svg << number(x_of(static_cast<double>(sample.frame))) << "," << number(y_of(s.value(sample))) << " ";
            }
        } else {
            for (std::size_t c = 0; c < columns; ++c) {
                const std::size_t begin = samples.size() * c / columns, end = samples.size() * (c + 1) / columns;
                double lo = s.value(samples[begin]), hi = lo;
                for (std::size_t i = begin; i < end; ++i) {
                    lo = std::min(lo, s.value(samples[i]));
                    hi = std::max(hi, s.value(samples[i]));
                }
                const double x = x_of(static_cast<double>(samples[begin].frame));
                svg << number(x) << "," << number(y_of(lo)) << " " << number(x) << "," << number(y_of(hi)) << " ";
            }
        }
        svg << "\"/>\n";
        const double ly = top + 16 + 18.0 * static_cast<double>(k);
        svg << "<line x1=\"" << kLeft + kPlotWidth + 12 << "\" x2=\"" << kLeft + kPlotWidth + 32 << "\" y1=\""
            << number(ly - 4) << "\" y2=\"" << number(ly - 4) << "\" stroke=\"" << s.colour << "\" stroke-width=\"2\"/>\n";
        svg << "<text x=\"" << kLeft + kPlotWidth + 38 << "\" y=\"" << number(ly) << "\" font-size=\"12\">" << s.name
            << "</text>\n";
    }
}

}  // namespace

std::string soak_svg(const std::vector<SoakSample>& samples, const std::string& title, uint64_t warm_up_frames) {
    std::ostringstream svg;
    const double height = kTop + 2 * kChartHeight + kGap + 40;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"13\">\n";
    svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"" << kLeft << "\" y=\"18\" font-size=\"15\">" << samples::escape_html(title) << "</text>\n";
    if (samples.empty()) {
        svg << "<text x=\"" << kLeft << "\" y=\"60\">no frames</text>\n</svg>\n";
        return svg.str();
    }
    const double mib = 1024.0 * 1024.0;
    chart(svg, samples, kTop + 20, "Live GPU objects after each frame", "objects",
          {{"textures", "#1f77b4", [](const SoakSample& s) { return static_cast<double>(s.live.textures); }},
           {"buffers", "#ff7f0e", [](const SoakSample& s) { return static_cast<double>(s.live.buffers); }},
           {"pipelines", "#2ca02c", [](const SoakSample& s) { return static_cast<double>(s.live.pipelines); }},
           {"samplers", "#9467bd", [](const SoakSample& s) { return static_cast<double>(s.live.samplers); }}},
          warm_up_frames);
    chart(svg, samples, kTop + 20 + kChartHeight + kGap, "Memory after each frame (frame number below)", "MiB",
          {{"GPU objects", "#d62728",
            [mib](const SoakSample& s) { return static_cast<double>(s.live.total_bytes()) / mib; }},
           {"resident (RSS)", "#17becf",
            [mib](const SoakSample& s) { return static_cast<double>(s.resident_bytes) / mib; }}},
          warm_up_frames);
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace loom::deferred
