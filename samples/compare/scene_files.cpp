#include "scene_files.hpp"

#include <algorithm>
#include <cctype>

namespace loom::compare {
namespace {

bool is_scene_file(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension == ".gltf" || extension == ".glb";
}

}  // namespace

Result<std::vector<SceneFile>> find_scene_files(std::span<const std::filesystem::path> inputs) {
    std::vector<SceneFile> files;
    for (const std::filesystem::path& input : inputs) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(input, ec)) {
            files.push_back({input, input.filename().string()});
            continue;
        }
        if (!std::filesystem::is_directory(input, ec)) {
            return make_error(ErrorCode::InvalidArgument, input.string() + ": no such file or directory");
        }
        const std::filesystem::path root = input.lexically_normal();
        const std::string prefix = (root.has_filename() ? root.filename() : root.parent_path().filename()).string();
        std::vector<SceneFile> found;
        std::filesystem::recursive_directory_iterator it(root, std::filesystem::directory_options::skip_permission_denied, ec);
        if (ec) return make_error(ErrorCode::Io, input.string() + ": " + ec.message());
        for (; it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
            if (ec) return make_error(ErrorCode::Io, input.string() + ": " + ec.message());
            if (it->is_directory(ec) && it->path().filename() == "invalid") {
                it.disable_recursion_pending();
                continue;
            }
            if (!it->is_regular_file(ec) || !is_scene_file(it->path())) continue;
            const std::filesystem::path relative = it->path().lexically_relative(root);
            found.push_back({it->path(), (std::filesystem::path(prefix) / relative).generic_string()});
        }
        std::sort(found.begin(), found.end(), [](const SceneFile& a, const SceneFile& b) { return a.name < b.name; });
        files.insert(files.end(), found.begin(), found.end());
    }
    return files;
}

}  // namespace loom::compare
