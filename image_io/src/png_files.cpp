#include <cstring>
#include <system_error>

#include <stb_image.h>
#include <stb_image_write.h>

#include "decoder_reason.hpp"
#include "loom/image_io/image_io.hpp"

namespace loom::image_io {

using rhi::Format;
using rhi::Image;

Status write_png(const Image& image, const std::filesystem::path& path, const rhi::DisplayOptions& options) {
    if (image.empty()) return Error{ErrorCode::InvalidArgument, "cannot write empty image to " + path.string()};
    const Image rgba = rhi::to_rgba8(image, options);
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    const int ok = stbi_write_png(path.string().c_str(), static_cast<int>(rgba.width), static_cast<int>(rgba.height), 4,
                                  rgba.pixels.data(), static_cast<int>(rgba.row_bytes()));
    if (!ok) return Error{ErrorCode::Io, "could not write PNG " + path.string()};
    return {};
}

Result<Image> read_png(const std::filesystem::path& path) {
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load(path.string().c_str(), &w, &h, &n, 4);
    if (!data) return Error{ErrorCode::Io, "could not read PNG " + path.string() + ": " + detail::decoder_reason()};
    Image image(static_cast<uint32_t>(w), static_cast<uint32_t>(h), Format::RGBA8Unorm);
    std::memcpy(image.pixels.data(), data, image.pixels.size());
    stbi_image_free(data);
    return image;
}

Result<rhi::ImageComparison> compare_and_report(const Image& a, const Image& b, const std::filesystem::path& dir,
                                                const std::string& stem, const rhi::ImageCompareOptions& options) {
    auto result = rhi::compare_images(a, b, options);
    if (!result.ok() || result->equal()) return result;
    LOOM_TRY(write_png(a, dir / (stem + ".a.png")));
    LOOM_TRY(write_png(b, dir / (stem + ".b.png")));
    if (result->heatmap) LOOM_TRY(write_png(*result->heatmap, dir / (stem + ".diff.png")));
    return result;
}

}  // namespace loom::image_io
