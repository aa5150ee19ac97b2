#pragma once
// Plain descriptions of GPU objects and of the work recorded on them (after sokol_gfx's desc
// structs and WebGPU's descriptors). Every field has a sensible default; a description that is
// wrong comes back from the Device as an InvalidArgument error naming the object and field.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "loom/rhi/format.hpp"
#include "loom/rhi/handles.hpp"
#include "loom/rhi/inline_vector.hpp"

namespace loom::rhi {

// ---- bit flags -------------------------------------------------------------------------------

/// Opt-in for the bit operators below: specialise to std::true_type for a flag enum.
template <class E>
struct EnableBitFlags : std::false_type {};

/// An enum that opted in to the bit operators.
template <class E>
concept BitFlags = EnableBitFlags<E>::value;

/// The union of two flag sets.
template <BitFlags E>
constexpr E operator|(E a, E b) {
    using U = std::underlying_type_t<E>;
    return static_cast<E>(static_cast<U>(a) | static_cast<U>(b));
}
/// The intersection of two flag sets.
template <BitFlags E>
constexpr E operator&(E a, E b) {
    using U = std::underlying_type_t<E>;
    return static_cast<E>(static_cast<U>(a) & static_cast<U>(b));
}
/// Adds the flags of `b` to `a`.
template <BitFlags E>
constexpr E& operator|=(E& a, E b) { return a = a | b; }
/// True when every flag of `wanted` is set in `flags`.
template <BitFlags E>
constexpr bool has_all(E flags, E wanted) { return (flags & wanted) == wanted; }
/// True when any flag of `wanted` is set in `flags`.
template <BitFlags E>
constexpr bool has_any(E flags, E wanted) { return static_cast<std::underlying_type_t<E>>(flags & wanted) != 0; }

// ---- textures --------------------------------------------------------------------------------

/// The shape of a texture: 2D, an array of 2D layers, a 3D volume, or a cube (6 layers).
enum class TextureDimension : uint8_t { Tex2D, Tex2DArray, Tex3D, Cube };

/// How a texture is used besides upload and readback (which are always allowed); flags.
enum class TextureUsage : uint32_t {
    None = 0,
    Sampled = 1u << 0,                 ///< read in shaders through a sampler
    ColorAttachment = 1u << 1,         ///< rendered to as a colour target
    DepthStencilAttachment = 1u << 2,  ///< rendered to as depth/stencil target
    Storage = 1u << 3,                 ///< read/written as a storage image
    CopySrc = 1u << 4,                 ///< source of copies and readback
    CopyDst = 1u << 5,                 ///< destination of copies and uploads
};
/// TextureUsage values combine with | and &.
template <>
struct EnableBitFlags<TextureUsage> : std::true_type {};

/// Where a texture lives inside a heap (memory aliasing). Offsets must respect the alignment
/// reported by Device::texture_memory_requirements.
struct TexturePlacement {
    HeapHandle heap;
    uint64_t offset = 0;
};

/// Everything a texture is created with (Device::create_texture).
struct TextureDesc {
    std::string name;  ///< shown in errors, debuggers and plans
    TextureDimension dimension = TextureDimension::Tex2D;
    Format format = Format::RGBA8Unorm;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t depth_or_layers = 1;  ///< depth for Tex3D, layers for arrays, 6 for Cube
    uint32_t mip_levels = 1;
    uint32_t samples = 1;
    /// Readback and upload are always allowed; these say how else the texture is used.
    TextureUsage usage = TextureUsage::Sampled | TextureUsage::ColorAttachment;
    /// Set to place the texture inside a heap (only where Capabilities::placed_resources).
    std::optional<TexturePlacement> placement;
};

/// Size and alignment a texture or buffer needs inside a heap.
struct MemoryRequirements {
    uint64_t size = 0;
    uint64_t alignment = 1;
};

/// A block of memory for placed textures and buffers (Device::create_heap).
struct HeapDesc {
    std::string name;
    uint64_t size = 0;
};

// ---- buffers ---------------------------------------------------------------------------------

/// How a buffer is used besides upload and readback (always allowed); flags.
enum class BufferUsage : uint32_t {
    None = 0,
    Vertex = 1u << 0,
    Index = 1u << 1,
    Uniform = 1u << 2,
    Storage = 1u << 3,
    Indirect = 1u << 4,
    CopySrc = 1u << 5,
    CopyDst = 1u << 6,
};
/// BufferUsage values combine with | and &.
template <>
struct EnableBitFlags<BufferUsage> : std::true_type {};

/// Where a buffer lives inside a heap (memory aliasing). Offsets respect the alignment of
/// Device::buffer_memory_requirements.
struct BufferPlacement {
    HeapHandle heap;
    uint64_t offset = 0;
};

/// Everything a buffer is created with (Device::create_buffer).
struct BufferDesc {
    std::string name;
    uint64_t size = 0;
    /// Uploads (Device::write_buffer) and readback are always allowed.
    BufferUsage usage = BufferUsage::Vertex;
    /// Set to place the buffer inside a heap (only where Capabilities::placed_resources). A
    /// placed buffer that overlaps another placed resource shares its bytes: whoever used them
    /// last owns them, and the buffer's contents are undefined until it is written again.
    /// (Braced so that `{name, size, usage}` initialisers need not mention it.)
    std::optional<BufferPlacement> placement{};
};

/// The type of the indices in an index buffer.
enum class IndexType : uint8_t { Uint16, Uint32 };

/// The arguments of one indexed draw as indirect draws read them from a buffer
/// (CommandList::draw_indexed_indirect): the layout of GL's DrawElementsIndirectCommand and of
/// VkDrawIndexedIndirectCommand, 20 bytes.
struct DrawIndexedIndirectCommand {
    uint32_t index_count = 0;
    uint32_t instance_count = 1;
    uint32_t first_index = 0;
    int32_t base_vertex = 0;
    uint32_t first_instance = 0;
};
static_assert(sizeof(DrawIndexedIndirectCommand) == 20, "indirect commands are read by the GPU as five 32-bit words");

// ---- samplers --------------------------------------------------------------------------------

/// Texel filtering: the nearest texel, or a linear blend of the neighbours.
enum class Filter : uint8_t { Nearest, Linear };
/// What a sampler reads outside [0, 1].
enum class AddressMode : uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };
/// A comparison, for depth tests and depth-comparison samplers.
enum class CompareOp : uint8_t { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };
/// The colour AddressMode::ClampToBorder reads outside the texture.
enum class BorderColor : uint8_t { TransparentBlack, OpaqueBlack, OpaqueWhite };

