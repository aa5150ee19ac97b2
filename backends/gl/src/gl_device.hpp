#pragma once
// The GL implementation of rhi::Device and rhi::CommandList.
//
// Commands are recorded (validated, resolved to GL names, state-tracked) into a list of
// closures and executed at end_frame(), so that, as on Vulkan, uploads made while a frame is
// recorded land before the frame's commands, and a misused command is skipped while the rest
// of the frame still runs.

#include <array>
#include <cstring>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "gl_app_state.hpp"
#include "gl_context.hpp"
#include "gl_debug.hpp"
#include "gl_frame_array.hpp"
#include "gl_objects.hpp"
#include "gl_state_cache.hpp"
#include "loom/gl/gl_device.hpp"
#include "loom/gl/gl_embed.hpp"
#include "loom/rhi/checked_math.hpp"
#include "loom/rhi/command_list_state.hpp"
#include "loom/rhi/handle_pool.hpp"
#include "loom/rhi/validation.hpp"

// Functions of the per-draw path, inlined where they are called: they run for every draw, and
// the calls between them cost more than their bodies (docs/BENCHMARKS.md, "The RHI per draw").
#if defined(__GNUC__)
#define LOOM_GL_HOT [[gnu::always_inline]] inline
#else
#define LOOM_GL_HOT inline
#endif

namespace loom::gl {

class GlDevice;

/// A recorded GL command, run against the state cache at end_frame().
using GlCommand = std::function<void(GlStateCache&)>;

using rhi::kMaxPushConstantBytes;

class GlCommandList final : public rhi::CommandList {
public:
    explicit GlCommandList(GlDevice& device);

    void begin_render_pass(const rhi::RenderPassDesc& desc) override;
    void end_render_pass() override;
    void set_pipeline(rhi::PipelineHandle pipeline) override;
    void set_viewport(const rhi::Viewport& viewport) override;
    void set_scissor(const rhi::Rect& rect) override;
    void set_bind_group(uint32_t set, const rhi::BindGroup& group) override;
    void set_buffer(uint32_t set, uint32_t binding, const rhi::BufferBinding& range) override;
    void push_constants(std::span<const std::byte> data, uint32_t offset) override;
    void set_vertex_buffer(uint32_t slot, rhi::BufferHandle buffer, uint64_t offset) override;
    void set_index_buffer(rhi::BufferHandle buffer, rhi::IndexType type, uint64_t offset) override;
    rhi::BufferBinding transient_uniforms(std::span<const std::byte> data) override;
    void set_uniforms(uint32_t set, uint32_t binding, std::span<const std::byte> data) override;
    /// DeviceDesc::validation (see rhi::CommandListState::validating).
    void set_validation(bool on) { state_.set_validation(on); }
    void draw(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance) override;
    void draw_indexed(uint32_t index_count, uint32_t instance_count, uint32_t first_index, int32_t base_vertex,
                      uint32_t first_instance) override;
    void dispatch(uint32_t groups_x, uint32_t groups_y, uint32_t groups_z) override;
    void draw_indexed_indirect(rhi::BufferHandle buffer, uint64_t offset, uint32_t draw_count, uint32_t stride) override;
    void copy_buffer(rhi::BufferHandle src, uint64_t src_offset, rhi::BufferHandle dst, uint64_t dst_offset,
                     uint64_t size) override;
    void copy_texture(const rhi::TextureCopy& copy) override;
    void transition(rhi::TextureHandle texture, rhi::ResourceState state) override;
    void transition(rhi::TextureHandle texture, rhi::ResourceState state, const rhi::TextureRange& range) override;
    void transition(rhi::BufferHandle buffer, rhi::ResourceState state) override;
    void begin_timer(std::string_view label) override;
    void end_timer() override;
    void push_debug_group(std::string_view label) override;
    void pop_debug_group() override;
    void set_queue(rhi::QueueType queue) override;
    rhi::QueueSignal signal_queue() override;
    void wait_queue(rhi::QueueSignal signal) override;

