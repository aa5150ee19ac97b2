// load(): reads the file, checks the GLB container and the JSON, validates the document
// (gltf_validate), lets tinygltf load it with the files the validator already read, and
// converts the result (gltf_convert).
#include <algorithm>
#include <cctype>
#include <climits>
#include <exception>
#include <fstream>
#include <new>
#include <span>
#include <string>
#include <system_error>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "glb.hpp"
#include "gltf_convert.hpp"
#include "gltf_validate.hpp"
#include "loom/rhi/log.hpp"
#include "loom/gltf/gltf.hpp"

namespace loom::gltf {

using namespace loom::scene;  // the importer builds the scene model's types

namespace {

using detail::located_message;

Error parse_error(const std::string& file_label, const std::string& what) {
    return make_error(ErrorCode::Parse, located_message(file_label, "", what));
}

// Collapses tinygltf's multi-line messages into one line.
std::string one_line(std::string text) {
    std::replace(text.begin(), text.end(), '\r', '\n');
    std::string result;
    bool pending_separator = false;
    for (const char c : text) {
        if (c == '\n') {
            pending_separator = !result.empty();
            continue;
        }
        if (pending_separator) result += "; ";
        pending_separator = false;
        result += c;
    }
    return result;
}

Result<std::vector<unsigned char>> read_file(const std::filesystem::path& path, const std::string& file_label) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return make_error(ErrorCode::Io, file_label + ": file not found");
    if (std::filesystem::is_directory(path, ec)) return make_error(ErrorCode::Io, file_label + ": is a directory, not a file");
    std::ifstream stream(path, std::ios::binary);
    if (!stream) return make_error(ErrorCode::Io, file_label + ": cannot open file");
    stream.seekg(0, std::ios::end);
    const std::streamoff size = stream.tellg();
    stream.seekg(0, std::ios::beg);
    if (size < 0) return make_error(ErrorCode::Io, file_label + ": cannot determine the file size");
    // tinygltf takes the document's length as an unsigned int.
    if (static_cast<uint64_t>(size) > UINT_MAX) {
        return make_error(ErrorCode::Parse, file_label + ": file of " + std::to_string(size) + " bytes is too large");
    }
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    stream.read(reinterpret_cast<char*>(bytes.data()), size);
    if (!stream) return make_error(ErrorCode::Io, file_label + ": cannot read file");
    return bytes;
}

bool has_glb_extension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".glb";
}

// tinygltf reads every file through these callbacks; they serve only the files the validator
// resolved and read (so tinygltf never searches other directories or expands paths).
struct FileStore {
    const std::map<std::string, std::vector<unsigned char>>* files = nullptr;
};

bool store_file_exists(const std::string& path, void* user) {
    const auto* store = static_cast<const FileStore*>(user);
    return store->files->count(path) != 0;
}

std::string store_expand_path(const std::string& path, void*) { return path; }

bool store_read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const auto* store = static_cast<const FileStore*>(user);
    const auto found = store->files->find(path);
    if (found == store->files->end()) {
        if (err != nullptr) *err += "file not resolved by the importer: " + path;
        return false;
    }
    *out = found->second;
    return true;
}

bool store_write_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err != nullptr) *err += "the importer never writes files";
    return false;
}

