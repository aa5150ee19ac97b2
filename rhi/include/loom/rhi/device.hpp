#pragma once
// The render-hardware interface: a small Device / CommandList pair (after NVRHI's IDevice and
// ICommandList) that the OpenGL and Vulkan backends implement identically.
//
// Conventions (the same on every backend; docs/architecture.md, "Conventions that make the two
// APIs agree"): NDC y points up, depth runs 0..1, row 0 of every framebuffer, texture, upload and
// readback is the top row, counter-clockwise triangles (as seen in NDC) are front faces.
//
// A frame is recorded between begin_frame() and end_frame(). Uploads (write_buffer,
// write_texture) may happen at any time and are ordered before the commands of the next frame
// submitted. Readbacks wait for the GPU.

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/image.hpp"
#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"
#include "loom/rhi/window_input.hpp"

namespace loom::rhi {

/// The graphics APIs loom has a backend for.
enum class Backend : uint8_t { OpenGL, Vulkan };

/// "gl" or "vulkan".
std::string_view backend_name(Backend backend);
/// Accepts "gl", "opengl", "vulkan", "vk".
std::optional<Backend> parse_backend(std::string_view name);

/// The window of a windowed device.
struct WindowDesc {
    std::string title = "loom";
    uint32_t width = 1280;
    uint32_t height = 720;
    bool vsync = true;
    bool resizable = true;
};

/// How to create a device (rhi::create_device).
struct DeviceDesc {
    Backend backend = Backend::OpenGL;
    /// Headless devices render offscreen only; windowed ones open a GLFW window with a
    /// back buffer (see Device::backbuffer()).
    bool headless = true;
    WindowDesc window;
    /// Enable API debug output (KHR_debug on GL, the Khronos validation layer on Vulkan).
    /// Messages go to the logger; errors are logged at LogLevel::Error. On by default, and
    /// create_device logs it at LogLevel::Info: on Vulkan it loads the Khronos validation
    /// layer, which costs far more per draw than loom itself. Turn it off for builds you ship
    /// or measure.
    bool debug = true;
    /// Check recorded commands against the resources they use and refuse misuse with an error
    /// (loom's own validation layer, rhi::validation, independent of `debug`): bind groups
    /// against the pipeline's layout, vertex and index buffers and index ranges, the pipeline
    /// against the render pass, viewports, indirect arguments. Off: these checks are skipped
    /// and a misuse is undefined behaviour, as in the raw API; the order of commands (frames,
    /// render passes, timers, queues), copies, transitions and every description at creation
    /// are still checked. Also compiled out with the CMake option LOOM_RHI_VALIDATION=OFF.
    bool validation = true;
};

/// What a backend can do with one format.
struct FormatCapabilities {
    bool sampled = false;
    bool filterable = false;   ///< linear filtering when sampled
    bool color_attachment = false;
    bool blendable = false;
    bool depth_stencil_attachment = false;
    bool storage = false;
    /// The sample counts a 2D texture of this format can have, one bit per count (bit value n
    /// set: n samples; 1 is always set where the format is usable).
    uint32_t sample_counts = 1;
};

/// What a device can do: per-format capabilities, limits and features. Plans may depend on them.
struct Capabilities {
    Backend backend = Backend::OpenGL;
    std::string device_name;   ///< e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string api_version;   ///< e.g. "4.5 (Core Profile) Mesa 22.3.6"
    std::array<FormatCapabilities, kFormatCount> formats{};
    /// Textures and buffers can be placed at offsets inside heaps (memory aliasing); Vulkan yes, GL no.
    bool placed_resources = false;
    bool timestamps = false;
    /// RasterState::polygon = PolygonMode::Line (GL always; Vulkan with fillModeNonSolid).
    bool polygon_mode_line = false;
    /// RasterState::depth_clamp (GL always; Vulkan with the depthClamp feature).
    bool depth_clamp = false;
    /// CommandList::draw_indexed_indirect is implemented (both built-in backends). Where it is
    /// false, draw each DrawIndexedIndirectCommand with draw_indexed instead.
    bool draw_indirect = false;
    /// Width and height of a 2D or array texture.
    uint32_t max_texture_size = 0;
    /// Width, height and depth of a 3D texture.
    uint32_t max_texture_size_3d = 0;
    /// Width (= height) of a cube texture's faces.
    uint32_t max_texture_size_cube = 0;
    /// Layers of an array texture.
    uint32_t max_texture_layers = 0;
    /// Samples per texel of a multisampled colour or depth attachment (1: no multisampling).
    uint32_t max_samples = 0;
    uint32_t max_color_attachments = 0;
    uint64_t uniform_buffer_offset_alignment = 256;
    uint64_t storage_buffer_offset_alignment = 256;
    /// The compute queue (CommandList::set_queue) is a queue of its own that runs beside the
    /// graphics queue. Where false its commands run on the graphics queue in recording order
    /// (GL; Vulkan devices with one queue, such as lavapipe), with the same results.
    bool async_compute = false;

