#pragma once
// Passes and their ports. A pass is a node of the frame graph with named ports: `input` (reads a
// texture), `output` (produces a new texture), `inout` (reads a texture and modifies it in
// place, e.g. drawing shadows onto an existing colour target). Ports are declared in port sets,
// and a pass is composed from port sets the way the paper (Hafner, ELS 2019, §5, Listings 3-5)
// builds its deferred pass from a deferred, a shadow-receiving and a high-pass class.
//
// Declaring and composing ports touches no GPU. Execution is a separate step: the executor
// (executor.hpp) calls execute() once per frame with a PassContext whose ports are resolved to
// real textures. Derive from Pass and override execute(), or hand a callback to on_execute().

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "loom/framegraph/buffer_spec.hpp"
#include "loom/framegraph/texture_spec.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

class PassContext;

/// How a port uses its texture: reads it, produces it, or modifies it in place.
enum class PortKind : uint8_t {
    Input,   ///< reads the texture produced by the port connected to it
    Output,  ///< produces a new texture
    InOut,   ///< reads the texture of its source and modifies it in the same physical texture
};

/// "input", "output", "inout".
std::string_view port_kind_name(PortKind kind);

/// What flows through a port: a texture or a buffer. Connected ports carry the same type.
enum class ResourceType : uint8_t { Texture, Buffer };

/// "texture", "buffer".
std::string_view resource_type_name(ResourceType type);

/// What a pass records, which decides what its ports' roles imply and what it may record:
/// a graphics pass draws in render passes (written textures are attachments, read ones are
/// sampled); a compute pass dispatches and never opens a render pass (written textures are
/// storage images, read ones sampled; buffers storage); a copy pass copies (written resources
/// are copy destinations, read ones copy sources).
enum class PassKind : uint8_t { Graphics, Compute, Copy };

/// "graphics", "compute", "copy".
std::string_view pass_kind_name(PassKind kind);

/// The queue a pass is submitted to. Compute and copy passes may ask for the async compute
/// queue: where the device has one, they run there beside the graphics queue, with the
/// semaphores and queue-ownership transfers the plan derives (Plan::queue_syncs,
/// Plan::ownership_transfers); elsewhere the same plan runs serially on one queue.
enum class Queue : uint8_t { Graphics, AsyncCompute };

/// "graphics", "async_compute".
std::string_view queue_name(Queue queue);

/// True for the kinds that take a source (input, inout).
inline bool port_reads(PortKind kind) { return kind != PortKind::Output; }
/// True for the kinds that produce a texture others can read (output, inout).
inline bool port_writes(PortKind kind) { return kind != PortKind::Input; }

/// Why `name` cannot name a pass or a port, or nullopt when it can. A name is non-empty and
/// has no '.' (it separates pass and port in "pass.port" and in resource names) and no
/// control character (a newline would split every line-based output: tables, logs, errors).
std::optional<std::string> name_problem(std::string_view name);

/// `name` in single quotes with control characters written as \n, \t or \xNN, so that an error
/// naming a user's name (which may be one name_problem() refuses) is still one line.
std::string quoted_name(std::string_view name);

/// The mip levels and array layers of a texture a port reads or writes (rhi::TextureRange;
/// counts of rhi::kRemainingSubresources run to the last level or layer). Two ports of one pass
/// may read one texture and modify it in place when their ranges are disjoint: a down-sampling
/// pass reads mip k-1 and writes mip k of one pyramid.
using SubresourceRange = rhi::TextureRange;

/// Every mip level and layer.
inline constexpr SubresourceRange kWholeTexture{};
/// Mip level `level`, every layer.
inline SubresourceRange mip(uint32_t level) { return {level, 1, 0, rhi::kRemainingSubresources}; }
/// Layer `index` (of an array; 6 faces of a cube are layers too), every mip level.
inline SubresourceRange layer(uint32_t index) { return {0, rhi::kRemainingSubresources, index, 1}; }
/// `count` mip levels from `base`, every layer.
inline SubresourceRange mips(uint32_t base, uint32_t count) { return {base, count, 0, rhi::kRemainingSubresources}; }
/// Mip `level` of layer `index`.
inline SubresourceRange mip_of_layer(uint32_t level, uint32_t index) { return {level, 1, index, 1}; }

/// "whole", "mip 2", "mips 1..3", "layer 4", "mip 0 layers 2..5".
std::string describe_range(const SubresourceRange& range);

/// True when the two ranges share a subresource (before resolution: open counts run to the end).
bool overlaps(const SubresourceRange& a, const SubresourceRange& b);
/// True when the two byte ranges share a byte (size 0: to the end).
bool overlaps(const BufferRange& a, const BufferRange& b);

