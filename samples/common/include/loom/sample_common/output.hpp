#pragma once
// Writing what a sample rendered.

#include <filesystem>

#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::samples {

/// Reads mip 0 / layer 0 of `texture` back and writes it as a PNG at `path`, creating the
/// parent directories. Errors name the texture or the file.
Status save_texture_png(rhi::Device& device, rhi::TextureHandle texture, const std::filesystem::path& path);

}  // namespace loom::samples
