#pragma once
// Runs loom-compare's cases: one device per compiled-in backend for the whole run; per scene
// file the import, then per backend the upload (shared by the pipelines) and per pipeline one
// frame; then the backends compared (plans, created resources, final pictures) and the
// pictures written.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "case_result.hpp"
#include "compare_options.hpp"
#include "loom/passes/composer.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"
#include "scene_files.hpp"

namespace loom::compare {

class CaseRunner {
public:
    /// Creates a headless device with API validation for every compiled-in backend. Errors: a
    /// backend that cannot make a device (its message).
    static Result<std::unique_ptr<CaseRunner>> create(const Options& options);
    ~CaseRunner();
    CaseRunner(const CaseRunner&) = delete;
    CaseRunner& operator=(const CaseRunner&) = delete;

    /// The cases of one scene file: one per pipeline, or one "load" case when the file does not
    /// load (a failure, unless errors are expected) or errors are expected. Pictures go under
    /// options.out / "cases".
    std::vector<CaseResult> run(const SceneFile& file);

    [[nodiscard]] std::vector<rhi::Backend> backends() const;

private:
    explicit CaseRunner(Options options) : options_(std::move(options)) {}
    /// A case of `file` with a unique id.
    CaseResult new_case(const SceneFile& file, const std::string& pipeline);
    CaseResult expect_error(const SceneFile& file);
    /// Checks the runs (errors, messages, created resources) and compares the backends (plans,
    /// pictures); returns the pictures' heat map.
    std::optional<rhi::Image> compare(CaseResult& result, const std::vector<rhi::Image>& images);
    Status write_pictures(CaseResult& result, const std::vector<rhi::Image>& images,
                          const std::optional<rhi::Image>& heatmap);
    /// Compares the forward case's pictures with the deferred case's on every backend that
    /// rendered both; records the first backend's metrics (and heat map) in `forward`.
    void compare_pipelines(const CaseResult& deferred, const std::vector<rhi::Image>& deferred_images, CaseResult& forward,
                           const std::vector<rhi::Image>& forward_images);

    Options options_;
    std::set<std::string> used_ids_;
    std::vector<std::unique_ptr<rhi::Device>> devices_;
    std::shared_ptr<passes::ShaderLibrary> library_;
};

}  // namespace loom::compare