/// Everything a sampler is created with (Device::create_sampler).
struct SamplerDesc {
    std::string name;
    Filter min_filter = Filter::Linear;
    Filter mag_filter = Filter::Linear;
    Filter mipmap_filter = Filter::Nearest;
    AddressMode address_u = AddressMode::ClampToEdge;
    AddressMode address_v = AddressMode::ClampToEdge;
    AddressMode address_w = AddressMode::ClampToEdge;
    float min_lod = 0.0f;
    float max_lod = 1000.0f;
    float max_anisotropy = 1.0f;
    /// Set for depth-comparison (shadow) samplers.
    std::optional<CompareOp> compare;
    BorderColor border = BorderColor::TransparentBlack;
};

// ---- pipelines -------------------------------------------------------------------------------

/// The type of one vertex attribute in a vertex buffer.
enum class VertexFormat : uint8_t {
    Float, Float2, Float3, Float4,
    Int, Int2, Int3, Int4,
    Uint, Uint2, Uint3, Uint4,
    UByte4Norm, Byte4Norm, UShort2Norm, Short2Norm, UShort4Norm, Short4Norm,
};

/// Whether a vertex buffer advances per vertex or per instance.
enum class VertexStepMode : uint8_t { PerVertex, PerInstance };

/// One attribute read from a vertex buffer slot.
struct VertexAttribute {
    uint32_t location = 0;  ///< matches `layout(location = N) in` in the vertex shader
    VertexFormat format = VertexFormat::Float3;
    uint32_t offset = 0;
};

/// Vertex buffer slots (CommandList::set_vertex_buffer, GraphicsPipelineDesc::vertex_buffers).
inline constexpr uint32_t kMaxVertexBuffers = 16;

/// One vertex buffer slot: its stride and the attributes read from it.
struct VertexBufferLayout {
    uint32_t stride = 0;
    VertexStepMode step = VertexStepMode::PerVertex;
    std::vector<VertexAttribute> attributes;
};

