#include "imgui_renderer.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "loom/shader_compiler/shader_compiler.hpp"

namespace loom::overlay {
namespace {

// ImGui positions are framebuffer pixels with y down; loom's NDC has y up (row 0 on top).
constexpr const char* kVertexSource = R"(#version 450
layout(location = 0) in vec2 position;
layout(location = 1) in vec2 uv;
layout(location = 2) in vec4 color;
layout(push_constant) uniform Transform {
    vec2 scale;
    vec2 translate;
    float linearize;
} transform;
layout(location = 0) out vec2 v_uv;
layout(location = 1) out vec4 v_color;
void main() {
    v_uv = uv;
    // ImGui's colours are display (sRGB) values; an sRGB target encodes what it is given, so
    // they are decoded first (a 2.2 gamma, close enough for a UI).
    v_color = transform.linearize > 0.5 ? vec4(pow(color.rgb, vec3(2.2)), color.a) : color;
    gl_Position = vec4(position * transform.scale + transform.translate, 0.0, 1.0);
}
)";

constexpr const char* kFragmentSource = R"(#version 450
layout(set = 0, binding = 0) uniform sampler2D atlas;
layout(location = 0) in vec2 v_uv;
layout(location = 1) in vec4 v_color;
layout(location = 0) out vec4 color;
void main() {
    color = v_color * texture(atlas, v_uv);
}
)";

struct Transform {
    float scale[2];
    float translate[2];
    float linearize;
    float padding[3];
};

}  // namespace

Result<std::unique_ptr<ImGuiRenderer>> ImGuiRenderer::create(rhi::Device& device, rhi::Format target_format) {
    if (!ImGui::GetCurrentContext()) {
        return Error{ErrorCode::InvalidState, "ImGuiRenderer::create: no current ImGui context"};
    }
    std::unique_ptr<ImGuiRenderer> renderer(new ImGuiRenderer(device, target_format));
    LOOM_TRY(renderer->build());
    return renderer;
}

Status ImGuiRenderer::build() {
    shader_compiler::ShaderCompiler compiler;
    auto vs = compiler.create_shader(device_, {"imgui.vert", rhi::ShaderStage::Vertex, kVertexSource, {}});
    if (!vs) return vs.take_error();
    vertex_shader_ = *vs;
    auto fs = compiler.create_shader(device_, {"imgui.frag", rhi::ShaderStage::Fragment, kFragmentSource, {}});
    if (!fs) return fs.take_error();
    fragment_shader_ = *fs;

    rhi::GraphicsPipelineDesc desc;
    desc.name = "imgui";
    desc.vertex = vertex_shader_;
    desc.fragment = fragment_shader_;
    rhi::VertexBufferLayout layout;
    layout.stride = sizeof(ImDrawVert);
    layout.attributes = {
        {0, rhi::VertexFormat::Float2, static_cast<uint32_t>(offsetof(ImDrawVert, pos))},
        {1, rhi::VertexFormat::Float2, static_cast<uint32_t>(offsetof(ImDrawVert, uv))},
        {2, rhi::VertexFormat::UByte4Norm, static_cast<uint32_t>(offsetof(ImDrawVert, col))},
    };
    desc.vertex_buffers = {layout};
    desc.color_formats = {target_format_};
    desc.blend = {rhi::BlendState::over()};
    auto pipeline = device_.create_graphics_pipeline(desc);
    if (!pipeline) return pipeline.take_error();
    pipeline_ = *pipeline;

    rhi::SamplerDesc linear;
    linear.name = "imgui atlas";
    auto sampler = device_.create_sampler(linear);
    if (!sampler) return sampler.take_error();
    sampler_ = *sampler;

    ImGuiIO& io = ImGui::GetIO();
    unsigned char* pixels = nullptr;
    int width = 0, height = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &width, &height);
    rhi::TextureDesc atlas;
    atlas.name = "imgui font atlas";
    atlas.format = rhi::Format::RGBA8Unorm;
    atlas.width = static_cast<uint32_t>(width);
    atlas.height = static_cast<uint32_t>(height);
    atlas.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::CopyDst;
    auto texture = device_.create_texture(atlas);
    if (!texture) return texture.take_error();
    atlas_ = *texture;
    const auto bytes = std::as_bytes(std::span(pixels, static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4));
    LOOM_TRY(device_.write_texture(atlas_, rhi::TextureRegion{}, bytes));
    // The one texture the overlay draws with; ImGui hands it back with every command.
    io.Fonts->SetTexID(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(1)));
    io.BackendFlags |= ImGuiBackendFlags_RendererHasVtxOffset;
    return {};
}

ImGuiRenderer::~ImGuiRenderer() {
    for (rhi::BufferHandle b : {vertices_, indices_}) {
        if (b) (void)device_.destroy(b);
    }
    if (atlas_) (void)device_.destroy(atlas_);
    if (sampler_) (void)device_.destroy(sampler_);
    if (pipeline_) (void)device_.destroy(pipeline_);
    for (rhi::ShaderHandle s : {fragment_shader_, vertex_shader_}) {
        if (s) (void)device_.destroy(s);
    }
}

