#include "loom/framegraph/pass.hpp"

#include <algorithm>

#include "loom/framegraph/join.hpp"
#include "quoted_name.hpp"
#include "text.hpp"

namespace loom::fg {

std::string_view port_kind_name(PortKind kind) {
    switch (kind) {
        case PortKind::Input: return "input";
        case PortKind::Output: return "output";
        case PortKind::InOut: return "inout";
    }
    return "unknown";
}

std::string_view resource_type_name(ResourceType type) {
    switch (type) {
        case ResourceType::Texture: return "texture";
        case ResourceType::Buffer: return "buffer";
    }
    return "unknown";
}

std::string_view pass_kind_name(PassKind kind) {
    switch (kind) {
        case PassKind::Graphics: return "graphics";
        case PassKind::Compute: return "compute";
        case PassKind::Copy: return "copy";
    }
    return "unknown";
}

std::string_view queue_name(Queue queue) {
    switch (queue) {
        case Queue::Graphics: return "graphics";
        case Queue::AsyncCompute: return "async_compute";
    }
    return "unknown";
}

std::optional<std::string> name_problem(std::string_view name) {
    if (name.empty()) return "is empty";
    for (const char c : name) {
        if (c == '.') return "contains '.', which separates pass and port names";
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7f) return "contains a control character (code " + std::to_string(byte) + ")";
    }
    return std::nullopt;
}

namespace detail {

std::string printable_name(std::string_view name) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (const char c : name) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '\n') {
            out += "\\n";
        } else if (c == '\t') {
            out += "\\t";
        } else if (byte < 0x20 || byte == 0x7f) {
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += c;
        }
    }
    return out;
}

}  // namespace detail

std::string quoted_name(std::string_view name) { return detail::concat("'", detail::printable_name(name), "'"); }

namespace {

// A length as LEB128: seven bits a byte, low bits first, the high bit set on all but the last.
void append_length(std::string& out, std::size_t length) {
    do {
        auto byte = static_cast<unsigned char>(length & 0x7f);
        length >>= 7;
        if (length != 0) byte |= 0x80;
        out.push_back(static_cast<char>(byte));
    } while (length != 0);
}

// Reads a length written by append_length at `at`, moving `at` past it.
std::size_t read_length(const char*& at) {
    std::size_t length = 0;
    for (unsigned shift = 0;; shift += 7) {
        const auto byte = static_cast<unsigned char>(*at++);
        length |= std::size_t{byte & 0x7fu} << shift;
        if ((byte & 0x80) == 0) return length;
    }
}

}  // namespace

std::string_view PortSetNames::const_iterator::operator*() const {
    const char* at = at_;
    const std::size_t length = read_length(at);
    return {at, length};
}

PortSetNames::const_iterator& PortSetNames::const_iterator::operator++() {
    const std::size_t length = read_length(at_);
    at_ += length;
    return *this;
}

PortSetNames::PortSetNames(std::initializer_list<std::string_view> names) {
    for (std::string_view name : names) push_back(name);
}

void PortSetNames::push_back(std::string_view name) {
    append_length(encoded_, name.size());
    encoded_.append(name);
}

bool PortSetNames::contains(std::string_view name) const { return std::find(begin(), end(), name) != end(); }

std::size_t PortSetNames::size() const { return static_cast<std::size_t>(std::distance(begin(), end())); }

std::string_view PortSetNames::front() const { return empty() ? std::string_view{} : *begin(); }

std::string_view PortSetNames::operator[](std::size_t index) const { return *std::next(begin(), static_cast<std::ptrdiff_t>(index)); }

bool operator==(const PortSetNames& names, const std::vector<std::string>& list) {
    return std::equal(names.begin(), names.end(), list.begin(), list.end());
}

namespace {

Port texture_port(std::string name, PortKind kind, TextureSpec spec, bool optional, const std::string& port_set,
                  SubresourceRange range) {
    Port port;
    port.name = std::move(name);
    port.kind = kind;
    port.spec = std::move(spec);
    port.optional = optional;
    port.port_sets = {port_set};
    port.range = range;
    return port;
}

Port buffer_port(std::string name, PortKind kind, BufferSpec spec, bool optional, const std::string& port_set,
                 BufferRange bytes) {
    Port port;
    port.name = std::move(name);
    port.kind = kind;
    port.optional = optional;
    port.port_sets = {port_set};
    port.type = ResourceType::Buffer;
    port.buffer = std::move(spec);
    port.bytes = bytes;
    return port;
}

// The end of a range's counted part: base + count, saturating for open counts.
uint64_t range_end(uint32_t base, uint32_t count) {
    return count == rhi::kRemainingSubresources ? UINT64_MAX : uint64_t{base} + count;
}

}  // namespace

