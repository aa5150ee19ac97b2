#pragma once
// Compiled shaders: SPIR-V for Vulkan, GLSL 450 for GL (both from one GLSL 450 source with
// Vulkan-style set/binding decorations), and the reflection both backends build layouts from.

#include <cstdint>
#include <string>
#include <vector>

namespace loom::rhi {

/// The pipeline stage a shader runs in.
enum class ShaderStage : uint8_t { Vertex, Fragment, Compute };

/// "vertex", "fragment" or "compute".
std::string_view shader_stage_name(ShaderStage stage);

/// Scalar type of a reflected variable.
enum class BaseType : uint8_t { Unknown, Bool, Int, Uint, Float, Double, Struct };

/// A reflected value type: base type, vector size (1..4), columns (1 for non-matrices) and
/// array length (0 when not an array).
struct ValueType {
    BaseType base = BaseType::Unknown;
    uint32_t vecsize = 1;
    uint32_t columns = 1;
    uint32_t array_size = 0;
    friend bool operator==(const ValueType&, const ValueType&) = default;
};

/// A member of a uniform/storage/push-constant block, with its std140/std430 offset.
struct BlockMember {
    std::string name;
    ValueType type;
    uint32_t offset = 0;
    uint32_t size = 0;          ///< bytes the member occupies (whole array for arrays)
    uint32_t array_stride = 0;  ///< for arrays
    uint32_t matrix_stride = 0; ///< for matrices
    friend bool operator==(const BlockMember&, const BlockMember&) = default;
};

/// A reflected uniform block (`layout(set, binding) uniform Name { ... }`).
struct UniformBlock {
    std::string name;  ///< block (type) name
    uint32_t set = 0;
    uint32_t binding = 0;
    uint32_t size = 0;  ///< declared size in bytes
    std::vector<BlockMember> members;
    friend bool operator==(const UniformBlock&, const UniformBlock&) = default;
};

/// A reflected storage buffer (`layout(set, binding) buffer Name { ... }`).
struct StorageBuffer {
    std::string name;
    uint32_t set = 0;
    uint32_t binding = 0;
    uint32_t size = 0;  ///< size without a trailing runtime array
    bool read_only = false;
    std::vector<BlockMember> members;
    friend bool operator==(const StorageBuffer&, const StorageBuffer&) = default;
};

/// The dimension a shader samples or writes a texture as.
enum class TextureKind : uint8_t { Tex2D, Tex2DArray, Tex3D, Cube };

/// A combined image sampler (`sampler2D`, `sampler2DShadow`, ...).
struct SampledTexture {
    std::string name;
    uint32_t set = 0;
    uint32_t binding = 0;
    TextureKind kind = TextureKind::Tex2D;
    bool shadow = false;        ///< a depth-comparison sampler
    BaseType sampled_type = BaseType::Float;  ///< Float, Int (isampler) or Uint (usampler)
    uint32_t array_size = 0;    ///< 0 when not an array of samplers
    friend bool operator==(const SampledTexture&, const SampledTexture&) = default;
};

/// A storage image (`image2D`).
struct StorageImage {
    std::string name;
    uint32_t set = 0;
    uint32_t binding = 0;
    TextureKind kind = TextureKind::Tex2D;
    std::string format;  ///< the GLSL layout qualifier, e.g. "rgba8"
    bool read_only = false;
    bool write_only = false;
    friend bool operator==(const StorageImage&, const StorageImage&) = default;
};

/// A stage input or output (`layout(location = N) in vec3 position`).
struct StageVariable {
    std::string name;
    uint32_t location = 0;
    ValueType type;
    friend bool operator==(const StageVariable&, const StageVariable&) = default;
};

/// The reflected push-constant block (a uniform buffer at kGlPushConstantBinding on GL).
struct PushConstantBlock {
    std::string name;
    uint32_t size = 0;
    std::vector<BlockMember> members;
    friend bool operator==(const PushConstantBlock&, const PushConstantBlock&) = default;
};

/// Everything a shader declares: resources by (set, binding), stage inputs/outputs, push constants, work group size.
struct ShaderReflection {
    std::vector<UniformBlock> uniform_blocks;
    std::vector<StorageBuffer> storage_buffers;
    std::vector<SampledTexture> textures;
    std::vector<StorageImage> storage_images;
    std::vector<StageVariable> inputs;    ///< vertex inputs for a vertex shader
    std::vector<StageVariable> outputs;   ///< fragment outputs for a fragment shader
    std::vector<PushConstantBlock> push_constants;  ///< at most one
    uint32_t workgroup_size[3] = {1, 1, 1};         ///< compute shaders
};

/// Number of descriptor sets and bindings per set loom supports on every backend.
inline constexpr uint32_t kMaxBindGroups = 4;
inline constexpr uint32_t kMaxBindingsPerGroup = 16;
/// Bytes of push constants (CommandList::push_constants) on every backend (Vulkan guarantees
/// only 128; lavapipe and the desktop drivers loom runs on have 256).
inline constexpr uint32_t kMaxPushConstantBytes = 256;

/// The GL binding point of Vulkan-style (set, binding): the one place where that mapping is
/// defined. GL has a separate binding namespace per resource kind (uniform buffers, texture
/// units, image units, storage buffers). Uniform buffers and texture units have room for all
/// kMaxBindGroups * kMaxBindingsPerGroup points on any GL 4.5 driver; image units and storage
/// buffer bindings may have as few as 8, so the GL backend checks those against the driver's
/// limits and reports Unsupported, naming the shader and binding, when a point is out of range.
constexpr uint32_t gl_binding_point(uint32_t set, uint32_t binding) {
    return set * kMaxBindingsPerGroup + binding;
}

/// GL uniform-buffer binding that emulates Vulkan push constants.
inline constexpr uint32_t kGlPushConstantBinding = kMaxBindGroups * kMaxBindingsPerGroup;

/// A compiled shader stage, ready for Device::create_shader.
struct ShaderModule {
    std::string name;  ///< source file or composed name, used in errors
    ShaderStage stage = ShaderStage::Vertex;
    std::string entry_point = "main";
    std::vector<uint32_t> spirv;  ///< SPIR-V for Vulkan
    std::string gl_source;        ///< GLSL 450 core for GL, bindings remapped with gl_binding_point
    ShaderReflection reflection;
};

}  // namespace loom::rhi