/// How vertices form primitives.
enum class PrimitiveTopology : uint8_t { TriangleList, TriangleStrip, LineList, LineStrip, PointList };
/// Which faces are culled.
enum class CullMode : uint8_t { None, Front, Back };
/// Which winding, as seen in normalised device coordinates (y up), is the front face.
enum class FrontFace : uint8_t { CounterClockwise, Clockwise };
/// Filled triangles, or their edges (Line needs fillModeNonSolid on Vulkan).
enum class PolygonMode : uint8_t { Fill, Line };

/// Rasteriser state of a graphics pipeline: culling, facing, polygon mode, depth clamp and bias.
struct RasterState {
    CullMode cull = CullMode::None;
    FrontFace front_face = FrontFace::CounterClockwise;
    PolygonMode polygon = PolygonMode::Fill;
    bool depth_clamp = false;
    float depth_bias_constant = 0.0f;
    float depth_bias_slope = 0.0f;
};

/// Depth test and depth writes of a graphics pipeline.
struct DepthState {
    bool test = false;
    bool write = false;
    CompareOp compare = CompareOp::Less;
};

/// A factor of the blend equation.
enum class BlendFactor : uint8_t {
    Zero, One, SrcColor, OneMinusSrcColor, DstColor, OneMinusDstColor,
    SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha, ConstantColor, OneMinusConstantColor,
};
/// How the weighted source and destination are combined.
enum class BlendOp : uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

/// Which colour channels are written; flags.
enum class ColorMask : uint8_t { None = 0, R = 1, G = 2, B = 4, A = 8, All = 15 };
/// ColorMask values combine with | and &.
template <>
struct EnableBitFlags<ColorMask> : std::true_type {};

/// Blending and write mask of one colour attachment.
struct BlendState {
    bool enabled = false;
    BlendFactor src_color = BlendFactor::One;
    BlendFactor dst_color = BlendFactor::Zero;
    BlendOp color_op = BlendOp::Add;
    BlendFactor src_alpha = BlendFactor::One;
    BlendFactor dst_alpha = BlendFactor::Zero;
    BlendOp alpha_op = BlendOp::Add;
    ColorMask write_mask = ColorMask::All;

    /// "Over" for straight (not premultiplied) alpha: colour × alpha + behind × (1 − alpha);
    /// alpha accumulates as coverage (alpha + behind × (1 − alpha)).
    static BlendState over() {
        BlendState blend;
        blend.enabled = true;
        blend.src_color = BlendFactor::SrcAlpha;
        blend.dst_color = BlendFactor::OneMinusSrcAlpha;
        blend.src_alpha = BlendFactor::One;
        blend.dst_alpha = BlendFactor::OneMinusSrcAlpha;
        return blend;
    }
};

/// Everything a graphics pipeline is created with: shaders, vertex layout, fixed-function state and the formats it renders to.
struct GraphicsPipelineDesc {
    std::string name;
    ShaderHandle vertex;
    ShaderHandle fragment;
    std::vector<VertexBufferLayout> vertex_buffers;  ///< slot i is vertex_buffers[i]
    PrimitiveTopology topology = PrimitiveTopology::TriangleList;
    RasterState raster;
    DepthState depth;
    std::vector<Format> color_formats;  ///< one per colour attachment, in attachment order
    std::vector<BlendState> blend;      ///< per colour attachment; empty means no blending
    Format depth_format = Format::Undefined;
    uint32_t samples = 1;
};

/// A compute pipeline: one compute shader.
struct ComputePipelineDesc {
    std::string name;
    ShaderHandle compute;
};

// ---- render passes ---------------------------------------------------------------------------

/// What an attachment holds when a render pass begins: its contents, a clear value, or anything.
enum class LoadOp : uint8_t { Load, Clear, DontCare };
/// Whether an attachment's contents are kept after a render pass.
enum class StoreOp : uint8_t { Store, DontCare };

/// One colour attachment of a render pass: the texture (mip, layer) and its load/store actions.
struct ColorAttachment {
    TextureHandle texture;
    uint32_t mip = 0;
    uint32_t layer = 0;
    LoadOp load = LoadOp::Clear;
    StoreOp store = StoreOp::Store;
    /// Converted to the attachment's kind: float/unorm/snorm use it as is, integer formats
    /// round it (double holds every 32-bit integer exactly).
    std::array<double, 4> clear{0.0, 0.0, 0.0, 0.0};
};