    /// The capabilities of one format.
    [[nodiscard]] const FormatCapabilities& format(Format f) const { return formats[static_cast<std::size_t>(f)]; }
};

/// Objects alive on a device and the GPU memory they hold (textures and buffers; heaps count
/// as memory, the textures and buffers placed in them count as textures and buffers but not
/// again as memory).
struct ResourceStats {
    uint64_t textures = 0;
    uint64_t buffers = 0;
    uint64_t heaps = 0;
    uint64_t samplers = 0;
    uint64_t shaders = 0;
    uint64_t pipelines = 0;
    uint64_t texture_bytes = 0;
    uint64_t buffer_bytes = 0;
    uint64_t heap_bytes = 0;
    /// Texture, buffer and heap bytes together.
    [[nodiscard]] uint64_t total_bytes() const { return texture_bytes + buffer_bytes + heap_bytes; }
    /// Equal counts and bytes of every kind (the soak test's "nothing leaked").
    friend bool operator==(const ResourceStats&, const ResourceStats&) = default;
};

/// Work done by the last finished frame, counted by the backend.
struct FrameStats {
    uint64_t api_calls = 0;        ///< calls into GL / vkCmd* recorded
    uint64_t draw_calls = 0;
    uint64_t dispatches = 0;
    uint64_t pipeline_binds = 0;   ///< actual program/pipeline changes (after filtering)
    uint64_t texture_binds = 0;
    uint64_t buffer_binds = 0;     ///< vertex, index, uniform and storage buffer bindings
    uint64_t render_passes = 0;
    uint64_t bytes_uploaded = 0;   ///< write_buffer / write_texture / transient uniforms
    /// Buffer transitions (CommandList::transition of a buffer) that needed a barrier: on GL a
    /// glMemoryBarrier after storage writes, on Vulkan a buffer memory barrier (also for
    /// write-after-read); transitions that need none are not counted.
    uint64_t buffer_barriers = 0;
};

/// GPU time of one labelled range of a frame.
struct TimerResult {
    std::string label;
    double gpu_ms = 0.0;
};

/// Records the commands of one frame. Obtained from Device::begin_frame(), valid until
/// Device::end_frame(). Misuse (a stale handle, a draw outside a render pass) is recorded and
/// returned by end_frame() as an Error; the offending command is skipped.
class CommandList {
public:
    /// Command lists are owned by their device.
    virtual ~CommandList() = default;

    /// Begins rendering into the attachments of `desc` (moved to the attachment states), with their load actions.
    virtual void begin_render_pass(const RenderPassDesc& desc) = 0;
    /// Ends the render pass, applying the store actions.
    virtual void end_render_pass() = 0;

    /// Uses `pipeline` for the following draws or dispatches; a graphics pipeline must match the pass's formats.
    virtual void set_pipeline(PipelineHandle pipeline) = 0;
    /// Defaults to the full attachment size at begin_render_pass.
    virtual void set_viewport(const Viewport& viewport) = 0;
    /// Defaults to the full attachment size at begin_render_pass.
    virtual void set_scissor(const Rect& rect) = 0;
    /// Binds the resources of `layout(set = set)` for the following draws/dispatches.
    virtual void set_bind_group(uint32_t set, const BindGroup& group) = 0;
    /// Binds `range` (a uniform or storage buffer range, e.g. one transient_uniforms returned)
    /// at binding `binding` of set `set`, keeping the set's other bindings: per-draw data
    /// without building a BindGroup. Checked like set_bind_group at the next draw or dispatch.
    /// Where only the offset of a uniform range changed since the last draw, the backends bind
    /// it again without checking or writing anything else (Vulkan: a dynamic offset).
    virtual void set_buffer(uint32_t set, uint32_t binding, const BufferBinding& range) = 0;
    /// Vulkan push constants (emulated with a uniform buffer on GL).
    virtual void push_constants(std::span<const std::byte> data, uint32_t offset = 0) = 0;
    /// Binds `buffer` (from `offset`) to vertex buffer slot `slot` of the pipeline's layout.
    virtual void set_vertex_buffer(uint32_t slot, BufferHandle buffer, uint64_t offset = 0) = 0;
    /// Binds the index buffer for draw_indexed.
    virtual void set_index_buffer(BufferHandle buffer, IndexType type, uint64_t offset = 0) = 0;

