#include <charconv>
#include <concepts>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "loom/framegraph/export.hpp"

namespace loom::fg {
namespace {

// Writes JSON text straight to a stream, value by value, so a large plan is never held as one
// document (nor as one string): memory stays that of a small buffer. The text is exactly what
// nlohmann::json::dump(indent) prints for the same document: the same separators and
// indentation, its string escaping, and keys in its (sorted) order, which is why every object
// below lists its members alphabetically. Export.StreamedJsonIsWhatTheWholeDocumentDumps...
// checks that.
class JsonWriter {
public:
    JsonWriter(std::ostream& out, int indent) : out_(out), indent_(indent) {}
    JsonWriter(const JsonWriter&) = delete;
    JsonWriter& operator=(const JsonWriter&) = delete;
    ~JsonWriter() { flush(); }

    void begin_object() { open('{'); }
    void end_object() { close('}'); }
    void begin_array() { open('['); }
    void end_array() { close(']'); }

    /// The key of the next member of the current object.
    void key(std::string_view name) {
        separate();
        write_string(name);
        buffer_ += indent_ >= 0 ? ": " : ":";
        after_key_ = true;
    }

    void value(std::string_view text) {
        separate();
        write_string(text);
    }
    void value(const char* text) { value(std::string_view(text)); }
    void value(const std::string& text) { value(std::string_view(text)); }
    void value(bool flag) {
        separate();
        buffer_ += flag ? "true" : "false";
    }
    void value(std::nullptr_t) {
        separate();
        buffer_ += "null";
    }
    template <std::unsigned_integral T>
    void value(T number) {
        separate();
        char digits[24];
        const auto end = std::to_chars(digits, digits + sizeof digits, number).ptr;
        buffer_.append(digits, end);
    }

    template <class T>
    void member(std::string_view name, const T& item) {
        key(name);
        value(item);
    }

    /// An array member of plain values.
    template <class Range>
    void array_member(std::string_view name, const Range& items) {
        key(name);
        begin_array();
        for (const auto& item : items) value(item);
        end_array();
    }

    void flush() {
        out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
        buffer_.clear();
    }

private:
    struct Level {
        std::size_t count = 0;
    };

    // Before a value or key: the comma after the previous one and the new line.
    void separate() {
        if (after_key_) {  // the value of a member follows its key on the same line
            after_key_ = false;
            return;
        }
        if (levels_.empty()) return;
        if (levels_.back().count++ > 0) buffer_ += ',';
        newline(levels_.size());
        if (buffer_.size() >= kFlushAt) flush();
    }

    void open(char bracket) {
        separate();
        buffer_ += bracket;
        levels_.push_back({});
    }

    void close(char bracket) {
        const bool empty = levels_.back().count == 0;
        levels_.pop_back();
        if (!empty) newline(levels_.size());
        buffer_ += bracket;
    }

    void newline(std::size_t depth) {
        if (indent_ < 0) return;
        buffer_ += '\n';
        buffer_.append(depth * static_cast<std::size_t>(indent_), ' ');
    }

    void write_string(std::string_view text) {
        bool plain = true;
        for (char c : text) {
            const auto byte = static_cast<unsigned char>(c);
            plain = plain && byte >= 0x20 && byte < 0x80 && c != '"' && c != '\\';
        }
        if (plain) {
            buffer_ += '"';
            buffer_ += text;
            buffer_ += '"';
            return;
        }
        // Escapes and UTF-8 as json prints them; text that is not UTF-8 gets U+FFFD instead
        // of an exception.
        buffer_ += nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }

    static constexpr std::size_t kFlushAt = 1 << 16;

