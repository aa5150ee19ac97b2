// SPIR-V -> reflection and GL GLSL through SPIRV-Cross. One code path serves compile() and
// from_spirv(), so a shader reflects the same whether it was compiled now or at build time.

#include "spirv_cross.hpp"

#include <algorithm>
#include <exception>
#include <string_view>
#include <vector>

#include <spirv_glsl.hpp>

namespace loom::shader_compiler::detail {

// Everything this library makes is an rhi::ShaderModule and its reflection.
using namespace loom::rhi;
namespace {

using spirv_cross::CompilerGLSL;
using spirv_cross::Resource;
using spirv_cross::SPIRType;

/// A reflection failure: which resource, and why.
struct ReflectError {
    std::string message;
};

BaseType to_base_type(SPIRType::BaseType type) {
    switch (type) {
        case SPIRType::Boolean: return BaseType::Bool;
        case SPIRType::Int: return BaseType::Int;
        case SPIRType::UInt: return BaseType::Uint;
        case SPIRType::Float: return BaseType::Float;
        case SPIRType::Double: return BaseType::Double;
        case SPIRType::Struct: return BaseType::Struct;
        default: return BaseType::Unknown;
    }
}

/// Element count of a (possibly multi-dimensional) array; 0 for a non-array or a runtime array.
uint32_t array_length(const SPIRType& type) {
    if (type.array.empty()) return 0;
    uint32_t count = 1;
    for (std::size_t i = 0; i < type.array.size(); ++i) {
        if (!type.array_size_literal[i]) return 0;  // sized by a specialisation constant
        count *= type.array[i];
    }
    return count;
}

ValueType to_value_type(const SPIRType& type) {
    ValueType value;
    value.base = to_base_type(type.basetype);
    value.vecsize = type.vecsize;
    value.columns = type.columns;
    value.array_size = array_length(type);
    return value;
}

std::string_view image_format_name(spv::ImageFormat format) {
    switch (format) {
        case spv::ImageFormatRgba32f: return "rgba32f";
        case spv::ImageFormatRgba16f: return "rgba16f";
        case spv::ImageFormatR32f: return "r32f";
        case spv::ImageFormatRgba8: return "rgba8";
        case spv::ImageFormatRgba8Snorm: return "rgba8_snorm";
        case spv::ImageFormatRg32f: return "rg32f";
        case spv::ImageFormatRg16f: return "rg16f";
        case spv::ImageFormatR11fG11fB10f: return "r11f_g11f_b10f";
        case spv::ImageFormatR16f: return "r16f";
        case spv::ImageFormatRgba16: return "rgba16";
        case spv::ImageFormatRgb10A2: return "rgb10_a2";
        case spv::ImageFormatRg16: return "rg16";
        case spv::ImageFormatRg8: return "rg8";
        case spv::ImageFormatR16: return "r16";
        case spv::ImageFormatR8: return "r8";
        case spv::ImageFormatRgba16Snorm: return "rgba16_snorm";
        case spv::ImageFormatRg16Snorm: return "rg16_snorm";
        case spv::ImageFormatRg8Snorm: return "rg8_snorm";
        case spv::ImageFormatR16Snorm: return "r16_snorm";
        case spv::ImageFormatR8Snorm: return "r8_snorm";
        case spv::ImageFormatRgba32i: return "rgba32i";
        case spv::ImageFormatRgba16i: return "rgba16i";
        case spv::ImageFormatRgba8i: return "rgba8i";
        case spv::ImageFormatR32i: return "r32i";
        case spv::ImageFormatRg32i: return "rg32i";
        case spv::ImageFormatRg16i: return "rg16i";
        case spv::ImageFormatRg8i: return "rg8i";
        case spv::ImageFormatR16i: return "r16i";
        case spv::ImageFormatR8i: return "r8i";
        case spv::ImageFormatRgba32ui: return "rgba32ui";
        case spv::ImageFormatRgba16ui: return "rgba16ui";
        case spv::ImageFormatRgba8ui: return "rgba8ui";
        case spv::ImageFormatR32ui: return "r32ui";
        case spv::ImageFormatRgb10a2ui: return "rgb10_a2ui";
        case spv::ImageFormatRg32ui: return "rg32ui";
        case spv::ImageFormatRg16ui: return "rg16ui";
        case spv::ImageFormatRg8ui: return "rg8ui";
        case spv::ImageFormatR16ui: return "r16ui";
        case spv::ImageFormatR8ui: return "r8ui";
        default: return "";
    }
}

spv::ExecutionModel execution_model(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex: return spv::ExecutionModelVertex;
        case ShaderStage::Fragment: return spv::ExecutionModelFragment;
        case ShaderStage::Compute: return spv::ExecutionModelGLCompute;
    }
    return spv::ExecutionModelVertex;
}

/// Reads reflection out of one SPIR-V module; collects every problem before failing.
class Reflector {
public:
    Reflector(const CompilerGLSL& compiler, const std::string& shader_name)
        : compiler_(compiler), shader_name_(shader_name) {}

