// GlDevice: creating and destroying textures, buffers, samplers, shaders and pipelines, and the
// framebuffer-object and vertex-array caches.
#include <algorithm>
#include <bit>

#include "gl_device.hpp"
#include "loom/rhi/subresources.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::gl {
namespace {

using rhi::has_any;

using rhi::validation::in_quotes;

uint64_t texture_bytes(const rhi::TextureDesc& d) {
    uint64_t total = 0;
    const uint64_t bpt = rhi::format_info(d.format).bytes_per_texel;
    for (uint32_t m = 0; m < d.mip_levels; ++m) {
        const rhi::Extent3D e = rhi::mip_extent(d, m);
        total += uint64_t{e.width} * e.height * rhi::mip_layers(d, m) * bpt * d.samples;
    }
    return total;
}

GLenum gl_filter(rhi::Filter f) { return f == rhi::Filter::Linear ? GL_LINEAR : GL_NEAREST; }

GLenum gl_address(rhi::AddressMode m) {
    switch (m) {
        case rhi::AddressMode::Repeat: return GL_REPEAT;
        case rhi::AddressMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
        case rhi::AddressMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case rhi::AddressMode::ClampToBorder: return GL_CLAMP_TO_BORDER;
    }
    return GL_CLAMP_TO_EDGE;
}

GLenum gl_compare(rhi::CompareOp op) {
    switch (op) {
        case rhi::CompareOp::Never: return GL_NEVER;
        case rhi::CompareOp::Less: return GL_LESS;
        case rhi::CompareOp::Equal: return GL_EQUAL;
        case rhi::CompareOp::LessEqual: return GL_LEQUAL;
        case rhi::CompareOp::Greater: return GL_GREATER;
        case rhi::CompareOp::NotEqual: return GL_NOTEQUAL;
        case rhi::CompareOp::GreaterEqual: return GL_GEQUAL;
        case rhi::CompareOp::Always: return GL_ALWAYS;
    }
    return GL_LESS;
}

GLenum gl_blend_factor(rhi::BlendFactor f) {
    switch (f) {
        case rhi::BlendFactor::Zero: return GL_ZERO;
        case rhi::BlendFactor::One: return GL_ONE;
        case rhi::BlendFactor::SrcColor: return GL_SRC_COLOR;
        case rhi::BlendFactor::OneMinusSrcColor: return GL_ONE_MINUS_SRC_COLOR;
        case rhi::BlendFactor::DstColor: return GL_DST_COLOR;
        case rhi::BlendFactor::OneMinusDstColor: return GL_ONE_MINUS_DST_COLOR;
        case rhi::BlendFactor::SrcAlpha: return GL_SRC_ALPHA;
        case rhi::BlendFactor::OneMinusSrcAlpha: return GL_ONE_MINUS_SRC_ALPHA;
        case rhi::BlendFactor::DstAlpha: return GL_DST_ALPHA;
        case rhi::BlendFactor::OneMinusDstAlpha: return GL_ONE_MINUS_DST_ALPHA;
        case rhi::BlendFactor::ConstantColor: return GL_CONSTANT_COLOR;
        case rhi::BlendFactor::OneMinusConstantColor: return GL_ONE_MINUS_CONSTANT_COLOR;
    }
    return GL_ONE;
}

GLenum gl_blend_op(rhi::BlendOp op) {
    switch (op) {
        case rhi::BlendOp::Add: return GL_FUNC_ADD;
        case rhi::BlendOp::Subtract: return GL_FUNC_SUBTRACT;
        case rhi::BlendOp::ReverseSubtract: return GL_FUNC_REVERSE_SUBTRACT;
        case rhi::BlendOp::Min: return GL_MIN;
        case rhi::BlendOp::Max: return GL_MAX;
    }
    return GL_FUNC_ADD;
}

GLenum gl_topology(rhi::PrimitiveTopology t) {
    switch (t) {
        case rhi::PrimitiveTopology::TriangleList: return GL_TRIANGLES;
        case rhi::PrimitiveTopology::TriangleStrip: return GL_TRIANGLE_STRIP;
        case rhi::PrimitiveTopology::LineList: return GL_LINES;
        case rhi::PrimitiveTopology::LineStrip: return GL_LINE_STRIP;
        case rhi::PrimitiveTopology::PointList: return GL_POINTS;
    }
    return GL_TRIANGLES;
}

/// Components, GL type, normalised, integer (glVertexArrayAttribIFormat) of a vertex format.
struct VertexFormatInfo {
    GLint components;
    GLenum type;
    bool normalized;
    bool integer;
};

VertexFormatInfo vertex_format_info(rhi::VertexFormat f) {
    using V = rhi::VertexFormat;
    switch (f) {
        case V::Float: return {1, GL_FLOAT, false, false};
        case V::Float2: return {2, GL_FLOAT, false, false};
        case V::Float3: return {3, GL_FLOAT, false, false};
        case V::Float4: return {4, GL_FLOAT, false, false};
        case V::Int: return {1, GL_INT, false, true};
        case V::Int2: return {2, GL_INT, false, true};
        case V::Int3: return {3, GL_INT, false, true};
        case V::Int4: return {4, GL_INT, false, true};
        case V::Uint: return {1, GL_UNSIGNED_INT, false, true};
        case V::Uint2: return {2, GL_UNSIGNED_INT, false, true};
        case V::Uint3: return {3, GL_UNSIGNED_INT, false, true};
        case V::Uint4: return {4, GL_UNSIGNED_INT, false, true};
        case V::UByte4Norm: return {4, GL_UNSIGNED_BYTE, true, false};
        case V::Byte4Norm: return {4, GL_BYTE, true, false};
        case V::UShort2Norm: return {2, GL_UNSIGNED_SHORT, true, false};
        case V::Short2Norm: return {2, GL_SHORT, true, false};
        case V::UShort4Norm: return {4, GL_UNSIGNED_SHORT, true, false};
        case V::Short4Norm: return {4, GL_SHORT, true, false};
    }
    return {4, GL_FLOAT, false, false};
}

std::string info_log(GLuint object, bool program) {
    GLint length = 0;
    if (program) {
        glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
    } else {
        glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
    }
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    if (program) {
        glGetProgramInfoLog(object, length, nullptr, log.data());
    } else {
        glGetShaderInfoLog(object, length, nullptr, log.data());
    }
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log;
}

void set_label(GLenum kind, GLuint object, const std::string& name) {
    if (!name.empty()) glObjectLabel(kind, object, static_cast<GLsizei>(name.size()), name.data());
}

}  // namespace