    /// Copies `data` into per-frame uniform memory and returns a binding for it, valid until
    /// the end of the frame (for per-draw constants without managing buffers).
    virtual BufferBinding transient_uniforms(std::span<const std::byte> data) = 0;
    /// `data` copied into transient uniform memory and bound at binding `binding` of set `set`:
    /// set_buffer(set, binding, transient_uniforms(data)) in one call, which a backend can make
    /// cheaper than the two (the range is its own, so nothing about it needs checking).
    virtual void set_uniforms(uint32_t set, uint32_t binding, std::span<const std::byte> data) {
        set_buffer(set, binding, transient_uniforms(data));
    }

    virtual void draw(uint32_t vertex_count, uint32_t instance_count = 1, uint32_t first_vertex = 0,
                      uint32_t first_instance = 0) = 0;
    virtual void draw_indexed(uint32_t index_count, uint32_t instance_count = 1, uint32_t first_index = 0,
                              int32_t base_vertex = 0, uint32_t first_instance = 0) = 0;
    /// Runs the compute pipeline over groups_x * groups_y * groups_z work groups (outside render passes).
    virtual void dispatch(uint32_t groups_x, uint32_t groups_y = 1, uint32_t groups_z = 1) = 0;
    /// `draw_count` indexed draws with the bound state, their arguments read by the GPU from
    /// `buffer` (BufferUsage::Indirect) at `offset` + i * `stride` (DrawIndexedIndirectCommand;
    /// offset and stride multiples of 4): one command for many draws that share a pipeline,
    /// bindings and vertex/index buffers (a multi-draw). The instance index of draw i starts at
    /// its first_instance, so per-instance vertex attributes can select per-draw data, and so
    /// does gl_InstanceIndex where GL has ARB_shader_draw_parameters (gl_BaseInstanceARB);
    /// without it, GL emulates the base instance with a uniform set per draw call and refuses
    /// indirect draws of pipelines that read gl_InstanceIndex (Unsupported). Only where
    /// Capabilities::draw_indirect; the default implementation, for backends without it, logs
    /// an error and draws nothing.
    virtual void draw_indexed_indirect(BufferHandle buffer, uint64_t offset, uint32_t draw_count,
                                       uint32_t stride = sizeof(DrawIndexedIndirectCommand));

    virtual void copy_buffer(BufferHandle src, uint64_t src_offset, BufferHandle dst, uint64_t dst_offset,
                             uint64_t size) = 0;
    /// Copies a region between textures of copy-compatible formats (outside render passes).
    virtual void copy_texture(const TextureCopy& copy) = 0;

    /// Moves a resource into `state` (from the state the backend tracked for it). Needed before
    /// sampling a texture that was rendered to, before storage access, and after it.
    virtual void transition(TextureHandle texture, ResourceState state) = 0;
    /// Moves the subresources in `range` of `texture` to `state` (the rest keep theirs): e.g.
    /// mip k-1 to ShaderRead while mip k goes to Storage or RenderTarget. A range outside the
    /// texture is an InvalidArgument error naming it.
    virtual void transition(TextureHandle texture, ResourceState state, const TextureRange& range) = 0;
    /// Moves a buffer into `state` (e.g. after storage writes, before it is read as a uniform or vertex buffer).
    virtual void transition(BufferHandle buffer, ResourceState state) = 0;

    /// GPU timing of the commands between begin_timer and end_timer (not nested).
    virtual void begin_timer(std::string_view label) = 0;
    /// Ends the range begun by begin_timer.
    virtual void end_timer() = 0;

    /// Debug markers shown in API debuggers (RenderDoc, apitrace).
    virtual void push_debug_group(std::string_view label) = 0;
    /// Ends the debug group begun last.
    virtual void pop_debug_group() = 0;