std::string describe_range(const SubresourceRange& range) {
    auto part = [](std::string_view one, std::string_view many, uint32_t base, uint32_t count) -> std::string {
        if (base == 0 && count == rhi::kRemainingSubresources) return {};
        if (count == 1) return std::string(one) + " " + std::to_string(base);
        if (count == rhi::kRemainingSubresources) return std::string(many) + " " + std::to_string(base) + "..";
        return std::string(many) + " " + std::to_string(base) + ".." + std::to_string(uint64_t{base} + count - 1);
    };
    const std::string mips = part("mip", "mips", range.base_mip, range.mip_count);
    const std::string layers = part("layer", "layers", range.base_layer, range.layer_count);
    if (mips.empty() && layers.empty()) return "whole";
    if (mips.empty()) return layers;
    if (layers.empty()) return mips;
    return mips + " " + layers;
}

bool overlaps(const SubresourceRange& a, const SubresourceRange& b) {
    auto intersect = [](uint32_t a_base, uint32_t a_count, uint32_t b_base, uint32_t b_count) {
        return a_base < range_end(b_base, b_count) && b_base < range_end(a_base, a_count);
    };
    return intersect(a.base_mip, a.mip_count, b.base_mip, b.mip_count) &&
           intersect(a.base_layer, a.layer_count, b.base_layer, b.layer_count);
}

bool overlaps(const BufferRange& a, const BufferRange& b) {
    const uint64_t a_end = a.size == 0 ? UINT64_MAX : a.offset + a.size;
    const uint64_t b_end = b.size == 0 ? UINT64_MAX : b.offset + b.size;
    return a.offset < b_end && b.offset < a_end;
}

PortSet& PortSet::declare(std::string port, PortKind kind, TextureSpec spec, bool optional, SubresourceRange range) {
    declarations_.push_back(texture_port(std::move(port), kind, std::move(spec), optional, name_, range));
    return *this;
}

PortSet& PortSet::declare_buffer(std::string port, PortKind kind, BufferSpec spec, bool optional, BufferRange bytes) {
    declarations_.push_back(buffer_port(std::move(port), kind, std::move(spec), optional, name_, bytes));
    return *this;
}

Pass::Pass(std::string name) : name_(std::move(name)) {}

Pass::~Pass() = default;

Pass& Pass::add(const PortSet& ports) {
    // A port set's name appears in errors and in Port::port_sets, so it follows the rules of
    // pass and port names; its ports are not added. A port set named after the pass (the graph
    // file's own ports) is checked as the pass name by add_pass.
    if (auto problem = ports.name() == name_ ? std::nullopt : name_problem(ports.name())) {
        if (!error_) {
            error_ = make_error(ErrorCode::Graph, "pass " + quoted_name(name_) + ": the port set name " +
                                                      quoted_name(ports.name()) + " " + *problem);
        }
        return *this;
    }
    for (const Port& declaration : ports.declarations()) merge(declaration, ports.name());
    return *this;
}

Pass& Pass::declare(std::string port, PortKind kind, TextureSpec spec, bool optional, SubresourceRange range) {
    merge(texture_port(std::move(port), kind, std::move(spec), optional, name_, range), name_);
    return *this;
}

Pass& Pass::declare_buffer(std::string port, PortKind kind, BufferSpec spec, bool optional, BufferRange bytes) {
    merge(buffer_port(std::move(port), kind, std::move(spec), optional, name_, bytes), name_);
    return *this;
}

const Port* Pass::find_port(std::string_view name) const {
    auto index = port_index(name);
    return index ? &ports_[*index] : nullptr;
}

std::optional<uint32_t> Pass::port_index(std::string_view name) const {
    if (port_indices_.empty()) {
        for (uint32_t i = 0; i < ports_.size(); ++i) {
            if (detail::same_name(ports_[i].name, name)) return i;
        }
        return std::nullopt;
    }
    auto it = port_indices_.find(name);
    if (it == port_indices_.end()) return std::nullopt;
    return it->second;
}

Pass& Pass::read(PortAddress source, TextureSpec spec, SubresourceRange range) {
    std::string port = "read" + std::to_string(reads_.size());
    // Every read adds its own port, read0, read1, ...: only a port declared otherwise can have
    // the new name (most passes read before they declare anything else, and skip the search).
    if (!error_ && ports_.size() != reads_.size() && port_index(port)) {
        error_ = make_error(ErrorCode::Graph, "pass " + quoted_name(name_) + ": read() names its input " +
                                                  quoted_name(port) + ", a name the pass already declares");
        return *this;
    }
    const auto index = static_cast<uint32_t>(ports_.size());
    Port input = texture_port(std::move(port), PortKind::Input, std::move(spec), false, name_, range);
    if (error_) {
        merge(std::move(input), name_);  // as any declaration after an error
    } else {
        append_port(std::move(input));  // the name is new (checked above): nothing to merge with
    }
    if (reads_.empty()) reads_.reserve(kFirstPorts);
    reads_.emplace_back(index, source);
    return *this;
}