/// Index of a pass in a graph (declaration order).
struct PassId {
    uint32_t index = 0;
    friend bool operator==(const PassId&, const PassId&) = default;
};

/// A port of a graph by indices: pass (declaration order) and port (Pass::ports() order). The
/// typed handle of a port: connect, mark_output and Pass::read take it, no name is looked up.
struct PortAddress {
    uint32_t pass = 0;
    uint32_t port = 0;
    friend bool operator==(const PortAddress&, const PortAddress&) = default;
    friend auto operator<=>(const PortAddress&, const PortAddress&) = default;
};

/// The port `index` of pass `pass`: a pass's ports are numbered in the order their names were
/// first declared (Pass::ports()), so the first output a pass declares after two inputs is
/// port_of(id, 2).
inline PortAddress port_of(PassId pass, uint32_t index) { return {pass.index, index}; }

/// The names of the port sets that declared a port, in the order they did. Nearly every port
/// has one, usually short: the names are kept in one string (each prefixed by its length), so
/// one name up to 14 bytes takes no allocation. Reads like a list of string_views.
class PortSetNames {
public:
    class const_iterator {
    public:
        using iterator_category = std::forward_iterator_tag;
        using value_type = std::string_view;
        using difference_type = std::ptrdiff_t;
        using pointer = const std::string_view*;
        using reference = std::string_view;

        const_iterator() = default;
        std::string_view operator*() const;
        const_iterator& operator++();
        const_iterator operator++(int) {
            const_iterator before = *this;
            ++*this;
            return before;
        }
        friend bool operator==(const const_iterator&, const const_iterator&) = default;

    private:
        friend class PortSetNames;
        const_iterator(const char* at) : at_(at) {}
        const char* at_ = nullptr;
    };
    using iterator = const_iterator;
    using value_type = std::string_view;
    using size_type = std::size_t;

    PortSetNames() = default;
    PortSetNames(std::initializer_list<std::string_view> names);

    /// Appends `name` (kept as given; Pass::add checks port set names).
    void push_back(std::string_view name);
    /// True when `name` is one of the names.
    [[nodiscard]] bool contains(std::string_view name) const;
    [[nodiscard]] std::size_t size() const;
    [[nodiscard]] bool empty() const { return encoded_.empty(); }
    /// The first name; "" when there is none.
    [[nodiscard]] std::string_view front() const;
    /// The name at `index` (< size()).
    [[nodiscard]] std::string_view operator[](std::size_t index) const;
    [[nodiscard]] const_iterator begin() const { return const_iterator(encoded_.data()); }
    [[nodiscard]] const_iterator end() const { return const_iterator(encoded_.data() + encoded_.size()); }

    friend bool operator==(const PortSetNames&, const PortSetNames&) = default;
    /// The same names in the same order.
    friend bool operator==(const PortSetNames& names, const std::vector<std::string>& list);

private:
    std::string encoded_;  // per name: its length (LEB128), then its bytes
};

/// One declared port.
struct Port {
    std::string name;
    PortKind kind = PortKind::Input;
    /// The texture constraints (texture ports).
    TextureSpec spec;
    /// Input/inout: may stay unconnected (the pass then runs without it; an unconnected
    /// optional inout starts a fresh texture). Output: when nothing reads it and it is not a
    /// graph output, no texture is allocated for it.
    bool optional = false;
    /// Names of the port sets that declared this port, in the order they did.
    PortSetNames port_sets;
    /// Texture or buffer.
    ResourceType type = ResourceType::Texture;
    /// The buffer constraints (buffer ports).
    BufferSpec buffer;
    /// Texture ports: the mip levels and layers it reads or writes (the whole texture by default).
    SubresourceRange range{};
    /// Buffer ports: the bytes it reads or writes (the whole buffer by default).
    BufferRange bytes{};

    friend bool operator==(const Port&, const Port&) = default;
};

/// A named set of port declarations that passes are composed from. (loom::passes pairs one
/// with shader code in a PassPart.)
class PortSet {
public:
    /// An empty port set called `name` (named in errors about its ports; Pass::add refuses
    /// names that name_problem() refuses).
    explicit PortSet(std::string name) : name_(std::move(name)) {}

