#pragma once
// What the executor does around every pass, decided once per plan (and per set of imported and
// history bindings) in one place: which texture backs each port, the state each texture must be
// in before the pass (sampled inputs → ShaderRead / DepthRead, storage ports → Storage), the
// load and store actions of attachment ports, the states imported textures are left in, and the
// copies that keep history textures. Plain data, computed without a device, so tests can check
// it exactly.
//
// Load/store rules (docs/framegraph.md, "Executing a plan"):
// - a port that starts its resource (an output, or an unconnected optional inout) is its first
//   write in the frame: nothing earlier wrote it, so it is cleared (Clear; a pass that writes
//   every texel may ask for DontCare). On a placed texture this is also the aliasing hand-over:
//   the previous tenant's bytes are discarded (Undefined → attachment).
// - an inout continuing a resource, an input used as an attachment, and an imported texture
//   that starts on an inout load (Load);
// - a port stores (Store) when a later pass reads the resource, when it is a graph output, an
//   imported texture or the source of a history; otherwise its contents die with the pass
//   (DontCare).
//
// Attachment states need no entry: the backends move attachments into attachment states at
// begin_render_pass themselves. GL needs no barrier for render-to-texture-then-sample; where it
// needs glMemoryBarrier (after storage writes) the backend derives it from these transitions.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "loom/framegraph/graph.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// Where the texture behind a port comes from.
struct TextureSlot {
    /// Where the texture behind a port comes from.
    enum class Kind : uint8_t {
        None,     ///< no texture (an unconnected optional port)
        Plan,     ///< Plan::textures[index]
        Import,   ///< the application's texture bound by ImportBinding number `index`
        History,  ///< HistoryTexture number `index` (see ExecutionSchedule::histories)
    };
    Kind kind = Kind::None;
    uint32_t index = 0;

    /// True when the port has no texture.
    [[nodiscard]] bool empty() const { return kind == Kind::None; }
    friend bool operator==(const TextureSlot&, const TextureSlot&) = default;
};

/// "t3", "import 0", "history 1", "none".
std::string describe_slot(const TextureSlot& slot);

/// Where the buffer behind a buffer port comes from.
struct BufferSlot {
    /// Where the buffer behind a port comes from.
    enum class Kind : uint8_t {
        None,    ///< no buffer (an unconnected optional port, or a texture port)
        Plan,    ///< Plan::buffers[index]
        Import,  ///< the application's buffer bound by buffer import number `index`
    };
    Kind kind = Kind::None;
    uint32_t index = 0;

    /// True when the port has no buffer.
    [[nodiscard]] bool empty() const { return kind == Kind::None; }
    friend bool operator==(const BufferSlot&, const BufferSlot&) = default;
};

/// "b3", "buffer import 0", "none".
std::string describe_slot(const BufferSlot& slot);

/// An application texture (or buffer) bound to a port (Executor::import_texture, import_buffer). A port that has a
/// resource in the plan (output, inout, connected input) hands the whole resource to the
/// imported texture; a port without one (an unconnected optional input, an optional output
/// nobody reads) reads or writes the imported texture alone.
struct ImportBinding {
    PortRef port;
    /// The state the texture is left in after its last use in the frame (e.g. Present,
    /// ShaderRead, CopySrc).
    rhi::ResourceState final_state = rhi::ResourceState::ShaderRead;
};

/// The previous frame's contents of `source` read through `reader` (Executor::bind_history).
/// `reader` is an input port left unconnected in the graph (declare it optional).
struct HistoryBinding {
    PortRef reader;
    PortRef source;
};

/// A state change recorded outside render passes.
struct Transition {
    TextureSlot texture;
    rhi::ResourceState state = rhi::ResourceState::Undefined;
    /// The subresources that change state: a port's range, or the whole texture (the default
    /// TextureRange) when the port uses all of it.
    rhi::TextureRange range{};
    friend bool operator==(const Transition&, const Transition&) = default;
};

/// A buffer state change recorded outside render passes. A write followed by another write
/// (two compute passes filling one buffer in turn) is a transition to the same state: the
/// backends make it a barrier all the same.
struct BufferTransition {
    BufferSlot buffer;
    rhi::ResourceState state = rhi::ResourceState::Undefined;
    friend bool operator==(const BufferTransition&, const BufferTransition&) = default;
};