Status Pass::execute(PassContext& context) {
    if (execute_function_) return execute_function_(context);
    return {};
}

Status Pass::status() const {
    if (error_) return *error_;
    return {};
}

void Pass::append_port(Port&& port) {
    // Most passes declare a handful of ports: room for four at the first is one allocation
    // where growing one by one reallocates (and moves every port) at one, two and four. Past
    // that the room grows by half, not double: a Port is 240 bytes, and a pass of five ports
    // would otherwise hold room for eight.
    if (ports_.size() == ports_.capacity()) ports_.reserve(ports_.empty() ? kFirstPorts : ports_.size() + ports_.size() / 2);
    ports_.push_back(std::move(port));
    if (ports_.size() == kIndexedPorts) {
        for (uint32_t i = 0; i < ports_.size(); ++i) port_indices_.emplace(ports_[i].name, i);
    } else if (ports_.size() > kIndexedPorts) {
        port_indices_.emplace(ports_.back().name, static_cast<uint32_t>(ports_.size() - 1));
    }
}

void Pass::merge(Port declaration, const std::string& port_set) {
    const std::optional<uint32_t> known = port_index(declaration.name);
    if (!known) {
        if (declaration.port_sets.size() != 1 || declaration.port_sets.front() != port_set) {
            declaration.port_sets = {port_set};
        }
        append_port(std::move(declaration));
        return;
    }
    if (error_) return;  // keep the first error; later ones are usually consequences

    Port& existing = ports_[*known];
    const std::string first_set(existing.port_sets.front());
    if (existing.kind != declaration.kind) {
        error_ = make_error(ErrorCode::Graph, "pass " + quoted_name(name_) + ": port " +
                                                  quoted_name(declaration.name) + " is declared as " +
                                                  std::string(port_kind_name(existing.kind)) + " by port set " +
                                                  quoted_name(first_set) + " and as " +
                                                  std::string(port_kind_name(declaration.kind)) + " by port set " +
                                                  quoted_name(port_set));
        return;
    }
    if (existing.type != declaration.type) {
        error_ = make_error(ErrorCode::Graph, "pass " + quoted_name(name_) + ": port " +
                                                  quoted_name(declaration.name) + " is declared as a " +
                                                  std::string(resource_type_name(existing.type)) + " port by port set " +
                                                  quoted_name(first_set) + " and as a " +
                                                  std::string(resource_type_name(declaration.type)) +
                                                  " port by port set " + quoted_name(port_set));
        return;
    }
    if (existing.range != declaration.range || existing.bytes != declaration.bytes) {
        const bool buffer = existing.type == ResourceType::Buffer;
        auto bytes = [](const BufferRange& r) {
            return r.whole() ? std::string("whole") : std::to_string(r.offset) + "+" + std::to_string(r.size);
        };
        error_ = make_error(ErrorCode::Graph, "pass " + quoted_name(name_) + ": port " + quoted_name(declaration.name) +
                                                  " covers " + (buffer ? bytes(existing.bytes) : describe_range(existing.range)) +
                                                  " in port set " + quoted_name(first_set) + " but " +
                                                  (buffer ? bytes(declaration.bytes) : describe_range(declaration.range)) +
                                                  " in port set " + quoted_name(port_set));
        return;
    }
    const std::string a_name = name_ + "." + existing.name + " (port set '" + first_set + "')";
    const std::string b_name = name_ + "." + declaration.name + " (port set '" + port_set + "')";
    JoinContext context;
    context.a_name = a_name;
    context.b_name = b_name;
    if (existing.type == ResourceType::Buffer) {
        auto joined = join_buffer_specs(existing.buffer, declaration.buffer, context);
        if (!joined) {
            error_ = joined.take_error();
            return;
        }
        existing.buffer = std::move(*joined);
    } else {
        auto joined = join(existing.spec, declaration.spec, context);
        if (!joined) {
            error_ = joined.take_error();
            return;
        }
        existing.spec = std::move(*joined);
    }
    existing.optional = existing.optional && declaration.optional;
    if (!existing.port_sets.contains(port_set)) existing.port_sets.push_back(port_set);
}

}  // namespace loom::fg