    // -- used by GlDevice ---------------------------------------------------------------
    /// Starts recording a frame (the device has checked that none is being recorded).
    void begin();
    /// Closes what was left open (recording an error for the first) and hands over the
    /// commands, valid until the next begin() (the list keeps their storage from frame to frame).
    std::vector<GlCommand>& finish();
    /// What is open and bound; also whether a frame is being recorded.
    [[nodiscard]] const rhi::CommandListState& state() const { return state_; }
    [[nodiscard]] bool recording() const { return state_.recording(); }
    /// The first error recorded in this frame, if any.
    std::optional<Error>& first_error() { return first_error_; }
    /// Timer queries recorded this frame, in order.
    std::vector<std::pair<std::string, GLuint>>& timers() { return timers_; }
    /// Records an error from outside (e.g. begin_frame called twice).
    void fail(ErrorCode code, std::string message);
    void fail(Error error) { fail(error.code, std::move(error.message)); }

private:
    /// A binding resolved to GL names, ready to be applied through the state cache.
    struct ResolvedBinding {
        BindingKind kind = BindingKind::UniformBuffer;
        uint32_t point = 0;
        GLuint object = 0;
        GLuint sampler = 0;
        GLintptr offset = 0;
        GLsizeiptr size = 0;
        GLint level = 0;
        bool layered = false;
        GLint layer = 0;  ///< the layer bound when not layered
        GLenum access = GL_READ_WRITE;
        GLenum format = 0;
    };