/// The depth/stencil attachment of a render pass and its load/store actions.
struct DepthAttachment {
    TextureHandle texture;
    uint32_t mip = 0;
    uint32_t layer = 0;
    LoadOp depth_load = LoadOp::Clear;
    StoreOp depth_store = StoreOp::Store;
    float clear_depth = 1.0f;
    LoadOp stencil_load = LoadOp::DontCare;
    StoreOp stencil_store = StoreOp::DontCare;
    uint32_t clear_stencil = 0;
};

/// Colour attachments held without allocating: 8, as many as the devices loom knows allow.
inline constexpr std::size_t kInlineColorAttachments = 8;

/// Attachments must all have the same size (of the chosen mip). The backend moves them into
/// the attachment state itself; textures sampled inside the pass must have been transitioned
/// to ResourceState::ShaderRead before it begins. Built per frame, it allocates nothing: the
/// colour attachments are kept inside it (more than kInlineColorAttachments, which validation
/// refuses on every device loom knows, go to the heap), and a label the standard library keeps
/// in place (libstdc++ and libc++: up to 15 and 22 characters) or a reused one allocates nothing.
struct RenderPassDesc {
    std::string label;
    InlineVector<ColorAttachment, kInlineColorAttachments> colors;
    std::optional<DepthAttachment> depth;
};

/// Viewport in framebuffer pixels, origin top-left (row 0 is the top row).
struct Viewport {
    float x = 0.0f;
    float y = 0.0f;
    float width = 0.0f;
    float height = 0.0f;
    float min_depth = 0.0f;
    float max_depth = 1.0f;
};

/// Rectangle in framebuffer pixels, origin top-left.
struct Rect {
    int32_t x = 0;
    int32_t y = 0;
    uint32_t width = 0;
    uint32_t height = 0;
};

// ---- resource bindings -----------------------------------------------------------------------

/// A uniform or storage buffer range; size 0 means "to the end of the buffer".
struct BufferBinding {
    BufferHandle buffer;
    uint64_t offset = 0;
    uint64_t size = 0;
};

/// A count of TextureRange (and StorageTextureBinding::layer_count) meaning "to the last one".
inline constexpr uint32_t kRemainingSubresources = UINT32_MAX;

/// A range of mip levels and array layers of a texture. Counts of kRemainingSubresources mean
/// "to the last one"; the default is the whole texture. Layers are those of arrays and cubes
/// (a 2D or 3D texture has one).
struct TextureRange {
    uint32_t base_mip = 0;
    uint32_t mip_count = kRemainingSubresources;
    uint32_t base_layer = 0;
    uint32_t layer_count = kRemainingSubresources;
    friend bool operator==(const TextureRange&, const TextureRange&) = default;
};

/// A combined texture + sampler (`uniform sampler2D` in GLSL). `range` limits what the shader
/// sees to some mip levels and layers: its base_mip is the shader's level 0, its base_layer the
/// shader's layer 0. A range of one layer of an array texture can be bound to a `sampler2D`;
/// only the range's subresources need to be in ShaderRead (DepthRead).
struct TextureBinding {
    TextureHandle texture;
    SamplerHandle sampler;
    TextureRange range{};
};

/// A storage image (`uniform image2D` in GLSL): one mip level, and the layers base_layer ..
/// base_layer + layer_count - 1 of an array or cube (kRemainingSubresources: to the last). One
/// layer can be bound to an `image2D`, several to an `image2DArray`.
struct StorageTextureBinding {
    TextureHandle texture;
    uint32_t mip = 0;
    uint32_t base_layer = 0;
    uint32_t layer_count = kRemainingSubresources;
};

/// One entry of a bind group: what goes at `binding` of the set. Whether a buffer is bound as
/// uniform or storage buffer comes from the shader's reflection.
struct BindingEntry {
    uint32_t binding = 0;
    std::variant<BufferBinding, TextureBinding, StorageTextureBinding> resource;
};

/// The resources of one descriptor set (`layout(set = S, binding = B)`), built fluently:
/// `BindGroup{}.buffer(0, ubo).texture(1, albedo, sampler)`.
struct BindGroup {
    std::vector<BindingEntry> entries;

