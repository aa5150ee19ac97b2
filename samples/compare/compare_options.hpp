#pragma once
// The command line of loom-compare.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "loom/rhi/result.hpp"

namespace loom::compare {

/// The pipelines a case can render.
enum class PipelineKind : uint8_t { Deferred, Forward };

/// "deferred" or "forward".
std::string_view pipeline_name(PipelineKind pipeline);

struct Options {
    std::vector<PipelineKind> pipelines{PipelineKind::Deferred, PipelineKind::Forward};
    /// Files and directories as given; empty: the default data directory.
    std::vector<std::filesystem::path> scenes;
    uint32_t width = 480;
    uint32_t height = 270;
    std::filesystem::path out = "out/compare";
    /// A pixel differs when a channel of the final pictures differs by more than this (8-bit levels).
    double threshold = 1.0;
    /// Pixels that may differ (beyond the threshold) per picture, as a fraction of all pixels.
    double max_differing = 0.0;
    /// Print the results as one JSON object on stdout.
    bool json = false;
    /// Every scene must fail to load with a one-line error (the invalid-file check).
    bool expect_errors = false;
    /// Write an inspector page (docs/inspector.md) of each case's frame on each backend.
    bool inspector_pages = true;
    bool help = false;
};

/// Parses `args` (without the program name). Errors are InvalidArgument with a one-line message
/// naming the argument.
Result<Options> parse_options(std::span<const std::string> args);

/// The --help text.
std::string usage();

}  // namespace loom::compare