/// The state a buffer port's role puts its buffer in: Storage for a write, CopyDst for a copy's
/// write; for reads VertexBuffer, IndexBuffer, IndirectArgument, CopySrc, and ShaderRead for
/// uniform and storage reads.
rhi::ResourceState buffer_state(PortKind kind, rhi::BufferUsage usage);

/// One port of a scheduled pass.
struct PortSchedule {
    std::string name;
    PortKind kind = PortKind::Input;
    TextureSlot texture;
    std::optional<uint32_t> resource;  ///< Plan::resources index, when the plan has one
    rhi::TextureUsage usage = rhi::TextureUsage::None;
    /// The port starts its resource: nothing earlier in the frame wrote the texture.
    bool first_write = false;
    /// Load action if the port is used as an attachment (Clear for a first write: the pass may
    /// ask for DontCare instead).
    rhi::LoadOp load = rhi::LoadOp::Load;
    rhi::StoreOp store = rhi::StoreOp::Store;
    /// Texture ports: the mip levels and layers the port uses (PlanPort::range).
    rhi::TextureRange range{};
    /// Buffer ports: where the buffer comes from and how the port uses it.
    BufferSlot buffer;
    rhi::BufferUsage buffer_usage = rhi::BufferUsage::None;
    friend bool operator==(const PortSchedule&, const PortSchedule&) = default;
};

/// Copies the source texture into a history texture once the source is final for the frame.
struct HistoryCopy {
    uint32_t history = 0;
    TextureSlot source;
    friend bool operator==(const HistoryCopy&, const HistoryCopy&) = default;
};

/// Everything recorded around one pass of Plan::order.
struct PassSchedule {
    std::string name;
    std::vector<PortSchedule> ports;  ///< in PlanPass::ports order
    std::vector<Transition> before;   ///< transitions before the pass runs
    std::vector<Transition> after;    ///< transitions after it (final states of imports)
    std::vector<HistoryCopy> copies;  ///< history copies after it
    std::vector<BufferTransition> buffers_before;  ///< buffer transitions before the pass runs
    std::vector<BufferTransition> buffers_after;   ///< after it (final states of imported buffers)
    friend bool operator==(const PassSchedule&, const PassSchedule&) = default;
};

/// A texture that carries `source` into the next frame. With readers that run after the copy
/// it needs two textures used in turn (`copies` = 2), else one.
struct HistoryTexture {
    std::string source;               ///< "pass.port"
    uint32_t resource = 0;            ///< Plan::resources index of the source
    ResolvedSpec spec;                ///< the source's spec
    uint32_t copy_after = 0;          ///< position in Plan::order after which it is copied
    uint32_t textures = 1;            ///< 1, or 2 when readers run after the copy
    std::vector<std::string> readers; ///< "pass.port"
    friend bool operator==(const HistoryTexture&, const HistoryTexture&) = default;
};

/// Everything decided around the passes of a plan, once per plan and binding set: texture slots, load/store actions, transitions, history copies.
struct ExecutionSchedule {
    std::vector<PassSchedule> passes;           ///< one per Plan::order entry
    std::vector<bool> texture_needed;           ///< per Plan::textures: false when imports replace all its resources
    /// Per Plan::resources: the import backing it (an index into the texture imports, or for a
    /// buffer resource into the buffer imports).
    std::vector<std::optional<uint32_t>> resource_import;
    std::vector<HistoryTexture> histories;
    std::vector<bool> buffer_needed;            ///< per Plan::buffers: false when imports replace all its resources
    friend bool operator==(const ExecutionSchedule&, const ExecutionSchedule&) = default;
};

/// The state a texture of `format` is sampled in: DepthRead for depth/stencil formats, else
/// ShaderRead.
rhi::ResourceState sampled_state(rhi::Format format);

/// Builds the schedule of `plan`. Errors (ErrorCode::Graph) name the port at fault: an import
/// or history on a port that does not exist or whose pass does not run, two imports on one
/// resource, a texture import on a buffer port or a buffer import on a texture port, a history
/// reader that is connected in the graph or is not an input, a history source without a
/// texture or on a buffer port.
Result<ExecutionSchedule> build_execution_schedule(const Plan& plan, std::span<const ImportBinding> imports,
                                                   std::span<const HistoryBinding> histories,
                                                   std::span<const ImportBinding> buffer_imports = {});

}  // namespace loom::fg