    /// Binds a uniform or storage buffer range (size 0: to the end) at `binding`.
    BindGroup& buffer(uint32_t binding, BufferHandle buf, uint64_t offset = 0, uint64_t size = 0) {
        entries.push_back({binding, BufferBinding{buf, offset, size}});
        return *this;
    }
    /// Binds a buffer range, e.g. one from CommandList::transient_uniforms, at `binding`.
    BindGroup& buffer(uint32_t binding, const BufferBinding& range) {
        entries.push_back({binding, range});
        return *this;
    }
    /// Binds a texture (the subresources in `range`; all by default) with a sampler
    /// (`sampler2D`, `sampler2DArray`, ...) at `binding`.
    BindGroup& texture(uint32_t binding, TextureHandle tex, SamplerHandle sampler, TextureRange range = {}) {
        entries.push_back({binding, TextureBinding{tex, sampler, range}});
        return *this;
    }
    /// Binds one mip level (and a range of layers) of a texture as a storage image at `binding`.
    BindGroup& storage_texture(uint32_t binding, TextureHandle tex, uint32_t mip = 0, uint32_t base_layer = 0,
                               uint32_t layer_count = kRemainingSubresources) {
        entries.push_back({binding, StorageTextureBinding{tex, mip, base_layer, layer_count}});
        return *this;
    }
};

// ---- resource states and copies --------------------------------------------------------------

/// The state a resource is in, for explicit transitions (Vulkan layouts and barriers; GL
/// memory barriers for storage access). Backends track each texture's current state.
enum class ResourceState : uint8_t {
    Undefined,         ///< contents may be discarded
    ShaderRead,        ///< sampled texture / uniform or read-only storage buffer
    RenderTarget,      ///< colour attachment
    DepthWrite,        ///< depth/stencil attachment, written
    DepthRead,         ///< depth/stencil attachment or texture, read-only
    Storage,           ///< storage image / buffer, read-write in shaders
    CopySrc,
    CopyDst,
    Present,           ///< handed to the window system
    VertexBuffer,
    IndexBuffer,
    IndirectArgument,
};

/// The name of a state as errors print it ("ShaderRead").
constexpr std::string_view resource_state_name(ResourceState state) {
    switch (state) {
        case ResourceState::Undefined: return "Undefined";
        case ResourceState::ShaderRead: return "ShaderRead";
        case ResourceState::RenderTarget: return "RenderTarget";
        case ResourceState::DepthWrite: return "DepthWrite";
        case ResourceState::DepthRead: return "DepthRead";
        case ResourceState::Storage: return "Storage";
        case ResourceState::CopySrc: return "CopySrc";
        case ResourceState::CopyDst: return "CopyDst";
        case ResourceState::Present: return "Present";
        case ResourceState::VertexBuffer: return "VertexBuffer";
        case ResourceState::IndexBuffer: return "IndexBuffer";
        case ResourceState::IndirectArgument: return "IndirectArgument";
    }
    return "?";
}

/// The queues a frame's commands go to (CommandList::set_queue).
enum class QueueType : uint8_t { Graphics, Compute };

/// "graphics" or "compute".
constexpr std::string_view queue_type_name(QueueType queue) {
    return queue == QueueType::Graphics ? "graphics" : "compute";
}

/// A point in one queue's commands of the frame being recorded, which the other queue can wait
/// for (CommandList::signal_queue, CommandList::wait_queue); valid until the frame ends.
struct QueueSignal {
    uint32_t index = UINT32_MAX;       ///< signals of the frame are numbered from 0
    QueueType queue = QueueType::Graphics;  ///< the queue that signals

    friend bool operator==(const QueueSignal&, const QueueSignal&) = default;
};

/// A texel position (x, y, and z for 3D textures).
struct Origin3D {
    uint32_t x = 0, y = 0, z = 0;
};
/// A size in texels (width, height, depth).
struct Extent3D {
    uint32_t width = 1, height = 1, depth = 1;
};

/// A rectangle of one mip level and layer of a texture (rows top-first).
struct TextureRegion {
    uint32_t mip = 0;
    uint32_t layer = 0;
    Origin3D origin{};
    /// 0 means "the whole mip level" in that dimension.
    Extent3D extent{0, 0, 0};
};

/// A copy between two textures (CommandList::copy_texture).
struct TextureCopy {
    TextureHandle src;
    TextureRegion src_region;
    TextureHandle dst;
    TextureRegion dst_region;  ///< its extent is ignored; src_region's is used
};

}  // namespace loom::rhi
