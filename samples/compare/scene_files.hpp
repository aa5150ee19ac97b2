#pragma once
// Which glTF files a run covers.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "loom/rhi/result.hpp"

namespace loom::compare {

/// A scene file and the name it is reported under.
struct SceneFile {
    std::filesystem::path path;
    /// The path relative to the directory it was found in (with that directory's name in
    /// front), or the file name for a file given by itself.
    std::string name;
};

/// The .gltf and .glb files of `inputs`: files as given (any extension), directories searched
/// recursively, sorted by path within each directory. Subdirectories named "invalid" (the
/// invalid test files) are skipped: give such a directory itself to search it. Errors
/// (InvalidArgument, naming the path): an input that does not exist.
Result<std::vector<SceneFile>> find_scene_files(std::span<const std::filesystem::path> inputs);

}  // namespace loom::compare
