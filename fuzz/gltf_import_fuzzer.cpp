// Fuzz harness: a glTF file with its buffers and images -> gltf::load -> the CPU work a renderer
// does with the scene before any upload (packed geometry, every image's mip chain, the camera
// that frames it). Any input must give a scene or a clean one-line error naming the file: no
// crash, hang, leak or undefined behaviour (docs/fuzzing.md).
//
// Input format, so that one input can be a .glb or a .gltf with several files beside it:
//   <model>[\n--file--\n<file 0>[\n--file--\n<file 1>...]]
// The model is written as model.glb when it starts with the GLB magic "glTF", else as
// model.gltf; file k is written beside it as "k.bin" (URIs in the seeds name 0.bin, 1.bin, ...;
// images are recognised by their bytes, so an image can be "1.bin" too). At most kMaxFiles
// files; later separators stay in the last file's bytes. The last byte of the input picks the
// normal and tangent generation (bit 0: smooth normals, bit 1: tangents always), so both paths
// are explored without a format of their own.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "loom/rhi/log.hpp"
#include "loom/scene/camera.hpp"
#include "loom/gltf/gltf.hpp"
#include "loom/scene/packed_geometry.hpp"
#include "loom/scene/mip_chain.hpp"

namespace {

constexpr std::string_view kSeparator = "\n--file--\n";
constexpr std::size_t kMaxFiles = 8;

// Where the files of one input go: one directory per process (libFuzzer's -jobs/-fork run
// several), in /dev/shm when there is one so that the writes cost no disk I/O.
class Scratch {
public:
    Scratch() {
        std::error_code error;
        const std::filesystem::path base = std::filesystem::is_directory("/dev/shm", error)
                                               ? std::filesystem::path("/dev/shm")
                                               : std::filesystem::temp_directory_path();
        dir_ = base / ("loom-fuzz-gltf-" + std::to_string(::getpid()));
        std::filesystem::remove_all(dir_, error);
        std::filesystem::create_directories(dir_, error);
        if (error) {
            std::fprintf(stderr, "gltf_import fuzzer: cannot create %s: %s\n", dir_.c_str(), error.message().c_str());
            std::abort();
        }
    }
    ~Scratch() {
        std::error_code error;
        std::filesystem::remove_all(dir_, error);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;

    // Writes the input's files and returns the model's path. Files of the previous input that
    // this one does not have are removed, so that no input sees another's files.
    std::filesystem::path write(std::string_view input) {
        std::string_view rest = input;
        const std::size_t model_end = rest.find(kSeparator);
        const std::string_view model = rest.substr(0, model_end);
        rest = model_end == std::string_view::npos ? std::string_view{} : rest.substr(model_end + kSeparator.size());
        const bool glb = model.substr(0, 4) == "glTF";
        const std::filesystem::path model_path = dir_ / (glb ? "model.glb" : "model.gltf");
        std::error_code error;
        std::filesystem::remove(dir_ / (glb ? "model.gltf" : "model.glb"), error);
        put(model_path, model);

        std::size_t files = 0;
        bool more = model_end != std::string_view::npos;
        while (more && files < kMaxFiles) {
            std::size_t end = files + 1 == kMaxFiles ? std::string_view::npos : rest.find(kSeparator);
            put(dir_ / (std::to_string(files) + ".bin"), rest.substr(0, end));
            ++files;
            more = end != std::string_view::npos;
            if (more) rest = rest.substr(end + kSeparator.size());
        }
        for (std::size_t k = files; k < written_files_; ++k) {
            std::filesystem::remove(dir_ / (std::to_string(k) + ".bin"), error);
        }
        written_files_ = files;
        return model_path;
    }

private:
    static void put(const std::filesystem::path& path, std::string_view bytes) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) {
            std::fprintf(stderr, "gltf_import fuzzer: cannot write %s\n", path.c_str());
            std::abort();
        }
    }

    std::filesystem::path dir_;
    std::size_t written_files_ = 0;
};

// The importer promises one-line messages ("<file>: <JSON pointer>: <what>"); a newline
// would split logs and the tools' one-line errors, so it counts as a finding like a crash.
void require_one_line(std::string_view what, std::string_view message) {
    if (message.find('\n') != std::string_view::npos || message.find('\r') != std::string_view::npos) {
        std::fprintf(stderr, "gltf_import fuzzer: %.*s is not one line: %.*s\n", static_cast<int>(what.size()),
                     what.data(), static_cast<int>(message.size()), message.data());
        std::abort();
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static Scratch scratch;
    static const bool quiet = [] {
        // Warnings are many and expected; printing them would dominate the run time.
        loom::set_log_sink([](loom::LogLevel, std::string_view, std::string_view message) {
            require_one_line("a logged warning", message);
        });
        return true;
    }();
    (void)quiet;

    const std::string_view input(reinterpret_cast<const char*>(data), size);
    const std::filesystem::path path = scratch.write(input);

    loom::gltf::LoadOptions options;
    // Small enough that a legal but huge file (a sparse accessor of 2^24 zeros, a 16384^2
    // image) fails cleanly instead of making the fuzzer run out of memory or time.
    options.max_accessor_elements = uint64_t{1} << 16;
    options.max_image_dimension = 512;
    const uint8_t last = size == 0 ? 0 : data[size - 1];
    options.normals = (last & 1) != 0 ? loom::gltf::NormalGeneration::Smooth : loom::gltf::NormalGeneration::Flat;
    options.tangents =
        (last & 2) != 0 ? loom::gltf::TangentGeneration::Always : loom::gltf::TangentGeneration::WhenNormalMapped;

    auto scene = loom::gltf::load(path, options);
    if (!scene) {
        const std::string& message = scene.error().message;
        require_one_line("the error", message);
        if (message.rfind(path.string(), 0) != 0) {
            std::fprintf(stderr, "gltf_import fuzzer: the error does not name the file: %s\n", message.c_str());
            std::abort();
        }
        return 0;
    }

    // What PreparedScene (loom/renderer/gpu_scene.hpp) computes before uploading anything.
    const loom::scene::PackedGeometry geometry = loom::scene::pack_geometry(*scene);
    for (const loom::scene::DrawItem& item : scene->draw_items) (void)geometry.range(item);
    for (const loom::scene::TextureImage& image : scene->images) (void)loom::scene::mip_chain(image.image);
    (void)loom::scene::frame_bounds(scene->bounds, 16.0f / 9.0f);
    (void)scene->vertex_count();
    (void)scene->index_count();
    return 0;
}