    /// A push-constant block's copy for one draw (object 0: the pipeline has none).
    struct PushRange {
        GLuint object = 0;
        GLintptr offset = 0;
        GLsizeiptr size = 0;
    };
    /// Records a command other than a draw. Draws recorded after it check and resolve their
    /// state again (it may change what they checked, or GL state they set).
    void record(GlCommand command) {
        commands_.push_back(std::move(command));
        invalidate_draw_state();
        draw_run_open_ = false;
    }
    /// True when `status` is ok; else records its error (the command is then skipped).
    LOOM_GL_HOT bool accepted(Status&& status) {
        if (status.ok()) [[likely]] return true;
        refuse(std::move(status));
        return false;
    }
    /// Records the error of a refused command (out of line: the hot paths inline accepted).
    [[gnu::noinline]] void refuse(Status&& status) { fail(status.take_error()); }
    /// Resolves the current pipeline's bindings from the bound groups into bindings_; false
    /// (with an error recorded) when something is missing or in the wrong state.
    bool resolve_bindings(const GlPipeline& pipeline, std::string_view command);
    /// The last bindings resolved (of the pipeline still bound) again with new offsets, when the
    /// bound groups differ from what they were resolved from only in uniform offsets (see
    /// rhi/binding_reuse.hpp); false, with nothing recorded, otherwise.
    bool reuse_bindings(const GlPipeline& pipeline, bool allowed);
    /// Whether the resolved binding `i` of the draw pipeline (a buffer) takes `range` by a new
    /// offset alone: the same buffer (alive) and size, a uniform range whose new offset is
    /// aligned and inside. Keeps the new offset in resolved_entries_ when so.
    bool takes_new_offset(std::size_t i, const rhi::BufferBinding& range);
    /// A copy of the last binding state, to change without changing what earlier draws bound.
    void next_binding_state();
    /// Whether the bindings resolved for the draws before take `range` at (`set`, `binding`)
    /// with one offset changed (or unchanged: the pipeline does not read it), changing it when
    /// so. `transient`: the range is the device's own transient memory (nothing to look up).
    bool rebinds_offset(uint32_t set, uint32_t binding, const rhi::BufferBinding& range, bool transient);
    /// set_vertex_buffer and set_index_buffer past their common case (which records a
    /// VertexChange): the checks' messages, growth. `found`:
    /// the buffer looked up by the caller (null when stale or foreign).
    void set_vertex_buffer_slow(uint32_t slot, rhi::BufferHandle buffer, const GlBuffer* found, uint64_t offset);
    void set_index_buffer_slow(rhi::BufferHandle buffer, const GlBuffer* found, rhi::IndexType type, uint64_t offset);
    /// Whether `pipeline` has no push-constant block or push_range_ holds it as it is now.
    [[nodiscard]] bool push_constants_current(const GlPipeline& pipeline) const {
        return pipeline.push_constant_size == 0 ||
               (!push_dirty_ && push_range_.object != 0 && push_range_.size >= static_cast<GLsizeiptr>(pipeline.push_constant_size));
    }
    /// The push-constant block of `pipeline` as a uniform range: a copy per change, so that
    /// every draw sees the values current when it was recorded.
    PushRange push_constant_range(const GlPipeline& pipeline);
    /// The copy itself: the block, at least `pipeline`'s size, into push_range_.
    void copy_push_constants(const GlPipeline& pipeline);
    /// An indirect draw's arguments: glMultiDrawElementsIndirect from `buffer`.
    struct IndirectDraw {
        GLuint buffer = 0;
        uintptr_t offset = 0;
        GLsizei count = 0;
        GLsizei stride = 0;
    };
    /// A draw with every check and every state change it needs (draw and draw_indexed take it
    /// past their inline common case, through draw_slow and draw_indexed_slow).
    void draw_common(bool indexed, uint32_t count, uint32_t instance_count, uint32_t first, int32_t base_vertex,
                     uint32_t first_instance,
                     const std::optional<IndirectDraw>& indirect = std::nullopt);
    void draw_slow(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex, uint32_t first_instance);
    /// A draw of the current state after a change of the push constants: copies them, appends it.
    void draw_copying_push_constants(uint32_t vertex_count, uint32_t instance_count, uint32_t first_vertex,
                                     uint32_t first_instance);
    void draw_indexed_copying_push_constants(uint32_t index_count, uint32_t instance_count, uint32_t first_index,
                                             int32_t base_vertex, uint32_t first_instance);
    void draw_indexed_slow(uint32_t index_count, uint32_t instance_count, uint32_t first_index, int32_t base_vertex,
                           uint32_t first_instance);
    /// Appends the record of a checked draw of the current state (draws_ has room for it; push
    /// constants copied; draw_shared_ current); the caller counts it into its run.
    /// `flags`: kDrawIndexed, kDrawIndirect, kDrawNewState.
    void append_draw(uint8_t flags, uint32_t count, uint32_t instance_count, uint32_t first, int32_t base_vertex,
                     uint32_t first_instance);
    /// Starts a run of draws at the last one recorded: one command replays them all.
    void open_draw_run();
    // What consecutive draws share, resolved at the first draw after it changed and replayed
    // only when it differs from the previous draw's: the pipeline's fixed state, the vertex and
    // index buffers (on the pipeline's vertex array), the bindings of the bound groups. Their
    // arrays are ranges of blends_, vertex_bindings_ and bindings_.
    struct PipelineState {
        GLuint program = 0;
        GLenum topology = GL_TRIANGLES;
        GlRasterState raster;
        GLint base_instance_location = -1;
        uint32_t first_blend = 0, blend_count = 0;
    };
    struct VertexState {
        GLuint vao = 0;
        uint32_t first_vertex_binding = 0, vertex_binding_count = 0;
        GLuint index_buffer = 0;
        GLenum index_type = GL_UNSIGNED_INT;
        uint64_t index_offset = 0;  ///< of the bound index buffer
    };
    struct BindingState {
        uint32_t first_binding = 0, binding_count = 0;
    };
    struct VertexBinding {
        uint32_t slot;
        GLuint buffer;
        GLintptr offset;
        GLsizei stride;
    };
    /// One recorded draw: the states it draws with (indices into the arrays below) and its arguments.
    struct Draw {
        uint32_t pipeline_state = 0;
        uint32_t vertex_state = 0;
        uint32_t binding_state = 0;
        uint32_t count = 0;
        uint32_t instance_count = 0;
        uint32_t first = 0;  ///< with kDrawIndirect: the index of its arguments in indirect_draws_
        int32_t base_vertex = 0;
        uint32_t first_instance = 0;
        /// Vertex and index buffers bound since the draw before: the range [first_vertex_change,
        /// + vertex_change_count) of vertex_changes_, applied before this draw (see VertexChange).
        uint32_t first_vertex_change = 0;
        uint32_t vertex_change_count = 0;
        /// A uniform range of the binding state drawn at another offset (offset_override_), with
        /// kDrawOverride.
        uint32_t override_binding = kNoOverride;
        uint8_t flags = 0;  ///< kDraw* (what replay has to do besides the call)
        GLintptr override_offset = 0;
        PushRange push;  ///< with kDrawPush
    };
    static constexpr uint32_t kNoOverride = UINT32_MAX;
    // Draw::flags.
    static constexpr uint8_t kDrawIndexed = 1;
    static constexpr uint8_t kDrawIndirect = 2;
    static constexpr uint8_t kDrawOverride = 4;      ///< override_binding is set
    static constexpr uint8_t kDrawPush = 8;          ///< the pipeline has a push-constant block (push)
    static constexpr uint8_t kDrawBaseInstance = 16;  ///< the pipeline reads gl_InstanceIndex (base instance uniform)
    static constexpr uint8_t kDrawNewState = 32;  ///< states or override binding differ from the draw before
    uint8_t pipeline_draw_flags_ = 0;  ///< kDrawPush and kDrawBaseInstance of draw_pipeline_
    /// What consecutive draws share while nothing but per-draw data changes: the states' indices,
    /// the override's binding, the flags of the pipeline and the override. draw_common fills it
    /// (and marks its draw kDrawNewState); while draw_shared_valid_, the inline draw paths copy
    /// it. Whatever changes one of its sources clears draw_shared_valid_, and so does whatever
    /// clears pipeline_state_valid_, vertex_state_valid_ or binding_state_valid_ (it implies them).
    struct DrawShared {
        uint32_t pipeline_state = 0, vertex_state = 0, binding_state = 0;
        uint32_t override_binding = kNoOverride;
        uint8_t flags = 0;
    };
    DrawShared draw_shared_;
    bool draw_shared_valid_ = false;
    /// Per-draw vertex and index buffers without copying the vertex state: every buffer bound is
    /// recorded as a change that the next draw applies on top of its vertex state and what the
    /// draws before it bound (replay is in order). A new vertex state, resolved from the tracker,
    /// drops the changes no draw took. `slot` is a vertex buffer slot (< rhi::kMaxVertexBuffers;
    /// replay skips those the pipeline does not read), or else the index buffer, `slot` then
    /// holding its GL index type.
    struct VertexChange {
        uint32_t slot = 0;
        GLuint buffer = 0;
        GLintptr offset = 0;
    };