    /// Records a port declaration; Pass::add merges repeated names.
    PortSet& declare(std::string port, PortKind kind, TextureSpec spec = {}, bool optional = false,
                     SubresourceRange range = {});
    /// Declares an input port (reading `range` of the texture).
    PortSet& input(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::Input, std::move(spec), false, range);
    }
    /// Declares an output port.
    PortSet& output(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::Output, std::move(spec), false, range);
    }
    /// Declares an inout port (modifies `range` of its source's texture in place).
    PortSet& inout(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::InOut, std::move(spec), false, range);
    }
    /// Declares an input that may stay unconnected.
    PortSet& optional_input(std::string port, TextureSpec spec = {}) {
        return declare(std::move(port), PortKind::Input, std::move(spec), true);
    }
    /// Declares an output that gets no texture when nothing reads it.
    PortSet& optional_output(std::string port, TextureSpec spec = {}) {
        return declare(std::move(port), PortKind::Output, std::move(spec), true);
    }

    /// Records a buffer port declaration.
    PortSet& declare_buffer(std::string port, PortKind kind, BufferSpec spec = {}, bool optional = false,
                            BufferRange bytes = {});
    /// Declares a port reading (`bytes` of) a buffer.
    PortSet& buffer_input(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::Input, std::move(spec), false, bytes);
    }
    /// Declares a port producing a new buffer.
    PortSet& buffer_output(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::Output, std::move(spec), false, bytes);
    }
    /// Declares a port reading a buffer and modifying (`bytes` of) it in place.
    PortSet& buffer_inout(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::InOut, std::move(spec), false, bytes);
    }

    /// The port set's name.
    [[nodiscard]] const std::string& name() const { return name_; }
    /// Declarations in the order they were made (not merged).
    [[nodiscard]] const std::vector<Port>& declarations() const { return declarations_; }

private:
    std::string name_;
    std::vector<Port> declarations_;
};

/// A node of the frame graph. Ports come from port sets; the pass's own declarations (input(),
/// output(), ...) form a port set named after the pass.
///
/// Two declarations of the same port name (from two port sets, or twice from one) merge when they
/// have the same kind: the specs are joined (join.hpp, without a frame size) and the port is
/// optional only if every declaration says so. Different kinds, or specs that do not join, are
/// an error naming the pass, the port and both port sets. Declaration methods chain; the first
/// error is kept and reported by status() and by FrameGraph::add_pass.
class Pass {
public:
    /// A pass called `name` (unique in its graph) without ports.
    explicit Pass(std::string name);
    /// Passes may be subclassed (execute()).
    virtual ~Pass();
    Pass(const Pass&) = default;
    Pass& operator=(const Pass&) = default;
    Pass(Pass&&) noexcept = default;
    Pass& operator=(Pass&&) noexcept = default;

    /// Adds every port of `ports`, merging names declared before. A port set name that
    /// name_problem() refuses is an error (status()) naming the pass and the port set, and its
    /// ports are not added.
    Pass& add(const PortSet& ports);

