#include "formats.hpp"

#include <cmath>

namespace loom::vulkan {

using rhi::Format;

VkFormat to_vk_format(Format format) {
    switch (format) {
        case Format::Undefined: return VK_FORMAT_UNDEFINED;
        case Format::R8Unorm: return VK_FORMAT_R8_UNORM;
        case Format::R8Snorm: return VK_FORMAT_R8_SNORM;
        case Format::R8Uint: return VK_FORMAT_R8_UINT;
        case Format::R8Sint: return VK_FORMAT_R8_SINT;
        case Format::RG8Unorm: return VK_FORMAT_R8G8_UNORM;
        case Format::RG8Snorm: return VK_FORMAT_R8G8_SNORM;
        case Format::RG8Uint: return VK_FORMAT_R8G8_UINT;
        case Format::RG8Sint: return VK_FORMAT_R8G8_SINT;
        case Format::RGBA8Unorm: return VK_FORMAT_R8G8B8A8_UNORM;
        case Format::RGBA8Snorm: return VK_FORMAT_R8G8B8A8_SNORM;
        case Format::RGBA8Uint: return VK_FORMAT_R8G8B8A8_UINT;
        case Format::RGBA8Sint: return VK_FORMAT_R8G8B8A8_SINT;
        case Format::RGBA8Srgb: return VK_FORMAT_R8G8B8A8_SRGB;
        case Format::BGRA8Unorm: return VK_FORMAT_B8G8R8A8_UNORM;
        case Format::BGRA8Srgb: return VK_FORMAT_B8G8R8A8_SRGB;
        case Format::R16Unorm: return VK_FORMAT_R16_UNORM;
        case Format::RG16Unorm: return VK_FORMAT_R16G16_UNORM;
        case Format::RGBA16Unorm: return VK_FORMAT_R16G16B16A16_UNORM;
        case Format::R16Uint: return VK_FORMAT_R16_UINT;
        case Format::R16Sint: return VK_FORMAT_R16_SINT;
        case Format::R16Float: return VK_FORMAT_R16_SFLOAT;
        case Format::RG16Float: return VK_FORMAT_R16G16_SFLOAT;
        case Format::RGBA16Float: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case Format::R32Uint: return VK_FORMAT_R32_UINT;
        case Format::R32Sint: return VK_FORMAT_R32_SINT;
        case Format::R32Float: return VK_FORMAT_R32_SFLOAT;
        case Format::RG32Float: return VK_FORMAT_R32G32_SFLOAT;
        case Format::RGBA32Float: return VK_FORMAT_R32G32B32A32_SFLOAT;
        // loom's R11G11B10 has R in the low bits, as VK_FORMAT_B10G11R11_UFLOAT_PACK32 does.
        case Format::R11G11B10Float: return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
        // R in the low 10 bits, A in the top 2: Vulkan's A2B10G10R10.
        case Format::RGB10A2Unorm: return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
        case Format::RGB9E5Float: return VK_FORMAT_E5B9G9R9_UFLOAT_PACK32;
        case Format::Depth16: return VK_FORMAT_D16_UNORM;
        case Format::Depth24: return VK_FORMAT_X8_D24_UNORM_PACK32;
        case Format::Depth32F: return VK_FORMAT_D32_SFLOAT;
        case Format::Depth24Stencil8: return VK_FORMAT_D24_UNORM_S8_UINT;
        case Format::Depth32FStencil8: return VK_FORMAT_D32_SFLOAT_S8_UINT;
        case Format::Stencil8: return VK_FORMAT_S8_UINT;
    }
    return VK_FORMAT_UNDEFINED;
}

void query_format_capabilities(VkPhysicalDevice physical_device, rhi::Capabilities& caps) {
    for (Format f : rhi::all_formats()) {
        VkFormatProperties props{};
        vkGetPhysicalDeviceFormatProperties(physical_device, to_vk_format(f), &props);
        const VkFormatFeatureFlags features = props.optimalTilingFeatures;
        const bool transfer = (features & VK_FORMAT_FEATURE_TRANSFER_SRC_BIT) && (features & VK_FORMAT_FEATURE_TRANSFER_DST_BIT);
        rhi::FormatCapabilities& c = caps.formats[static_cast<std::size_t>(f)];
        // loom textures are always readable and writable through copies.
        if (!transfer) continue;
        c.sampled = features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
        c.filterable = c.sampled && (features & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT);
        c.color_attachment = features & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
        c.blendable = c.color_attachment && (features & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT);
        c.depth_stencil_attachment = features & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
        c.storage = features & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT;
        if (c.color_attachment || c.depth_stencil_attachment) {
            // The sample counts of a 2D attachment made the way image_create_info makes one.
            VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
            usage |= c.color_attachment ? VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT : VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
            if (c.sampled) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
            VkImageFormatProperties image{};
            if (vkGetPhysicalDeviceImageFormatProperties(physical_device, to_vk_format(f), VK_IMAGE_TYPE_2D, VK_IMAGE_TILING_OPTIMAL,
                                                         usage, 0, &image) == VK_SUCCESS) {
                c.sample_counts = static_cast<uint32_t>(image.sampleCounts) & 127u;
            }
        }
    }
}

VkCompareOp to_vk(rhi::CompareOp op) {
    switch (op) {
        case rhi::CompareOp::Never: return VK_COMPARE_OP_NEVER;
        case rhi::CompareOp::Less: return VK_COMPARE_OP_LESS;
        case rhi::CompareOp::Equal: return VK_COMPARE_OP_EQUAL;
        case rhi::CompareOp::LessEqual: return VK_COMPARE_OP_LESS_OR_EQUAL;
        case rhi::CompareOp::Greater: return VK_COMPARE_OP_GREATER;
        case rhi::CompareOp::NotEqual: return VK_COMPARE_OP_NOT_EQUAL;
        case rhi::CompareOp::GreaterEqual: return VK_COMPARE_OP_GREATER_OR_EQUAL;
        case rhi::CompareOp::Always: return VK_COMPARE_OP_ALWAYS;
    }
    return VK_COMPARE_OP_ALWAYS;
}

VkFilter to_vk(rhi::Filter filter) { return filter == rhi::Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }

VkSamplerMipmapMode to_vk_mipmap(rhi::Filter filter) {
    return filter == rhi::Filter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
}

VkSamplerAddressMode to_vk(rhi::AddressMode mode) {
    switch (mode) {
        case rhi::AddressMode::Repeat: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
        case rhi::AddressMode::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case rhi::AddressMode::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case rhi::AddressMode::ClampToBorder: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    }
    return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

VkBorderColor to_vk(rhi::BorderColor color) {
    switch (color) {
        case rhi::BorderColor::TransparentBlack: return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
        case rhi::BorderColor::OpaqueBlack: return VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
        case rhi::BorderColor::OpaqueWhite: return VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    }
    return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
}

VkFormat to_vk(rhi::VertexFormat format) {
    using V = rhi::VertexFormat;
    switch (format) {
        case V::Float: return VK_FORMAT_R32_SFLOAT;
        case V::Float2: return VK_FORMAT_R32G32_SFLOAT;
        case V::Float3: return VK_FORMAT_R32G32B32_SFLOAT;
        case V::Float4: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case V::Int: return VK_FORMAT_R32_SINT;
        case V::Int2: return VK_FORMAT_R32G32_SINT;
        case V::Int3: return VK_FORMAT_R32G32B32_SINT;
        case V::Int4: return VK_FORMAT_R32G32B32A32_SINT;
        case V::Uint: return VK_FORMAT_R32_UINT;
        case V::Uint2: return VK_FORMAT_R32G32_UINT;
        case V::Uint3: return VK_FORMAT_R32G32B32_UINT;
        case V::Uint4: return VK_FORMAT_R32G32B32A32_UINT;
        case V::UByte4Norm: return VK_FORMAT_R8G8B8A8_UNORM;
        case V::Byte4Norm: return VK_FORMAT_R8G8B8A8_SNORM;
        case V::UShort2Norm: return VK_FORMAT_R16G16_UNORM;
        case V::Short2Norm: return VK_FORMAT_R16G16_SNORM;
        case V::UShort4Norm: return VK_FORMAT_R16G16B16A16_UNORM;
        case V::Short4Norm: return VK_FORMAT_R16G16B16A16_SNORM;
    }
    return VK_FORMAT_UNDEFINED;
}

VkPrimitiveTopology to_vk(rhi::PrimitiveTopology topology) {
    switch (topology) {
        case rhi::PrimitiveTopology::TriangleList: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        case rhi::PrimitiveTopology::TriangleStrip: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        case rhi::PrimitiveTopology::LineList: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        case rhi::PrimitiveTopology::LineStrip: return VK_PRIMITIVE_TOPOLOGY_LINE_STRIP;
        case rhi::PrimitiveTopology::PointList: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    }
    return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags to_vk(rhi::CullMode mode) {
    switch (mode) {
        case rhi::CullMode::None: return VK_CULL_MODE_NONE;
        case rhi::CullMode::Front: return VK_CULL_MODE_FRONT_BIT;
        case rhi::CullMode::Back: return VK_CULL_MODE_BACK_BIT;
    }
    return VK_CULL_MODE_NONE;
}

// The viewport's negative height flips y from NDC to framebuffer, and Vulkan's facing test
// (the sign of the framebuffer-space area, y down) is the same flip: a triangle
// counter-clockwise in y-up NDC has positive area, so loom's winding maps one to one.
VkFrontFace to_vk(rhi::FrontFace face) {
    return face == rhi::FrontFace::CounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE : VK_FRONT_FACE_CLOCKWISE;
}

VkPolygonMode to_vk(rhi::PolygonMode mode) {
    return mode == rhi::PolygonMode::Line ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL;
}

VkBlendFactor to_vk(rhi::BlendFactor factor) {
    using B = rhi::BlendFactor;
    switch (factor) {
        case B::Zero: return VK_BLEND_FACTOR_ZERO;
        case B::One: return VK_BLEND_FACTOR_ONE;
        case B::SrcColor: return VK_BLEND_FACTOR_SRC_COLOR;
        case B::OneMinusSrcColor: return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
        case B::DstColor: return VK_BLEND_FACTOR_DST_COLOR;
        case B::OneMinusDstColor: return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
        case B::SrcAlpha: return VK_BLEND_FACTOR_SRC_ALPHA;
        case B::OneMinusSrcAlpha: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        case B::DstAlpha: return VK_BLEND_FACTOR_DST_ALPHA;
        case B::OneMinusDstAlpha: return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
        case B::ConstantColor: return VK_BLEND_FACTOR_CONSTANT_COLOR;
        case B::OneMinusConstantColor: return VK_BLEND_FACTOR_ONE_MINUS_CONSTANT_COLOR;
    }
    return VK_BLEND_FACTOR_ONE;
}

VkBlendOp to_vk(rhi::BlendOp op) {
    switch (op) {
        case rhi::BlendOp::Add: return VK_BLEND_OP_ADD;
        case rhi::BlendOp::Subtract: return VK_BLEND_OP_SUBTRACT;
        case rhi::BlendOp::ReverseSubtract: return VK_BLEND_OP_REVERSE_SUBTRACT;
        case rhi::BlendOp::Min: return VK_BLEND_OP_MIN;
        case rhi::BlendOp::Max: return VK_BLEND_OP_MAX;
    }
    return VK_BLEND_OP_ADD;
}

VkColorComponentFlags to_vk(rhi::ColorMask mask) {
    VkColorComponentFlags out = 0;
    if (rhi::has_all(mask, rhi::ColorMask::R)) out |= VK_COLOR_COMPONENT_R_BIT;
    if (rhi::has_all(mask, rhi::ColorMask::G)) out |= VK_COLOR_COMPONENT_G_BIT;
    if (rhi::has_all(mask, rhi::ColorMask::B)) out |= VK_COLOR_COMPONENT_B_BIT;
    if (rhi::has_all(mask, rhi::ColorMask::A)) out |= VK_COLOR_COMPONENT_A_BIT;
    return out;
}

VkAttachmentLoadOp to_vk(rhi::LoadOp op) {
    switch (op) {
        case rhi::LoadOp::Load: return VK_ATTACHMENT_LOAD_OP_LOAD;
        case rhi::LoadOp::Clear: return VK_ATTACHMENT_LOAD_OP_CLEAR;
        case rhi::LoadOp::DontCare: return VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    }
    return VK_ATTACHMENT_LOAD_OP_LOAD;
}

VkAttachmentStoreOp to_vk(rhi::StoreOp op) {
    return op == rhi::StoreOp::Store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
}

VkIndexType to_vk(rhi::IndexType type) {
    return type == rhi::IndexType::Uint16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32;
}

VkClearColorValue clear_color(Format format, const std::array<double, 4>& value) {
    VkClearColorValue out{};
    const rhi::ChannelKind kind = rhi::format_info(format).color_kind();
    for (std::size_t i = 0; i < 4; ++i) {
        if (kind == rhi::ChannelKind::Uint) {
            out.uint32[i] = static_cast<uint32_t>(std::llround(std::max(0.0, value[i])));
        } else if (kind == rhi::ChannelKind::Sint) {
            out.int32[i] = static_cast<int32_t>(std::llround(value[i]));
        } else {
            out.float32[i] = static_cast<float>(value[i]);
        }
    }
    return out;
}

}  // namespace loom::vulkan