// ---- textures --------------------------------------------------------------------------------

GLenum texture_target(const rhi::TextureDesc& d) {
    switch (d.dimension) {
        case rhi::TextureDimension::Tex2D: return d.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
        case rhi::TextureDimension::Tex2DArray: return GL_TEXTURE_2D_ARRAY;
        case rhi::TextureDimension::Tex3D: return GL_TEXTURE_3D;
        case rhi::TextureDimension::Cube: return GL_TEXTURE_CUBE_MAP;
    }
    return GL_TEXTURE_2D;
}

Result<rhi::TextureHandle> GlDevice::create_texture(const rhi::TextureDesc& desc) {
    context_->make_current();
    return create_texture_internal(desc, false);
}

Result<rhi::TextureHandle> GlDevice::create_texture_internal(const rhi::TextureDesc& desc, bool internal) {
    LOOM_TRY(rhi::validation::texture_desc(desc, caps_));
    GlTexture t;
    t.desc = desc;
    t.target = texture_target(desc);
    t.format = gl_format(desc.format);
    t.bytes = texture_bytes(desc);
    t.internal = internal;
    glCreateTextures(t.target, 1, &t.name);
    const auto w = static_cast<GLsizei>(desc.width), h = static_cast<GLsizei>(desc.height);
    const auto levels = static_cast<GLsizei>(desc.mip_levels);
    switch (t.target) {
        case GL_TEXTURE_2D:
        case GL_TEXTURE_CUBE_MAP: glTextureStorage2D(t.name, levels, t.format->internal_format, w, h); break;
        case GL_TEXTURE_2D_MULTISAMPLE:
            glTextureStorage2DMultisample(t.name, static_cast<GLsizei>(desc.samples), t.format->internal_format, w, h, GL_TRUE);
            break;
        default:
            glTextureStorage3D(t.name, levels, t.format->internal_format, w, h, static_cast<GLsizei>(desc.depth_or_layers));
            break;
    }
    set_label(GL_TEXTURE, t.name, desc.name);
    t.set_all(rhi::ResourceState::Undefined);
    if (!internal) {
        ++stats_.textures;
        stats_.texture_bytes += t.bytes;
    }
    return textures_.insert(std::move(t));
}