    /// Records the following commands for `queue` (a frame starts on Graphics). On the compute
    /// queue go dispatches, copies, transitions, timers and debug groups, never render passes.
    /// Where Capabilities::async_compute the two queues run side by side and only signal_queue
    /// and wait_queue order them; elsewhere the compute queue's commands run on the graphics
    /// queue in recording order. Switching queues needs no render pass, timer or debug group open.
    virtual void set_queue(QueueType queue) = 0;
    /// Marks the end of the commands recorded so far on the current queue: a wait_queue on the
    /// other queue holds back its later commands until these have finished.
    virtual QueueSignal signal_queue() = 0;
    /// The current queue's commands recorded from now on wait until the commands before
    /// `signal` (made on the other queue in this frame) have finished. A signal is waited at
    /// most once. The end of a frame waits for both queues by itself.
    virtual void wait_queue(QueueSignal signal) = 0;

    /// Convenience: push constants from a trivially copyable value.
    template <class T>
    void push_constants_of(const T& value, uint32_t offset = 0) {
        push_constants(std::as_bytes(std::span<const T, 1>(&value, 1)), offset);
    }
    /// Convenience: transient uniforms from a trivially copyable value.
    template <class T>
    BufferBinding transient_uniforms_of(const T& value) {
        return transient_uniforms(std::as_bytes(std::span<const T, 1>(&value, 1)));
    }
    /// Convenience: `value` copied into transient uniform memory and bound at (set, binding),
    /// the cheapest way to give each draw its own uniform block.
    template <class T>
    void set_uniforms_of(uint32_t set, uint32_t binding, const T& value) {
        set_uniforms(set, binding, std::as_bytes(std::span<const T, 1>(&value, 1)));
    }
};

/// One GPU device of one backend: creates and destroys resources, transfers data, records frames. Not thread-safe; use it from one thread.
class Device {
public:
    /// Waits for the GPU and destroys every object still alive.
    virtual ~Device() = default;

    /// Which API the device runs on.
    [[nodiscard]] virtual Backend backend() const = 0;
    /// What the device can do (see Capabilities).
    [[nodiscard]] virtual const Capabilities& capabilities() const = 0;

    // -- resources ------------------------------------------------------------------------
    virtual Result<TextureHandle> create_texture(const TextureDesc& desc) = 0;
    /// Creates a buffer; InvalidArgument for a size of 0, or for a placement outside its heap
    /// or not aligned as buffer_memory_requirements says (Unsupported without placed resources).
    virtual Result<BufferHandle> create_buffer(const BufferDesc& desc) = 0;
    /// Creates a sampler; InvalidArgument for inconsistent LODs or anisotropy.
    virtual Result<SamplerHandle> create_sampler(const SamplerDesc& desc) = 0;
    /// Creates a shader from a compiled module (SPIR-V for Vulkan, its GL source for GL).
    virtual Result<ShaderHandle> create_shader(const ShaderModule& module) = 0;
    /// Creates a graphics pipeline; errors name the pipeline and the field at fault.
    virtual Result<PipelineHandle> create_graphics_pipeline(const GraphicsPipelineDesc& desc) = 0;
    /// Creates a compute pipeline from one compute shader.
    virtual Result<PipelineHandle> create_compute_pipeline(const ComputePipelineDesc& desc) = 0;
    /// A block of memory for placed textures and buffers (Capabilities::placed_resources only).
    virtual Result<HeapHandle> create_heap(const HeapDesc& desc) = 0;
    /// Size and alignment `desc` needs inside a heap (Capabilities::placed_resources only).
    virtual Result<MemoryRequirements> texture_memory_requirements(const TextureDesc& desc) = 0;
    /// Size and alignment a buffer described by `desc` needs inside a heap (its placement is
    /// ignored). On devices without placed resources (GL) it is the size rounded up to 256
    /// bytes and an alignment of 256, so that a planner can size things the same way on every
    /// backend; placing the buffer is still refused there.
    virtual Result<MemoryRequirements> buffer_memory_requirements(const BufferDesc& desc) = 0;