    std::ostream& out_;
    int indent_;
    std::string buffer_;
    std::vector<Level> levels_;
    bool after_key_ = false;
};

void write_usage(JsonWriter& out, rhi::TextureUsage usage) {
    out.begin_array();
    for (auto flag : {rhi::TextureUsage::Sampled, rhi::TextureUsage::ColorAttachment,
                      rhi::TextureUsage::DepthStencilAttachment, rhi::TextureUsage::Storage,
                      rhi::TextureUsage::CopySrc, rhi::TextureUsage::CopyDst}) {
        if (rhi::has_all(usage, flag)) out.value(describe_usage(flag));
    }
    out.end_array();
}

void write_buffer_usage(JsonWriter& out, rhi::BufferUsage usage) {
    out.begin_array();
    for (auto flag : {rhi::BufferUsage::Vertex, rhi::BufferUsage::Index, rhi::BufferUsage::Uniform,
                      rhi::BufferUsage::Storage, rhi::BufferUsage::Indirect, rhi::BufferUsage::CopySrc,
                      rhi::BufferUsage::CopyDst}) {
        if (rhi::has_all(usage, flag)) out.value(describe_buffer_usage(flag));
    }
    out.end_array();
}

// The members of a resolved spec, each written by the caller at its place in key order.
void write_format(JsonWriter& out, const ResolvedSpec& spec) {
    out.member("format", rhi::format_name(spec.format));
    out.member("format_match", format_match_name(spec.format_match));
}

void write_port(JsonWriter& out, const Plan& plan, const PlanPort& port) {
    const bool buffer = port.type == ResourceType::Buffer;
    out.begin_object();
    if (buffer) {
        if (port.resource) {
            out.member("buffer", plan.resources[*port.resource].buffer);
        } else {
            out.member("buffer", nullptr);
        }
    }
    out.member("kind", port_kind_name(port.kind));
    out.member("name", port.name);
    out.member("optional", port.optional);
    if (port.resource) {
        // The range is concrete only for a port with a resource (counts resolved against it).
        out.key("range");
        out.begin_object();
        if (buffer) {
            out.member("offset", port.bytes.offset);
            out.member("size", port.bytes.size);
        } else {
            out.member("base_layer", port.range.base_layer);
            out.member("base_mip", port.range.base_mip);
            out.member("layer_count", port.range.layer_count);
            out.member("mip_count", port.range.mip_count);
        }
        out.end_object();
        out.member("resource", *port.resource);
        if (!buffer) out.member("texture", plan.resources[*port.resource].texture);
        out.member("type", resource_type_name(port.type));
        out.key("usage");
        if (buffer) {
            write_buffer_usage(out, port.buffer_usage);
        } else {
            write_usage(out, port.usage);
        }
    } else {
        out.member("resource", nullptr);
        if (!buffer) out.member("texture", nullptr);
        out.member("type", resource_type_name(port.type));
    }
    out.end_object();
}

void write_pass(JsonWriter& out, const Plan& plan, const PlanPass& pass) {
    out.begin_object();
    out.member("declaration_index", pass.declaration_index);
    out.member("kind", pass_kind_name(pass.kind));
    out.member("name", pass.name);
    out.key("ports");
    out.begin_array();
    for (const PlanPort& port : pass.ports) write_port(out, plan, port);
    out.end_array();
    out.member("queue", queue_name(pass.queue));
    out.member("side_effect", pass.side_effect);
    out.end_object();
}

// A texture edge names its texture, a buffer edge its buffer.
void write_edge(JsonWriter& out, const Plan& plan, const PlanEdge& e) {
    const PlanPass& from = plan.order[e.from_pass];
    const PlanPass& to = plan.order[e.to_pass];
    const PlanResource& resource = plan.resources[e.resource];
    out.begin_object();
    if (resource.type == ResourceType::Buffer) out.member("buffer", resource.buffer);
    out.member("from", from.name + "." + from.ports[e.from_port].name);
    out.member("resource", e.resource);
    if (resource.type == ResourceType::Texture) out.member("texture", resource.texture);
    out.member("to", to.name + "." + to.ports[e.to_port].name);
    out.end_object();
}

void write_lifetime(JsonWriter& out, const Lifetime& lifetime, std::string_view key = "lifetime") {
    out.key(key);
    out.begin_array();
    out.value(lifetime.first);
    out.value(lifetime.last);
    out.end_array();
}

// A buffer resource has no format, extent, samples, mips or layers: its own members.
void write_buffer_resource(JsonWriter& out, const PlanResource& r) {
    out.begin_object();
    out.member("alignment", r.alignment);
    out.member("buffer", r.buffer);
    out.member("bytes", r.bytes);
    out.member("graph_output", r.graph_output);
    write_lifetime(out, r.lifetime);
    out.member("name", r.name);
    write_lifetime(out, r.occupancy, "occupancy");
    out.array_member("ports", r.ports);
    out.member("queue_shared", r.queue_shared);
    out.member("size", r.buffer_spec.size);
    out.member("spec_alignment", r.buffer_spec.alignment);
    out.member("spec_class", r.spec_class);
    out.member("type", resource_type_name(r.type));
    out.key("usage");
    write_buffer_usage(out, r.buffer_spec.usage);
    out.end_object();
}

void write_resource(JsonWriter& out, const PlanResource& r) {
    if (r.type == ResourceType::Buffer) {
        write_buffer_resource(out, r);
        return;
    }
    out.begin_object();
    out.member("alignment", r.alignment);
    out.member("bytes", r.bytes);
    write_format(out, r.spec);
    out.member("graph_output", r.graph_output);
    out.member("height", r.spec.extent.height);
    out.member("layers", r.spec.layers);
    if (r.spec.cube) out.member("cube", true);
    write_lifetime(out, r.lifetime);
    out.member("mips", r.spec.mips);
    out.member("name", r.name);
    write_lifetime(out, r.occupancy, "occupancy");
    out.array_member("ports", r.ports);
    out.member("queue_shared", r.queue_shared);
    if (r.requested_format) {
        out.member("requested_format", describe_features(*r.requested_format));
    } else {
        out.member("requested_format", nullptr);
    }
    out.member("samples", r.spec.samples);
    out.member("spec_class", r.spec_class);
    out.member("texture", r.texture);
    out.member("type", resource_type_name(r.type));
    out.key("usage");
    write_usage(out, r.spec.usage);
    out.member("width", r.spec.extent.width);
    out.end_object();
}

void write_spec_class(JsonWriter& out, const SpecClass& c) {
    out.begin_object();
    if (c.type == ResourceType::Buffer) {
        out.member("peak_live", c.peak_live);
        out.array_member("resources", c.resources);
        out.member("size", c.buffer_spec.size);
        out.member("spec_alignment", c.buffer_spec.alignment);
        out.member("type", resource_type_name(c.type));
        out.key("usage");
        write_buffer_usage(out, c.buffer_spec.usage);
        out.end_object();
        return;
    }
    write_format(out, c.spec);
    out.member("height", c.spec.extent.height);
    out.member("layers", c.spec.layers);
    if (c.spec.cube) out.member("cube", true);
    out.member("mips", c.spec.mips);
    out.member("peak_live", c.peak_live);
    out.array_member("resources", c.resources);
    out.member("samples", c.spec.samples);
    out.member("type", resource_type_name(c.type));
    out.key("usage");
    write_usage(out, c.spec.usage);
    out.member("width", c.spec.extent.width);
    out.end_object();
}

void write_buffer(JsonWriter& out, const PlanBuffer& b) {
    out.begin_object();
    out.member("alignment", b.alignment);
    out.member("bytes", b.bytes);
    if (b.placement) out.member("heap", b.placement->heap);
    out.member("name", b.name);
    if (b.placement) out.member("offset", b.placement->offset);
    out.array_member("resources", b.resources);
    out.member("size", b.spec.size);
    out.member("spec_alignment", b.spec.alignment);
    out.key("usage");
    write_buffer_usage(out, b.spec.usage);
    out.end_object();
}

void write_texture(JsonWriter& out, const PlanTexture& t) {
    out.begin_object();
    out.member("alignment", t.alignment);
    out.member("bytes", t.bytes);
    write_format(out, t.spec);
    if (t.placement) out.member("heap", t.placement->heap);
    out.member("height", t.spec.extent.height);
    out.member("layers", t.spec.layers);
    if (t.spec.cube) out.member("cube", true);
    out.member("mips", t.spec.mips);
    out.member("name", t.name);
    if (t.placement) out.member("offset", t.placement->offset);
    out.array_member("resources", t.resources);
    out.member("samples", t.spec.samples);
    out.key("usage");
    write_usage(out, t.spec.usage);
    out.member("width", t.spec.extent.width);
    out.end_object();
}

// A position a sync or transfer refers to, and the pass there (null at the frame's start or end:
// a position of null, or the order's length).
void write_position(JsonWriter& out, const Plan& plan, std::string_view key, std::string_view pass_key,
                    uint32_t position) {
    const bool at_pass = position != kFrameStart && position < plan.order.size();
    if (position == kFrameStart) {
        out.member(key, nullptr);
    } else {
        out.member(key, position);
    }
    if (at_pass) {
        out.member(pass_key, plan.order[position].name);
    } else {
        out.member(pass_key, nullptr);
    }
}

void write_queue_sync(JsonWriter& out, const Plan& plan, const QueueSync& sync) {
    out.begin_object();
    out.member("from", queue_name(sync.from));
    write_position(out, plan, "signal_after", "signal_pass", sync.signal_after);
    out.member("to", queue_name(sync.to));
    write_position(out, plan, "wait_before", "wait_pass", sync.wait_before);
    out.end_object();
}

void write_transfer(JsonWriter& out, const Plan& plan, const OwnershipTransfer& t) {
    out.begin_object();
    write_position(out, plan, "acquire_before", "acquire_pass", t.acquire_before);
    out.member("from", queue_name(t.from));
    write_position(out, plan, "release_after", "release_pass", t.release_after);
    out.member("resource", t.resource);
    out.member("resource_name", plan.resources[t.resource].name);
    out.member("to", queue_name(t.to));
    out.end_object();
}

}  // namespace

void write_plan_json(std::ostream& stream, const Plan& plan, int indent) {
    char hash[24];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(plan_hash(plan)));
    const PlanSummary& s = plan.summary;

