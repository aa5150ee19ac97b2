#pragma once
// Draws Dear ImGui's draw data through loom's RHI, so that one renderer serves every backend:
// the font atlas is a texture, each frame's vertices and indices go into buffers that grow as
// needed, and every ImGui command is a scissored indexed draw onto the target's contents.

#include <memory>

#include "loom/rhi/device.hpp"

struct ImDrawData;

namespace loom::overlay {

class ImGuiRenderer {
public:
    /// Uploads the current ImGui context's font atlas (and gives it its texture id) and builds
    /// the pipeline that draws into `target_format` textures. Needs a current ImGui context.
    static Result<std::unique_ptr<ImGuiRenderer>> create(rhi::Device& device, rhi::Format target_format);
    ~ImGuiRenderer();
    ImGuiRenderer(const ImGuiRenderer&) = delete;
    ImGuiRenderer& operator=(const ImGuiRenderer&) = delete;

    /// Records `data` over the contents of `target` (a colour attachment of the target format,
    /// left in the RenderTarget state). Nothing is recorded for empty draw data.
    Status record(rhi::CommandList& commands, rhi::TextureHandle target, const ImDrawData& data);

    [[nodiscard]] rhi::Format target_format() const { return target_format_; }
    /// Bytes of the vertex and index buffers as they have grown (for the overlay's own cost).
    [[nodiscard]] uint64_t buffer_bytes() const { return vertex_capacity_ + index_capacity_; }

private:
    ImGuiRenderer(rhi::Device& device, rhi::Format target_format) : device_(device), target_format_(target_format) {}
    Status build();
    /// Makes `buffer` hold at least `bytes` (recreated larger, by half again, when it does not).
    Status reserve(rhi::BufferHandle& buffer, uint64_t& capacity, uint64_t bytes, rhi::BufferUsage usage, const char* name);

    rhi::Device& device_;
    rhi::Format target_format_;
    rhi::ShaderHandle vertex_shader_;
    rhi::ShaderHandle fragment_shader_;
    rhi::PipelineHandle pipeline_;
    rhi::TextureHandle atlas_;
    rhi::SamplerHandle sampler_;
    rhi::BufferHandle vertices_;
    rhi::BufferHandle indices_;
    uint64_t vertex_capacity_ = 0;
    uint64_t index_capacity_ = 0;
};

}  // namespace loom::overlay