    ShaderReflection reflect(const spirv_cross::ShaderResources& resources, ShaderStage stage) {
        ShaderReflection out;
        for (const Resource& res : resources.uniform_buffers) {
            UniformBlock block;
            block.name = block_name(res);
            bind_point(res, block.name, block.set, block.binding);
            reject_block_array(res, block.name);
            const SPIRType& type = compiler_.get_type(res.base_type_id);
            block.size = static_cast<uint32_t>(compiler_.get_declared_struct_size(type));
            block.members = members(type, res.base_type_id);
            out.uniform_blocks.push_back(std::move(block));
        }
        for (const Resource& res : resources.storage_buffers) {
            StorageBuffer buffer;
            buffer.name = block_name(res);
            bind_point(res, buffer.name, buffer.set, buffer.binding);
            reject_block_array(res, buffer.name);
            const SPIRType& type = compiler_.get_type(res.base_type_id);
            buffer.size = static_cast<uint32_t>(compiler_.get_declared_struct_size(type));
            buffer.read_only = compiler_.get_buffer_block_flags(res.id).get(spv::DecorationNonWritable);
            buffer.members = members(type, res.base_type_id);
            out.storage_buffers.push_back(std::move(buffer));
        }
        for (const Resource& res : resources.sampled_images) {
            SampledTexture texture;
            texture.name = variable_name(res);
            bind_point(res, texture.name, texture.set, texture.binding);
            const SPIRType& type = compiler_.get_type(res.type_id);
            texture.kind = texture_kind(type, texture.name, "sampler");
            texture.shadow = type.image.depth;
            texture.sampled_type = to_base_type(compiler_.get_type(type.image.type).basetype);
            texture.array_size = array_length(type);
            out.textures.push_back(std::move(texture));
        }
        for (const Resource& res : resources.storage_images) {
            StorageImage image;
            image.name = variable_name(res);
            bind_point(res, image.name, image.set, image.binding);
            const SPIRType& type = compiler_.get_type(res.type_id);
            image.kind = texture_kind(type, image.name, "storage image");
            if (!type.array.empty()) fail(image.name, "arrays of storage images are not supported");
            image.format = std::string(image_format_name(type.image.format));
            image.read_only = compiler_.has_decoration(res.id, spv::DecorationNonWritable);
            image.write_only = compiler_.has_decoration(res.id, spv::DecorationNonReadable);
            out.storage_images.push_back(std::move(image));
        }
        for (const Resource& res : resources.separate_images) {
            fail(variable_name(res), "separate images are not supported; use a combined image sampler (sampler2D)");
        }
        for (const Resource& res : resources.separate_samplers) {
            fail(variable_name(res), "separate samplers are not supported; use a combined image sampler (sampler2D)");
        }
        for (const Resource& res : resources.subpass_inputs) fail(variable_name(res), "subpass inputs are not supported");
        for (const Resource& res : resources.atomic_counters) fail(variable_name(res), "atomic counters are not supported");
        for (const Resource& res : resources.acceleration_structures) {
            fail(variable_name(res), "acceleration structures are not supported");
        }
        if (stage == ShaderStage::Vertex) out.inputs = stage_variables(resources.stage_inputs);
        if (stage == ShaderStage::Fragment) out.outputs = stage_variables(resources.stage_outputs);
        for (const Resource& res : resources.push_constant_buffers) {
            PushConstantBlock block;
            block.name = block_name(res);
            const SPIRType& type = compiler_.get_type(res.base_type_id);
            block.size = static_cast<uint32_t>(compiler_.get_declared_struct_size(type));
            block.members = members(type, res.base_type_id);
            out.push_constants.push_back(std::move(block));
        }
        if (stage == ShaderStage::Compute) {
            for (uint32_t axis = 0; axis < 3; ++axis) {
                out.workgroup_size[axis] = compiler_.get_execution_mode_argument(spv::ExecutionModeLocalSize, axis);
            }
        }
        sort_by_binding(out.uniform_blocks);
        sort_by_binding(out.storage_buffers);
        sort_by_binding(out.textures);
        sort_by_binding(out.storage_images);
        return out;
    }

