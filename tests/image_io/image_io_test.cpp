// loom::image_io: PNG files and encoded images to and from rhi::Image.
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include <gtest/gtest.h>

#include "loom/image_io/image_io.hpp"
#include "loom_test/test_support.hpp"

using namespace loom;
using namespace loom::rhi;

namespace {

std::vector<unsigned char> file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST(ImagePng, WriteReadRoundTripAndReportOnDifference) {
    Image a(3, 2, Format::RGBA8Unorm);
    a.store(0, 0, {1, 0, 0, 1});
    a.store(2, 1, {0, 0, 1, 1});
    const auto dir = loom::test::output_dir() / "image_io_test";
    const auto path = dir / "roundtrip.png";
    ASSERT_TRUE(image_io::write_png(a, path).ok());
    auto back = image_io::read_png(path);
    ASSERT_TRUE(back.ok()) << back.error().to_string();
    EXPECT_EQ(back->pixels, a.pixels);

    Image b = a;
    b.store(1, 1, {0, 1, 0, 1});
    std::filesystem::remove(dir / "case.diff.png");
    auto cmp = image_io::compare_and_report(a, b, dir, "case");
    ASSERT_TRUE(cmp.ok());
    EXPECT_FALSE(cmp->equal());
    EXPECT_TRUE(std::filesystem::exists(dir / "case.diff.png"));
    EXPECT_TRUE(std::filesystem::exists(dir / "case.a.png"));

    auto missing = image_io::read_png(dir / "does-not-exist.png");
    ASSERT_FALSE(missing.ok());
    EXPECT_EQ(missing.error().code, ErrorCode::Io);
}

TEST(ImageIo, EncodedImagesReportTheirSizeAndDecodeToTheAskedFormat) {
    Image picture(5, 3, Format::RGBA8Unorm);
    picture.store(4, 2, {0.2, 0.4, 0.6, 1.0});
    const auto path = loom::test::output_dir() / "image_io_test" / "encoded.png";
    ASSERT_TRUE(image_io::write_png(picture, path).ok());
    const std::vector<unsigned char> bytes = file_bytes(path);
    ASSERT_FALSE(bytes.empty());

    auto size = image_io::encoded_image_size(bytes);
    ASSERT_TRUE(size.ok()) << size.error().to_string();
    EXPECT_EQ(size->width, 5u);
    EXPECT_EQ(size->height, 3u);

    auto srgb = image_io::decode_image(bytes, Format::RGBA8Srgb);
    ASSERT_TRUE(srgb.ok()) << srgb.error().to_string();
    EXPECT_EQ(srgb->format, Format::RGBA8Srgb);
    EXPECT_EQ(srgb->pixels, picture.pixels);  // the same bytes; the format says how to read them
}

TEST(ImageIo, BadEncodedImagesAreParseErrorsAndOtherFormatsAreRefused) {
    auto empty = image_io::encoded_image_size({});
    ASSERT_FALSE(empty.ok());
    EXPECT_EQ(empty.error().code, ErrorCode::Parse);
    EXPECT_EQ(empty.error().message, "image data is empty");

    const std::vector<unsigned char> garbage{'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'a', 'g', 'e'};
    auto size = image_io::encoded_image_size(garbage);
    ASSERT_FALSE(size.ok());
    EXPECT_EQ(size.error().code, ErrorCode::Parse);
    EXPECT_EQ(size.error().message.rfind("cannot decode image: ", 0), 0u) << size.error().message;
    auto decoded = image_io::decode_image(garbage, Format::RGBA8Unorm);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().code, ErrorCode::Parse);

    auto wrong_format = image_io::decode_image(garbage, Format::RGBA16Float);
    ASSERT_FALSE(wrong_format.ok());
    EXPECT_EQ(wrong_format.error().code, ErrorCode::InvalidArgument);
    EXPECT_EQ(wrong_format.error().message, "decode_image: format RGBA16Float is not RGBA8Unorm or RGBA8Srgb");
}

TEST(ImageIo, DecoderReasonsFromTheFileArePrintable) {
    // A PNG signature, then a critical chunk of an unknown type whose name holds a newline:
    // stb_image puts the type bytes into its failure reason.
    std::vector<unsigned char> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    const unsigned char ihdr[] = {0, 0, 0, 13, 'I', 'H', 'D', 'R', 0, 0, 0, 1, 0, 0, 0, 1, 8, 6, 0, 0, 0, 0, 0, 0, 0};
    png.insert(png.end(), std::begin(ihdr), std::end(ihdr));
    const unsigned char odd[] = {0, 0, 0, 0, 'A', '\n', 'C', 'D', 0, 0, 0, 0};
    png.insert(png.end(), std::begin(odd), std::end(odd));
    auto decoded = image_io::decode_image(png, Format::RGBA8Unorm);
    ASSERT_FALSE(decoded.ok());
    EXPECT_EQ(decoded.error().message.find('\n'), std::string::npos) << decoded.error().message;
}