    /// Destroying is deferred until the GPU no longer uses the object. Stale or foreign
    /// handles give an InvalidHandle error.
    virtual Status destroy(TextureHandle texture) = 0;
    /// Destroys a buffer once the GPU no longer uses it.
    virtual Status destroy(BufferHandle buffer) = 0;
    /// Destroys a sampler once the GPU no longer uses it.
    virtual Status destroy(SamplerHandle sampler) = 0;
    /// Destroys a shader (pipelines made from it keep working).
    virtual Status destroy(ShaderHandle shader) = 0;
    /// Destroys a pipeline once the GPU no longer uses it.
    virtual Status destroy(PipelineHandle pipeline) = 0;
    /// Textures and buffers placed in the heap must have been destroyed first.
    virtual Status destroy(HeapHandle heap) = 0;

    /// The description a texture was created with.
    virtual Result<TextureDesc> texture_desc(TextureHandle texture) = 0;
    /// The description a buffer was created with.
    virtual Result<BufferDesc> buffer_desc(BufferHandle buffer) = 0;

    // -- data transfer --------------------------------------------------------------------
    virtual Status write_buffer(BufferHandle buffer, uint64_t offset, std::span<const std::byte> data) = 0;
    /// `data` holds the region's rows top-first, tightly packed, in the texture's format.
    virtual Status write_texture(TextureHandle texture, const TextureRegion& region,
                                 std::span<const std::byte> data) = 0;
    /// Reads one mip level / layer (a depth slice of a 3D texture) back, waiting for the GPU.
    /// Rows top-first. A multisampled colour texture is resolved first (samples averaged, or one
    /// sample taken for integer formats); a multisampled depth/stencil one is Unsupported.
    virtual Result<Image> read_texture(TextureHandle texture, uint32_t mip = 0, uint32_t layer = 0) = 0;
    /// Reads `size` bytes of a buffer from `offset` (waits for the GPU).
    virtual Result<std::vector<std::byte>> read_buffer(BufferHandle buffer, uint64_t offset, uint64_t size) = 0;

    // -- frames ---------------------------------------------------------------------------
    /// Starts recording a frame. On a windowed device this also acquires the back buffer.
    virtual CommandList& begin_frame() = 0;
    /// Submits the frame (and presents on a windowed device). Returns the first error recorded
    /// in the frame's command list. Does not wait for the GPU; a few frames may be in flight.
    virtual Status end_frame() = 0;
    /// Waits until the GPU has finished all submitted work.
    virtual Status wait_idle() = 0;

    /// GPU timings of the most recent frame whose results are available (may lag a frame or
    /// two; after wait_idle() they are those of the last frame).
    virtual std::vector<TimerResult> timer_results() = 0;

    /// Objects alive on the device and the memory they hold (see ResourceStats).
    [[nodiscard]] virtual ResourceStats resource_stats() const = 0;
    /// The work of the last finished frame (see FrameStats).
    [[nodiscard]] virtual FrameStats last_frame_stats() const = 0;

    // -- window (windowed devices; headless ones return defaults) ---------------------------
    /// Processes window events; false once the user closed the window (always false headless).
    virtual bool poll_window() = 0;
    /// Size of the window's framebuffer in pixels (0x0 headless).
    [[nodiscard]] virtual Extent3D window_size() const = 0;
    /// The window's cursor, buttons, keys and text as of the latest poll_window() (see
    /// WindowInput). Headless devices, and devices on the application's own context or
    /// Vulkan device, report none: the application owns that window's events.
    [[nodiscard]] virtual const WindowInput& window_input() const;
    /// The texture presented at end_frame(); render into it as a colour attachment. Valid
    /// between begin_frame() and end_frame(); null on a headless device.
    virtual TextureHandle backbuffer() = 0;
};

/// Creates a device of a compiled-in backend. Unsupported if the backend was not built or the
/// machine lacks the API; the message says which.
///
/// Declared here, defined by the `loom::backends` library (backends/create_device.cpp): the
/// RHI cannot link the backends that are built on it, so the umbrella target that links every
/// compiled-in backend provides the factory. Link `loom::backends` to call it, or call a
/// backend's own factory (loom/gl/gl_device.hpp, loom/vulkan/vulkan_device.hpp) directly.
Result<std::unique_ptr<Device>> create_device(const DeviceDesc& desc);

/// The backends compiled into this build, in the order OpenGL, Vulkan (also loom::backends).
std::span<const Backend> compiled_backends();

}  // namespace loom::rhi