    [[nodiscard]] const std::vector<std::string>& errors() const { return errors_; }

private:
    template <class T>
    static void sort_by_binding(std::vector<T>& items) {
        std::sort(items.begin(), items.end(), [](const T& a, const T& b) {
            return a.set != b.set ? a.set < b.set : a.binding < b.binding;
        });
    }

    void fail(const std::string& resource, const std::string& why) {
        errors_.push_back(shader_name_ + ": resource '" + resource + "': " + why);
    }

    /// The block's type name ("Camera" in `uniform Camera { ... } camera;`).
    std::string block_name(const Resource& res) const {
        std::string name = compiler_.get_name(res.base_type_id);
        if (name.empty()) name = compiler_.get_name(res.id);
        return name.empty() ? res.name : name;
    }

    std::string variable_name(const Resource& res) const {
        std::string name = compiler_.get_name(res.id);
        return name.empty() ? res.name : name;
    }

    void bind_point(const Resource& res, const std::string& name, uint32_t& set, uint32_t& binding) {
        set = compiler_.get_decoration(res.id, spv::DecorationDescriptorSet);
        binding = compiler_.get_decoration(res.id, spv::DecorationBinding);
        if (set >= kMaxBindGroups) {
            fail(name, "set " + std::to_string(set) + " is out of range (loom supports sets 0.." +
                           std::to_string(kMaxBindGroups - 1) + ")");
        }
        if (binding >= kMaxBindingsPerGroup) {
            fail(name, "binding " + std::to_string(binding) + " is out of range (loom supports bindings 0.." +
                           std::to_string(kMaxBindingsPerGroup - 1) + ")");
        }
    }

    void reject_block_array(const Resource& res, const std::string& name) {
        if (!compiler_.get_type(res.type_id).array.empty()) fail(name, "arrays of blocks are not supported");
    }

    TextureKind texture_kind(const SPIRType& type, const std::string& name, const char* what) {
        if (type.image.ms) {
            fail(name, std::string("multisampled ") + what + "s are not supported");
            return TextureKind::Tex2D;
        }
        switch (type.image.dim) {
            case spv::Dim2D: return type.image.arrayed ? TextureKind::Tex2DArray : TextureKind::Tex2D;
            case spv::Dim3D: return TextureKind::Tex3D;
            case spv::DimCube:
                if (type.image.arrayed) fail(name, std::string("cube-map array ") + what + "s are not supported");
                return TextureKind::Cube;
            default:
                fail(name, std::string(what) + " dimensionality is not supported (use 2D, 2D array, 3D or cube)");
                return TextureKind::Tex2D;
        }
    }

    std::vector<BlockMember> members(const SPIRType& type, uint32_t type_id) const {
        std::vector<BlockMember> out;
        for (uint32_t i = 0; i < type.member_types.size(); ++i) {
            const SPIRType& member_type = compiler_.get_type(type.member_types[i]);
            BlockMember member;
            member.name = compiler_.get_member_name(type_id, i);
            member.type = to_value_type(member_type);
            member.offset = compiler_.type_struct_member_offset(type, i);
            member.size = static_cast<uint32_t>(compiler_.get_declared_struct_member_size(type, i));
            if (!member_type.array.empty()) member.array_stride = compiler_.type_struct_member_array_stride(type, i);
            if (member_type.columns > 1) member.matrix_stride = compiler_.type_struct_member_matrix_stride(type, i);
            out.push_back(std::move(member));
        }
        return out;
    }