Status GlDevice::destroy(rhi::TextureHandle texture) {
    context_->make_current();
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    if ((*found)->internal) {
        return Error{ErrorCode::InvalidArgument, "texture " + in_quotes((*found)->desc.name) + " belongs to the device"};
    }
    GlTexture t = std::move(*textures_.remove(texture));
    const GLuint name = t.name;
    // Views are loom's even on an imported texture.
    std::vector<GLuint> views = view_names(t);
    if (t.imported) {
        // The application's texture: only loom's framebuffers and views of it go.
        delete_later([this, name, views] {
            forget_framebuffers_with(name);
            if (!views.empty()) glDeleteTextures(static_cast<GLsizei>(views.size()), views.data());
        });
        return {};
    }
    --stats_.textures;
    stats_.texture_bytes -= t.bytes;
    delete_later([this, name, views] {
        forget_framebuffers_with(name);
        if (!views.empty()) glDeleteTextures(static_cast<GLsizei>(views.size()), views.data());
        glDeleteTextures(1, &name);
    });
    return {};
}

std::vector<GLuint> GlDevice::view_names(const GlTexture& t) {
    std::vector<GLuint> names;
    for (const auto& [key, view] : t.views) names.push_back(view);
    return names;
}

Result<GLuint> GlDevice::texture_view(GlTexture& t, const rhi::TextureRange& range, rhi::TextureKind kind) {
    GLenum target = GL_TEXTURE_2D;
    switch (kind) {
        case rhi::TextureKind::Tex2D: target = t.desc.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D; break;
        case rhi::TextureKind::Tex2DArray: target = t.desc.samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_ARRAY; break;
        case rhi::TextureKind::Tex3D: target = GL_TEXTURE_3D; break;
        case rhi::TextureKind::Cube: target = GL_TEXTURE_CUBE_MAP; break;
    }
    const std::array<uint32_t, 5> key{static_cast<uint32_t>(target), range.base_mip, range.mip_count, range.base_layer, range.layer_count};
    if (auto it = t.views.find(key); it != t.views.end()) return it->second;
    if (!t.immutable) {
        return Error{ErrorCode::Unsupported, "texture " + in_quotes(t.desc.name) +
                                                 ": a subresource range needs a texture view, and views need a texture made with "
                                                 "glTexStorage* (this imported one was not)"};
    }
    // glTextureView wants a name no target was ever bound to: glGenTextures, not glCreateTextures.
    GLuint view = 0;
    glGenTextures(1, &view);
    glTextureView(view, target, t.name, t.format->internal_format, range.base_mip, range.mip_count, range.base_layer, range.layer_count);
    set_label(GL_TEXTURE, view, t.desc.name + " (view)");
    t.views.emplace(key, view);
    return view;
}

Result<rhi::TextureDesc> GlDevice::texture_desc(rhi::TextureHandle texture) {
    auto found = textures_.get(texture);
    if (!found.ok()) return found.take_error();
    return (*found)->desc;
}

Result<rhi::BufferDesc> GlDevice::buffer_desc(rhi::BufferHandle buffer) {
    auto found = buffers_.get(buffer);
    if (!found.ok()) return found.take_error();
    return (*found)->desc;
}

// ---- buffers and samplers --------------------------------------------------------------------

Result<rhi::BufferHandle> GlDevice::create_buffer(const rhi::BufferDesc& desc) {
    context_->make_current();
    // Refuses placements: GL has no placed resources.
    LOOM_TRY(rhi::validation::buffer_desc(desc, caps_));
    GlBuffer b;
    b.desc = desc;
    glCreateBuffers(1, &b.name);
    // Dynamic storage: write_buffer updates it with glNamedBufferSubData.
    glNamedBufferStorage(b.name, static_cast<GLsizeiptr>(desc.size), nullptr, GL_DYNAMIC_STORAGE_BIT);
    set_label(GL_BUFFER, b.name, desc.name);
    ++stats_.buffers;
    stats_.buffer_bytes += desc.size;
    return buffers_.insert(std::move(b));
}