    /// Per-draw uniform data without copying the binding state: one uniform range of
    /// binding_states_.back() (an index into bindings_) rebound at `offset` by the draws recorded
    /// while it is set; a new binding state takes the offset over and clears it.
    struct OffsetOverride {
        uint32_t binding = kNoOverride;
        GLintptr offset = 0;
    };
    OffsetOverride offset_override_;
    std::size_t last_rebound_ = 0;  ///< the pipeline binding rebinds_offset found last (a hint)
    /// Whether the state checked and resolved for the previous draw holds for this one as it
    /// is; when something it relied on changed (a destruction, an indirect draw, the first
    /// indexed draw without an index buffer recorded), forgets it all.
    bool draw_state_current(bool indexed, bool indirect);
    /// Checks the bound state for a draw and records the parts that changed since the previous
    /// draw (after draw_state_current found it not current); false with an error recorded when
    /// it is refused.
    bool prepare_draw_state(const char* command, bool indexed, bool indirect);
    /// The GL calls of one draw (its shared state only when it differs from the last draw's).
    void replay_draw(GlStateCache& cache, const Draw& draw);
    /// The vertex and index buffers bound before `draw` (its VertexChange records).
    void replay_vertex_changes(GlStateCache& cache, const Draw& draw);
    /// The pipeline, vertex and binding states of `draw` that differ from those replayed last.
    void replay_shared_states(GlStateCache& cache, const Draw& draw);
    /// Consecutive draws with no other command between them: one entry of commands_ replays
    /// them all (a draw appends to the run instead of adding a command of its own).
    struct DrawRun {
        uint32_t first = 0, count = 0;  ///< a range of draws_
    };
    /// The GL calls of a run of draws.
    void replay_run(GlStateCache& cache, DrawRun run);
    void apply_bindings(GlStateCache& cache, uint32_t first, uint32_t count) const;
    /// Objects the device has destroyed so far (a draw state resolved before a destruction is
    /// checked again: its objects may be gone).
    [[nodiscard]] uint64_t device_removals() const;

