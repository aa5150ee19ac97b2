#include "plan_arguments.hpp"

#include <charconv>
#include <cstdint>

namespace loom::plan {
namespace {

Error bad(std::string message) { return make_error(ErrorCode::InvalidArgument, std::move(message)); }

bool parse_number(std::string_view text, uint64_t& out) {
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
    return error == std::errc{} && end == text.data() + text.size();
}

}  // namespace

std::optional<fg::Extent2D> parse_frame(std::string_view text) {
    const auto x = text.find('x');
    if (x == std::string_view::npos) return std::nullopt;
    uint64_t width = 0;
    uint64_t height = 0;
    if (!parse_number(text.substr(0, x), width) || !parse_number(text.substr(x + 1), height)) return std::nullopt;
    if (width == 0 || height == 0 || width > fg::kMaxTextureExtent || height > fg::kMaxTextureExtent) {
        return std::nullopt;
    }
    return fg::Extent2D{static_cast<uint32_t>(width), static_cast<uint32_t>(height)};
}

Result<Arguments> parse_arguments(std::span<const std::string> argv) {
    Arguments args;
    bool allocator_given = false;
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string_view arg = argv[i];
        auto value = [&]() -> std::optional<std::string_view> {
            if (i + 1 >= argv.size()) return std::nullopt;
            return std::string_view(argv[++i]);
        };
        if (arg == "--json") {
            args.json = true;
        } else if (arg == "--compare") {
            args.compare = true;
        } else if (arg == "--allocator" || arg == "--sharing" || arg == "--frame" || arg == "--max-heap" ||
                   arg == "--order" || arg == "--dot" || arg == "--inspect") {
            auto v = value();
            if (!v) return bad(std::string(arg) + " needs a value");
            if (arg == "--allocator") {
                auto kind = fg::parse_allocator(*v);
                if (!kind) return bad("--allocator: " + kind.error().message);
                args.options.allocator = *kind;
                allocator_given = true;
            } else if (arg == "--sharing") {
                if (*v == "equal") {
                    args.options.sharing = fg::SpecSharing::Equal;
                } else if (*v == "joinable") {
                    args.options.sharing = fg::SpecSharing::Joinable;
                } else {
                    return bad("--sharing must be equal or joinable, not '" + std::string(*v) + "'");
                }
            } else if (arg == "--frame") {
                args.frame = parse_frame(*v);
                if (!args.frame) {
                    return bad("--frame must be WxH (e.g. 1920x1080) with each side in 1.." +
                               std::to_string(fg::kMaxTextureExtent) + ", not '" + std::string(*v) + "'");
                }
            } else if (arg == "--order") {
                args.order = fg::parse_pass_order(*v);
                if (!args.order) return bad("--order must be declared or memory, not '" + std::string(*v) + "'");
            } else if (arg == "--max-heap") {
                if (!parse_number(*v, args.options.max_heap_bytes)) {
                    return bad("--max-heap must be a byte count, not '" + std::string(*v) + "'");
                }
            } else if (arg == "--inspect") {
                args.inspect = std::string(*v);
            } else {
                args.dot = std::string(*v);
            }
        } else if (arg == "--help" || arg == "-h") {
            args.help = true;
        } else if (arg.starts_with("-")) {
            return bad("unknown option '" + std::string(arg) + "'");
        } else if (args.graph.empty()) {
            args.graph = std::string(arg);
        } else {
            return bad("more than one graph file given ('" + args.graph + "', '" + std::string(arg) + "')");
        }
    }
    if (args.graph.empty() && !args.help) return bad("no graph file given; " + std::string(kUsage));
    if (args.compare && allocator_given) return bad("--compare plans with every allocator; leave out --allocator");
    if (args.compare && !args.dot.empty()) return bad("--compare prints figures, not one plan: leave out --dot");
    if (args.compare && !args.inspect.empty()) return bad("--compare prints figures, not one plan: leave out --inspect");
    return args;
}

}  // namespace loom::plan
