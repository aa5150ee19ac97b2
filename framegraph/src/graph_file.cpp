#include "loom/framegraph/graph_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <variant>

#include "json_document.hpp"
#include "json_structure.hpp"
#include "text.hpp"

namespace loom::fg {
namespace {

using detail::JsonValue;

// A value as it stands in the file (written as JSON again: no spaces, members sorted by key),
// cut short: error messages stay one short line whatever the file holds (a value can be
// megabytes long, and only what is shown is written).
std::string excerpt(JsonValue value) {
    constexpr std::size_t kMax = 60;
    std::string text = value.dump(kMax);
    if (text.size() > kMax) {
        text.resize(kMax);
        text += "...";
    }
    return text;
}

// A JSON pointer as a chain of its parents, which live on the reader's stack: the text is
// written only for an error message, not for every value read.
class Path {
public:
    Path() = default;  // the top level
    [[nodiscard]] Path member(std::string_view key) const { return Path(this, key, 0); }
    [[nodiscard]] Path element(std::size_t index) const { return Path(this, {}, index + 1); }
    [[nodiscard]] bool top_level() const { return parent_ == nullptr; }

    // "/passes/2/outputs/0" ("" for the top level), keys escaped as RFC 6901 has them.
    [[nodiscard]] std::string str() const {
        std::vector<const Path*> chain;
        for (const Path* p = this; p->parent_; p = p->parent_) chain.push_back(p);
        std::string out;
        for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
            out += '/';
            if ((*it)->index_ == 0) {
                out += json_pointer_token((*it)->key_);
            } else {
                detail::append(out, (*it)->index_ - 1);
            }
        }
        return out;
    }

private:
    Path(const Path* parent, std::string_view key, std::size_t index) : parent_(parent), key_(key), index_(index) {}

