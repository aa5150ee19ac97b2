#pragma once
// The command line every sample shares: --backend gl|vulkan, --size WxH, --out PATH, --window,
// --help. Sample-specific arguments are passed through in CommonOptions::rest.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::samples {

/// Defaults a sample chooses for the shared options.
struct CommonDefaults {
    uint32_t width = 640;
    uint32_t height = 480;
    std::filesystem::path out = "out/sample.png";
};

/// The shared options after parsing.
struct CommonOptions {
    rhi::Backend backend = rhi::Backend::OpenGL;
    uint32_t width = 640;
    uint32_t height = 480;
    std::filesystem::path out;
    bool window = false;
    bool help = false;
    /// Arguments not recognised here, in order (a sample rejects those it does not know).
    std::vector<std::string> rest;
};

/// Parses `args` (without the program name). Errors (unknown backend, malformed size, a
/// missing value) are InvalidArgument with a one-line message naming the argument.
Result<CommonOptions> parse_common_options(std::span<const std::string> args, const CommonDefaults& defaults = {});

/// Convenience for main(): parses argv[1..argc).
Result<CommonOptions> parse_common_options(int argc, char** argv, const CommonDefaults& defaults = {});

/// Help text for the shared options (one option per line, indented), mentioning the defaults.
std::string common_options_help(const CommonDefaults& defaults = {});

/// A device description for the options: the backend, headless unless --window, a window of
/// --size titled `title`, API debug output on.
rhi::DeviceDesc device_desc(const CommonOptions& options, const std::string& title);

/// Parses "WxH" (e.g. "640x480"); both sides positive.
Result<std::pair<uint32_t, uint32_t>> parse_size(const std::string& text);

/// Walks a sample's own arguments (CommonOptions::rest), each "--name value" or "--name=value":
///
///   ArgumentReader args(options.common.rest);
///   while (args.next()) {
///       if (args.name() == "--frames") { auto v = args.value(); ... }
///       else return args.unknown();
///   }
class ArgumentReader {
public:
    explicit ArgumentReader(std::span<const std::string> args) : args_(args) {}
    /// Moves to the next argument; false after the last.
    bool next();
    /// The argument's name ("--frames" also for "--frames=3").
    [[nodiscard]] const std::string& name() const { return name_; }
    /// Its value: the inline one, else the next argument, which it consumes. InvalidArgument
    /// "NAME needs a value" when there is none.
    Result<std::string> value();
    /// InvalidArgument "unknown argument 'ARG'" for the current argument as given.
    [[nodiscard]] Error unknown() const;

private:
    std::span<const std::string> args_;
    std::size_t index_ = 0;
    bool started_ = false;
    std::string name_;
    std::optional<std::string> inline_value_;
};

}  // namespace loom::samples