Status GlDevice::destroy(rhi::BufferHandle buffer) {
    context_->make_current();
    auto found = buffers_.get(buffer);
    if (!found.ok()) return found.take_error();
    if ((*found)->internal) {
        return Error{ErrorCode::InvalidArgument, "buffer " + in_quotes((*found)->desc.name) + " belongs to the device"};
    }
    GlBuffer b = std::move(*buffers_.remove(buffer));
    --stats_.buffers;
    stats_.buffer_bytes -= b.desc.size;
    const GLuint name = b.name;
    delete_later([name] { glDeleteBuffers(1, &name); });
    return {};
}

Result<rhi::SamplerHandle> GlDevice::create_sampler(const rhi::SamplerDesc& desc) {
    context_->make_current();
    LOOM_TRY(rhi::validation::sampler_desc(desc));
    GlSampler s;
    s.desc = desc;
    glCreateSamplers(1, &s.name);
    const GLenum min_filter = desc.min_filter == rhi::Filter::Linear
                                  ? (desc.mipmap_filter == rhi::Filter::Linear ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_NEAREST)
                                  : (desc.mipmap_filter == rhi::Filter::Linear ? GL_NEAREST_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(s.name, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min_filter));
    glSamplerParameteri(s.name, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_filter(desc.mag_filter)));
    glSamplerParameteri(s.name, GL_TEXTURE_WRAP_S, static_cast<GLint>(gl_address(desc.address_u)));
    glSamplerParameteri(s.name, GL_TEXTURE_WRAP_T, static_cast<GLint>(gl_address(desc.address_v)));
    glSamplerParameteri(s.name, GL_TEXTURE_WRAP_R, static_cast<GLint>(gl_address(desc.address_w)));
    glSamplerParameterf(s.name, GL_TEXTURE_MIN_LOD, desc.min_lod);
    glSamplerParameterf(s.name, GL_TEXTURE_MAX_LOD, desc.max_lod);
    if (desc.max_anisotropy > 1.0f && (epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
                                       epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic"))) {
        glSamplerParameterf(s.name, GL_TEXTURE_MAX_ANISOTROPY_EXT, desc.max_anisotropy);
    }
    if (desc.compare) {
        glSamplerParameteri(s.name, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(s.name, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(gl_compare(*desc.compare)));
    }
    const float black[4] = {0, 0, 0, 0}, opaque[4] = {0, 0, 0, 1}, white[4] = {1, 1, 1, 1};
    glSamplerParameterfv(s.name, GL_TEXTURE_BORDER_COLOR,
                         desc.border == rhi::BorderColor::OpaqueWhite   ? white
                         : desc.border == rhi::BorderColor::OpaqueBlack ? opaque
                                                                        : black);
    set_label(GL_SAMPLER, s.name, desc.name);
    ++stats_.samplers;
    return samplers_.insert(std::move(s));
}

Status GlDevice::destroy(rhi::SamplerHandle sampler) {
    context_->make_current();
    auto removed = samplers_.remove(sampler);
    if (!removed.ok()) return removed.take_error();
    --stats_.samplers;
    const GLuint name = removed->name;
    delete_later([name] { glDeleteSamplers(1, &name); });
    return {};
}

// ---- shaders and pipelines -------------------------------------------------------------------

Result<rhi::ShaderHandle> GlDevice::create_shader(const rhi::ShaderModule& module) {
    context_->make_current();
    const std::string what = "shader " + in_quotes(module.name) + " (" + std::string(rhi::shader_stage_name(module.stage)) + ")";
    if (module.gl_source.empty()) return Error{ErrorCode::InvalidArgument, what + ": gl_source is empty"};
    const GLenum type = module.stage == rhi::ShaderStage::Vertex     ? GL_VERTEX_SHADER
                        : module.stage == rhi::ShaderStage::Fragment ? GL_FRAGMENT_SHADER
                                                                     : GL_COMPUTE_SHADER;
    const GLuint shader = glCreateShader(type);
    const GLchar* source = module.gl_source.c_str();
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::string log = info_log(shader, false);
        glDeleteShader(shader);
        return Error{ErrorCode::ShaderCompile, what + ": the GL driver rejected the generated GLSL:\n" + log};
    }
    set_label(GL_SHADER, shader, module.name);
    GlShader s;
    s.name = module.name;
    s.stage = module.stage;
    s.reflection = module.reflection;
    s.name_gl = shader;
    ++stats_.shaders;
    return shaders_.insert(std::move(s));
}

