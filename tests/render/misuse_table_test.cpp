// The misuse table: every rule of the shared validation layer (loom/rhi/validation.hpp) and of
// the command-list state tracker (loom/rhi/command_list_state.hpp), broken once on a real device
// of each backend, must give the same ErrorCode and the same message on every backend. The
// expected message is written here in full; where it quotes a device limit or depends on a
// device capability, the row computes it from the device's Capabilities, so the same rule reads
// the same on two devices with the same limits.
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "loom/rhi/validation.hpp"
#include "loom_test/render_fixture.hpp"
#include "render_helpers.hpp"

namespace loom::test {
namespace {

using rhi::Format;
using rhi::TextureDimension;
using rhi::TextureUsage;

struct Expected {
    ErrorCode code = ErrorCode::InvalidArgument;
    std::string message;
};

struct Row {
    std::string rule;
    /// Whether the device can host this misuse at all (e.g. a multisampled depth texture).
    std::function<bool(const rhi::Capabilities&)> applies;
    /// The misuse; returns what the device said.
    std::function<Status(rhi::Device&)> misuse;
    /// Asked after the misuse, which may note what the message quotes (a stale handle's words).
    std::function<Expected(const rhi::Capabilities&)> expected;
};

bool always(const rhi::Capabilities&) { return true; }

std::function<Expected(const rhi::Capabilities&)> invalid(std::string message) {
    return [message](const rhi::Capabilities&) { return Expected{ErrorCode::InvalidArgument, message}; };
}
std::function<Expected(const rhi::Capabilities&)> expect(Expected expected) {
    return [expected](const rhi::Capabilities&) { return expected; };
}
std::function<Expected(const rhi::Capabilities&)> unsupported(std::string message) {
    return [message](const rhi::Capabilities&) { return Expected{ErrorCode::Unsupported, message}; };
}
std::function<Expected(const rhi::Capabilities&)> wrong_state(std::string message) {
    return [message](const rhi::Capabilities&) { return Expected{ErrorCode::InvalidState, message}; };
}

rhi::TextureDesc texture(const std::string& name, uint32_t width = 4, uint32_t height = 4) {
    rhi::TextureDesc desc;
    desc.name = name;
    desc.width = width;
    desc.height = height;
    desc.usage = TextureUsage::Sampled;
    return desc;
}

Status create(rhi::Device& device, const rhi::TextureDesc& desc) {
    auto made = device.create_texture(desc);
    if (!made.ok()) return made.take_error();
    return device.destroy(*made);
}

// Runs `use` on a texture made from `desc`, then destroys it.
Status with_texture(rhi::Device& device, const rhi::TextureDesc& desc, const std::function<Status(rhi::TextureHandle)>& use) {
    auto made = device.create_texture(desc);
    if (!made.ok()) return Error{ErrorCode::Backend, "setup: " + made.error().to_string()};
    Status status = use(*made);
    LOOM_TRY(device.destroy(*made));
    return status;
}

Status with_buffer(rhi::Device& device, uint64_t size, const std::function<Status(rhi::BufferHandle)>& use,
                   rhi::BufferUsage usage = rhi::BufferUsage::Vertex) {
    rhi::BufferDesc desc;
    desc.name = "b";
    desc.size = size;
    desc.usage = usage;
    auto made = device.create_buffer(desc);
    if (!made.ok()) return Error{ErrorCode::Backend, "setup: " + made.error().to_string()};
    Status status = use(*made);
    LOOM_TRY(device.destroy(*made));
    return status;
}

Status read(rhi::Device& device, rhi::TextureHandle t, uint32_t mip, uint32_t layer) {
    auto image = device.read_texture(t, mip, layer);
    return image.ok() ? Status{} : Status(image.take_error());
}

std::vector<Row> table() {
    std::vector<Row> rows;
    auto add = [&](std::string rule, std::function<Status(rhi::Device&)> misuse, std::function<Expected(const rhi::Capabilities&)> expected,
                   std::function<bool(const rhi::Capabilities&)> applies = always) {
        rows.push_back({std::move(rule), std::move(applies), std::move(misuse), std::move(expected)});
    };

    // ---- texture descriptions
    add("format Undefined", [](rhi::Device& d) { auto t = texture("t"); t.format = Format::Undefined; return create(d, t); },
        invalid("texture 't': format is Undefined"));
    add("zero size", [](rhi::Device& d) { return create(d, texture("t", 0, 4)); },
        invalid("texture 't': size 0x4x1 has a zero dimension"));
    add("layers on Tex2D", [](rhi::Device& d) { auto t = texture("t"); t.depth_or_layers = 2; return create(d, t); },
        invalid("texture 't': depth_or_layers is 2; a Tex2D texture has 1 (Tex2DArray has layers)"));
    add("cube with 5 faces", [](rhi::Device& d) { auto t = texture("t"); t.dimension = TextureDimension::Cube; t.depth_or_layers = 5; return create(d, t); },
        invalid("texture 't': depth_or_layers is 5; a Cube texture has 6"));
    add("cube not square", [](rhi::Device& d) { auto t = texture("t", 8, 4); t.dimension = TextureDimension::Cube; t.depth_or_layers = 6; return create(d, t); },
        invalid("texture 't': the faces of a Cube texture must be square, not 8x4"));
    add("3D depth format", [](rhi::Device& d) { auto t = texture("t"); t.dimension = TextureDimension::Tex3D; t.format = Format::Depth32F; t.depth_or_layers = 4; return create(d, t); },
        invalid("texture 't': a Tex3D texture cannot have the depth/stencil format Depth32F"));
    add("mip_levels 0", [](rhi::Device& d) { auto t = texture("t"); t.mip_levels = 0; return create(d, t); },
        invalid("texture 't': mip_levels 0 is not in 1..3 for a 4x4x1 texture"));
    add("mip_levels past the chain", [](rhi::Device& d) { auto t = texture("t", 8, 2); t.mip_levels = 5; return create(d, t); },
        invalid("texture 't': mip_levels 5 is not in 1..4 for a 8x2x1 texture"));
    add("3D mips count depth", [](rhi::Device& d) { auto t = texture("t", 2, 2); t.dimension = TextureDimension::Tex3D; t.depth_or_layers = 16; t.mip_levels = 6; return create(d, t); },
        invalid("texture 't': mip_levels 6 is not in 1..5 for a 2x2x16 texture"));
    add("samples 3", [](rhi::Device& d) { auto t = texture("t"); t.samples = 3; return create(d, t); },
        invalid("texture 't': samples 3 is not a power of two from 1 to 64"));
    add("samples 128", [](rhi::Device& d) { auto t = texture("t"); t.samples = 128; return create(d, t); },
        invalid("texture 't': samples 128 is not a power of two from 1 to 64"));
    add("multisampled array", [](rhi::Device& d) { auto t = texture("t"); t.dimension = TextureDimension::Tex2DArray; t.depth_or_layers = 2; t.samples = 4; return create(d, t); },
        invalid("texture 't': a multisampled texture is Tex2D, not Tex2DArray"));
    add("multisampled mips", [](rhi::Device& d) { auto t = texture("t"); t.samples = 4; t.mip_levels = 2; return create(d, t); },
        invalid("texture 't': a multisampled texture has one mip level, not 2"));
    add("multisampled storage", [](rhi::Device& d) { auto t = texture("t"); t.samples = 4; t.usage = TextureUsage::Storage; return create(d, t); },
        invalid("texture 't': a multisampled texture cannot have Storage usage"));
    add("colour usage, depth format", [](rhi::Device& d) { auto t = texture("t"); t.format = Format::Depth32F; t.usage = TextureUsage::ColorAttachment; return create(d, t); },
        invalid("texture 't': Depth32F is not a colour format (usage ColorAttachment)"));
    add("depth usage, colour format", [](rhi::Device& d) { auto t = texture("t"); t.usage = TextureUsage::DepthStencilAttachment; return create(d, t); },
        invalid("texture 't': RGBA8Unorm is not a depth/stencil format (usage DepthStencilAttachment)"));
    add("2D size past the limit",
        [](rhi::Device& d) { return create(d, texture("t", d.capabilities().max_texture_size + 1, 4)); },
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::Unsupported, "texture 't': size " + std::to_string(c.max_texture_size + 1) +
                                                        "x4x1 exceeds this device's limit of " + std::to_string(c.max_texture_size) +
                                                        " texels for a Tex2D texture"};
        });
    add("3D depth past the limit",
        [](rhi::Device& d) { auto t = texture("t"); t.dimension = TextureDimension::Tex3D; t.depth_or_layers = d.capabilities().max_texture_size_3d + 1; return create(d, t); },
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::Unsupported, "texture 't': size 4x4x" + std::to_string(c.max_texture_size_3d + 1) +
                                                        " exceeds this device's limit of " + std::to_string(c.max_texture_size_3d) +
                                                        " texels for a Tex3D texture"};
        });
    add("cube past the limit",
        [](rhi::Device& d) { const uint32_t n = d.capabilities().max_texture_size_cube + 1; auto t = texture("t", n, n); t.dimension = TextureDimension::Cube; t.depth_or_layers = 6; return create(d, t); },
        [](const rhi::Capabilities& c) {
            const std::string n = std::to_string(c.max_texture_size_cube + 1);
            return Expected{ErrorCode::Unsupported, "texture 't': size " + n + "x" + n + "x1 exceeds this device's limit of " +
                                                        std::to_string(c.max_texture_size_cube) + " texels for a Cube texture"};
        });
    add("array layers past the limit",
        [](rhi::Device& d) { auto t = texture("t"); t.dimension = TextureDimension::Tex2DArray; t.depth_or_layers = d.capabilities().max_texture_layers + 1; return create(d, t); },
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::Unsupported, "texture 't': " + std::to_string(c.max_texture_layers + 1) +
                                                        " layers exceed this device's limit of " + std::to_string(c.max_texture_layers)};
        });
    add("storage usage on an sRGB format", [](rhi::Device& d) { auto t = texture("t"); t.format = Format::RGBA8Srgb; t.usage = TextureUsage::Storage; return create(d, t); },
        unsupported("texture 't': RGBA8Srgb cannot be a storage image on this device"),
        [](const rhi::Capabilities& c) { return !c.format(Format::RGBA8Srgb).storage && c.format(Format::RGBA8Srgb).sampled; });
    add("placement without placed resources",
        [](rhi::Device& d) { auto t = texture("t"); t.placement = rhi::TexturePlacement{}; return create(d, t); },
        unsupported("texture 't': placement in a heap needs placed resources, which this device lacks"),
        [](const rhi::Capabilities& c) { return !c.placed_resources; });
    add("memory requirements of a bad description",
        [](rhi::Device& d) { auto r = d.texture_memory_requirements(texture("t", 0, 4)); return r.ok() ? Status{} : Status(r.take_error()); },
        [](const rhi::Capabilities& c) {
            return c.placed_resources
                       ? Expected{ErrorCode::InvalidArgument, "texture 't': size 0x4x1 has a zero dimension"}
                       : Expected{ErrorCode::Unsupported, "texture 't': memory requirements need placed resources, which this device lacks"};
        });

    // ---- buffers, samplers, heaps
    add("buffer size 0", [](rhi::Device& d) { rhi::BufferDesc b; b.name = "b"; auto r = d.create_buffer(b); return r.ok() ? Status{} : Status(r.take_error()); },
        invalid("buffer 'b': size is 0"));
    add("sampler LOD range", [](rhi::Device& d) { rhi::SamplerDesc s; s.name = "s"; s.min_lod = 2; s.max_lod = 1; auto r = d.create_sampler(s); return r.ok() ? Status{} : Status(r.take_error()); },
        invalid("sampler 's': min_lod 2 is above max_lod 1"));
    add("sampler anisotropy", [](rhi::Device& d) { rhi::SamplerDesc s; s.name = "s"; s.max_anisotropy = 0.5f; auto r = d.create_sampler(s); return r.ok() ? Status{} : Status(r.take_error()); },
        invalid("sampler 's': max_anisotropy 0.5 is below 1"));
    add("heap size 0", [](rhi::Device& d) { rhi::HeapDesc h; h.name = "h"; auto r = d.create_heap(h); return r.ok() ? Status{} : Status(r.take_error()); },
        [](const rhi::Capabilities& c) {
            return c.placed_resources ? Expected{ErrorCode::InvalidArgument, "heap 'h': size is 0"}
                                      : Expected{ErrorCode::Unsupported, "heap 'h': heaps need placed resources, which this device lacks"};
        });

    add("buffer placement without placed resources",
        [](rhi::Device& d) -> Status {
            rhi::BufferDesc b{"b", 64, rhi::BufferUsage::Storage};
            b.placement = rhi::BufferPlacement{};
            auto r = d.create_buffer(b);
            if (r.ok()) LOOM_TRY(d.destroy(*r));
            return r.ok() ? Status{} : Status(r.take_error());
        },
        unsupported("buffer 'b': placement in a heap needs placed resources, which this device lacks"),
        [](const rhi::Capabilities& c) { return !c.placed_resources; });
    add("buffer memory requirements of size 0",
        [](rhi::Device& d) { auto r = d.buffer_memory_requirements({"b", 0, rhi::BufferUsage::Storage}); return r.ok() ? Status{} : Status(r.take_error()); },
        invalid("buffer 'b': size is 0"));
    // Places 64-byte storage buffer 'b' in heap 'h' (sized from the buffer's requirements) at an
    // offset computed from them; `noted` keeps the requirements for the expected message.
    using FromRequirements = std::function<uint64_t(const rhi::MemoryRequirements&)>;
    auto placed_buffer = [](std::shared_ptr<rhi::MemoryRequirements> noted, FromRequirements heap_size, FromRequirements offset) {
        return [=](rhi::Device& d) -> Status {
            rhi::BufferDesc b{"b", 64, rhi::BufferUsage::Storage};
            auto req = d.buffer_memory_requirements(b);
            if (!req.ok()) return Error{ErrorCode::Backend, "setup: " + req.error().to_string()};
            *noted = *req;
            auto heap = d.create_heap({"h", heap_size(*req)});
            if (!heap.ok()) return Error{ErrorCode::Backend, "setup: " + heap.error().to_string()};
            b.placement = rhi::BufferPlacement{*heap, offset(*req)};
            auto made = d.create_buffer(b);
            if (made.ok()) LOOM_TRY(d.destroy(*made));
            LOOM_TRY(d.destroy(*heap));
            return made.ok() ? Status{} : Status(made.take_error());
        };
    };
    const auto placed_only = [](const rhi::Capabilities& c) { return c.placed_resources; };
    {
        auto noted = std::make_shared<rhi::MemoryRequirements>();
        add("buffer placement offset not aligned",
            placed_buffer(noted, [](const auto& r) { return 4 * (r.size + r.alignment); }, [](const auto& r) { return r.alignment / 2; }),
            [noted](const rhi::Capabilities&) {
                return Expected{ErrorCode::InvalidArgument, "buffer 'b' placed in heap 'h': offset " + std::to_string(noted->alignment / 2) +
                                                                " is not a multiple of the alignment " + std::to_string(noted->alignment)};
            },
            placed_only);
    }
    {
        auto noted = std::make_shared<rhi::MemoryRequirements>();
        add("buffer placement past the heap's end",
            placed_buffer(noted, [](const auto& r) { return r.size; }, [](const auto& r) { return r.alignment; }),
            [noted](const rhi::Capabilities&) {
                return Expected{ErrorCode::InvalidArgument, "buffer 'b' placed in heap 'h': range " + std::to_string(noted->alignment) + "+" +
                                                                std::to_string(noted->size) + " exceeds the heap size " + std::to_string(noted->size)};
            },
            placed_only);
    }

    // ---- buffer transfers
    const std::vector<std::byte> eight(8);
    add("write_buffer past the end", [eight](rhi::Device& d) { return with_buffer(d, 16, [&](rhi::BufferHandle b) { return d.write_buffer(b, 12, eight); }); },
        invalid("write_buffer to buffer 'b': 8 bytes at offset 12 exceed its size 16"));
    add("write_buffer offset wraps", [eight](rhi::Device& d) { return with_buffer(d, 16, [&](rhi::BufferHandle b) { return d.write_buffer(b, std::numeric_limits<uint64_t>::max() - 3, eight); }); },
        invalid("write_buffer to buffer 'b': 8 bytes at offset 18446744073709551612 exceed its size 16"));
    add("empty write_buffer past the end", [](rhi::Device& d) { return with_buffer(d, 16, [&](rhi::BufferHandle b) { return d.write_buffer(b, 17, {}); }); },
        invalid("write_buffer to buffer 'b': 0 bytes at offset 17 exceed its size 16"));
    add("read_buffer past the end", [](rhi::Device& d) {
            return with_buffer(d, 16, [&](rhi::BufferHandle b) { auto r = d.read_buffer(b, 12, 8); return r.ok() ? Status{} : Status(r.take_error()); });
        },
        invalid("read_buffer of buffer 'b': 8 bytes at offset 12 exceed its size 16"));

    // ---- texture transfers
    const auto mipped = [] { auto t = texture("t"); t.mip_levels = 3; return t; }();
    const auto array = [] { auto t = texture("t"); t.dimension = TextureDimension::Tex2DArray; t.depth_or_layers = 2; return t; }();
    const auto volume = [] { auto t = texture("t"); t.dimension = TextureDimension::Tex3D; t.depth_or_layers = 4; return t; }();
    auto write = [](rhi::TextureRegion region, std::size_t bytes) {
        return [region, bytes](rhi::Device& d, rhi::TextureHandle t) { return d.write_texture(t, region, std::vector<std::byte>(bytes)); };
    };
    auto on = [](rhi::TextureDesc desc, std::function<Status(rhi::Device&, rhi::TextureHandle)> use) {
        return [desc, use](rhi::Device& d) { return with_texture(d, desc, [&](rhi::TextureHandle t) { return use(d, t); }); };
    };
    add("write_texture mip", on(mipped, write({.mip = 3}, 4)), invalid("write_texture to texture 't': mip 3 does not exist (3 levels)"));
    add("write_texture layer of a 2D texture", on(texture("t"), write({.layer = 1}, 64)),
        invalid("write_texture to texture 't': layer 1 does not exist (1 layer)"));
    add("write_texture layer of an array", on(array, write({.layer = 2}, 64)),
        invalid("write_texture to texture 't': layer 2 does not exist (2 layers)"));
    add("write_texture layer of a 3D texture", on(volume, write({.layer = 1}, 64)),
        invalid("write_texture to texture 't': layer 1: a Tex3D texture has no layers (origin.z selects depth slices)"));
    add("write_texture depth on a 2D texture", on(texture("t"), write({.origin = {0, 0, 1}}, 64)),
        invalid("write_texture to texture 't': origin.z and extent.depth apply to Tex3D textures only"));
    add("write_texture region outside", on(texture("t"), write({.origin = {2, 0, 0}, .extent = {4, 4, 1}}, 64)),
        invalid("write_texture to texture 't': region 4x4x1 at (2,0,0) does not fit mip 0 (4x4x1)"));
    add("write_texture region wraps", on(texture("t"), write({.origin = {4294967295u, 0, 0}, .extent = {2, 1, 1}}, 8)),
        invalid("write_texture to texture 't': region 2x1x1 at (4294967295,0,0) does not fit mip 0 (4x4x1)"));
    add("write_texture origin past the mip", on(mipped, write({.mip = 1, .origin = {2, 0, 0}}, 0)),
        invalid("write_texture to texture 't': region 0x2x1 at (2,0,0) does not fit mip 1 (2x2x1)"));
    add("write_texture byte count", on(texture("t"), write({}, 3)),
        invalid("write_texture to texture 't': 3 bytes given, the region needs 64"));
    add("write_texture 3D slices", on(volume, write({.origin = {0, 0, 1}}, 64)),
        invalid("write_texture to texture 't': 64 bytes given, the region needs 192"));
    add("write_texture multisampled",
        on([] { auto t = texture("t"); t.samples = 4; t.usage = TextureUsage::ColorAttachment; return t; }(), write({}, 64)),
        unsupported("write_texture to texture 't': a multisampled texture cannot be uploaded to"),
        [](const rhi::Capabilities& c) { return (c.format(Format::RGBA8Unorm).sample_counts & 4u) != 0; });
    add("read_texture mip", on(mipped, [](rhi::Device& d, rhi::TextureHandle t) { return read(d, t, 5, 0); }),
        invalid("read_texture of texture 't': mip 5 does not exist (3 levels)"));
    add("read_texture layer", on(array, [](rhi::Device& d, rhi::TextureHandle t) { return read(d, t, 0, 2); }),
        invalid("read_texture of texture 't': layer 2 does not exist (2 layers)"));
    add("read_texture 3D slice of a smaller mip",
        on([] { auto t = texture("t"); t.dimension = TextureDimension::Tex3D; t.depth_or_layers = 4; t.mip_levels = 2; return t; }(),
           [](rhi::Device& d, rhi::TextureHandle t) { return read(d, t, 1, 2); }),
        invalid("read_texture of texture 't': depth slice 2 does not exist (2 depth slices in mip 1)"));
    add("read_texture multisampled depth",
        on([] { auto t = texture("t"); t.samples = 4; t.format = Format::Depth32F; t.usage = TextureUsage::DepthStencilAttachment; return t; }(),
           [](rhi::Device& d, rhi::TextureHandle t) { return read(d, t, 0, 0); }),
        unsupported("read_texture of texture 't': a multisampled depth/stencil texture cannot be read back"),
        [](const rhi::Capabilities& c) { return (c.format(Format::Depth32F).sample_counts & 4u) != 0; });

    // ---- pipelines
    // Creates pipeline `desc` (its shaders filled in from the compiled vertex and fragment
    // shaders, unless `keep_shaders`), then destroys what it made.
    auto pipeline = [](std::function<void(rhi::GraphicsPipelineDesc&, rhi::ShaderHandle vs, rhi::ShaderHandle fs)> edit) {
        return [edit](rhi::Device& d) -> Status {
            auto vs = make_shader(d, rhi::ShaderStage::Vertex, "v", kPositionVert);
            auto fs = make_shader(d, rhi::ShaderStage::Fragment, "f", kPushColorFrag);
            if (!vs.ok() || !fs.ok()) return Error{ErrorCode::Backend, "setup: shaders"};
            rhi::GraphicsPipelineDesc desc;
            desc.name = "p";
            desc.vertex = *vs;
            desc.fragment = *fs;
            desc.color_formats = {Format::RGBA8Unorm};
            desc.vertex_buffers = {rhi::VertexBufferLayout{12, rhi::VertexStepMode::PerVertex, {{0, rhi::VertexFormat::Float3, 0}}}};
            edit(desc, *vs, *fs);
            auto made = d.create_graphics_pipeline(desc);
            if (made.ok()) LOOM_TRY(d.destroy(*made));
            LOOM_TRY(d.destroy(*vs));
            LOOM_TRY(d.destroy(*fs));
            return made.ok() ? Status{} : Status(made.take_error());
        };
    };
    add("pipeline with a null vertex shader", pipeline([](auto& p, auto, auto) { p.vertex = {}; }),
        expect({ErrorCode::InvalidHandle, "pipeline 'p': vertex shader: shader handle is null"}));
    add("pipeline with stages swapped", pipeline([](auto& p, auto vs, auto fs) { p.vertex = fs; p.fragment = vs; }),
        invalid("pipeline 'p': vertex shader 'f' is a fragment shader"));
    add("pipeline without attachments", pipeline([](auto& p, auto, auto) { p.color_formats.clear(); }),
        invalid("pipeline 'p': no colour formats and no depth format"));
    add("pipeline samples", pipeline([](auto& p, auto, auto) { p.samples = 3; }),
        invalid("pipeline 'p': samples 3 is not a power of two from 1 to 64"));
    add("pipeline with too many colour formats", [pipeline](rhi::Device& d) {
            const std::size_t n = d.capabilities().max_color_attachments + 1;
            return pipeline([n](auto& p, auto, auto) { p.color_formats.assign(n, Format::RGBA8Unorm); })(d);
        },
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::Unsupported, "pipeline 'p': " + std::to_string(c.max_color_attachments + 1) +
                                                        " colour formats exceed this device's limit of " +
                                                        std::to_string(c.max_color_attachments) + " colour attachments"};
        });
    add("pipeline with more blend states than colours", pipeline([](auto& p, auto, auto) { p.blend.resize(2); }),
        invalid("pipeline 'p': 2 blend states for 1 colour format"));
    add("pipeline colour format", pipeline([](auto& p, auto, auto) { p.color_formats = {Format::Depth32F}; }),
        invalid("pipeline 'p': color_formats[0] Depth32F is not a colour format"));
    add("pipeline depth format", pipeline([](auto& p, auto, auto) { p.depth_format = Format::RGBA8Unorm; }),
        invalid("pipeline 'p': depth_format RGBA8Unorm is not a depth/stencil format"));
    add("pipeline depth test without depth", pipeline([](auto& p, auto, auto) { p.depth.test = true; }),
        invalid("pipeline 'p': depth test or write enabled without a depth_format"));
    add("pipeline blending an integer format", pipeline([](auto& p, auto, auto) { p.color_formats = {Format::R32Uint}; p.blend = {rhi::BlendState{.enabled = true}}; }),
        unsupported("pipeline 'p': blend[0] is enabled but R32Uint cannot be blended on this device"),
        [](const rhi::Capabilities& c) { return c.format(Format::R32Uint).color_attachment && !c.format(Format::R32Uint).blendable; });
    add("pipeline samples a format lacks", pipeline([](auto& p, auto, auto) { p.samples = 64; }),
        unsupported("pipeline 'p': color_formats[0] RGBA8Unorm cannot have 64 samples on this device"),
        [](const rhi::Capabilities& c) { return (c.format(Format::RGBA8Unorm).sample_counts & 64u) == 0; });
    add("pipeline attribute location twice", pipeline([](auto& p, auto, auto) { p.vertex_buffers.push_back(p.vertex_buffers[0]); }),
        invalid("pipeline 'p': vertex attribute location 0 is given twice (again in slot 1)"));
    add("pipeline vertex input not fed", pipeline([](auto& p, auto, auto) { p.vertex_buffers.clear(); }),
        invalid("pipeline 'p': vertex shader 'v' reads 'position' at location 0 but no vertex attribute provides it"));
    add("pipeline vertex buffers", pipeline([](auto& p, auto, auto) { p.vertex_buffers.resize(17); }),
        invalid("pipeline 'p': 17 vertex buffers exceed the 16 slots loom supports"));
    add("compute pipeline of a vertex shader", [](rhi::Device& d) -> Status {
            auto vs = make_shader(d, rhi::ShaderStage::Vertex, "v", kPositionVert);
            if (!vs.ok()) return Error{ErrorCode::Backend, "setup: shader"};
            auto made = d.create_compute_pipeline({"p", *vs});
            LOOM_TRY(d.destroy(*vs));
            return made.ok() ? Status{} : Status(made.take_error());
        },
        invalid("pipeline 'p': compute shader 'v' is a vertex shader"));

    // ---- commands (reported by end_frame)
    auto frame = [](std::function<void(rhi::Device&, rhi::CommandList&)> record) {
        return [record](rhi::Device& d) { return run_frame(d, [&](rhi::CommandList& list) { record(d, list); }); };
    };
    // Runs `record` with textures made from `descs`, then destroys them.
    auto with_textures = [](std::vector<rhi::TextureDesc> descs, std::function<void(rhi::CommandList&, const std::vector<rhi::TextureHandle>&)> record) {
        return [descs, record](rhi::Device& d) -> Status {
            std::vector<rhi::TextureHandle> made;
            for (const rhi::TextureDesc& desc : descs) {
                auto t = d.create_texture(desc);
                if (!t.ok()) return Error{ErrorCode::Backend, "setup: " + t.error().to_string()};
                made.push_back(*t);
            }
            Status status = run_frame(d, [&](rhi::CommandList& list) { record(list, made); });
            for (rhi::TextureHandle t : made) LOOM_TRY(d.destroy(t));
            return status;
        };
    };
    auto target = [](const std::string& name, uint32_t size = 4, Format format = Format::RGBA8Unorm) {
        auto t = texture(name, size, size);
        t.format = format;
        t.usage = format_info(format).is_color() ? TextureUsage::ColorAttachment | TextureUsage::Sampled
                                                 : TextureUsage::DepthStencilAttachment | TextureUsage::Sampled;
        return t;
    };
    auto pass_with = [](std::vector<rhi::TextureHandle> colors, rhi::TextureHandle depth = {}, uint32_t layer = 0) {
        rhi::RenderPassDesc desc;
        desc.label = "p";
        for (rhi::TextureHandle c : colors) desc.colors.push_back({.texture = c, .layer = layer});
        if (!depth.is_null()) desc.depth = rhi::DepthAttachment{.texture = depth};
        return desc;
    };
    auto begin = [pass_with](std::vector<std::size_t> colors, std::optional<std::size_t> depth = std::nullopt, uint32_t layer = 0) {
        return [=](rhi::CommandList& list, const std::vector<rhi::TextureHandle>& t) {
            std::vector<rhi::TextureHandle> handles;
            for (std::size_t i : colors) handles.push_back(t[i]);
            list.begin_render_pass(pass_with(handles, depth ? t[*depth] : rhi::TextureHandle{}, layer));
            list.end_render_pass();
        };
    };
    add("render pass without attachments", frame([](rhi::Device&, rhi::CommandList& list) {
            rhi::RenderPassDesc empty;
            empty.label = "p";
            list.begin_render_pass(empty);
            list.end_render_pass();
        }),
        invalid("begin_render_pass 'p': no attachments"));
    add("render pass with too many colour attachments", [target](rhi::Device& d) {
            return with_texture(d, target("t"), [&](rhi::TextureHandle t) {
                rhi::RenderPassDesc desc;
                desc.label = "p";
                desc.colors.resize(d.capabilities().max_color_attachments + 1, rhi::ColorAttachment{.texture = t});
                return run_frame(d, [&](rhi::CommandList& list) {
                    list.begin_render_pass(desc);
                    list.end_render_pass();
                });
            });
        },
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::Unsupported, "begin_render_pass 'p': " + std::to_string(c.max_color_attachments + 1) +
                                                        " colour attachments exceed this device's limit of " + std::to_string(c.max_color_attachments)};
        });
    add("render pass with a null attachment", frame([pass_with](rhi::Device&, rhi::CommandList& list) {
            list.begin_render_pass(pass_with({rhi::TextureHandle{}}));
            list.end_render_pass();
        }),
        expect({ErrorCode::InvalidHandle, "begin_render_pass 'p': colors[0]: texture handle is null"}));
    add("depth format as colour attachment", with_textures({target("d", 4, Format::Depth32F)}, begin({0})),
        invalid("begin_render_pass 'p': colors[0] (texture 'd'): Depth32F is not a colour format"));
    add("colour format as depth attachment", with_textures({target("c"), target("c2")}, begin({0}, 1)),
        invalid("begin_render_pass 'p': depth (texture 'c2'): RGBA8Unorm is not a depth/stencil format"));
    add("attachment without the usage", with_textures({texture("t")}, begin({0})),
        invalid("begin_render_pass 'p': colors[0] (texture 't') lacks usage ColorAttachment"));
    add("3D attachment", with_textures({[] { auto t = texture("v"); t.dimension = TextureDimension::Tex3D; t.depth_or_layers = 2; t.usage = TextureUsage::ColorAttachment; return t; }()}, begin({0})),
        unsupported("begin_render_pass 'p': colors[0] (texture 'v'): rendering into a Tex3D texture is not supported"));
    add("attachment layer", with_textures({target("t")}, begin({0}, std::nullopt, 1)),
        invalid("begin_render_pass 'p': colors[0] (texture 't'): mip 0 layer 1 does not exist (1 level, 1 layer)"));
    add("attachments of two sizes", with_textures({target("small"), target("large", 8)}, begin({0, 1})),
        invalid("begin_render_pass 'p': colors[1] (texture 'large') is 8x8 but colors[0] is 4x4"));
    add("attachments of two sample counts",
        with_textures({target("c"), [&] { auto t = target("d", 4, Format::Depth32F); t.samples = 4; t.usage = TextureUsage::DepthStencilAttachment; return t; }()}, begin({0}, 1)),
        invalid("begin_render_pass 'p': depth (texture 'd') has 4 samples but colors[0] has 1"),
        [](const rhi::Capabilities& c) { return (c.format(Format::Depth32F).sample_counts & 4u) != 0; });

    auto copy_buffer = [](uint64_t src_offset, uint64_t dst_offset, uint64_t size) {
        return [=](rhi::Device& d) {
            return with_buffer(d, 16, [&](rhi::BufferHandle b) {
                return run_frame(d, [&](rhi::CommandList& list) { list.copy_buffer(b, src_offset, b, dst_offset, size); });
            });
        };
    };
    add("copy_buffer source range", copy_buffer(12, 0, 8), invalid("copy_buffer from 'b' to 'b': 8 bytes at source offset 12 exceed its size 16"));
    add("copy_buffer destination range", copy_buffer(0, 18446744073709551615ull, 8),
        invalid("copy_buffer from 'b' to 'b': 8 bytes at destination offset 18446744073709551615 exceed its size 16"));
    add("copy_buffer overlap", copy_buffer(0, 4, 8), invalid("copy_buffer from 'b' to 'b': the ranges at 0 and 4 overlap (8 bytes each)"));

    auto copy = [](rhi::TextureRegion src, rhi::TextureRegion dst, std::size_t to = 1) {
        return [=](rhi::CommandList& list, const std::vector<rhi::TextureHandle>& t) {
            list.copy_texture(rhi::TextureCopy{t[0], src, t[to], dst});
        };
    };
    add("copy_texture formats", with_textures({target("a"), target("b", 4, Format::RGBA16Float)}, copy({}, {})),
        invalid("copy_texture from 'a' to 'b': formats RGBA8Unorm and RGBA16Float are not copy-compatible (equal, or colour formats of one texel size)"));
    add("copy_texture depth formats", with_textures({target("a", 4, Format::Depth32F), target("b", 4, Format::R32Float)}, copy({}, {})),
        invalid("copy_texture from 'a' to 'b': formats Depth32F and R32Float are not copy-compatible (equal, or colour formats of one texel size)"));
    add("copy_texture sample counts", with_textures({target("a"), [&] { auto t = target("b"); t.samples = 4; t.usage = TextureUsage::ColorAttachment; return t; }()}, copy({}, {})),
        invalid("copy_texture from 'a' to 'b': sample counts differ (1 and 4)"),
        [](const rhi::Capabilities& c) { return (c.format(Format::RGBA8Unorm).sample_counts & 4u) != 0; });
    add("copy_texture 3D to 2D", with_textures({volume, target("b")}, copy({}, {})),
        unsupported("copy_texture from 't' to 'b': copies between a Tex3D texture and a Tex2D texture are not supported"));
    add("copy_texture source mip", with_textures({target("a"), target("b")}, copy({.mip = 3}, {})),
        invalid("copy_texture from 'a' to 'b': source mip 3 does not exist (1 level)"));
    add("copy_texture destination layer", with_textures({target("a"), array}, copy({}, {.layer = 2})),
        invalid("copy_texture from 'a' to 't': destination layer 2 does not exist (2 layers)"));
    add("copy_texture region past the destination", with_textures({target("a", 8), target("b")}, copy({}, {})),
        invalid("copy_texture from 'a' to 'b': region 8x8x1 at (0,0,0) does not fit destination mip 0 (4x4x1)"));
    add("copy_texture region past the source", with_textures({target("a"), target("b")}, copy({.origin = {3, 0, 0}, .extent = {2, 1, 1}}, {})),
        invalid("copy_texture from 'a' to 'b': region 2x1x1 at (3,0,0) does not fit source mip 0 (4x4x1)"));
    add("copy_texture onto itself", with_textures({target("a")}, copy({}, {}, 0)),
        invalid("copy_texture from 'a' to 'a': source and destination are one subresource (mip 0, layer 0)"));

    // Records `record` with buffer 'b' (16 bytes of `usage`).
    auto with_b = [](rhi::BufferUsage usage, std::function<void(rhi::CommandList&, rhi::BufferHandle)> record) {
        return [usage, record](rhi::Device& d) {
            return with_buffer(d, 16, [&](rhi::BufferHandle b) { return run_frame(d, [&](rhi::CommandList& list) { record(list, b); }); }, usage);
        };
    };
    add("vertex buffer handle", frame([](rhi::Device&, rhi::CommandList& list) { list.set_vertex_buffer(0, {}); }),
        expect({ErrorCode::InvalidHandle, "set_vertex_buffer: buffer handle is null"}));
    add("vertex buffer usage", with_b(rhi::BufferUsage::Index, [](rhi::CommandList& list, rhi::BufferHandle b) { list.set_vertex_buffer(0, b); }),
        invalid("set_vertex_buffer: slot 0: buffer 'b' lacks usage Vertex"));
    add("vertex buffer offset", with_b(rhi::BufferUsage::Vertex, [](rhi::CommandList& list, rhi::BufferHandle b) { list.set_vertex_buffer(2, b, 16); }),
        invalid("set_vertex_buffer: slot 2: buffer 'b': offset 16 is not inside its 16 bytes"));
    add("index buffer usage", with_b(rhi::BufferUsage::Vertex, [](rhi::CommandList& list, rhi::BufferHandle b) { list.set_index_buffer(b, rhi::IndexType::Uint16); }),
        invalid("set_index_buffer: buffer 'b' lacks usage Index"));
    add("index buffer offset", with_b(rhi::BufferUsage::Index, [](rhi::CommandList& list, rhi::BufferHandle b) { list.set_index_buffer(b, rhi::IndexType::Uint16, 3); }),
        invalid("set_index_buffer: buffer 'b': offset 3 is not inside its 16 bytes or not a multiple of the index size 2"));
    add("indirect usage", with_b(rhi::BufferUsage::Vertex, [](rhi::CommandList& list, rhi::BufferHandle b) { list.draw_indexed_indirect(b, 0, 1); }),
        invalid("draw_indexed_indirect: buffer 'b' lacks usage Indirect"));
    add("indirect stride", with_b(rhi::BufferUsage::Indirect, [](rhi::CommandList& list, rhi::BufferHandle b) { list.draw_indexed_indirect(b, 0, 1, 8); }),
        invalid("draw_indexed_indirect: buffer 'b': offset 0 and stride 8 must be multiples of 4, the stride at least 20"));
    add("indirect range", [](rhi::Device& d) {
            return with_buffer(d, 32, [&](rhi::BufferHandle b) {
                return run_frame(d, [&](rhi::CommandList& list) { list.draw_indexed_indirect(b, 4, 2); });
            }, rhi::BufferUsage::Indirect);
        },
        invalid("draw_indexed_indirect: buffer 'b': 2 commands from offset 4 run past its end (32 bytes)"));
    add("index range of a draw", [](rhi::Device& d) -> Status {
            auto color = make_target(d, "t", Format::RGBA8Unorm, 4, 4);
            auto solid = make_solid_pipeline(d, Format::RGBA8Unorm);
            auto vertices = make_buffer_of(d, "v", rhi::BufferUsage::Vertex, std::vector<float>(9, 0.0f));
            auto indices = make_buffer_of(d, "i", rhi::BufferUsage::Index, std::vector<uint16_t>{0, 1, 2, 0});
            if (!color.ok() || !solid.ok() || !vertices.ok() || !indices.ok()) return Error{ErrorCode::Backend, "setup"};
            Status status = run_frame(d, [&](rhi::CommandList& list) {
                list.begin_render_pass(clear_pass("p", *color, {0, 0, 0, 1}));
                list.set_pipeline(*solid);
                list.set_vertex_buffer(0, *vertices);
                list.set_index_buffer(*indices, rhi::IndexType::Uint16, 2);
                list.push_constants_of(std::array<float, 4>{1, 1, 1, 1});
                list.draw_indexed(3, 1, 1);
                list.end_render_pass();
            });
            LOOM_TRY(d.destroy(*solid));
            LOOM_TRY(d.destroy(*vertices));
            LOOM_TRY(d.destroy(*indices));
            LOOM_TRY(d.destroy(*color));
            return status;
        },
        invalid("draw_indexed: 3 indices from index 1 run past the end of index buffer 'i' (8 bytes from offset 2)"));
    // Bind groups against what a compute pipeline reads: a sampled texture at binding 0 and a
    // storage buffer at binding 1. `bind` makes the group from texture 't' (usage `usage`,
    // uploaded so that it is in ShaderRead unless `upload` is false), sampler 's' and buffer 'b'.
    struct Resources {
        rhi::TextureHandle t;
        rhi::SamplerHandle s;
        rhi::BufferHandle b;
    };
    auto dispatch_with = [](TextureUsage usage, rhi::BufferUsage buffer_usage, bool upload,
                            std::function<std::optional<rhi::BindGroup>(const Resources&)> bind) {
        return [=](rhi::Device& d) -> Status {
            auto cs = make_shader(d, rhi::ShaderStage::Compute, "c", R"(#version 450
layout(local_size_x = 1) in;
layout(set = 0, binding = 0) uniform sampler2D tex;
layout(set = 0, binding = 1) buffer Result { vec4 value; } result;
void main() { result.value = textureLod(tex, vec2(0.5), 0.0); }
)");
            if (!cs.ok()) return Error{ErrorCode::Backend, "setup: " + cs.error().to_string()};
            auto p = d.create_compute_pipeline({"p", *cs});
            auto t = d.create_texture([&] { auto desc = texture("t"); desc.usage = usage; return desc; }());
            rhi::SamplerDesc sampler;
            sampler.name = "s";
            auto smp = d.create_sampler(sampler);
            auto b = d.create_buffer({"b", 64, buffer_usage});
            if (!p.ok() || !t.ok() || !smp.ok() || !b.ok()) return Error{ErrorCode::Backend, "setup"};
            if (upload) LOOM_TRY(d.write_texture(*t, {}, std::vector<std::byte>(64)));
            const std::optional<rhi::BindGroup> group = bind({*t, *smp, *b});
            Status status = run_frame(d, [&](rhi::CommandList& list) {
                list.set_pipeline(*p);
                if (group) list.set_bind_group(0, *group);
                list.dispatch(1);
            });
            LOOM_TRY(d.destroy(*p));
            LOOM_TRY(d.destroy(*cs));
            LOOM_TRY(d.destroy(*t));
            LOOM_TRY(d.destroy(*smp));
            LOOM_TRY(d.destroy(*b));
            return status;
        };
    };
    auto both = [](const Resources& r) { return std::optional(rhi::BindGroup{}.texture(0, r.t, r.s).buffer(1, r.b)); };
    add("binding not bound", dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true, [](const Resources&) { return std::nullopt; }),
        expect({ErrorCode::InvalidState, "dispatch: pipeline 'p' set 0 binding 0 ('tex') is not bound"}));
    add("binding of the wrong kind",
        dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true,
                      [](const Resources& r) { return std::optional(rhi::BindGroup{}.buffer(0, r.b).buffer(1, r.b)); }),
        invalid("dispatch: pipeline 'p' set 0 binding 0 ('tex') is a sampled texture but the bind group has a buffer there"));
    add("binding a null texture",
        dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true,
                      [](const Resources& r) { return std::optional(rhi::BindGroup{}.texture(0, rhi::TextureHandle{}, r.s).buffer(1, r.b)); }),
        expect({ErrorCode::InvalidHandle, "dispatch: pipeline 'p' set 0 binding 0 ('tex'): texture handle is null"}));
    add("sampling a texture without Sampled usage", dispatch_with(TextureUsage::Storage, rhi::BufferUsage::Storage, false, both),
        invalid("dispatch: pipeline 'p' set 0 binding 0 ('tex'): texture 't' lacks usage Sampled"));
    add("storage buffer without Storage usage", dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Uniform, true, both),
        invalid("dispatch: pipeline 'p' set 0 binding 1 ('Result'): buffer 'b' lacks usage Storage"));
    add("storage buffer offset",
        dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true,
                      [](const Resources& r) { return std::optional(rhi::BindGroup{}.texture(0, r.t, r.s).buffer(1, r.b, 4)); }),
        [](const rhi::Capabilities& c) {
            return Expected{ErrorCode::InvalidArgument, "dispatch: pipeline 'p' set 0 binding 1 ('Result'): 60 bytes at offset 4 of buffer 'b' "
                                                        "(64 bytes) are empty, outside it or not aligned to " +
                                                            std::to_string(c.storage_buffer_offset_alignment)};
        },
        [](const rhi::Capabilities& c) { return c.storage_buffer_offset_alignment > 4; });
    add("sampling a texture in the wrong state", dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, false, both),
        expect({ErrorCode::InvalidState, "dispatch: pipeline 'p' set 0 binding 0 ('tex'): texture 't' is in state Undefined; "
                                         "transition it to ShaderRead first"}));
    add("sampled range past the mips",
        dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true,
                      [](const Resources& r) { return std::optional(rhi::BindGroup{}.texture(0, r.t, r.s, {.base_mip = 1}).buffer(1, r.b)); }),
        invalid("dispatch: pipeline 'p' set 0 binding 0 ('tex'): texture 't': mips 1.. are not inside its 1 mip level"));
    add("sampled range without layers",
        dispatch_with(TextureUsage::Sampled, rhi::BufferUsage::Storage, true,
                      [](const Resources& r) { return std::optional(rhi::BindGroup{}.texture(0, r.t, r.s, {.layer_count = 0}).buffer(1, r.b)); }),
        invalid("dispatch: pipeline 'p' set 0 binding 0 ('tex'): texture 't': 0 layers from 0 are not inside its 1 layer"));
    add("viewport without area", frame([](rhi::Device&, rhi::CommandList& list) { list.set_viewport({0, 0, 0, 4, 0, 1}); }),
        invalid("set_viewport: 0x4 at (0,0) with depths 0..1: the size must be positive and the depths within 0..1"));
    add("viewport depth", frame([](rhi::Device&, rhi::CommandList& list) { list.set_viewport({0, 0, 4, 4, 0, 2}); }),
        invalid("set_viewport: 4x4 at (0,0) with depths 0..2: the size must be positive and the depths within 0..1"));
    add("push constants past 256 bytes", frame([](rhi::Device&, rhi::CommandList& list) { list.push_constants(std::vector<std::byte>(16), 250); }),
        invalid("push_constants: 16 bytes at offset 250 exceed the 256 bytes loom supports"));
    add("bind group set", frame([](rhi::Device&, rhi::CommandList& list) { list.set_bind_group(4, {}); }),
        invalid("set_bind_group: set 4 is beyond the 4 sets loom supports"));
    add("bind group binding", frame([](rhi::Device&, rhi::CommandList& list) { list.set_bind_group(1, rhi::BindGroup{}.buffer(16, rhi::BufferHandle{})); }),
        invalid("set_bind_group: set 1 binding 16 is beyond the 16 bindings per set loom supports"));
    add("vertex buffer slot", frame([](rhi::Device&, rhi::CommandList& list) { list.set_vertex_buffer(16, {}); }),
        invalid("set_vertex_buffer: slot 16 is beyond the 16 slots loom supports"));
    // Transitions of texture 'c' (RGBA8, ColorAttachment and Sampled) or 'd' (Depth32F) to `state`.
    auto transition = [with_textures, target](bool depth, rhi::ResourceState state) {
        return with_textures({depth ? target("d", 4, Format::Depth32F) : target("c")},
                             [state](rhi::CommandList& list, const std::vector<rhi::TextureHandle>& t) {
                                 list.transition(t[0], state);
                             });
    };
    add("texture transition to a depth state", transition(false, rhi::ResourceState::DepthWrite),
        invalid("transition: texture 'c' (RGBA8Unorm) cannot be in state DepthWrite"));
    add("texture transition to a buffer state", transition(false, rhi::ResourceState::VertexBuffer),
        invalid("transition: texture 'c' (RGBA8Unorm) cannot be in state VertexBuffer"));
    add("texture transition without the usage", transition(false, rhi::ResourceState::Storage),
        invalid("transition: texture 'c' to Storage needs Storage usage"));
    add("depth texture transition to RenderTarget", transition(true, rhi::ResourceState::RenderTarget),
        invalid("transition: texture 'd' (Depth32F) cannot be in state RenderTarget"));
    auto range_transition = [with_textures, target](rhi::TextureRange range) {
        return with_textures({target("c")}, [range](rhi::CommandList& list, const std::vector<rhi::TextureHandle>& t) {
            list.transition(t[0], rhi::ResourceState::ShaderRead, range);
        });
    };
    add("texture range transition past the mips", range_transition({.base_mip = 0, .mip_count = 2}),
        invalid("transition: texture 'c': mips 0..1 are not inside its 1 mip level"));
    add("texture range transition past the layers", range_transition({.base_layer = 1}),
        invalid("transition: texture 'c': layers 1.. are not inside its 1 layer"));
    auto to_render_target = [](rhi::CommandList& list, rhi::BufferHandle b) {
        list.transition(b, rhi::ResourceState::RenderTarget);
    };
    add("buffer transition to an attachment state", with_b(rhi::BufferUsage::Storage, to_render_target),
        invalid("transition: buffer 'b' cannot be in state RenderTarget"));

    // ---- command-list state (rhi::CommandListState): frames, render passes, bound state,
    // timers and debug groups. Each row records into a frame with a kit of objects: target 't'
    // (4x4 RGBA8), graphics pipeline 'solid' (RGBA8, reads vertex slot 0), compute pipeline
    // 'c', vertex buffer 'v' and index buffer 'i'.
    struct Kit {
        rhi::TextureHandle target;
        rhi::PipelineHandle solid;
        rhi::PipelineHandle compute;
        rhi::BufferHandle vertices;
        rhi::BufferHandle indices;
    };
    // Runs `record` in a frame with a kit; returns what `record` returns when that is an error
    // (a Device call's), else end_frame's status.
    using KitRecord = std::function<Status(rhi::Device&, rhi::CommandList&, const Kit&)>;
    auto with_kit = [](KitRecord record) {
        return [record](rhi::Device& d) -> Status {
            auto t = make_target(d, "t", Format::RGBA8Unorm, 4, 4);
            auto solid = make_solid_pipeline(d, Format::RGBA8Unorm);
            auto cs = make_shader(d, rhi::ShaderStage::Compute, "c",
                                  "#version 450\nlayout(local_size_x = 1) in;\nvoid main() {}\n");
            if (!cs.ok()) return Error{ErrorCode::Backend, "setup: " + cs.error().to_string()};
            auto compute = d.create_compute_pipeline({"c", *cs});
            LOOM_TRY(d.destroy(*cs));
            auto vertices = make_buffer_of(d, "v", rhi::BufferUsage::Vertex | rhi::BufferUsage::CopySrc,
                                           std::vector<float>(9, 0.0f));
            auto indices = make_buffer_of(d, "i", rhi::BufferUsage::Index | rhi::BufferUsage::CopyDst,
                                          std::vector<uint16_t>{0, 1, 2, 0});
            if (!t.ok() || !solid.ok() || !compute.ok() || !vertices.ok() || !indices.ok()) {
                return Error{ErrorCode::Backend, "setup"};
            }
            const Kit kit{*t, *solid, *compute, *vertices, *indices};
            Status inside;
            Status ended = run_frame(d, [&](rhi::CommandList& list) { inside = record(d, list, kit); });
            LOOM_TRY(d.destroy(kit.target));
            LOOM_TRY(d.destroy(kit.solid));
            LOOM_TRY(d.destroy(kit.compute));
            LOOM_TRY(d.destroy(kit.vertices));
            LOOM_TRY(d.destroy(kit.indices));
            return inside.ok() ? ended : inside;
        };
    };
    // Records `record` (which returns nothing) inside render pass 'p' on the kit's target.
    auto in_pass = [with_kit](std::function<void(rhi::CommandList&, const Kit&)> record) {
        return with_kit([record](rhi::Device&, rhi::CommandList& list, const Kit& k) {
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            record(list, k);
            list.end_render_pass();
            return Status{};
        });
    };
    auto outside_pass = [with_kit](std::function<void(rhi::CommandList&, const Kit&)> record) {
        return with_kit([record](rhi::Device&, rhi::CommandList& list, const Kit& k) {
            record(list, k);
            return Status{};
        });
    };
    const std::string outside_only = " is open; dispatches, copies, transitions and readbacks go outside render passes";

    add("begin_frame twice", [](rhi::Device& d) {
            d.begin_frame();
            d.begin_frame();
            return d.end_frame();
        },
        wrong_state("begin_frame: the previous frame was not ended; call end_frame first"));
    add("end_frame without a frame", [](rhi::Device& d) { return d.end_frame(); },
        wrong_state("end_frame: no frame is being recorded; call begin_frame first"));
    add("end_frame with a render pass open", with_kit([](rhi::Device&, rhi::CommandList& list, const Kit& k) {
            list.begin_render_pass(clear_pass("left open", k.target, {0, 0, 0, 1}));
            return Status{};
        }),
        wrong_state("end_frame: render pass 'left open' was not ended"));
    add("end_frame with a timer open", outside_pass([](rhi::CommandList& list, const Kit&) { list.begin_timer("t"); }),
        wrong_state("end_frame: timer 't' was not ended"));
    add("end_frame with debug groups open", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.push_debug_group("a");
            list.push_debug_group("b");
        }),
        wrong_state("end_frame: 2 debug groups were not popped"));
    add("render passes nested", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.begin_render_pass(clear_pass("q", k.target, {0, 0, 0, 1}));
        }),
        wrong_state("begin_render_pass 'q': render pass 'p' is still open; render passes do not nest"));
    add("end_render_pass without a render pass",
        outside_pass([](rhi::CommandList& list, const Kit&) { list.end_render_pass(); }),
        wrong_state("end_render_pass: no render pass is open"));
    add("draw outside a render pass", outside_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.set_vertex_buffer(0, k.vertices);
            list.draw(3);
        }),
        wrong_state("draw: no render pass is open; draws go inside a render pass"));
    add("draw_indexed outside a render pass",
        outside_pass([](rhi::CommandList& list, const Kit&) { list.draw_indexed(3); }),
        wrong_state("draw_indexed: no render pass is open; draws go inside a render pass"));
    add("draw without a pipeline", in_pass([](rhi::CommandList& list, const Kit&) { list.draw(3); }),
        wrong_state("draw: no pipeline is set; call set_pipeline first"));
    add("draw with a compute pipeline", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.compute);
            list.draw(3);
        }),
        wrong_state("draw: pipeline 'c' is a compute pipeline; draws need a graphics pipeline"));
    add("set_pipeline with a null handle", in_pass([](rhi::CommandList& list, const Kit&) { list.set_pipeline({}); }),
        expect({ErrorCode::InvalidHandle, "set_pipeline: pipeline handle is null"}));
    const std::string wide_in_p = "pipeline 'solid' targets [RGBA16Float] depth Undefined x1, "
                                  "render pass 'p' has [RGBA8Unorm] depth Undefined x1";
    // Draws with `wide` (a pipeline for RGBA16Float) in pass 'p' on the RGBA8 target, set inside the pass or before it.
    auto with_wide = [with_kit](bool set_inside) {
        return with_kit([set_inside](rhi::Device& d, rhi::CommandList& list, const Kit& k) -> Status {
            auto wide = make_solid_pipeline(d, Format::RGBA16Float);
            if (!wide.ok()) return Error{ErrorCode::Backend, "setup: " + wide.error().to_string()};
            if (!set_inside) list.set_pipeline(*wide);
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            if (set_inside) list.set_pipeline(*wide);
            list.set_vertex_buffer(0, k.vertices);
            list.draw(3);
            list.end_render_pass();
            return d.destroy(*wide);
        });
    };
    add("pipeline for other attachments set in the pass", with_wide(true), invalid("set_pipeline: " + wide_in_p));
    add("pipeline for other attachments set before the pass", with_wide(false), invalid("draw: " + wide_in_p));
    // The pool's words for the destroyed object, noted by the misuse for the expected message.
    auto stale_pipeline = std::make_shared<std::string>();
    add("draw with a destroyed pipeline",
        with_kit([stale_pipeline](rhi::Device& d, rhi::CommandList& list, const Kit& k) -> Status {
            auto doomed = make_solid_pipeline(d, Format::RGBA8Unorm);
            if (!doomed.ok()) return Error{ErrorCode::Backend, "setup: " + doomed.error().to_string()};
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            list.set_pipeline(*doomed);
            list.set_vertex_buffer(0, k.vertices);
            LOOM_TRY(d.destroy(*doomed));
            *stale_pipeline = d.destroy(*doomed).error().message;
            list.draw(3);
            list.end_render_pass();
            return Status{};
        }),
        [stale_pipeline](const rhi::Capabilities&) {
            return Expected{ErrorCode::InvalidHandle, "draw: pipeline 'solid': " + *stale_pipeline};
        });
    add("draw without a vertex buffer the pipeline reads", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.draw(3);
        }),
        wrong_state("draw: pipeline 'solid' reads vertex buffer slot 0, but no vertex buffer is bound there"));
    auto stale_buffer = std::make_shared<std::string>();
    // Draws (indexed when `indexed`) with a buffer destroyed after it was bound as vertex buffer or index buffer.
    auto destroyed_buffer = [with_kit, stale_buffer](bool indexed) {
        return with_kit([stale_buffer, indexed](rhi::Device& d, rhi::CommandList& list, const Kit& k) -> Status {
            auto doomed = make_buffer_of(d, "doomed", indexed ? rhi::BufferUsage::Index : rhi::BufferUsage::Vertex,
                                         std::vector<float>(9, 0.0f));
            if (!doomed.ok()) return Error{ErrorCode::Backend, "setup: " + doomed.error().to_string()};
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            list.set_pipeline(k.solid);
            list.set_vertex_buffer(0, indexed ? k.vertices : *doomed);
            if (indexed) list.set_index_buffer(*doomed, rhi::IndexType::Uint16);
            LOOM_TRY(d.destroy(*doomed));
            *stale_buffer = d.destroy(*doomed).error().message;
            if (indexed) {
                list.draw_indexed(3);
            } else {
                list.draw(3);
            }
            list.end_render_pass();
            return Status{};
        });
    };
    add("draw with a destroyed vertex buffer", destroyed_buffer(false), [stale_buffer](const rhi::Capabilities&) {
        return Expected{ErrorCode::InvalidHandle, "draw: vertex buffer slot 0: " + *stale_buffer};
    });
    add("draw_indexed with a destroyed index buffer", destroyed_buffer(true), [stale_buffer](const rhi::Capabilities&) {
        return Expected{ErrorCode::InvalidHandle, "draw_indexed: index buffer: " + *stale_buffer};
    });
    add("draw_indexed without an index buffer", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.set_vertex_buffer(0, k.vertices);
            list.draw_indexed(3);
        }),
        wrong_state("draw_indexed: no index buffer is bound; call set_index_buffer first"));
    // Rebinding vertex or index buffers between draws keeps the checked draw (the backends skip
    // the full check): the first indexed draw still checks the index buffer, and each indexed
    // draw its range against the buffer and offset bound last.
    add("draw_indexed without an index buffer after draws", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.set_vertex_buffer(0, k.vertices);
            list.draw(3);
            list.set_vertex_buffer(0, k.vertices);
            list.draw_indexed(3);
        }),
        wrong_state("draw_indexed: no index buffer is bound; call set_index_buffer first"));
    add("draw_indexed past the index buffer bound again at a later offset", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.set_vertex_buffer(0, k.vertices);
            list.set_index_buffer(k.indices, rhi::IndexType::Uint16);
            list.draw_indexed(4);
            list.set_index_buffer(k.indices, rhi::IndexType::Uint16, 4);
            list.draw_indexed(3);
        }),
        invalid("draw_indexed: 3 indices from index 0 run past the end of index buffer 'i' (8 bytes from offset 4)"));
    add("dispatch without a pipeline", outside_pass([](rhi::CommandList& list, const Kit&) { list.dispatch(1); }),
        wrong_state("dispatch: no pipeline is set; call set_pipeline first"));
    add("dispatch with a graphics pipeline", outside_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.solid);
            list.dispatch(1);
        }),
        wrong_state("dispatch: pipeline 'solid' is a graphics pipeline; dispatches need a compute pipeline"));
    add("dispatch inside a render pass", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_pipeline(k.compute);
            list.dispatch(1);
        }),
        wrong_state("dispatch: render pass 'p'" + outside_only));
    add("copy_buffer inside a render pass",
        in_pass([](rhi::CommandList& list, const Kit& k) { list.copy_buffer(k.vertices, 0, k.indices, 0, 4); }),
        wrong_state("copy_buffer: render pass 'p'" + outside_only));
    add("copy_texture inside a render pass", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.copy_texture({k.target, {}, k.target, {.mip = 0, .layer = 0}});
        }),
        wrong_state("copy_texture: render pass 'p'" + outside_only));
    add("texture transition inside a render pass", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.transition(k.target, rhi::ResourceState::ShaderRead);
        }),
        wrong_state("transition: render pass 'p'" + outside_only));
    add("buffer transition inside a render pass", in_pass([](rhi::CommandList& list, const Kit& k) {
            list.transition(k.vertices, rhi::ResourceState::VertexBuffer);
        }),
        wrong_state("transition: render pass 'p'" + outside_only));
    add("read_texture inside a render pass", with_kit([](rhi::Device& d, rhi::CommandList& list, const Kit& k) {
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            Status status = read(d, k.target, 0, 0);
            list.end_render_pass();
            return status;
        }),
        wrong_state("read_texture of texture 't': render pass 'p'" + outside_only));
    add("read_buffer inside a render pass", with_kit([](rhi::Device& d, rhi::CommandList& list, const Kit& k) {
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            auto bytes = d.read_buffer(k.vertices, 0, 4);
            list.end_render_pass();
            return bytes.ok() ? Status{} : Status(bytes.take_error());
        }),
        wrong_state("read_buffer of buffer 'v': render pass 'p'" + outside_only));
    add("timers nested", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.begin_timer("a");
            list.begin_timer("b");
            list.end_timer();
        }),
        wrong_state("begin_timer 'b': timer 'a' is still open; timers do not nest"));
    add("end_timer without a timer", outside_pass([](rhi::CommandList& list, const Kit&) { list.end_timer(); }),
        wrong_state("end_timer: no timer is open"));
    add("pop_debug_group without a group",
        outside_pass([](rhi::CommandList& list, const Kit&) { list.pop_debug_group(); }),
        wrong_state("pop_debug_group: no debug group is open"));

    // ---- queues (CommandList::set_queue, signal_queue, wait_queue)
    add("render pass on the compute queue", outside_pass([](rhi::CommandList& list, const Kit& k) {
            list.set_queue(rhi::QueueType::Compute);
            list.begin_render_pass(clear_pass("p", k.target, {0, 0, 0, 1}));
            list.end_render_pass();
        }),
        wrong_state("begin_render_pass 'p': the commands go to the compute queue, which runs no render passes; "
                    "set_queue(QueueType::Graphics) first"));
    add("set_queue inside a render pass",
        in_pass([](rhi::CommandList& list, const Kit&) { list.set_queue(rhi::QueueType::Compute); }),
        wrong_state("set_queue(compute): render pass 'p'" + outside_only));
    add("set_queue with a timer open", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.begin_timer("t");
            list.set_queue(rhi::QueueType::Compute);
            list.end_timer();
        }),
        wrong_state("set_queue(compute): timer 't' is open; end it first"));
    add("set_queue with a debug group open", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.push_debug_group("g");
            list.set_queue(rhi::QueueType::Compute);
            list.pop_debug_group();
        }),
        wrong_state("set_queue(compute): 1 debug group(s) open; pop them first"));
    add("wait_queue on the signalling queue", outside_pass([](rhi::CommandList& list, const Kit&) {
            const rhi::QueueSignal signal = list.signal_queue();
            list.wait_queue(signal);
        }),
        invalid("wait_queue(signal 0): made on the graphics queue, which is the queue recording; wait on the other one"));
    add("wait_queue twice", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.set_queue(rhi::QueueType::Compute);
            const rhi::QueueSignal signal = list.signal_queue();
            list.set_queue(rhi::QueueType::Graphics);
            list.wait_queue(signal);
            list.wait_queue(signal);
        }),
        invalid("wait_queue(signal 0): already waited for; a signal is waited at most once"));
    add("wait_queue on a signal of no frame", outside_pass([](rhi::CommandList& list, const Kit&) {
            list.wait_queue(rhi::QueueSignal{3, rhi::QueueType::Compute});
        }),
        invalid("wait_queue(signal 3): not a signal of this frame (0 made so far)"));
    return rows;
}

class MisuseTable : public RenderTest {};

TEST_P(MisuseTable, EveryRuleGivesOneCodeAndMessageOnEveryBackend) {
    const rhi::Capabilities& caps = device().capabilities();
    int checked = 0;
    for (const Row& row : table()) {
        SCOPED_TRACE(row.rule);
        if (!row.applies(caps)) continue;
        // Refused before the API sees it: no debug or validation message may be logged (the
        // fixture fails the test on one).
        const Status status = row.misuse(device());
        const Expected expected = row.expected(caps);
        ASSERT_FALSE(status.ok()) << "accepted";
        EXPECT_EQ(error_code_name(status.error().code), error_code_name(expected.code)) << status.error().message;
        EXPECT_EQ(status.error().message, expected.message);
        ++checked;
    }
    // Rows skipped for a capability are few; most rules are checked on every device.
    EXPECT_GE(checked, 100);
    // The device is still usable after every refusal.
    LOOM_ASSIGN_OR_FAIL(auto target, make_target(device(), "after", Format::RGBA8Unorm, 4, 4));
    LOOM_ASSERT_OK(device().destroy(target));
}

}  // namespace

LOOM_INSTANTIATE_RENDER_TEST(MisuseTable);

}  // namespace loom::test
