#pragma once
// Small frame-graph passes for the execution tests: fullscreen triangles (gl_VertexIndex) with
// inline GLSL, so that every value a pass writes is known exactly. Patterns depend on the
// column only (gl_FragCoord.x), which reads the same in every orientation convention.

#include <array>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "loom/framegraph/framegraph.hpp"
#include "loom/rhi/device.hpp"

/// Assigns the value of a Result expression to `lhs`, or fails the test with its error.
#define LOOM_EXEC_CONCAT_INNER(a, b) a##b
#define LOOM_EXEC_CONCAT(a, b) LOOM_EXEC_CONCAT_INNER(a, b)
#define LOOM_ASSIGN_OR_FAIL(lhs, expr)                                                         \
    auto LOOM_EXEC_CONCAT(loom_result_, __LINE__) = (expr);                                    \
    ASSERT_TRUE(LOOM_EXEC_CONCAT(loom_result_, __LINE__).ok())                                 \
        << #expr << ": " << LOOM_EXEC_CONCAT(loom_result_, __LINE__).error().to_string();      \
    lhs = std::move(*LOOM_EXEC_CONCAT(loom_result_, __LINE__))

/// Fails the test when a Status expression is an error.
#define LOOM_ASSERT_OK(expr)                                                                   \
    do {                                                                                       \
        auto loom_status_ = (expr);                                                            \
        ASSERT_TRUE(loom_status_.ok()) << #expr << ": " << loom_status_.error().to_string();   \
    } while (false)

namespace loom::test {

using Color = std::array<float, 4>;

/// Push constants of the fill shader: `left` for columns x < split, else `right`.
struct FillConstants {
    Color left{};
    Color right{};
    float split = 0.0f;
    float pad[3] = {0.0f, 0.0f, 0.0f};
};

/// Push constants of the filter shader: out = texelFetch(src) * mul + add.
struct FilterConstants {
    Color mul{1, 1, 1, 1};
    Color add{};
};

/// Push constants of the combine shader: out = a * wa + b * wb.
struct CombineConstants {
    Color wa{1, 1, 1, 1};
    Color wb{1, 1, 1, 1};
};

/// Pipelines for the test passes, created on one device and destroyed with it.
class TestPrograms {
public:
    explicit TestPrograms(rhi::Device& device) : device_(device) {}
    ~TestPrograms();
    TestPrograms(const TestPrograms&) = delete;
    TestPrograms& operator=(const TestPrograms&) = delete;

    /// Writes FillConstants colours into one colour attachment of `format`.
    Result<rhi::PipelineHandle> fill(rhi::Format format);
    /// Writes FillConstants colours (left) at depth `right.x` with depth test Always.
    Result<rhi::PipelineHandle> fill_depth(rhi::Format color, rhi::Format depth);
    /// Writes depth = FillConstants left.x (left half) / right.x (right half), no colour.
    Result<rhi::PipelineHandle> depth_only(rhi::Format depth);
    /// out = texelFetch(set 0 binding 0) * mul + add.
    Result<rhi::PipelineHandle> filter(rhi::Format format);
    /// out = a * wa + b * wb (a: binding 0, b: binding 1).
    Result<rhi::PipelineHandle> combine(rhi::Format format);
    /// Nearest-filtering sampler.
    Result<rhi::SamplerHandle> sampler();
    /// A shader of `stage` compiled from GLSL `code` (destroyed with the programs).
    Result<rhi::ShaderHandle> shader(rhi::ShaderStage stage, const std::string& name, const std::string& code);
    /// A compute pipeline from GLSL `code` (cached by name).
    Result<rhi::PipelineHandle> compute(const std::string& name, const std::string& code);
    /// Keeps `pipeline` to destroy it with the programs.
    void adopt(rhi::PipelineHandle pipeline, const std::string& name) { pipelines_.emplace_back(name, pipeline); }
    /// A fullscreen-triangle pipeline with the given fragment shader (cached by name and formats);
    /// with a depth format, depth test Always and writes as `depth_write` says.
    Result<rhi::PipelineHandle> make(const std::string& name, const std::string& fragment, std::vector<rhi::Format> colors,
                                     rhi::Format depth = rhi::Format::Undefined, bool depth_write = false);

private:
    Result<rhi::ShaderHandle> vertex_shader();

    rhi::Device& device_;
    rhi::ShaderHandle vertex_;
    rhi::SamplerHandle sampler_;
    std::vector<std::pair<std::string, rhi::PipelineHandle>> pipelines_;
    std::vector<rhi::ShaderHandle> shaders_;
};

/// A pass drawing FillConstants into its output `port` (cleared first by the plan).
fg::Pass fill_pass(const std::string& name, const std::string& port, const fg::TextureSpec& spec,
                   rhi::PipelineHandle pipeline, FillConstants constants);
/// A pass reading `in` and writing `out` = in * mul + add.
fg::Pass filter_pass(const std::string& name, const std::string& in, const std::string& out, const fg::TextureSpec& spec,
                     rhi::PipelineHandle pipeline, rhi::SamplerHandle sampler, FilterConstants constants);
/// A pass reading `a` and `b` and writing `out` = a * wa + b * wb.
fg::Pass combine_pass(const std::string& name, const std::string& a, const std::string& b, const std::string& out,
                      const fg::TextureSpec& spec, rhi::PipelineHandle pipeline, rhi::SamplerHandle sampler,
                      CombineConstants constants);

/// The texel at (x, y) of `texture` (reads the whole texture back).
std::array<double, 4> texel(rhi::Device& device, rhi::TextureHandle texture, uint32_t x, uint32_t y);

/// Writes `texture` under output_dir()/execution/<name>.png for inspection.
void save_texture(rhi::Device& device, rhi::TextureHandle texture, const std::string& name);

/// Executor and device stats for failure messages.
inline std::string describe(const fg::ExecutionStats& stats) { return fg::describe_stats(stats); }

}  // namespace loom::test