Status GlDevice::destroy(rhi::ShaderHandle shader) {
    context_->make_current();
    auto removed = shaders_.remove(shader);
    if (!removed.ok()) return removed.take_error();
    --stats_.shaders;
    const GLuint name = removed->name_gl;
    delete_later([name] { glDeleteShader(name); });
    return {};
}

namespace {

/// Links `shaders` into a program and collects the bindings of their reflections.
Result<GlPipeline> link_program(const std::string& pipeline_name, std::initializer_list<const GlShader*> shaders,
                                const GlDevice::Limits& limits) {
    GlPipeline p;
    p.name = pipeline_name;
    const std::string what = "pipeline " + in_quotes(pipeline_name);
    auto add_binding = [&](uint32_t set, uint32_t binding, BindingKind kind, const std::string& name,
                           const GlShader& shader, GLenum access, rhi::TextureKind texture_kind = rhi::TextureKind::Tex2D) -> Status {
        if (set >= rhi::kMaxBindGroups || binding >= rhi::kMaxBindingsPerGroup) {
            return Error{ErrorCode::Unsupported, what + ": shader " + in_quotes(shader.name) + " uses set " +
                                                     std::to_string(set) + " binding " + std::to_string(binding) +
                                                     " beyond loom's " + std::to_string(rhi::kMaxBindGroups) + " sets of " +
                                                     std::to_string(rhi::kMaxBindingsPerGroup) + " bindings"};
        }
        const uint32_t point = rhi::gl_binding_point(set, binding);
        if (kind == BindingKind::StorageImage && point >= limits.max_image_units) {
            return Error{ErrorCode::Unsupported, what + ": storage image " + in_quotes(name) + " of shader " + in_quotes(shader.name) +
                                                     " (set " + std::to_string(set) + ", binding " + std::to_string(binding) +
                                                     ") maps to GL image unit " + std::to_string(point) + " but the driver has " +
                                                     std::to_string(limits.max_image_units)};
        }
        if (kind == BindingKind::StorageBuffer && point >= limits.max_storage_buffer_bindings) {
            return Error{ErrorCode::Unsupported, what + ": storage buffer " + in_quotes(name) + " of shader " +
                                                     in_quotes(shader.name) + " (set " + std::to_string(set) + ", binding " +
                                                     std::to_string(binding) + ") maps to GL storage binding " +
                                                     std::to_string(point) + " but the driver has " +
                                                     std::to_string(limits.max_storage_buffer_bindings)};
        }
        for (const PipelineBinding& existing : p.bindings) {
            if (existing.set == set && existing.binding == binding) {
                if (existing.kind != kind) {
                    return Error{ErrorCode::ShaderLink, what + ": set " + std::to_string(set) + " binding " +
                                                            std::to_string(binding) + " has different kinds in its stages"};
                }
                return {};
            }
        }
        p.bindings.push_back({set, binding, kind, name, access, texture_kind});
        return {};
    };
    for (const GlShader* shader : shaders) {
        const rhi::ShaderReflection& r = shader->reflection;
        for (const auto& u : r.uniform_blocks) LOOM_TRY(add_binding(u.set, u.binding, BindingKind::UniformBuffer, u.name, *shader, 0));
        for (const auto& s : r.storage_buffers) LOOM_TRY(add_binding(s.set, s.binding, BindingKind::StorageBuffer, s.name, *shader, 0));
        for (const auto& t : r.textures) {
            LOOM_TRY(add_binding(t.set, t.binding, BindingKind::SampledTexture, t.name, *shader, 0, t.kind));
        }
        for (const auto& i : r.storage_images) {
            const GLenum access = i.read_only ? GL_READ_ONLY : i.write_only ? GL_WRITE_ONLY : GL_READ_WRITE;
            LOOM_TRY(add_binding(i.set, i.binding, BindingKind::StorageImage, i.name, *shader, access, i.kind));
        }
        for (const auto& pc : r.push_constants) p.push_constant_size = std::max(p.push_constant_size, pc.size);
    }
    // In (set, binding) order, as Vulkan's set layouts list them: draws check them in this order.
    std::sort(p.bindings.begin(), p.bindings.end(), [](const PipelineBinding& a, const PipelineBinding& b) {
        return std::pair(a.set, a.binding) < std::pair(b.set, b.binding);
    });
    if (p.push_constant_size > kMaxPushConstantBytes) {
        return Error{ErrorCode::Unsupported, what + ": push constants of " + std::to_string(p.push_constant_size) +
                                                 " bytes exceed the " + std::to_string(kMaxPushConstantBytes) + " supported"};
    }
    p.program = glCreateProgram();
    for (const GlShader* shader : shaders) glAttachShader(p.program, shader->name_gl);
    glLinkProgram(p.program);
    for (const GlShader* shader : shaders) glDetachShader(p.program, shader->name_gl);
    GLint ok = GL_FALSE;
    glGetProgramiv(p.program, GL_LINK_STATUS, &ok);
    if (!ok) {
        std::string log = info_log(p.program, true);
        glDeleteProgram(p.program);
        std::string names;
        for (const GlShader* shader : shaders) names += (names.empty() ? "" : " + ") + in_quotes(shader->name);
        return Error{ErrorCode::ShaderLink, what + ": linking " + names + " failed:\n" + log};
    }
    set_label(GL_PROGRAM, p.program, pipeline_name);
    p.base_instance_location = glGetUniformLocation(p.program, "SPIRV_Cross_BaseInstance");
    return p;
}

}  // namespace