Status ImGuiRenderer::reserve(rhi::BufferHandle& buffer, uint64_t& capacity, uint64_t bytes, rhi::BufferUsage usage,
                              const char* name) {
    if (bytes <= capacity && buffer) return {};
    const uint64_t size = std::max<uint64_t>(bytes + bytes / 2, 64 * 1024);
    auto created = device_.create_buffer(rhi::BufferDesc{name, size, usage});
    if (!created) return created.take_error();
    // Destroying waits for the GPU to finish with the old buffer (the device defers it).
    if (buffer) (void)device_.destroy(buffer);
    buffer = *created;
    capacity = size;
    return {};
}

Status ImGuiRenderer::record(rhi::CommandList& commands, rhi::TextureHandle target, const ImDrawData& data) {
    const float fb_width = data.DisplaySize.x * data.FramebufferScale.x;
    const float fb_height = data.DisplaySize.y * data.FramebufferScale.y;
    if (data.TotalVtxCount == 0 || fb_width <= 0.0f || fb_height <= 0.0f) return {};

    // Every list's vertices and indices, one after the other; draws address them by offsets.
    std::vector<ImDrawVert> vertices;
    std::vector<ImDrawIdx> indices;
    vertices.reserve(static_cast<std::size_t>(data.TotalVtxCount));
    indices.reserve(static_cast<std::size_t>(data.TotalIdxCount));
    for (int n = 0; n < data.CmdListsCount; ++n) {
        const ImDrawList* list = data.CmdLists[n];
        vertices.insert(vertices.end(), list->VtxBuffer.Data, list->VtxBuffer.Data + list->VtxBuffer.Size);
        indices.insert(indices.end(), list->IdxBuffer.Data, list->IdxBuffer.Data + list->IdxBuffer.Size);
    }
    const auto vertex_bytes = std::as_bytes(std::span(vertices));
    const auto index_bytes = std::as_bytes(std::span(indices));
    LOOM_TRY(reserve(vertices_, vertex_capacity_, vertex_bytes.size(), rhi::BufferUsage::Vertex, "imgui vertices"));
    LOOM_TRY(reserve(indices_, index_capacity_, index_bytes.size(), rhi::BufferUsage::Index, "imgui indices"));
    // Uploads are ordered before the frame's commands, and after the GPU's earlier use.
    LOOM_TRY(device_.write_buffer(vertices_, 0, vertex_bytes));
    LOOM_TRY(device_.write_buffer(indices_, 0, index_bytes));

    commands.transition(atlas_, rhi::ResourceState::ShaderRead);
    rhi::RenderPassDesc pass;
    pass.label = "imgui overlay";
    rhi::ColorAttachment color;
    color.texture = target;
    color.load = rhi::LoadOp::Load;
    pass.colors.push_back(color);
    commands.begin_render_pass(pass);
    commands.set_pipeline(pipeline_);
    commands.set_viewport({0.0f, 0.0f, fb_width, fb_height});
    Transform transform{};
    transform.scale[0] = 2.0f / data.DisplaySize.x;
    transform.scale[1] = -2.0f / data.DisplaySize.y;
    transform.translate[0] = -1.0f - data.DisplayPos.x * transform.scale[0];
    transform.translate[1] = 1.0f - data.DisplayPos.y * transform.scale[1];
    transform.linearize = rhi::format_info(target_format_).features.srgb ? 1.0f : 0.0f;
    commands.push_constants_of(transform);
    commands.set_bind_group(0, rhi::BindGroup{}.texture(0, atlas_, sampler_));
    commands.set_vertex_buffer(0, vertices_);
    commands.set_index_buffer(indices_, sizeof(ImDrawIdx) == 2 ? rhi::IndexType::Uint16 : rhi::IndexType::Uint32);

    const ImVec2 clip_offset = data.DisplayPos;
    const ImVec2 clip_scale = data.FramebufferScale;
    uint32_t vertex_base = 0, index_base = 0;
    for (int n = 0; n < data.CmdListsCount; ++n) {
        const ImDrawList* list = data.CmdLists[n];
        for (const ImDrawCmd& cmd : list->CmdBuffer) {
            if (cmd.UserCallback) {
                // The overlay's own windows never add callbacks; a reset request needs no action.
                if (cmd.UserCallback != ImDrawCallback_ResetRenderState) cmd.UserCallback(list, &cmd);
                continue;
            }
            // The clip rectangle in framebuffer pixels, inside the framebuffer.
            const float x0 = std::clamp((cmd.ClipRect.x - clip_offset.x) * clip_scale.x, 0.0f, fb_width);
            const float y0 = std::clamp((cmd.ClipRect.y - clip_offset.y) * clip_scale.y, 0.0f, fb_height);
            const float x1 = std::clamp((cmd.ClipRect.z - clip_offset.x) * clip_scale.x, 0.0f, fb_width);
            const float y1 = std::clamp((cmd.ClipRect.w - clip_offset.y) * clip_scale.y, 0.0f, fb_height);
            if (x1 <= x0 || y1 <= y0 || cmd.ElemCount == 0) continue;
            commands.set_scissor({static_cast<int32_t>(x0), static_cast<int32_t>(y0), static_cast<uint32_t>(x1 - x0),
                                  static_cast<uint32_t>(y1 - y0)});
            commands.draw_indexed(cmd.ElemCount, 1, index_base + cmd.IdxOffset,
                                  static_cast<int32_t>(vertex_base + cmd.VtxOffset));
        }
        vertex_base += static_cast<uint32_t>(list->VtxBuffer.Size);
        index_base += static_cast<uint32_t>(list->IdxBuffer.Size);
    }
    commands.end_render_pass();
    return {};
}

}  // namespace loom::overlay