    GlDevice* device_;
    rhi::CommandListState state_;
    std::vector<GlCommand> commands_;
    // Storage for the frame's draws, kept from frame to frame so that steady-state recording
    // allocates nothing.
    FrameArray<Draw> draws_;
    std::vector<IndirectDraw> indirect_draws_;
    FrameArray<DrawRun> draw_runs_;
    bool draw_run_open_ = false;  ///< the last command is draw_runs_.back(): the next draw joins it
    FrameArray<PipelineState> pipeline_states_;
    FrameArray<VertexState> vertex_states_;
    FrameArray<BindingState> binding_states_;
    std::vector<GlBlendState> blends_;
    FrameArray<VertexBinding> vertex_bindings_;
    FrameArray<VertexChange> vertex_changes_;
    std::size_t first_pending_change_ = 0;  ///< vertex_changes_ from here on: for the next draw
    FrameArray<ResolvedBinding> bindings_;
    /// The entries binding_states_.back() was resolved from, one per pipeline binding.
    std::vector<rhi::BindingEntry> resolved_entries_;
    /// The last of each kind of state still holds for the next draw: nothing of that kind was
    /// bound, nothing begun, recorded or destroyed since (a new pipeline changes all three).
    bool pipeline_state_valid_ = false;
    bool vertex_state_valid_ = false;
    bool binding_state_valid_ = false;
    bool binding_state_drawn_ = false;  ///< a draw was recorded with binding_states_.back()
    bool vertex_state_indexed_ = false;  ///< vertex_states_.back() has an index buffer (was made for indexed draws)
    bool draw_checked_indexed_ = false;  ///< the last check_draw was of an indexed draw
    uint64_t draw_state_removals_ = 0;
    const GlPipeline* draw_pipeline_ = nullptr;  ///< the pipeline of pipeline_states_.back()
    /// The states whose GL calls were replayed last (UINT32_MAX: none, or other commands since).
    uint32_t replayed_pipeline_ = UINT32_MAX;
    uint32_t replayed_vertex_ = UINT32_MAX;
    uint32_t replayed_bindings_ = UINT32_MAX;
    /// The index buffer's type and offset as replayed so far (the vertex state's, then changes).
    GLenum replayed_topology_ = GL_TRIANGLES;
    GLenum replayed_index_type_ = GL_UNSIGNED_INT;
    uint64_t replayed_index_offset_ = 0;
    /// Forgets every state resolved for draws (the next draw checks and resolves all again).
    void invalidate_draw_state() {
        pipeline_state_valid_ = vertex_state_valid_ = binding_state_valid_ = false;
        draw_shared_valid_ = false;
    }
    /// Forgets the vertex state or the binding state (and so what draws share: draw_shared_valid_
    /// implies both).
    void invalidate_vertex_state() { vertex_state_valid_ = draw_shared_valid_ = false; }
    void invalidate_binding_state() { binding_state_valid_ = draw_shared_valid_ = false; }
    std::optional<Error> first_error_;
    // The GL side of the open render pass.
    GLuint pass_framebuffer_ = 0;
    std::vector<GLenum> pass_discard_after_;  ///< attachments whose store op is DontCare
    bool push_dirty_ = false;                 ///< push constants changed since push_range_ was made
    PushRange push_range_;                    ///< the last copy of the push constants (object 0: none yet)
    std::vector<std::pair<std::string, GLuint>> timers_;
};

class GlDevice final : public rhi::Device {
public:
    static Result<std::unique_ptr<GlDevice>> create(const rhi::DeviceDesc& desc);
    /// A device on the application's current context (see loom/gl/gl_embed.hpp).
    static Result<std::unique_ptr<GlDevice>> create_on_current_context(const CurrentContextDesc& desc);
    ~GlDevice() override;