const rhi::validation::ResourceLookup& GlDevice::resource_lookup() {
    // Made once: every draw asks for it.
    if (!resource_lookup_.buffer) resource_lookup_ = rhi::validation::lookup_in(buffers_, textures_, samplers_);
    return resource_lookup_;
}

rhi::PipelineLookup GlDevice::pipeline_lookup() {
    return [this](rhi::PipelineHandle handle) -> Result<rhi::PipelineFacts> {
        auto found = pipelines_.get(handle);
        if (!found.ok()) return found.take_error();
        const GlPipeline& p = **found;
        return rhi::PipelineFacts{.name = p.name,
                                  .compute = p.compute,
                                  .color_formats = p.color_formats,
                                  .depth_format = p.depth_format,
                                  .samples = p.samples,
                                  .vertex_buffers = static_cast<uint32_t>(p.strides.size())};
    };
}

rhi::validation::ShaderLookup GlDevice::shader_lookup() {
    return [this](rhi::ShaderHandle handle) -> Result<rhi::validation::ShaderFacts> {
        auto found = shaders_.get(handle);
        if (!found.ok()) return found.take_error();
        return rhi::validation::ShaderFacts{(*found)->name, (*found)->stage, &(*found)->reflection};
    };
}

Result<rhi::PipelineHandle> GlDevice::create_graphics_pipeline(const rhi::GraphicsPipelineDesc& desc) {
    context_->make_current();
    LOOM_TRY(rhi::validation::graphics_pipeline(desc, caps_, shader_lookup()));
    // Both shaders were found by the validation above.
    const GlShader* vs = *shaders_.get(desc.vertex);
    const GlShader* fs = *shaders_.get(desc.fragment);
    auto linked = link_program(desc.name, {vs, fs}, limits_);
    if (!linked.ok()) return linked.take_error();
    GlPipeline p = std::move(*linked);
    auto vao = vertex_array_for(desc.vertex_buffers, p.vao_key);
    if (!vao.ok()) {
        glDeleteProgram(p.program);
        return vao.take_error();
    }
    p.vao = *vao;
    for (const auto& layout : desc.vertex_buffers) p.strides.push_back(layout.stride);
    p.topology = gl_topology(desc.topology);
    GlRasterState& r = p.raster;
    r.cull_enabled = desc.raster.cull != rhi::CullMode::None;
    r.cull_face = desc.raster.cull == rhi::CullMode::Front ? GL_FRONT : GL_BACK;
    // glClipControl(GL_UPPER_LEFT) flips y between NDC and window coordinates, but GL 4.5
    // (section 14.6.1, from ARB_clip_control) negates the polygon area term when the origin is
    // upper-left, so facing is decided as in y-up NDC and glFrontFace needs no correction. The
    // culling render test proves that a counter-clockwise NDC triangle is front-facing.
    r.front_face = desc.raster.front_face == rhi::FrontFace::CounterClockwise ? GL_CCW : GL_CW;
    r.polygon_mode = desc.raster.polygon == rhi::PolygonMode::Line ? GL_LINE : GL_FILL;
    r.depth_clamp = desc.raster.depth_clamp;
    r.depth_bias_constant = desc.raster.depth_bias_constant;
    r.depth_bias_slope = desc.raster.depth_bias_slope;
    r.depth_test = desc.depth.test;
    r.depth_write = desc.depth.write;
    r.depth_func = gl_compare(desc.depth.compare);
    for (std::size_t i = 0; i < desc.color_formats.size(); ++i) {
        GlBlendState b;
        if (i < desc.blend.size()) {
            const rhi::BlendState& s = desc.blend[i];
            b.enabled = s.enabled;
            b.src_color = gl_blend_factor(s.src_color);
            b.dst_color = gl_blend_factor(s.dst_color);
            b.color_op = gl_blend_op(s.color_op);
            b.src_alpha = gl_blend_factor(s.src_alpha);
            b.dst_alpha = gl_blend_factor(s.dst_alpha);
            b.alpha_op = gl_blend_op(s.alpha_op);
            b.write_mask = static_cast<uint8_t>(s.write_mask);
        }
        p.blend.push_back(b);
    }
    p.color_formats = desc.color_formats;
    p.depth_format = desc.depth_format;
    p.samples = desc.samples;
    ++stats_.pipelines;
    return pipelines_.insert(std::move(p));
}