    // Declarations on the pass's own port set.
    Pass& declare(std::string port, PortKind kind, TextureSpec spec = {}, bool optional = false,
                  SubresourceRange range = {});
    /// Declares an input port on the pass's own port set, reading `range` of the texture.
    Pass& input(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::Input, std::move(spec), false, range);
    }
    /// Declares an output port on the pass's own port set (writing `range` of the new texture).
    Pass& output(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::Output, std::move(spec), false, range);
    }
    /// Declares an inout port (modifies `range` of its source's texture in place).
    Pass& inout(std::string port, TextureSpec spec = {}, SubresourceRange range = {}) {
        return declare(std::move(port), PortKind::InOut, std::move(spec), false, range);
    }
    /// Declares an input that may stay unconnected.
    Pass& optional_input(std::string port, TextureSpec spec = {}) {
        return declare(std::move(port), PortKind::Input, std::move(spec), true);
    }
    /// Declares an output that gets no texture when nothing reads it.
    Pass& optional_output(std::string port, TextureSpec spec = {}) {
        return declare(std::move(port), PortKind::Output, std::move(spec), true);
    }

    /// Declares an input reading the texture that `source` (an output or inout of a pass
    /// already in the graph) writes, and connects it when the pass is added: a read in one
    /// step, by the handle of the write. The port is called "read<n>", n counting this pass's
    /// reads from 0 (a name the pass declared itself is an error naming it).
    Pass& read(PortAddress source, TextureSpec spec = {}, SubresourceRange range = {});
    /// What read() declared: (index of the input in ports(), the port it reads), in order.
    [[nodiscard]] const std::vector<std::pair<uint32_t, PortAddress>>& reads() const { return reads_; }

    // Buffer ports on the pass's own port set (see BufferSpec for what a port's usage means).
    Pass& declare_buffer(std::string port, PortKind kind, BufferSpec spec = {}, bool optional = false,
                         BufferRange bytes = {});
    /// Declares a port reading (`bytes` of) a buffer.
    Pass& buffer_input(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::Input, std::move(spec), false, bytes);
    }
    /// Declares a port producing a new buffer.
    Pass& buffer_output(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::Output, std::move(spec), false, bytes);
    }
    /// Declares a port reading a buffer and modifying (`bytes` of) it in place.
    Pass& buffer_inout(std::string port, BufferSpec spec = {}, BufferRange bytes = {}) {
        return declare_buffer(std::move(port), PortKind::InOut, std::move(spec), false, bytes);
    }
    /// Declares a buffer input that may stay unconnected.
    Pass& optional_buffer_input(std::string port, BufferSpec spec = {}) {
        return declare_buffer(std::move(port), PortKind::Input, std::move(spec), true);
    }
    /// Declares a buffer output that gets no buffer when nothing reads it.
    Pass& optional_buffer_output(std::string port, BufferSpec spec = {}) {
        return declare_buffer(std::move(port), PortKind::Output, std::move(spec), true);
    }

    /// Sets what the pass records (graphics by default; see PassKind).
    Pass& set_kind(PassKind kind) {
        kind_ = kind;
        return *this;
    }
    /// What the pass records.
    [[nodiscard]] PassKind kind() const { return kind_; }

    /// Sets the queue the pass runs on (graphics by default). Only compute and copy passes may
    /// run on Queue::AsyncCompute; planning a graphics pass there is an error naming it.
    Pass& set_queue(Queue queue) {
        queue_ = queue;
        return *this;
    }
    /// The queue the pass asks for.
    [[nodiscard]] Queue queue() const { return queue_; }

    /// Marks the pass as having effects outside the graph (present, readback, writes to a
    /// buffer): it is never culled.
    Pass& set_side_effect(bool side_effect = true) {
        side_effect_ = side_effect;
        return *this;
    }
    /// True when the pass is never culled.
    [[nodiscard]] bool side_effect() const { return side_effect_; }

    /// Pins the pass: in every pass order (PassOrder) it keeps its place relative to the other
    /// pinned passes and to the side-effect passes as in the declared order, e.g. a UI overlay
    /// stays after tone mapping even where nothing connects them. Without pins only the
    /// dependencies (and FrameGraph::require_order) order passes under PassOrder::Memory.
    Pass& keep_declared_order(bool keep = true) {
        keep_declared_order_ = keep;
        return *this;
    }
    /// True when the pass is pinned by keep_declared_order().
    [[nodiscard]] bool keeps_declared_order() const { return keep_declared_order_; }

    /// The work the pass records every frame (see PassContext). Runs the callback set with
    /// on_execute(); without one it records nothing. An error returned here fails the frame and
    /// comes back from the executor naming the pass.
    virtual Status execute(PassContext& context);

    /// Sets the callback the default execute() runs (for passes that are not subclasses).
    using ExecuteFunction = std::function<Status(PassContext&)>;
    Pass& on_execute(ExecuteFunction function) {
        execute_function_ = std::move(function);
        return *this;
    }
    /// True when a callback was set with on_execute().
    [[nodiscard]] bool has_execute_function() const { return static_cast<bool>(execute_function_); }

    /// The pass's name.
    [[nodiscard]] const std::string& name() const { return name_; }
    /// Merged ports, in the order their names were first declared.
    [[nodiscard]] const std::vector<Port>& ports() const { return ports_; }
    /// The port called `name`, or nullptr.
    [[nodiscard]] const Port* find_port(std::string_view name) const;
    /// Index of the port called `name` in ports().
    [[nodiscard]] std::optional<uint32_t> port_index(std::string_view name) const;
    /// Success, or the first declaration error.
    [[nodiscard]] Status status() const;

private:
    // FrameGraph::redeclare keeps the ports of the passes it removes (moved out just before
    // they are destroyed) to compare the next declaration with.
    friend class FrameGraph;

    void merge(Port declaration, const std::string& port_set);
    // Adds a port whose name the pass does not declare yet.
    void append_port(Port&& port);

    std::string name_;
    std::vector<Port> ports_;
    // Port name -> index in ports_, so merging a declaration and finding a port by name do
    // not scan every port (a pass may have very many). Filled only from kIndexedPorts ports on:
    // below that a scan of ports_ is cheaper than building the map.
    static constexpr std::size_t kIndexedPorts = 16;
    // Room made for ports (and reads) at the first one declared.
    static constexpr std::size_t kFirstPorts = 4;
    std::map<std::string, uint32_t, std::less<>> port_indices_;
    std::vector<std::pair<uint32_t, PortAddress>> reads_;
    bool side_effect_ = false;
    bool keep_declared_order_ = false;
    PassKind kind_ = PassKind::Graphics;
    Queue queue_ = Queue::Graphics;
    std::optional<Error> error_;
    ExecuteFunction execute_function_;
};

}  // namespace loom::fg
