#include "glb.hpp"

#include <string>

#include "checked_math.hpp"

namespace loom::gltf::detail {

namespace {

constexpr uint32_t kMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr std::size_t kHeaderSize = 12;
constexpr std::size_t kChunkHeaderSize = 8;

uint32_t read_u32(std::span<const unsigned char> bytes, std::size_t offset) {
    return static_cast<uint32_t>(bytes[offset]) | (static_cast<uint32_t>(bytes[offset + 1]) << 8) |
           (static_cast<uint32_t>(bytes[offset + 2]) << 16) | (static_cast<uint32_t>(bytes[offset + 3]) << 24);
}

std::string hex32(uint32_t value) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string text = "0x";
    for (int shift = 28; shift >= 0; shift -= 4) text += kHex[(value >> shift) & 15u];
    return text;
}

Error glb_error(const std::string& what) { return make_error(ErrorCode::Parse, "GLB: " + what); }

}  // namespace

bool has_glb_magic(std::span<const unsigned char> file) {
    return file.size() >= 4 && read_u32(file, 0) == kMagic;
}

Result<GlbChunks> parse_glb(std::span<const unsigned char> file) {
    if (file.size() < kHeaderSize) {
        return glb_error("unexpected end of header (file has " + std::to_string(file.size()) + " bytes, the header needs 12)");
    }
    const uint32_t magic = read_u32(file, 0);
    if (magic != kMagic) return glb_error("invalid magic " + hex32(magic) + " (expected \"glTF\")");
    const uint32_t version = read_u32(file, 4);
    if (version != 2) return glb_error("unsupported container version " + std::to_string(version) + " (expected 2)");
    const uint32_t length = read_u32(file, 8);
    if (length > file.size()) {
        return glb_error("declared length " + std::to_string(length) + " exceeds the file size " +
                         std::to_string(file.size()));
    }
    GlbChunks chunks;
    // Bytes after the declared length are not part of the GLB (a warning, as the validator has it).
    chunks.trailing_bytes = file.size() - length;
    file = file.first(length);

    bool have_json = false;
    std::size_t offset = kHeaderSize;
    unsigned index = 0;
    while (offset < file.size()) {
        if (file.size() - offset < kChunkHeaderSize) {
            return glb_error("unexpected end of chunk header at byte " + std::to_string(offset));
        }
        const uint32_t chunk_length = read_u32(file, offset);
        const uint32_t chunk_type = read_u32(file, offset + 4);
        const std::size_t data_offset = offset + kChunkHeaderSize;
        if (!range_fits(data_offset, chunk_length, file.size())) {
            return glb_error("chunk " + std::to_string(index) + " (type " + hex32(chunk_type) + ") length " +
                             std::to_string(chunk_length) + " does not fit in the file (" +
                             std::to_string(file.size() - data_offset) + " bytes left)");
        }
        if (chunk_length % 4 != 0) {
            return glb_error("chunk " + std::to_string(index) + " length " + std::to_string(chunk_length) +
                             " is not a multiple of 4");
        }
        const std::span<const unsigned char> data = file.subspan(data_offset, chunk_length);
        if (index == 0) {
            if (chunk_type != kJsonChunk) {
                return glb_error("first chunk has type " + hex32(chunk_type) + ", expected JSON (0x4e4f534a)");
            }
            if (chunk_length == 0) return glb_error("JSON chunk is empty");
            chunks.json = std::string_view(reinterpret_cast<const char*>(data.data()), data.size());
            have_json = true;
        } else if (chunk_type == kJsonChunk) {
            return glb_error("chunk " + std::to_string(index) + " is a second JSON chunk");
        } else if (chunk_type == kBinChunk) {
            if (index != 1) return glb_error("BIN chunk must be the second chunk, found it as chunk " + std::to_string(index));
            chunks.bin = data;
        }
        // Chunks of other types are ignored, as the specification requires.
        offset = data_offset + chunk_length;
        ++index;
    }
    if (!have_json) return glb_error("file has no JSON chunk");
    return chunks;
}

}  // namespace loom::gltf::detail
