#pragma once
// The GL objects behind the RHI handles, as the device stores them.

#include <cstdint>
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
    /// The state the next recorded command sees (tracked while recording).
    rhi::ResourceState state = rhi::ResourceState::Undefined;
    uint64_t bytes = 0;
    /// Owned by the device (the window back buffer): not counted in ResourceStats.
    bool internal = false;
    /// Wraps an application texture (import_gl_texture): never deleted, not counted.
    bool imported = false;
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
