#pragma once
// The GL objects behind the RHI handles, as the device stores them.

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "gl_formats.hpp"
#include "gl_state_cache.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/shader.hpp"
#include "loom/rhi/validation.hpp"

namespace loom::gl {

struct GlTexture {
    rhi::TextureDesc desc;
    GLuint name = 0;
    GLenum target = 0;
    const GlFormat* format = nullptr;
    /// The state the next recorded command sees, per subresource (index mip * layers() +
    /// layer), tracked while recording. GL orders everything but storage writes by itself; the
    /// states say where a storage write needs a glMemoryBarrier before the next use, and keep
    /// the checks of sampled and storage bindings the same as on Vulkan.
    std::vector<rhi::ResourceState> states;
    uint64_t bytes = 0;
    /// Owned by the device (the window back buffer): not counted in ResourceStats.
    bool internal = false;
    /// Wraps an application texture (import_gl_texture): never deleted, not counted.
    bool imported = false;
    /// Made with glTextureStorage* (loom's own always; imports maybe not): views need it.
    bool immutable = true;
    /// Texture views of subresource ranges (glTextureView), made on first use and deleted with
    /// the texture: by {view target, base mip, mips, base layer, layers}.
    std::map<std::array<uint32_t, 5>, GLuint> views;

    /// Layers as TextureRange counts them: of arrays and cubes; 1 for 2D and 3D textures.
    [[nodiscard]] uint32_t layers() const { return rhi::validation::range_layers(desc); }
    [[nodiscard]] std::size_t subresource(uint32_t mip, uint32_t layer) const { return std::size_t{mip} * layers() + layer; }
    /// Every subresource in `state` (creation, imports, the back buffer each frame).
    void set_all(rhi::ResourceState state) { states.assign(std::size_t{desc.mip_levels} * layers(), state); }
    /// Each subresource of a (resolved) range.
    template <class F>
    void for_each_in(const rhi::TextureRange& r, F&& f) const {
        for (uint32_t m = r.base_mip; m < r.base_mip + r.mip_count; ++m) {
            for (uint32_t l = r.base_layer; l < r.base_layer + r.layer_count; ++l) f(subresource(m, l));
        }
    }
};

/// The GL texture target of a description (2D, 2D multisample, 2D array, 3D, cube).
GLenum texture_target(const rhi::TextureDesc& desc);

struct GlBuffer {
    rhi::BufferDesc desc;
    GLuint name = 0;
    rhi::ResourceState state = rhi::ResourceState::Undefined;
    /// Owned by the device (transient uniform memory): not counted in ResourceStats.
    bool internal = false;
};

struct GlSampler {
    rhi::SamplerDesc desc;
    GLuint name = 0;
};

struct GlShader {
    std::string name;
    rhi::ShaderStage stage = rhi::ShaderStage::Vertex;
    rhi::ShaderReflection reflection;
    GLuint name_gl = 0;
};

/// What a pipeline expects at one (set, binding), from the reflection of its stages.
using BindingKind = rhi::validation::BindingKind;

struct PipelineBinding {
    uint32_t set = 0;
    uint32_t binding = 0;
    BindingKind kind = BindingKind::UniformBuffer;
    std::string name;  ///< the GLSL name, for error messages
    GLenum image_access = GL_READ_WRITE;
    /// Textures and storage images: the declared dimension (the target of a view).
    rhi::TextureKind texture_kind = rhi::TextureKind::Tex2D;
};

struct GlPipeline {
    std::string name;
    bool compute = false;
    GLuint program = 0;
    std::vector<PipelineBinding> bindings;
    uint32_t push_constant_size = 0;  ///< 0 when the pipeline has no push constants
    /// SPIRV-Cross emulates gl_InstanceIndex's base instance with this uniform (-1 if unused).
    GLint base_instance_location = -1;

    // graphics only
    GLuint vao = 0;
    std::vector<uint32_t> vao_key;
    std::vector<uint32_t> strides;  ///< per vertex buffer slot
    GLenum topology = GL_TRIANGLES;
    GlRasterState raster;
    std::vector<GlBlendState> blend;  ///< one per colour attachment
    std::vector<rhi::Format> color_formats;
    rhi::Format depth_format = rhi::Format::Undefined;
    uint32_t samples = 1;
};

}  // namespace loom::gl