    JsonWriter out(stream, indent);
    out.begin_object();
    out.member("allocator", plan.allocator);
    out.key("buffers");
    out.begin_array();
    for (const PlanBuffer& b : plan.buffers) write_buffer(out, b);
    out.end_array();
    out.array_member("culled", plan.culled);
    out.key("edges");
    out.begin_array();
    for (const PlanEdge& e : plan.edges) write_edge(out, plan, e);
    out.end_array();
    out.key("frame");
    out.begin_object();
    out.member("height", plan.frame.height);
    out.member("width", plan.frame.width);
    out.end_object();
    out.array_member("graph_outputs", plan.graph_outputs);
    out.member("hash", std::string_view(hash));
    out.array_member("heaps", plan.heaps);
    out.key("order");
    out.begin_array();
    for (const PlanPass& pass : plan.order) out.value(pass.name);
    out.end_array();
    out.key("ownership_transfers");
    out.begin_array();
    for (const OwnershipTransfer& t : plan.ownership_transfers) write_transfer(out, plan, t);
    out.end_array();
    out.member("pass_order", pass_order_name(plan.pass_order));
    out.key("passes");
    out.begin_array();
    for (const PlanPass& pass : plan.order) write_pass(out, plan, pass);
    out.end_array();
    out.key("queue_syncs");
    out.begin_array();
    for (const QueueSync& sync : plan.queue_syncs) write_queue_sync(out, plan, sync);
    out.end_array();
    out.key("resources");
    out.begin_array();
    for (const PlanResource& r : plan.resources) write_resource(out, r);
    out.end_array();
    out.member("sharing", spec_sharing_name(plan.sharing));
    out.key("spec_classes");
    out.begin_array();
    for (const SpecClass& c : plan.spec_classes) write_spec_class(out, c);
    out.end_array();
    out.key("summary");
    out.begin_object();
    out.member("buffer_bytes", s.buffer_bytes);
    out.member("buffers", s.buffers);
    out.member("bytes", s.bytes);
    out.member("lower_bound_buffers", s.lower_bound_buffers);
    out.member("lower_bound_bytes", s.lower_bound_bytes);
    out.member("lower_bound_textures", s.lower_bound_textures);
    out.member("naive_buffers", s.naive_buffers);
    out.member("naive_bytes", s.naive_bytes);
    out.member("naive_textures", s.naive_textures);
    out.member("textures", s.textures);
    out.end_object();
    out.key("textures");
    out.begin_array();
    for (const PlanTexture& t : plan.textures) write_texture(out, t);
    out.end_array();
    out.end_object();
}

std::string plan_to_json(const Plan& plan, int indent) {
    std::ostringstream out;
    write_plan_json(out, plan, indent);
    return std::move(out).str();
}

}  // namespace loom::fg