    const Path* parent_ = nullptr;
    std::string_view key_;   // a member's key, when index_ is 0
    std::size_t index_ = 0;  // an element's index + 1
};

// Where the file declares each port of a pass, in Pass::ports() order (see GraphFile::pointer).
using PortLocation = GraphFile::PortLocation;

std::string lowercase(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

// Reads one JSON document into a FrameGraph, keeping the JSON pointer for error messages.
class GraphReader {
public:
    explicit GraphReader(std::string_view source) : source_(source) {}

    Result<GraphFile> read(JsonValue root) {
        GraphFile file;
        const Path top;
        if (!root.is_object()) return fail(top, "the top level must be an object");
        LOOM_TRY(only_keys(root, top, {"frame", "passes", "connections", "outputs", "description", "order",
                                       "order_constraints"}));
        if (auto description = root.find("description"); description && !description->is_string()) {
            return fail(top.member("description"), "must be a string (what the graph is, where it comes from)");
        }

        if (auto found = root.find("frame")) {
            const JsonValue frame = *found;
            const Path path = top.member("frame");
            if (!frame.is_object()) return fail(path, "must be an object {\"width\": W, \"height\": H}");
            LOOM_TRY(only_keys(frame, path, {"width", "height"}));
            auto width = positive(frame, path, "width", true, kMaxTextureExtent);
            if (!width) return width.take_error();
            auto height = positive(frame, path, "height", true, kMaxTextureExtent);
            if (!height) return height.take_error();
            file.frame = {**width, **height};
        }

        if (auto found = root.find("order")) {
            const JsonValue order = *found;
            std::optional<PassOrder> parsed;
            if (order.is_string()) parsed = parse_pass_order(std::string(order.string()));
            if (!parsed) return fail(top.member("order"), "must be one of declared, memory, not " + excerpt(order));
            file.order = *parsed;
        }

        const auto passes = root.find("passes");
        if (!passes) return fail(top, "missing \"passes\"");
        const Path passes_path = top.member("passes");
        if (!passes->is_array()) return fail(passes_path, "must be an array");
        file.first_port_location.reserve(passes->size() + 1);
        for (std::size_t i = 0; i < passes->size(); ++i) {
            const Path path = passes_path.element(i);
            file.first_port_location.push_back(static_cast<uint32_t>(file.port_locations.size()));
            auto pass = read_pass((*passes)[i], path, file.port_locations);
            if (!pass) return pass.take_error();
            auto added = file.graph.add_pass(std::move(*pass));
            if (!added) return at(path, added.take_error());
        }
        file.first_port_location.push_back(static_cast<uint32_t>(file.port_locations.size()));

        if (auto found = root.find("connections")) {
            const JsonValue connections = *found;
            const Path list_path = top.member("connections");
            if (!connections.is_array()) return fail(list_path, "must be an array of [\"pass.port\", \"pass.port\"]");
            for (std::size_t i = 0; i < connections.size(); ++i) {
                const Path path = list_path.element(i);
                const JsonValue pair = connections[i];
                if (!pair.is_array() || pair.size() != 2) return fail(path, "must be [\"pass.port\", \"pass.port\"]");
                auto from = port_ref(pair[0], path.element(0));
                if (!from) return from.take_error();
                auto to = port_ref(pair[1], path.element(1));
                if (!to) return to.take_error();
                // By handles when both names are known (no PortRef strings); otherwise by name,
                // which says which name is unknown.
                const auto from_address = address(file.graph, *from);
                const auto to_address = address(file.graph, *to);
                auto connected = from_address && to_address ? file.graph.connect(*from_address, *to_address)
                                                            : file.graph.connect(port_ref_of(*from), port_ref_of(*to));
                if (!connected) return at(path, connected.take_error());
            }
        }

        if (auto found = root.find("outputs")) {
            const JsonValue outputs = *found;
            const Path list_path = top.member("outputs");
            if (!outputs.is_array()) return fail(list_path, "must be an array of \"pass.port\"");
            for (std::size_t i = 0; i < outputs.size(); ++i) {
                const Path path = list_path.element(i);
                auto ref = port_ref(outputs[i], path);
                if (!ref) return ref.take_error();
                const auto port = address(file.graph, *ref);
                auto marked = port ? file.graph.mark_output(*port) : file.graph.mark_output(port_ref_of(*ref));
                if (!marked) return at(path, marked.take_error());
            }
        }
        if (auto found = root.find("order_constraints")) {
            const JsonValue constraints = *found;
            const Path list_path = top.member("order_constraints");
            constexpr const char* kPair = "[\"earlier pass\", \"later pass\"]";
            if (!constraints.is_array()) return fail(list_path, std::string("must be an array of ") + kPair);
            for (std::size_t i = 0; i < constraints.size(); ++i) {
                const Path path = list_path.element(i);
                const JsonValue pair = constraints[i];
                if (!pair.is_array() || pair.size() != 2) return fail(path, std::string("must be ") + kPair);
                for (std::size_t side = 0; side < 2; ++side) {
                    if (!pair[side].is_string()) {
                        return fail(path.element(side), "must be a pass name, not " + excerpt(pair[side]));
                    }
                }
                auto required = file.graph.require_order(pair[0].string(), pair[1].string());
                if (!required) return at(path, required.take_error());
            }
        }

        file.source = std::string(source_);
        return file;
    }

private:
    // A "pass.port" reference split at its last '.' (parse_port_ref's rule), as views.
    struct PortName {
        std::string_view pass;
        std::string_view port;
    };

    static PortRef port_ref_of(const PortName& name) { return PortRef{std::string(name.pass), std::string(name.port)}; }

    // The port `name` names in `graph`, if both names are known.
    static std::optional<PortAddress> address(const FrameGraph& graph, const PortName& name) {
        const auto pass = graph.find_pass(name.pass);
        if (!pass) return std::nullopt;
        const auto port = graph.pass(*pass).port_index(name.port);
        if (!port) return std::nullopt;
        return PortAddress{pass->index, *port};
    }

    Error fail(const Path& path, const std::string& problem) const {
        std::string message(source_);
        message += ": ";
        if (!path.top_level()) {
            message += path.str();
            message += ": ";
        }
        message += problem;
        return make_error(ErrorCode::Parse, std::move(message));
    }

    // An error from the graph itself (ErrorCode::Graph, Join) located at a JSON path.
    Error at(const Path& path, Error error) const {
        error.message = std::string(source_) + ": " + path.str() + ": " + error.message;
        return error;
    }

    // The first key of `object` (in byte order, as nlohmann::json's sorted objects listed them)
    // that is not allowed.
    Status only_keys(JsonValue object, const Path& path, std::initializer_list<std::string_view> allowed) const {
        std::optional<std::string_view> unknown;
        for (std::size_t i = 0; i < object.size(); ++i) {
            const std::string_view key = object.key(i);
            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
            if (!unknown || key < *unknown) unknown = key;
        }
        if (!unknown) return {};
        std::string known;
        for (std::string_view key : allowed) known += (known.empty() ? "" : ", ") + std::string(key);
        return fail(path.member(*unknown), "unknown key (expected one of: " + known + ")");
    }

    // A positive integer member up to `max`; nullopt when absent and not required.
    Result<std::optional<uint32_t>> positive(JsonValue object, const Path& path, const char* key,
                                             bool required = false, uint32_t max = 1u << 30) const {
        const auto found = object.find(key);
        if (!found) {
            if (required) return fail(path, std::string("missing \"") + key + "\"");
            return std::optional<uint32_t>{};
        }
        const JsonValue value = *found;
        if (!value.is_number_integer()) return fail(path.member(key), "must be a positive integer, not " + excerpt(value));
        const auto number = value.as_int64();
        if (number < 1) return fail(path.member(key), "must be a positive integer, not " + excerpt(value));
        if (value.is_number_unsigned() ? value.as_uint64() > max : static_cast<uint64_t>(number) > max) {
            return fail(path.member(key), "must be at most " + std::to_string(max) + ", not " + excerpt(value));
        }
        return std::optional<uint32_t>(static_cast<uint32_t>(number));
    }

    Result<bool> boolean(JsonValue object, const Path& path, const char* key) const {
        const auto value = object.find(key);
        if (!value) return false;
        if (!value->is_boolean()) return fail(path.member(key), "must be true or false, not " + excerpt(*value));
        return value->boolean();
    }

    Result<PortName> port_ref(JsonValue value, const Path& path) const {
        if (!value.is_string()) return fail(path, "must be a \"pass.port\" string, not " + excerpt(value));
        const std::string_view text = value.string();
        const auto dot = text.rfind('.');
        if (dot == std::string_view::npos || dot == 0 || dot + 1 == text.size()) {
            return fail(path, "\"" + std::string(text) + "\" is not of the form \"pass.port\"");
        }
        return PortName{text.substr(0, dot), text.substr(dot + 1)};
    }

    // A pass, its ports declared straight into it; where each port is first declared is
    // appended to `locations` (in Pass::ports() order).
    Result<Pass> read_pass(JsonValue object, const Path& path, std::vector<PortLocation>& locations) {
        if (!object.is_object()) return fail(path, "a pass must be an object");
        LOOM_TRY(only_keys(object, path,
                           {"name", "kind", "queue", "inputs", "outputs", "inouts", "parts", "side_effect",
                            "keep_declared_order"}));
        const auto name = object.find("name");
        if (!name || !name->is_string() || name->string().empty()) {
            return fail(path.member("name"), "a pass needs a non-empty string name");
        }
        Pass pass{std::string(name->string())};
        auto side_effect = boolean(object, path, "side_effect");
        if (!side_effect) return side_effect.take_error();
        pass.set_side_effect(*side_effect);
        auto pinned = boolean(object, path, "keep_declared_order");
        if (!pinned) return pinned.take_error();
        pass.keep_declared_order(*pinned);
        if (auto found = object.find("kind")) {
            const JsonValue kind = *found;
            static constexpr std::array<PassKind, 3> kKinds{PassKind::Graphics, PassKind::Compute, PassKind::Copy};
            const auto match = std::find_if(kKinds.begin(), kKinds.end(), [&](PassKind k) {
                return kind.is_string() && kind.string() == pass_kind_name(k);
            });
            if (match == kKinds.end()) {
                return fail(path.member("kind"), "must be one of graphics, compute, copy, not " + excerpt(kind));
            }
            pass.set_kind(*match);
        }
        if (auto found = object.find("queue")) {
            const JsonValue queue = *found;
            static constexpr std::array<Queue, 2> kQueues{Queue::Graphics, Queue::AsyncCompute};
            const auto match = std::find_if(kQueues.begin(), kQueues.end(), [&](Queue q) {
                return queue.is_string() && queue.string() == queue_name(q);
            });
            if (match == kQueues.end()) {
                return fail(path.member("queue"), "must be one of graphics, async_compute, not " + excerpt(queue));
            }
            pass.set_queue(*match);
        }

        // The pass's own ports first (Pass::declare: the port set named after the pass), then
        // each port set of "parts", as Pass::add composes them.
        LOOM_TRY(read_ports(object, path, kOwnPorts, [&](Port& port, PortKind kind, const PortLocation& location) {
            const std::size_t known = pass.ports().size();
            if (port.type == ResourceType::Buffer) {
                pass.declare_buffer(std::move(port.name), kind, port.buffer, port.optional, port.bytes);
            } else {
                pass.declare(std::move(port.name), kind, std::move(port.spec), port.optional, port.range);
            }
            if (pass.ports().size() > known) locations.push_back(location);
        }));
        if (auto found = object.find("parts")) {
            const JsonValue parts = *found;
            const Path parts_path = path.member("parts");
            if (!parts.is_array()) return fail(parts_path, "must be an array of port sets");
            std::vector<PortLocation> declared;  // where each of the set's declarations is
            for (std::size_t i = 0; i < parts.size(); ++i) {
                const Path set_path = parts_path.element(i);
                const JsonValue set = parts[i];
                if (!set.is_object()) return fail(set_path, "a port set must be an object");
                LOOM_TRY(only_keys(set, set_path, {"name", "inputs", "outputs", "inouts"}));
                const auto set_name = set.find("name");
                if (!set_name || !set_name->is_string()) {
                    return fail(set_path.member("name"), "a port set needs a string name");
                }
                PortSet ports{std::string(set_name->string())};
                declared.clear();
                LOOM_TRY(read_ports(set, set_path, static_cast<uint32_t>(i),
                                    [&](Port& port, PortKind kind, const PortLocation& location) {
                                        if (port.type == ResourceType::Buffer) {
                                            ports.declare_buffer(std::move(port.name), kind, port.buffer,
                                                                 port.optional, port.bytes);
                                        } else {
                                            ports.declare(std::move(port.name), kind, std::move(port.spec),
                                                          port.optional, port.range);
                                        }
                                        declared.push_back(location);
                                    }));
                const std::size_t known = pass.ports().size();
                pass.add(ports);
                // The ports the set added, in order: each is located at its first declaration
                // in the set.
                for (std::size_t k = known; k < pass.ports().size(); ++k) {
                    const auto& declarations = ports.declarations();
                    for (std::size_t d = 0; d < declarations.size(); ++d) {
                        if (declarations[d].name != pass.ports()[k].name) continue;
                        locations.push_back(declared[d]);
                        break;
                    }
                }
            }
        }
        if (auto status = pass.status(); !status) return at(path, status.take_error());
        return pass;
    }

    // Reads the "inputs", "outputs" and "inouts" of a pass or port set (`part`: its index in
    // "parts", or kOwnPorts), giving each port to `declare` with its kind and place.
    template <class Declare>
    Status read_ports(JsonValue object, const Path& path, uint32_t part, Declare&& declare) const {
        static constexpr std::array<std::pair<const char*, PortKind>, 3> kLists{
            {{"inputs", PortKind::Input}, {"outputs", PortKind::Output}, {"inouts", PortKind::InOut}}};
        for (const auto& [key, kind] : kLists) {
            const auto found = object.find(key);
            if (!found) continue;
            const JsonValue list = *found;
            const Path list_path = path.member(key);
            if (!list.is_array()) return fail(list_path, "must be an array of ports");
            for (std::size_t i = 0; i < list.size(); ++i) {
                auto port = read_port(list[i], list_path.element(i));
                if (!port) return port.take_error();
                declare(*port, kind, PortLocation{part, kind, static_cast<uint32_t>(i)});
            }
        }
        return {};
    }

    Result<Port> read_port(JsonValue object, const Path& path) const {
        if (!object.is_object()) return fail(path, "a port must be an object with a \"name\"");
        auto type = read_type(object, path);
        if (!type) return type.take_error();
        if (*type == ResourceType::Buffer) return read_buffer_port(object, path);
        // A buffer property on a texture port most likely means a forgotten "type": say so
        // rather than list the texture keys.
        if (object.contains("alignment")) {
            return fail(path.member("alignment"), "\"alignment\" is a property of buffer ports; a texture port takes none "
                                             "(add \"type\": \"buffer\" for a buffer port)");
        }
        LOOM_TRY(only_keys(object, path,
                           {"name", "type", "format", "channels", "bits", "kind", "srgb", "depth", "stencil", "size",
                            "scale", "samples", "mips", "layers", "cube", "range", "optional", "usage"}));
        auto name = port_name(object, path);
        if (!name) return name.take_error();
        Port port;
        port.name = std::move(*name);
        TextureSpec& spec = port.spec;

        auto format = read_format(object, path);
        if (!format) return format.take_error();
        spec.format = *format;

        if (object.contains("size") && object.contains("scale")) return fail(path, "give \"size\" or \"scale\", not both");
        if (object.contains("size")) {
            JsonValue size = object.at("size");
            const bool pair = size.is_array() && size.size() == 2 &&
                              size[0].is_number_integer() && size[1].is_number_integer();
            if (!pair) {
                // A byte count or a per-pixel/per-tile object is a buffer's size.
                const std::string hint = size.is_number_integer() || size.is_object()
                                             ? " (a buffer's size needs \"type\": \"buffer\")"
                                             : "";
                return fail(path.member("size"), "must be [width, height] in texels, not " + excerpt(size) + hint);
            }
            auto side_in_range = [](JsonValue v) {
                if (v.is_number_unsigned()) return v.as_uint64() >= 1 && v.as_uint64() <= kMaxTextureExtent;
                return v.as_int64() >= 1 && v.as_int64() <= int64_t{kMaxTextureExtent};
            };
            const bool in_range = side_in_range(size[0]) && side_in_range(size[1]);
            if (!in_range) {
                return fail(path.member("size"), "each side must be in 1.." + std::to_string(kMaxTextureExtent) + ", not " +
                                                excerpt(size));
            }
            spec.size = SizeSpec::absolute(static_cast<uint32_t>(size[0].as_uint64()), static_cast<uint32_t>(size[1].as_uint64()));
        }
        if (object.contains("scale")) {
            JsonValue scale = object.at("scale");
            auto valid_scale = [](JsonValue v) { return v.is_number() && v.as_double() > 0.0 && v.as_double() <= 16.0; };
            if (valid_scale(scale)) {
                spec.size = SizeSpec::relative(static_cast<float>(scale.as_double()));
            } else if (scale.is_array() && scale.size() == 2 && valid_scale(scale[0]) && valid_scale(scale[1])) {
                spec.size = SizeSpec::relative(static_cast<float>(scale[0].as_double()), static_cast<float>(scale[1].as_double()));
            } else {
                return fail(path.member("scale"), "must be a number in (0, 16] or [sx, sy], not " + excerpt(scale));
            }
        }
        // The limits of texture_spec.hpp, refused here with a JSON pointer rather than later by
        // resolve(); mips also depend on the resolved size, which resolve() checks.
        auto samples = positive(object, path, "samples", false, kMaxTextureSamples);
        if (!samples) return samples.take_error();
        if (*samples) {
            if (!std::has_single_bit(**samples)) {
                return fail(path.member("samples"), "must be one of 1, 2, 4, 8, 16, 32, 64, not " + excerpt(object.at("samples")));
            }
            spec.samples = **samples;
        }
        auto mips = positive(object, path, "mips", false, kMaxMips);
        if (!mips) return mips.take_error();
        if (*mips) spec.mips = **mips;
        auto layers = positive(object, path, "layers", false, kMaxTextureLayers);
        if (!layers) return layers.take_error();
        if (*layers) spec.layers = **layers;
        auto cube = boolean(object, path, "cube");
        if (!cube) return cube.take_error();
        if (*cube) {
            spec.cube = true;
            if (!spec.layers) spec.layers = 6;  // a cube map's faces; other counts fail when planned
        }
        if (object.contains("range")) {
            auto range = read_texture_range(object.at("range"), path.member("range"));
            if (!range) return range.take_error();
            port.range = *range;
        }
        auto optional = boolean(object, path, "optional");
        if (!optional) return optional.take_error();
        port.optional = *optional;

        if (object.contains("usage")) {
            JsonValue usage = object.at("usage");
            const Path usage_path = path.member("usage");
            if (!usage.is_array()) return fail(usage_path, "must be an array of usage names");
            for (std::size_t i = 0; i < usage.size(); ++i) {
                const Path where = usage_path.element(i);
                if (!usage[i].is_string()) return fail(where, "must be a usage name, not " + excerpt(usage[i]));
                auto flag = parse_usage_flag(usage[i].string());
                if (!flag) {
                    return fail(where, "unknown usage \"" + std::string(usage[i].string()) +
                                           "\" (sampled, color_attachment, depth_stencil_attachment, storage, "
                                           "copy_src, copy_dst)");
                }
                spec.usage |= *flag;
            }
        }
        return port;
    }

    Result<std::string> port_name(JsonValue object, const Path& path) const {
        if (!object.contains("name") || !object.at("name").is_string() || object.at("name").string().empty()) {
            return fail(path.member("name"), "a port needs a non-empty string name");
        }
        return std::string(object.at("name").string());
    }

    // "type": "texture" (the default) or "buffer".
    Result<ResourceType> read_type(JsonValue object, const Path& path) const {
        if (!object.contains("type")) return ResourceType::Texture;
        JsonValue type = object.at("type");
        for (ResourceType t : {ResourceType::Texture, ResourceType::Buffer}) {
            if (type.is_string() && type.string() == resource_type_name(t)) return t;
        }
        return fail(path.member("type"), "must be \"texture\" or \"buffer\", not " + excerpt(type));
    }

    // An integer in [min, max] (up to 2^40, a buffer's limit, so 64 bits).
    Result<uint64_t> whole_number(JsonValue value, const Path& where, uint64_t min, uint64_t max) const {
        const std::string wanted = min == 0 ? "a non-negative integer" : "a positive integer";
        if (!value.is_number_integer()) return fail(where, "must be " + wanted + ", not " + excerpt(value));
        if (!value.is_number_unsigned() && value.as_int64() < 0) {
            return fail(where, "must be " + wanted + ", not " + excerpt(value));
        }
        const auto number = value.as_uint64();
        if (number < min) return fail(where, "must be " + wanted + ", not " + excerpt(value));
        if (number > max) return fail(where, "must be at most " + std::to_string(max) + ", not " + excerpt(value));
        return number;
    }

    // "range" of a texture port: {"mip": k} or {"mips": [base, count]} ([base]: to the last
    // level), and likewise "layer" / "layers"; what is not given is every level (layer).
    Result<SubresourceRange> read_texture_range(JsonValue value, const Path& path) const {
        if (!value.is_object()) {
            return fail(path, "must be an object such as {\"mip\": 1} or {\"mips\": [1, 2], \"layer\": 0}, not " +
                                  excerpt(value));
        }
        LOOM_TRY(only_keys(value, path, {"mip", "mips", "layer", "layers"}));
        SubresourceRange range;
        // Bases and counts within the texture limits; whether the texture has that many levels
        // (layers) is known once it is resolved, and planning checks it.
        auto part = [&](const char* one, const char* many, uint32_t limit, uint32_t& base, uint32_t& count) -> Status {
            if (value.contains(one) && value.contains(many)) {
                return fail(path, std::string("give \"") + one + "\" or \"" + many + "\", not both");
            }
            if (value.contains(one)) {
                auto index = whole_number(value.at(one), path.member(one), 0, limit - 1);
                if (!index) return index.take_error();
                base = static_cast<uint32_t>(*index);
                count = 1;
            } else if (value.contains(many)) {
                JsonValue pair = value.at(many);
                const Path where = path.member(many);
                if (!pair.is_array() || pair.empty() || pair.size() > 2) {
                    return fail(where, "must be [base, count] or [base] (from base to the last), not " + excerpt(pair));
                }
                auto first = whole_number(pair[0], where.member("0"), 0, limit - 1);
                if (!first) return first.take_error();
                base = static_cast<uint32_t>(*first);
                count = rhi::kRemainingSubresources;
                if (pair.size() == 2) {
                    auto n = whole_number(pair[1], where.member("1"), 1, limit - base);
                    if (!n) return n.take_error();
                    count = static_cast<uint32_t>(*n);
                }
            }
            return {};
        };
        LOOM_TRY(part("mip", "mips", kMaxMips, range.base_mip, range.mip_count));
        LOOM_TRY(part("layer", "layers", kMaxTextureLayers, range.base_layer, range.layer_count));
        return range;
    }

    // A buffer port: "size", "usage", "alignment", "range", "optional".
    Result<Port> read_buffer_port(JsonValue object, const Path& path) const {
        // Texture properties on a buffer port: name the key and what a buffer port takes.
        static constexpr std::array<std::string_view, 12> kTextureKeys{
            "format", "channels", "bits", "kind", "srgb", "depth", "stencil", "scale", "samples", "mips", "layers", "cube"};
        for (std::string_view key : kTextureKeys) {
            if (!object.contains(key)) continue;
            return fail(path.member(key),
                        "\"" + std::string(key) + "\" is a property of texture ports; a buffer port takes name, type, "
                        "size, usage, alignment, range, optional");
        }
        LOOM_TRY(only_keys(object, path, {"name", "type", "size", "usage", "alignment", "range", "optional"}));
        auto name = port_name(object, path);
        if (!name) return name.take_error();
        Port port;
        port.name = std::move(*name);
        port.type = ResourceType::Buffer;
        BufferSpec& spec = port.buffer;

        if (object.contains("size")) {
            auto size = read_buffer_size(object.at("size"), path.member("size"));
            if (!size) return size.take_error();
            spec.size = *size;
        }
        if (object.contains("alignment")) {
            auto alignment = whole_number(object.at("alignment"), path.member("alignment"), 1, kMaxBufferAlignment);
            if (!alignment) return alignment.take_error();
            if (!std::has_single_bit(*alignment)) {
                return fail(path.member("alignment"), "must be a power of two, not " + excerpt(object.at("alignment")));
            }
            spec.alignment = *alignment;
        }
        if (object.contains("range")) {
            JsonValue range = object.at("range");
            const Path where = path.member("range");
            if (!range.is_object()) {
                return fail(where, "must be {\"offset\": bytes, \"size\": bytes} (no size: to the end), not " +
                                       excerpt(range));
            }
            LOOM_TRY(only_keys(range, where, {"offset", "size"}));
            if (range.contains("offset")) {
                auto offset = whole_number(range.at("offset"), where.member("offset"), 0, kMaxBufferBytes - 1);
                if (!offset) return offset.take_error();
                port.bytes.offset = *offset;
            }
            if (range.contains("size")) {
                auto size = whole_number(range.at("size"), where.member("size"), 1, kMaxBufferBytes - port.bytes.offset);
                if (!size) return size.take_error();
                port.bytes.size = *size;
            }
        }
        auto optional = boolean(object, path, "optional");
        if (!optional) return optional.take_error();
        port.optional = *optional;

        if (object.contains("usage")) {
            JsonValue usage = object.at("usage");
            const Path usage_path = path.member("usage");
            if (!usage.is_array()) return fail(usage_path, "must be an array of buffer usage names");
            for (std::size_t i = 0; i < usage.size(); ++i) {
                const Path where = usage_path.element(i);
                if (!usage[i].is_string()) return fail(where, "must be a usage name, not " + excerpt(usage[i]));
                auto flag = parse_buffer_usage_flag(usage[i].string());
                if (!flag) {
                    return fail(where, "unknown buffer usage \"" + std::string(usage[i].string()) +
                                           "\" (vertex, index, uniform, storage, indirect, copy_src, copy_dst)");
                }
                spec.usage |= *flag;
            }
        }
        return port;
    }

    // A buffer's "size": a byte count, {"per_pixel": bytes, "scale": s} (scale 1 by default)
    // or {"per_tile": bytes, "tile": [w, h]}.
    Result<BufferSize> read_buffer_size(JsonValue value, const Path& path) const {
        if (value.is_number_integer()) {
            auto bytes = whole_number(value, path, 1, kMaxBufferBytes);
            if (!bytes) return bytes.take_error();
            return BufferSize::absolute(*bytes);
        }
        if (!value.is_object()) {
            return fail(path, "must be a byte count, {\"per_pixel\": bytes, \"scale\": s} or {\"per_tile\": bytes, "
                              "\"tile\": [w, h]}, not " + excerpt(value));
        }
        LOOM_TRY(only_keys(value, path, {"per_pixel", "scale", "per_tile", "tile"}));
        const bool per_pixel = value.contains("per_pixel");
        if (per_pixel == value.contains("per_tile")) return fail(path, "give \"per_pixel\" or \"per_tile\" (one of them)");
        const char* unit = per_pixel ? "per_pixel" : "per_tile";
        auto bytes = whole_number(value.at(unit), path.member(unit), 1, kMaxBufferBytes);
        if (!bytes) return bytes.take_error();
        if (per_pixel) {
            if (value.contains("tile")) return fail(path.member("tile"), "goes with \"per_tile\", not \"per_pixel\"");
            float scale = 1.0f;
            if (value.contains("scale")) {
                JsonValue s = value.at("scale");
                if (!s.is_number() || !(s.as_double() > 0.0 && s.as_double() <= 16.0)) {
                    return fail(path.member("scale"), "must be a number in (0, 16], not " + excerpt(s));
                }
                scale = static_cast<float>(s.as_double());
            }
            return BufferSize::per_pixel(*bytes, scale);
        }
        if (value.contains("scale")) return fail(path.member("scale"), "goes with \"per_pixel\", not \"per_tile\"");
        if (!value.contains("tile")) return fail(path, "missing \"tile\": [width, height] in pixels");
        JsonValue tile = value.at("tile");
        if (!tile.is_array() || tile.size() != 2) {
            return fail(path.member("tile"), "must be [width, height] in pixels, not " + excerpt(tile));
        }
        auto width = whole_number(tile[0], path.member("tile").element(0), 1, kMaxTextureExtent);
        if (!width) return width.take_error();
        auto height = whole_number(tile[1], path.member("tile").element(1), 1, kMaxTextureExtent);
        if (!height) return height.take_error();
        return BufferSize::per_tile(static_cast<uint32_t>(*width), static_cast<uint32_t>(*height), *bytes);
    }

    Result<std::optional<rhi::FormatFeatures>> read_format(JsonValue object, const Path& path) const {
        const bool partial_color = object.contains("channels") || object.contains("bits") || object.contains("kind") ||
                                   object.contains("srgb");
        const bool partial_depth = object.contains("depth") || object.contains("stencil");
        if (object.contains("format")) {
            if (partial_color || partial_depth) {
                return fail(path, "give \"format\" or partial constraints (channels, bits, kind, srgb, depth, "
                                  "stencil), not both");
            }
            JsonValue value = object.at("format");
            if (!value.is_string()) return fail(path.member("format"), "must be a format name, not " + excerpt(value));
            auto format = parse_format_alias(value.string());
            if (!format) return fail(path.member("format"), "unknown format \"" + std::string(value.string()) + "\"");
            return std::optional(rhi::format_info(*format).features);
        }
        if (!partial_color && !partial_depth) return std::optional<rhi::FormatFeatures>{};

        std::optional<rhi::ChannelKind> kind;
        if (object.contains("kind")) {
            static constexpr std::array<rhi::ChannelKind, 5> kKinds{rhi::ChannelKind::Unorm, rhi::ChannelKind::Snorm,
                                                                    rhi::ChannelKind::Float, rhi::ChannelKind::Uint,
                                                                    rhi::ChannelKind::Sint};
            JsonValue value = object.at("kind");
            for (rhi::ChannelKind k : kKinds) {
                if (value.is_string() && value.string() == rhi::channel_kind_name(k)) kind = k;
            }
            if (!kind) return fail(path.member("kind"), "must be one of unorm, snorm, float, uint, sint, not " + excerpt(value));
        }
        auto bits_of = [&](const char* key, uint32_t max) -> Result<std::optional<uint32_t>> {
            auto bits = positive(object, path, key);
            if (!bits) return bits.take_error();
            if (*bits && **bits > max) {
                return fail(path.member(key), "must be at most " + std::to_string(max) + ", not " +
                                                  std::to_string(**bits));
            }
            return *bits;
        };

        if (partial_depth) {
            if (object.contains("channels") || object.contains("bits") || object.contains("srgb")) {
                return fail(path, "depth/stencil constraints do not take channels, bits or srgb");
            }
            auto depth = bits_of("depth", 32);
            if (!depth) return depth.take_error();
            auto stencil = bits_of("stencil", 8);
            if (!stencil) return stencil.take_error();
            if (kind && *kind != rhi::ChannelKind::Unorm && *kind != rhi::ChannelKind::Float) {
                return fail(path.member("kind"), "depth is unorm or float");
            }
            rhi::FormatFeatures features{};
            if (*depth) {
                const rhi::ChannelKind depth_kind =
                    kind.value_or(**depth == 32 ? rhi::ChannelKind::Float : rhi::ChannelKind::Unorm);
                features.depth = rhi::Channel{static_cast<uint8_t>(**depth), depth_kind};
            }
            if (*stencil) features.stencil_bits = static_cast<uint8_t>(**stencil);
            return std::optional(features);
        }

        auto channels = bits_of("channels", 4);
        if (!channels) return channels.take_error();
        auto bits = bits_of("bits", 32);
        if (!bits) return bits.take_error();
        auto srgb = boolean(object, path, "srgb");
        if (!srgb) return srgb.take_error();
        rhi::FormatFeatures features =
            color_features(channels->value_or(4), bits->value_or(8), kind.value_or(rhi::ChannelKind::Unorm));
        features.srgb = *srgb;
        return std::optional(features);
    }

    // A full mip chain of kMaxTextureExtent texels per side.
    static constexpr uint32_t kMaxMips = 17;
    static_assert(kMaxTextureExtent == 1u << (kMaxMips - 1));

    static constexpr uint32_t kOwnPorts = GraphFile::PortLocation::kOwnPorts;

    std::string_view source_;
};

}  // namespace

namespace {

bool equals_ignoring_case(std::string_view a, std::string_view lower) {
    return a.size() == lower.size() && std::equal(a.begin(), a.end(), lower.begin(), [](char x, char y) {
               return std::tolower(static_cast<unsigned char>(x)) == static_cast<unsigned char>(y);
           });
}

// Every rhi format name in lower case, in rhi::all_formats() order: made once, because a graph
// file names a format on every port, and lower-casing every known name for every port cost
// some sixty allocations per port.
const std::vector<std::pair<std::string, rhi::Format>>& lowercase_format_names() {
    static const auto names = [] {
        std::vector<std::pair<std::string, rhi::Format>> out;
        for (rhi::Format format : rhi::all_formats()) out.emplace_back(lowercase(rhi::format_name(format)), format);
        return out;
    }();
    return names;
}

}  // namespace

std::optional<rhi::Format> parse_format_alias(std::string_view name) {
    if (auto exact = rhi::parse_format(name)) return exact;
    static constexpr std::array<std::pair<std::string_view, rhi::Format>, 6> kDepth{{
        {"d16", rhi::Format::Depth16},
        {"d24", rhi::Format::Depth24},
        {"d32f", rhi::Format::Depth32F},
        {"d24s8", rhi::Format::Depth24Stencil8},
        {"d32fs8", rhi::Format::Depth32FStencil8},
        {"s8", rhi::Format::Stencil8},
    }};
    for (const auto& [alias, format] : kDepth) {
        if (equals_ignoring_case(name, alias)) return format;
    }
    // The first format whose name, ignoring case, is the name itself, the name + "unorm", or
    // (for a trailing 'f') the name with "float" for the 'f'; compared in place, no copies.
    constexpr std::string_view kUnorm = "unorm";
    constexpr std::string_view kFloat = "float";
    const bool trailing_f = !name.empty() && std::tolower(static_cast<unsigned char>(name.back())) == 'f';
    const std::string_view without_f = trailing_f ? name.substr(0, name.size() - 1) : std::string_view();
    for (const auto& [known_name, format] : lowercase_format_names()) {
        const std::string_view known = known_name;
        if (equals_ignoring_case(name, known)) return format;
        if (known.ends_with(kUnorm) && equals_ignoring_case(name, known.substr(0, known.size() - kUnorm.size()))) {
            return format;
        }
        if (trailing_f && known.ends_with(kFloat) &&
            equals_ignoring_case(without_f, known.substr(0, known.size() - kFloat.size()))) {
            return format;
        }
    }
    return std::nullopt;
}

Result<GraphFile> parse_graph_json(std::string_view text, std::string_view source) {
    auto parsed = detail::JsonDocument::parse(text, kMaxGraphFileDepth);
    if (auto* error = std::get_if<detail::JsonError>(&parsed)) {
        std::string message(source);
        if (error->line > 0) detail::append(message, ":", error->line, ":", error->column);
        message += ": ";
        message += error->message;
        return make_error(ErrorCode::Parse, std::move(message));
    }
    const auto& document = std::get<detail::JsonDocument>(parsed);
    return GraphReader(source).read(document.root());
}

Result<GraphFile> load_graph_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(ErrorCode::Io, "cannot read graph file " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return make_error(ErrorCode::Io, "error while reading graph file " + path.string());
    return parse_graph_json(text.str(), path.string());
}

std::optional<std::string> GraphFile::pointer(std::string_view subject) const {
    const auto dot = subject.find('.');
    const auto pass = graph.find_pass(subject.substr(0, dot));
    // Passes the file declared (the graph may have grown since).
    if (!pass || pass->index + 1 >= first_port_location.size()) return std::nullopt;
    std::string pointer = "/passes/";
    detail::append(pointer, pass->index);
    if (dot == std::string_view::npos) return pointer;
    const auto port = graph.pass(*pass).port_index(subject.substr(dot + 1));
    const uint32_t first = first_port_location[pass->index];
    if (!port || *port >= first_port_location[pass->index + 1] - first) return std::nullopt;
    const PortLocation& location = port_locations[first + *port];
    if (location.part != PortLocation::kOwnPorts) detail::append(pointer, "/parts/", location.part);
    static constexpr std::array<std::string_view, 3> kLists{"/inputs/", "/outputs/", "/inouts/"};
    detail::append(pointer, kLists[static_cast<std::size_t>(location.list)], location.index);
    return pointer;
}

Error locate_in_graph_file(const GraphFile& file, Error error) {
    // The subjects' JSON pointers, in the order the error names them, each once.
    std::vector<std::string> pointers;
    for (const std::string& subject : error.subjects) {
        auto pointer = file.pointer(subject);
        if (!pointer) continue;
        if (std::find(pointers.begin(), pointers.end(), *pointer) == pointers.end()) pointers.push_back(std::move(*pointer));
    }
    std::string prefix = file.source + ": ";
    if (!pointers.empty()) prefix += pointers.front() + ": ";
    error.message = prefix + error.message;
    if (pointers.size() > 1) {
        std::string also;
        for (std::size_t i = 1; i < pointers.size(); ++i) also += (i > 1 ? ", " : "") + pointers[i];
        error.message += " (see also " + also + ")";
    }
    return error;
}

}  // namespace loom::fg