Result<rhi::PipelineHandle> GlDevice::create_compute_pipeline(const rhi::ComputePipelineDesc& desc) {
    context_->make_current();
    LOOM_TRY(rhi::validation::compute_pipeline(desc, shader_lookup()));
    auto linked = link_program(desc.name, {*shaders_.get(desc.compute)}, limits_);
    if (!linked.ok()) return linked.take_error();
    linked->compute = true;
    ++stats_.pipelines;
    return pipelines_.insert(std::move(*linked));
}

Status GlDevice::destroy(rhi::PipelineHandle pipeline) {
    context_->make_current();
    auto removed = pipelines_.remove(pipeline);
    if (!removed.ok()) return removed.take_error();
    --stats_.pipelines;
    const GLuint program = removed->program;
    std::vector<uint32_t> key = removed->compute ? std::vector<uint32_t>{} : removed->vao_key;
    const bool compute = removed->compute;
    delete_later([this, program, key, compute] {
        glDeleteProgram(program);
        if (!compute) release_vertex_array(key);
    });
    return {};
}

// ---- caches ----------------------------------------------------------------------------------

Result<GLuint> GlDevice::vertex_array_for(const std::vector<rhi::VertexBufferLayout>& layout, std::vector<uint32_t>& key) {
    key.clear();
    for (const auto& slot : layout) {
        key.push_back(slot.stride);
        key.push_back(static_cast<uint32_t>(slot.step));
        key.push_back(static_cast<uint32_t>(slot.attributes.size()));
        for (const auto& a : slot.attributes) {
            key.push_back(a.location);
            key.push_back(static_cast<uint32_t>(a.format));
            key.push_back(a.offset);
        }
    }
    auto it = vertex_arrays_.find(key);
    if (it != vertex_arrays_.end()) {
        ++it->second.users;
        return it->second.vao;
    }
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    for (std::size_t slot = 0; slot < layout.size(); ++slot) {
        const auto s = static_cast<GLuint>(slot);
        glVertexArrayBindingDivisor(vao, s, layout[slot].step == rhi::VertexStepMode::PerInstance ? 1 : 0);
        for (const auto& a : layout[slot].attributes) {
            const VertexFormatInfo f = vertex_format_info(a.format);
            glEnableVertexArrayAttrib(vao, a.location);
            if (f.integer) {
                glVertexArrayAttribIFormat(vao, a.location, f.components, f.type, a.offset);
            } else {
                glVertexArrayAttribFormat(vao, a.location, f.components, f.type, f.normalized ? GL_TRUE : GL_FALSE, a.offset);
            }
            glVertexArrayAttribBinding(vao, a.location, s);
        }
    }
    vertex_arrays_[key] = VertexArrayEntry{vao, 1};
    return vao;
}