    std::vector<StageVariable> stage_variables(const spirv_cross::SmallVector<Resource>& resources) const {
        std::vector<StageVariable> out;
        for (const Resource& res : resources) {
            StageVariable variable;
            variable.name = variable_name(res);
            variable.location = compiler_.get_decoration(res.id, spv::DecorationLocation);
            variable.type = to_value_type(compiler_.get_type(res.type_id));
            out.push_back(std::move(variable));
        }
        std::sort(out.begin(), out.end(),
                  [](const StageVariable& a, const StageVariable& b) { return a.location < b.location; });
        return out;
    }

    const CompilerGLSL& compiler_;
    const std::string& shader_name_;
    std::vector<std::string> errors_;
};

/// Moves every (set, binding) to its GL binding point and the push constants to their UBO.
void remap_for_gl(CompilerGLSL& compiler, const spirv_cross::ShaderResources& resources) {
    auto remap = [&](const spirv_cross::SmallVector<Resource>& list) {
        for (const Resource& res : list) {
            const uint32_t set = compiler.get_decoration(res.id, spv::DecorationDescriptorSet);
            const uint32_t binding = compiler.get_decoration(res.id, spv::DecorationBinding);
            compiler.unset_decoration(res.id, spv::DecorationDescriptorSet);
            compiler.set_decoration(res.id, spv::DecorationBinding, gl_binding_point(set, binding));
        }
    };
    remap(resources.uniform_buffers);
    remap(resources.storage_buffers);
    remap(resources.sampled_images);
    remap(resources.storage_images);
    for (const Resource& res : resources.push_constant_buffers) {
        compiler.set_decoration(res.id, spv::DecorationBinding, kGlPushConstantBinding);
    }
}

std::string join_lines(const std::vector<std::string>& lines) {
    std::string out;
    for (const auto& line : lines) {
        if (!out.empty()) out += '\n';
        out += line;
    }
    return out;
}

}  // namespace

Result<ShaderModule> module_from_spirv(std::string name, ShaderStage stage, std::span<const uint32_t> spirv) {
    if (spirv.size() < 5 || spirv[0] != 0x07230203u) {
        return make_error(ErrorCode::ShaderCompile, name + ": not a SPIR-V module (bad size or magic number)");
    }
    try {
        CompilerGLSL compiler(spirv.data(), spirv.size());
        if (compiler.get_execution_model() != execution_model(stage)) {
            return make_error(ErrorCode::ShaderCompile, name + ": SPIR-V entry point is not a " +
                                                            std::string(shader_stage_name(stage)) + " shader");
        }
        const spirv_cross::ShaderResources resources = compiler.get_shader_resources();
        Reflector reflector(compiler, name);
        ShaderReflection reflection = reflector.reflect(resources, stage);
        if (!reflector.errors().empty()) {
            return make_error(ErrorCode::ShaderCompile, join_lines(reflector.errors()));
        }

        CompilerGLSL::Options options;
        options.version = 450;
        options.es = false;
        options.vulkan_semantics = false;
        options.emit_push_constant_as_uniform_buffer = true;
        // The GL backend sets glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE): GL then sees clip space
        // exactly like Vulkan, so no depth or y fixups may be emitted.
        options.vertex.fixup_clipspace = false;
        options.vertex.flip_vert_y = false;
        // gl_InstanceIndex includes the base instance in Vulkan; SPIRV-Cross adds the uniform
        // SPIRV_Cross_BaseInstance to gl_InstanceID (GL 4.5 has no gl_BaseInstance).
        options.vertex.support_nonzero_base_instance = true;
        compiler.set_common_options(options);
        remap_for_gl(compiler, resources);

        ShaderModule module;
        module.gl_source = compiler.compile();
        module.name = std::move(name);
        module.stage = stage;
        module.entry_point = "main";
        module.spirv.assign(spirv.begin(), spirv.end());
        module.reflection = std::move(reflection);
        return module;
    } catch (const std::exception& e) {
        std::string message = name + ": SPIRV-Cross: " + e.what();
        if (std::string_view(e.what()).find("cannot be expressed") != std::string_view::npos) {
            // Push constants become a std140 uniform block in GL and must keep their Vulkan
            // (std430) offsets there; arrays of scalars or vec2 have different strides.
            message += " (GL needs every push-constant and uniform block layout to be valid std140: "
                       "use arrays of vec4-sized elements)";
        }
        return make_error(ErrorCode::ShaderCompile, std::move(message));
    }
}

}  // namespace loom::shader_compiler::detail