// Keeps images encoded; the converter decodes only those materials use, in the colour space
// of their use.
bool keep_encoded_image(tinygltf::Image* image, const int, std::string* err, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
    if (bytes == nullptr || size <= 0) {
        if (err != nullptr) *err += "image data is empty";
        return false;
    }
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

// Gives buffers the names under which the file store serves their data, and index accessors
// without a bufferView a zero-filled one (buffers and views appended, so indices stay valid).
void apply_rewrites(nlohmann::json& root, const detail::ValidationOutput& validated) {
    for (const auto& [index, name] : validated.image_rewrites) root["images"][index]["uri"] = name;
    for (const std::string& pointer : validated.integers_written_as_floats) {
        nlohmann::json& value = root[nlohmann::json::json_pointer(pointer)];
        value = static_cast<uint64_t>(value.get<double>());
    }
    for (const auto& [index, rewrite] : validated.buffer_rewrites) {
        nlohmann::json& buffer = root["buffers"][index];
        buffer["uri"] = rewrite.first;
        buffer["byteLength"] = rewrite.second;
    }
    for (const auto& [accessor_index, file] : validated.zero_index_accessors) {
        const auto& [name, length] = file;
        nlohmann::json& accessor = root["accessors"][accessor_index];
        root["buffers"].push_back({{"uri", name}, {"byteLength", length}});
        root["bufferViews"].push_back({{"buffer", root["buffers"].size() - 1}, {"byteLength", length}});
        accessor["bufferView"] = root["bufferViews"].size() - 1;
    }
}

Result<Scene> load_file(const std::filesystem::path& path, const LoadOptions& options) {
    const std::string file_label = path.string();
    auto bytes = read_file(path, file_label);
    if (!bytes) return bytes.take_error();

    // The container: GLB (by magic, and any *.glb must be one) or plain JSON.
    const bool is_glb = detail::has_glb_magic(*bytes) || has_glb_extension(path);
    std::string_view json_text(reinterpret_cast<const char*>(bytes->data()), bytes->size());
    std::optional<std::span<const unsigned char>> bin;
    std::size_t glb_trailing_bytes = 0;
    if (is_glb) {
        auto chunks = detail::parse_glb(*bytes);
        if (!chunks) return parse_error(file_label, chunks.error().message);
        json_text = chunks->json;
        bin = chunks->bin;
        glb_trailing_bytes = chunks->trailing_bytes;
    }

    // The JSON itself.
    if (json_text.size() >= 3 && static_cast<unsigned char>(json_text[0]) == 0xEF &&
        static_cast<unsigned char>(json_text[1]) == 0xBB && static_cast<unsigned char>(json_text[2]) == 0xBF) {
        return parse_error(file_label, "invalid JSON: the text starts with a UTF-8 byte order mark, which glTF forbids");
    }
    nlohmann::json root;
    try {
        root = nlohmann::json::parse(json_text.begin(), json_text.end());
    } catch (const nlohmann::json::exception& e) {
        std::string what = e.what();
        // Drop nlohmann's "[json.exception.parse_error.101] " prefix.
        if (const std::size_t bracket = what.find("] "); what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
            what.erase(0, bracket + 2);
        }
        return parse_error(file_label, "invalid JSON: " + one_line(what));
    }

    // The importer's own checks, which also read every file the document refers to.
    detail::ValidationInput input;
    input.file_label = file_label;
    input.base_dir = path.parent_path();
    input.tinygltf_base_dir = path.parent_path().string();
    input.is_glb = is_glb;
    input.glb_bin = bin;
    input.options = &options;
    auto validated = detail::validate_document(root, input);
    if (!validated) return validated.take_error();
    // tinygltf parses the validated document as JSON text, GLB files too (their BIN chunk is
    // served as a file), with the stand-ins the validator made for what tinygltf cannot take.
    apply_rewrites(root, *validated);
    const std::string document = root.dump();
    root = nlohmann::json();  // free it before tinygltf builds its own copy
    bytes->clear();
    bytes->shrink_to_fit();
    FileStore store{&validated->files};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&store_file_exists, &store_expand_path, &store_read_file, &store_write_file,
                                                &store});
    loader.SetImageLoader(&keep_encoded_image, nullptr);
    tinygltf::Model model;
    std::string err;
    std::string warn;
    if (document.size() > UINT_MAX) return parse_error(file_label, "the JSON document is too large");
    const bool loaded = loader.LoadASCIIFromString(&model, &err, &warn, document.data(),
                                                   static_cast<unsigned int>(document.size()), input.tinygltf_base_dir);
    if (!loaded) {
        return parse_error(file_label, "tinygltf: " + (err.empty() ? std::string("loading failed") : one_line(err)));
    }
    std::vector<std::string> warnings = std::move(validated->warnings);
    if (const auto& fractional = validated->integers_written_as_floats; !fractional.empty()) {
        warnings.push_back(located_message(file_label, fractional.front(),
                                           std::to_string(fractional.size()) +
                                               " integer(s) written with a fraction (as 1.0), read as integers"));
    }
    if (glb_trailing_bytes != 0) {
        warnings.insert(warnings.begin(), located_message(file_label, "", "GLB: " + std::to_string(glb_trailing_bytes) +
                                                                              " bytes after the declared length are ignored"));
    }
    if (!warn.empty()) warnings.push_back(located_message(file_label, "", "tinygltf: " + one_line(warn)));

    auto scene = detail::convert_model(model, file_label, options, validated->unavailable_buffers, warnings);
    if (!scene) return scene.take_error();
    scene->warnings = std::move(warnings);
    for (const std::string& warning : scene->warnings) log_warning("gltf", warning);
    return scene;
}

}  // namespace

Result<Scene> load(const std::filesystem::path& path, const LoadOptions& options) {
    // Nothing below throws for a bad file; this only turns the unexpected (allocation failure,
    // a library exception) into an error instead of terminating the program.
    try {
        return load_file(path, options);
    } catch (const std::bad_alloc&) {
        return make_error(ErrorCode::OutOfMemory, path.string() + ": out of memory while loading");
    } catch (const std::exception& e) {
        return make_error(ErrorCode::Parse, path.string() + ": " + one_line(e.what()));
    }
}

}  // namespace loom::gltf