void GlDevice::release_vertex_array(const std::vector<uint32_t>& key) {
    auto it = vertex_arrays_.find(key);
    if (it == vertex_arrays_.end()) return;
    if (--it->second.users == 0) {
        glDeleteVertexArrays(1, &it->second.vao);
        vertex_arrays_.erase(it);
    }
}

GLuint GlDevice::framebuffer_for(const std::vector<std::pair<const GlTexture*, std::array<uint32_t, 2>>>& colors,
                                 const GlTexture* depth, std::array<uint32_t, 2> depth_mip_layer) {
    context_->make_current();  // recording may interleave with calls on another device
    std::vector<GLuint> key;
    for (const auto& [texture, mip_layer] : colors) key.insert(key.end(), {texture->name, mip_layer[0], mip_layer[1]});
    key.push_back(0);  // separates colours from depth
    if (depth) key.insert(key.end(), {depth->name, depth_mip_layer[0], depth_mip_layer[1]});
    auto it = framebuffers_.find(key);
    if (it != framebuffers_.end()) return it->second;

    GLuint fbo = 0;
    glCreateFramebuffers(1, &fbo);
    auto attach = [fbo](GLenum point, const GlTexture& t, uint32_t mip, uint32_t layer) {
        if (t.target == GL_TEXTURE_2D || t.target == GL_TEXTURE_2D_MULTISAMPLE) {
            glNamedFramebufferTexture(fbo, point, t.name, static_cast<GLint>(mip));
        } else {
            glNamedFramebufferTextureLayer(fbo, point, t.name, static_cast<GLint>(mip), static_cast<GLint>(layer));
        }
    };
    std::vector<GLenum> draw_buffers;
    for (std::size_t i = 0; i < colors.size(); ++i) {
        const GLenum point = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        attach(point, *colors[i].first, colors[i].second[0], colors[i].second[1]);
        draw_buffers.push_back(point);
    }
    if (depth) attach(attachment_point(depth->desc.format, 0), *depth, depth_mip_layer[0], depth_mip_layer[1]);
    if (draw_buffers.empty()) {
        glNamedFramebufferDrawBuffer(fbo, GL_NONE);
    } else {
        glNamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(draw_buffers.size()), draw_buffers.data());
    }
    glNamedFramebufferReadBuffer(fbo, draw_buffers.empty() ? GL_NONE : GL_COLOR_ATTACHMENT0);
    if (glCheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        glDeleteFramebuffers(1, &fbo);
        return 0;
    }
    framebuffers_[key] = fbo;
    return fbo;
}

void GlDevice::forget_framebuffers_with(GLuint texture) {
    for (auto it = framebuffers_.begin(); it != framebuffers_.end();) {
        const auto& key = it->first;
        bool uses = false;
        // Keys are triples (name, mip, layer) with one 0 separator before the depth triple.
        std::size_t i = 0;
        while (i < key.size()) {
            if (key[i] == 0) {
                ++i;
                continue;
            }
            if (key[i] == texture) uses = true;
            i += 3;
        }
        if (uses) {
            glDeleteFramebuffers(1, &it->second);
            it = framebuffers_.erase(it);
        } else {
            ++it;
        }
    }
}

void GlDevice::delete_later(std::function<void()> destroy_gl) {
    if (list_ && list_->recording()) {
        deferred_deletes_.push_back(std::move(destroy_gl));
        return;
    }
    destroy_gl();
    // GL may hand the deleted names out again; the cache must not trust them.
    cache_->invalidate();
}

}  // namespace loom::gl
