#include "compare_options.hpp"

#include <charconv>
#include <cmath>

#include "loom/sample_common/options.hpp"

namespace loom::compare {
namespace {

Error bad(const std::string& message) { return make_error(ErrorCode::InvalidArgument, message); }

Result<double> parse_number(const std::string& name, const std::string& text, double low, double high) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value) ||
        value < low || value > high) {
        return bad(name + " expects a number from " + std::to_string(low) + " to " + std::to_string(high) +
                   ", got '" + text + "'");
    }
    return value;
}

}  // namespace

std::string_view pipeline_name(PipelineKind pipeline) {
    return pipeline == PipelineKind::Deferred ? "deferred" : "forward";
}

Result<Options> parse_options(std::span<const std::string> args) {
    Options options;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string name = args[i], value;
        const bool inline_value = name.rfind("--", 0) == 0 && name.find('=') != std::string::npos;
        if (inline_value) {
            value = name.substr(name.find('=') + 1);
            name = name.substr(0, name.find('='));
        }
        auto take = [&]() -> Result<std::string> {
            if (inline_value) return value;
            if (i + 1 >= args.size()) return bad(name + " needs a value");
            return args[++i];
        };
        if (name == "--help" || name == "-h") {
            options.help = true;
        } else if (name == "--json") {
            options.json = true;
        } else if (name == "--expect-errors") {
            options.expect_errors = true;
        } else if (name == "--no-inspect") {
            options.inspector_pages = false;
        } else if (name == "--pipeline") {
            auto v = take();
            if (!v) return v.take_error();
            if (*v == "deferred") {
                options.pipelines = {PipelineKind::Deferred};
            } else if (*v == "forward") {
                options.pipelines = {PipelineKind::Forward};
            } else if (*v == "all") {
                options.pipelines = {PipelineKind::Deferred, PipelineKind::Forward};
            } else {
                return bad("--pipeline expects deferred, forward or all, got '" + *v + "'");
            }
        } else if (name == "--scenes") {
            // Every following argument up to the next option.
            if (inline_value) {
                if (value.empty()) return bad("--scenes needs a file or directory");
                options.scenes.emplace_back(value);
            }
            while (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) options.scenes.emplace_back(args[++i]);
            if (options.scenes.empty()) return bad("--scenes needs at least one file or directory");
        } else if (name == "--size") {
            auto v = take();
            if (!v) return v.take_error();
            auto size = samples::parse_size(*v);
            if (!size) return size.take_error();
            options.width = size->first;
            options.height = size->second;
        } else if (name == "--out") {
            auto v = take();
            if (!v) return v.take_error();
            if (v->empty()) return bad("--out needs a directory");
            options.out = *v;
        } else if (name == "--threshold") {
            auto v = take();
            if (!v) return v.take_error();
            auto number = parse_number(name, *v, 0.0, 255.0);
            if (!number) return number.take_error();
            options.threshold = *number;
        } else if (name == "--max-differing") {
            auto v = take();
            if (!v) return v.take_error();
            auto number = parse_number(name, *v, 0.0, 1.0);
            if (!number) return number.take_error();
            options.max_differing = *number;
        } else {
            return bad("unknown argument '" + args[i] + "'");
        }
    }
    return options;
}

std::string usage() {
    return "usage: loom-compare [--pipeline deferred|forward|all] [--scenes DIR_OR_FILE...] [--size WxH]\n"
           "                    [--out DIR] [--threshold N] [--max-differing F] [--json] [--expect-errors]\n"
           "                    [--no-inspect]\n"
           "Renders every glTF scene through each pipeline on every compiled-in backend (headless), and\n"
           "compares the backends: the plans (hash, textures, bytes, and what each backend created) and\n"
           "the final pictures (largest channel difference, pixels above the threshold, PSNR). Writes\n"
           "DIR/report.html (with each case's pictures, difference heat map and inspector pages beside\n"
           "it) and DIR/report.json; exits 1 when any case fails, 2 on a usage error.\n\n"
           "  --pipeline NAME     deferred, forward or all (default all)\n"
           "  --scenes PATH...    .gltf/.glb files and directories searched recursively (directories named\n"
           "                      'invalid' are skipped unless given themselves); default: the test data\n"
           "                      directory's gltf/ folder\n"
           "  --size WxH          picture size (default 480x270)\n"
           "  --out DIR           where the report goes (default out/compare)\n"
           "  --threshold N       a pixel differs when a channel differs by more than N levels (default 1)\n"
           "  --max-differing F   fraction of a picture's pixels that may differ (default 0)\n"
           "  --json              print the results as one JSON object on stdout\n"
           "  --expect-errors     every scene must fail to load with a one-line error naming the file\n"
           "                      (the check for invalid files); nothing is rendered\n"
           "  --no-inspect        write no inspector page (the plan, barriers, timings and memory of each\n"
           "                      case's frame on each backend, as loom-inspect shows them)\n"
           "  --help              this text\n";
}

}  // namespace loom::compare