    [[nodiscard]] rhi::Backend backend() const override { return rhi::Backend::OpenGL; }
    [[nodiscard]] const rhi::Capabilities& capabilities() const override { return caps_; }

    Result<rhi::TextureHandle> create_texture(const rhi::TextureDesc& desc) override;
    Result<rhi::BufferHandle> create_buffer(const rhi::BufferDesc& desc) override;
    Result<rhi::SamplerHandle> create_sampler(const rhi::SamplerDesc& desc) override;
    Result<rhi::ShaderHandle> create_shader(const rhi::ShaderModule& module) override;
    Result<rhi::PipelineHandle> create_graphics_pipeline(const rhi::GraphicsPipelineDesc& desc) override;
    Result<rhi::PipelineHandle> create_compute_pipeline(const rhi::ComputePipelineDesc& desc) override;
    Result<rhi::HeapHandle> create_heap(const rhi::HeapDesc& desc) override;
    Result<rhi::MemoryRequirements> texture_memory_requirements(const rhi::TextureDesc& desc) override;
    Result<rhi::MemoryRequirements> buffer_memory_requirements(const rhi::BufferDesc& desc) override;

    Status destroy(rhi::TextureHandle texture) override;
    Status destroy(rhi::BufferHandle buffer) override;
    Status destroy(rhi::SamplerHandle sampler) override;
    Status destroy(rhi::ShaderHandle shader) override;
    Status destroy(rhi::PipelineHandle pipeline) override;
    Status destroy(rhi::HeapHandle heap) override;

    Result<rhi::TextureDesc> texture_desc(rhi::TextureHandle texture) override;
    Result<rhi::BufferDesc> buffer_desc(rhi::BufferHandle buffer) override;

    Status write_buffer(rhi::BufferHandle buffer, uint64_t offset, std::span<const std::byte> data) override;
    Status write_texture(rhi::TextureHandle texture, const rhi::TextureRegion& region,
                         std::span<const std::byte> data) override;
    Result<rhi::Image> read_texture(rhi::TextureHandle texture, uint32_t mip, uint32_t layer) override;
    Result<std::vector<std::byte>> read_buffer(rhi::BufferHandle buffer, uint64_t offset, uint64_t size) override;

    rhi::CommandList& begin_frame() override;
    Status end_frame() override;
    Status wait_idle() override;
    std::vector<rhi::TimerResult> timer_results() override;

    [[nodiscard]] rhi::ResourceStats resource_stats() const override { return stats_; }
    [[nodiscard]] rhi::FrameStats last_frame_stats() const override { return last_frame_; }

    bool poll_window() override;
    [[nodiscard]] rhi::Extent3D window_size() const override;
    [[nodiscard]] const rhi::WindowInput& window_input() const override;
    rhi::TextureHandle backbuffer() override;

    [[nodiscard]] GlCacheStats cache_stats() const { return {framebuffers_.size(), vertex_arrays_.size()}; }

    // -- embedding (loom/gl/gl_embed.hpp) ------------------------------------------------
    Result<rhi::TextureHandle> import_texture(GLuint name, const rhi::TextureDesc& desc, rhi::ResourceState state);
    Result<GLuint> texture_name(rhi::TextureHandle texture);
    Status blit_to_framebuffer(rhi::TextureHandle texture, GLuint framebuffer, GLint x, GLint y, GLsizei width,
                               GLsizei height);
    /// On the application's context: saves its GL state for the lifetime of the scope and
    /// restores it after (nothing on a context loom owns).
    [[nodiscard]] GlAppStateScope app_state_scope() { return GlAppStateScope(app_state_.get(), *cache_); }

