#include "loom/sample_common/options.hpp"

#include <charconv>

namespace loom::samples {
namespace {

Error bad(const std::string& message) { return Error{ErrorCode::InvalidArgument, message}; }

bool parse_positive(std::string_view text, uint32_t& out) {
    if (text.empty()) return false;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    return ec == std::errc{} && end == text.data() + text.size() && out > 0;
}

}  // namespace

Result<std::pair<uint32_t, uint32_t>> parse_size(const std::string& text) {
    const auto x = text.find('x');
    uint32_t w = 0, h = 0;
    if (x == std::string::npos || !parse_positive(std::string_view(text).substr(0, x), w) ||
        !parse_positive(std::string_view(text).substr(x + 1), h)) {
        return bad("--size expects WIDTHxHEIGHT with positive integers (e.g. 640x480), got '" + text + "'");
    }
    return std::pair{w, h};
}

Result<CommonOptions> parse_common_options(std::span<const std::string> args, const CommonDefaults& defaults) {
    CommonOptions options;
    options.width = defaults.width;
    options.height = defaults.height;
    options.out = defaults.out;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        // Accept both "--name value" and "--name=value".
        std::string name = arg, value;
        bool inline_value = false;
        if (arg.rfind("--", 0) == 0) {
            const auto eq = arg.find('=');
            if (eq != std::string::npos) {
                name = arg.substr(0, eq);
                value = arg.substr(eq + 1);
                inline_value = true;
            }
        }
        auto take_value = [&]() -> Result<std::string> {
            if (inline_value) return value;
            if (i + 1 >= args.size()) return bad(name + " needs a value");
            return args[++i];
        };
        if (name == "--help" || name == "-h") {
            options.help = true;
        } else if (name == "--window") {
            options.window = true;
        } else if (name == "--backend") {
            auto v = take_value();
            if (!v.ok()) return v.take_error();
            auto backend = rhi::parse_backend(*v);
            if (!backend) return bad("--backend expects gl or vulkan, got '" + *v + "'");
            options.backend = *backend;
        } else if (name == "--size") {
            auto v = take_value();
            if (!v.ok()) return v.take_error();
            auto size = parse_size(*v);
            if (!size.ok()) return size.take_error();
            options.width = size->first;
            options.height = size->second;
        } else if (name == "--out") {
            auto v = take_value();
            if (!v.ok()) return v.take_error();
            if (v->empty()) return bad("--out needs a file name");
            options.out = *v;
        } else {
            options.rest.push_back(arg);
        }
    }
    return options;
}

Result<CommonOptions> parse_common_options(int argc, char** argv, const CommonDefaults& defaults) {
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    return parse_common_options(args, defaults);
}

std::string common_options_help(const CommonDefaults& defaults) {
    return "  --backend gl|vulkan  graphics API (default gl)\n"
           "  --size WxH           image size in pixels (default " +
           std::to_string(defaults.width) + "x" + std::to_string(defaults.height) +
           ")\n"
           "  --out PATH           PNG to write (default " +
           defaults.out.string() +
           ")\n"
           "  --window             show the result in a window instead of writing a PNG\n"
           "  --help               this text\n";
}

rhi::DeviceDesc device_desc(const CommonOptions& options, const std::string& title) {
    rhi::DeviceDesc desc;
    desc.backend = options.backend;
    desc.headless = !options.window;
    desc.debug = true;
    desc.window.title = title;
    desc.window.width = options.width;
    desc.window.height = options.height;
    return desc;
}

bool ArgumentReader::next() {
    if (started_) ++index_;
    started_ = true;
    if (index_ >= args_.size()) return false;
    name_ = args_[index_];
    inline_value_.reset();
    if (name_.rfind("--", 0) == 0) {
        if (const auto equals = name_.find('='); equals != std::string::npos) {
            inline_value_ = name_.substr(equals + 1);
            name_ = name_.substr(0, equals);
        }
    }
    return true;
}

Result<std::string> ArgumentReader::value() {
    if (inline_value_) return *inline_value_;
    if (index_ + 1 >= args_.size()) return make_error(ErrorCode::InvalidArgument, name_ + " needs a value");
    return args_[++index_];
}

Error ArgumentReader::unknown() const {
    return Error{ErrorCode::InvalidArgument, "unknown argument '" + args_[index_] + "'"};
}

}  // namespace loom::samples