    // -- used by GlCommandList ----------------------------------------------------------
    /// The buffers, textures and samplers of this device as the validation layer sees them.
    const rhi::validation::ResourceLookup& resource_lookup();
    /// The pipelines of this device as the command-list state sees them.
    rhi::PipelineLookup pipeline_lookup();
    rhi::HandlePool<rhi::TextureTag, GlTexture>& textures() { return textures_; }
    rhi::HandlePool<rhi::BufferTag, GlBuffer>& buffers() { return buffers_; }
    rhi::HandlePool<rhi::SamplerTag, GlSampler>& samplers() { return samplers_; }
    rhi::HandlePool<rhi::PipelineTag, GlPipeline>& pipelines() { return pipelines_; }
    /// Objects removed so far from the device's pools (textures, buffers, samplers, shaders,
    /// pipelines): unchanged, every object found alive before is still alive.
    [[nodiscard]] uint64_t removals() const { return removals_; }
    /// The texture view of the (resolved) `range` of `texture` as a shader declares it (`kind`),
    /// made on first use and kept until the texture goes; Unsupported for an imported texture
    /// without immutable storage.
    Result<GLuint> texture_view(GlTexture& texture, const rhi::TextureRange& range, rhi::TextureKind kind);
    /// The names of a texture's views (deleted with it).
    static std::vector<GLuint> view_names(const GlTexture& texture);
    /// The framebuffer object for this attachment set (created on first use); 0 when GL
    /// reports the set incomplete.
    GLuint framebuffer_for(const std::vector<std::pair<const GlTexture*, std::array<uint32_t, 2>>>& colors,
                           const GlTexture* depth, std::array<uint32_t, 2> depth_mip_layer);
    /// Copies `data` into this frame's transient uniform memory.
    /// `name`, when given, receives the GL name of the buffer the binding is in.
    LOOM_GL_HOT rhi::BufferBinding allocate_transient(std::span<const std::byte> data, GLuint* name = nullptr) {
        // The common case inline (per draw for push constants): room in the frame's last chunk.
        if (!frame_chunks_.empty()) [[likely]] {
            TransientChunk& chunk = frame_chunks_.back();
            // GL's offset alignments are powers of two in practice; any other takes the division.
            const uint64_t offset = uniform_alignment_mask_ != 0
                                        ? (chunk.used + uniform_alignment_mask_) & ~uniform_alignment_mask_
                                        : checked::align_up_in_range(chunk.used, caps_.uniform_buffer_offset_alignment);
            const uint64_t size = data.empty() ? 1 : data.size();
            if (offset + size <= chunk.size) [[likely]] {
                copy_small(chunk.data + offset, data);
                chunk.used = offset + size;
                pending_uploads_ += data.size();
                if (name) *name = chunk.name;
                return rhi::BufferBinding{chunk.buffer, offset, size};
            }
        }
        return allocate_transient_chunk(data, name);
    }
    /// memcpy, with the sizes of per-draw constants copied inline (no call into the C library).
    LOOM_GL_HOT static void copy_small(std::byte* to, std::span<const std::byte> data) {
        switch (data.size()) {
            case 0: return;
            case 16: std::memcpy(to, data.data(), 16); return;
            case 32: std::memcpy(to, data.data(), 32); return;
            case 64: std::memcpy(to, data.data(), 64); return;
            default: std::memcpy(to, data.data(), data.size());
        }
    }
    GLuint acquire_query();
    void discard_first_timer_query();
    /// Counts upload bytes into the frame being prepared.
    void count_upload(uint64_t bytes) { pending_uploads_ += bytes; }
    void count_render_pass() { ++render_passes_in_frame_; }
    struct Limits {
        uint32_t max_image_units = 8;
        uint32_t max_storage_buffer_bindings = 8;
    };
    [[nodiscard]] const Limits& limits() const { return limits_; }

private:
    GlDevice()
        : textures_(id_, &removals_), buffers_(id_, &removals_), samplers_(id_, &removals_), shaders_(id_, &removals_),
          pipelines_(id_, &removals_) {}
    /// Sets up a device on `context_` (current): checks the version, loom's global state
    /// (owned contexts only), capabilities, the state cache and the command list.
    Status init(bool debug, bool validation);

    void init_capabilities();
    /// allocate_transient when the frame's last chunk has no room: another chunk (a free one, or
    /// a new buffer), then the data in it.
    rhi::BufferBinding allocate_transient_chunk(std::span<const std::byte> data, GLuint* name);
    /// Runs `destroy_gl` now, or after the recorded frame has executed.
    void delete_later(std::function<void()> destroy_gl);
    void forget_framebuffers_with(GLuint texture);
    Result<GLuint> vertex_array_for(const std::vector<rhi::VertexBufferLayout>& layout, std::vector<uint32_t>& key);
    void release_vertex_array(const std::vector<uint32_t>& key);
    Result<rhi::TextureHandle> create_texture_internal(const rhi::TextureDesc& desc, bool internal);
    /// The shaders of this device as the validation layer sees them.
    rhi::validation::ShaderLookup shader_lookup();
    void collect_timers(bool wait);
    void recycle_transient_chunks(bool wait);
    void ensure_backbuffer();
    Result<rhi::Image> read_texture_gl(GlTexture& texture, uint32_t mip, uint32_t layer);

    struct TransientChunk {
        rhi::BufferHandle buffer;
        GLuint name = 0;
        uint64_t size = 0;
        uint64_t used = 0;
        /// Where the data goes: the buffer mapped for the device's lifetime (persistent and
        /// coherent: no upload call, as a hand-written ring would do), or, where GL refused
        /// the mapping, `staging`, uploaded at end_frame.
        std::byte* data = nullptr;
        std::vector<std::byte> staging;
        GLsync fence = nullptr;
    };
    struct FrameTimers {
        std::vector<std::pair<std::string, GLuint>> queries;
    };
    struct VertexArrayEntry {
        GLuint vao = 0;
        uint32_t users = 0;
    };

    uint16_t id_ = rhi::next_device_id();
    std::unique_ptr<GlContext> context_;
    /// On an application's context: its state around loom's work, and its debug output.
    std::unique_ptr<GlAppState> app_state_;
    std::optional<SavedDebugOutput> saved_debug_output_;
    rhi::Capabilities caps_;
    /// uniform_buffer_offset_alignment - 1 when it is a power of two (0 otherwise): the per-draw
    /// transient allocation rounds up with a mask instead of a division.
    uint64_t uniform_alignment_mask_ = 0;
    rhi::validation::ResourceLookup resource_lookup_;  ///< see resource_lookup()
    Limits limits_;
    uint64_t removals_ = 0;  ///< objects removed from any of the pools below (removals())
    rhi::HandlePool<rhi::TextureTag, GlTexture> textures_;
    rhi::HandlePool<rhi::BufferTag, GlBuffer> buffers_;
    rhi::HandlePool<rhi::SamplerTag, GlSampler> samplers_;
    rhi::HandlePool<rhi::ShaderTag, GlShader> shaders_;
    rhi::HandlePool<rhi::PipelineTag, GlPipeline> pipelines_;
    rhi::ResourceStats stats_;
    rhi::FrameStats last_frame_;
    uint64_t pending_uploads_ = 0;
    uint64_t render_passes_in_frame_ = 0;
    GlCallCounters counters_;
    std::unique_ptr<GlStateCache> cache_;
    std::unique_ptr<GlCommandList> list_;
    uint64_t frame_index_ = 0;
    std::vector<std::function<void()>> deferred_deletes_;

    std::map<std::vector<GLuint>, GLuint> framebuffers_;
    std::map<std::vector<uint32_t>, VertexArrayEntry> vertex_arrays_;

    std::vector<TransientChunk> free_chunks_;
    std::vector<TransientChunk> frame_chunks_;
    std::deque<TransientChunk> busy_chunks_;

    std::vector<GLuint> free_queries_;
    std::deque<FrameTimers> pending_timers_;
    std::vector<rhi::TimerResult> latest_timers_;

    rhi::TextureHandle backbuffer_;
    GLuint backbuffer_fbo_ = 0;
};

}  // namespace loom::gl
