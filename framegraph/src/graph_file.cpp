#include "loom/framegraph/graph_file.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "json_structure.hpp"

namespace loom::fg {
namespace {

using nlohmann::json;

// A value as it stands in the file, cut short: error messages stay one short line whatever
// the file holds (a value can be megabytes long).
std::string excerpt(const nlohmann::json& value) {
    constexpr std::size_t kMax = 60;
    std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    if (text.size() > kMax) text = text.substr(0, kMax) + "...";
    return text;
}

std::string lowercase(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

// Reads one JSON document into a FrameGraph, keeping the JSON pointer for error messages.
class GraphReader {
public:
    explicit GraphReader(std::string_view source) : source_(source) {}

    Result<GraphFile> read(const json& root) {
        GraphFile file;
        if (!root.is_object()) return fail("", "the top level must be an object");
        LOOM_TRY(only_keys(root, "", {"frame", "passes", "connections", "outputs", "description", "order",
                                      "order_constraints"}));
        if (root.contains("description") && !root["description"].is_string()) {
            return fail("/description", "must be a string (what the graph is, where it comes from)");
        }

        if (root.contains("frame")) {
            const json& frame = root["frame"];
            if (!frame.is_object()) return fail("/frame", "must be an object {\"width\": W, \"height\": H}");
            LOOM_TRY(only_keys(frame, "/frame", {"width", "height"}));
            auto width = positive(frame, "/frame", "width", true, kMaxTextureExtent);
            if (!width) return width.take_error();
            auto height = positive(frame, "/frame", "height", true, kMaxTextureExtent);
            if (!height) return height.take_error();
            file.frame = {**width, **height};
        }

        if (root.contains("order")) {
            const json& order = root["order"];
            std::optional<PassOrder> parsed;
            if (order.is_string()) parsed = parse_pass_order(order.get<std::string>());
            if (!parsed) return fail("/order", "must be one of declared, memory, not " + excerpt(order));
            file.order = *parsed;
        }

        if (!root.contains("passes")) return fail("", "missing \"passes\"");
        const json& passes = root["passes"];
        if (!passes.is_array()) return fail("/passes", "must be an array");
        for (std::size_t i = 0; i < passes.size(); ++i) {
            const std::string path = "/passes/" + std::to_string(i);
            auto pass = read_pass(passes[i], path);
            if (!pass) return pass.take_error();
            auto added = file.graph.add_pass(std::move(*pass));
            if (!added) return at(path, added.take_error());
        }

        if (root.contains("connections")) {
            const json& connections = root["connections"];
            if (!connections.is_array()) return fail("/connections", "must be an array of [\"pass.port\", \"pass.port\"]");
            for (std::size_t i = 0; i < connections.size(); ++i) {
                const std::string path = "/connections/" + std::to_string(i);
                const json& pair = connections[i];
                if (!pair.is_array() || pair.size() != 2) return fail(path, "must be [\"pass.port\", \"pass.port\"]");
                auto from = port_ref(pair[0], path + "/0");
                if (!from) return from.take_error();
                auto to = port_ref(pair[1], path + "/1");
                if (!to) return to.take_error();
                auto connected = file.graph.connect(*from, *to);
                if (!connected) return at(path, connected.take_error());
            }
        }

        if (root.contains("outputs")) {
            const json& outputs = root["outputs"];
            if (!outputs.is_array()) return fail("/outputs", "must be an array of \"pass.port\"");
            for (std::size_t i = 0; i < outputs.size(); ++i) {
                const std::string path = "/outputs/" + std::to_string(i);
                auto ref = port_ref(outputs[i], path);
                if (!ref) return ref.take_error();
                auto marked = file.graph.mark_output(*ref);
                if (!marked) return at(path, marked.take_error());
            }
        }
        if (root.contains("order_constraints")) {
            const json& constraints = root["order_constraints"];
            constexpr const char* kPair = "[\"earlier pass\", \"later pass\"]";
            if (!constraints.is_array()) return fail("/order_constraints", std::string("must be an array of ") + kPair);
            for (std::size_t i = 0; i < constraints.size(); ++i) {
                const std::string path = "/order_constraints/" + std::to_string(i);
                const json& pair = constraints[i];
                if (!pair.is_array() || pair.size() != 2) return fail(path, std::string("must be ") + kPair);
                for (std::size_t side = 0; side < 2; ++side) {
                    if (!pair[side].is_string()) {
                        return fail(path + "/" + std::to_string(side), "must be a pass name, not " + excerpt(pair[side]));
                    }
                }
                auto required = file.graph.require_order(pair[0].get<std::string>(), pair[1].get<std::string>());
                if (!required) return at(path, required.take_error());
            }
        }

        file.source = std::string(source_);
        file.pointers = std::move(pointers_);
        return file;
    }

private:
    Error fail(const std::string& path, const std::string& problem) const {
        return make_error(ErrorCode::Parse, std::string(source_) + ": " + (path.empty() ? "" : path + ": ") + problem);
    }

    // An error from the graph itself (ErrorCode::Graph, Join) located at a JSON path.
    Error at(const std::string& path, Error error) const {
        error.message = std::string(source_) + ": " + path + ": " + error.message;
        return error;
    }

    Status only_keys(const json& object, const std::string& path, std::initializer_list<std::string_view> allowed) const {
        for (auto it = object.begin(); it != object.end(); ++it) {
            if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
            std::string known;
            for (std::string_view key : allowed) known += (known.empty() ? "" : ", ") + std::string(key);
            return fail(path + "/" + json_pointer_token(it.key()), "unknown key (expected one of: " + known + ")");
        }
        return {};
    }

    // A positive integer member up to `max`; nullopt when absent and not required.
    Result<std::optional<uint32_t>> positive(const json& object, const std::string& path, const char* key,
                                             bool required = false, uint32_t max = 1u << 30) const {
        if (!object.contains(key)) {
            if (required) return fail(path, std::string("missing \"") + key + "\"");
            return std::optional<uint32_t>{};
        }
        const json& value = object[key];
        const std::string where = path + "/" + key;
        if (!value.is_number_integer()) return fail(where, "must be a positive integer, not " + excerpt(value));
        const auto number = value.get<int64_t>();
        if (number < 1) return fail(where, "must be a positive integer, not " + excerpt(value));
        if (value.is_number_unsigned() ? value.get<uint64_t>() > max : static_cast<uint64_t>(number) > max) {
            return fail(where, "must be at most " + std::to_string(max) + ", not " + excerpt(value));
        }
        return std::optional<uint32_t>(static_cast<uint32_t>(number));
    }

    Result<bool> boolean(const json& object, const std::string& path, const char* key) const {
        if (!object.contains(key)) return false;
        if (!object[key].is_boolean()) return fail(path + "/" + key, "must be true or false, not " + excerpt(object[key]));
        return object[key].get<bool>();
    }

    Result<PortRef> port_ref(const json& value, const std::string& path) const {
        if (!value.is_string()) return fail(path, "must be a \"pass.port\" string, not " + excerpt(value));
        auto ref = parse_port_ref(value.get<std::string>());
        if (!ref) return fail(path, "\"" + value.get<std::string>() + "\" is not of the form \"pass.port\"");
        return *ref;
    }

    Result<Pass> read_pass(const json& object, const std::string& path) {
        if (!object.is_object()) return fail(path, "a pass must be an object");
        LOOM_TRY(only_keys(object, path,
                           {"name", "kind", "queue", "inputs", "outputs", "inouts", "parts", "side_effect",
                            "keep_declared_order"}));
        if (!object.contains("name") || !object["name"].is_string() || object["name"].get<std::string>().empty()) {
            return fail(path + "/name", "a pass needs a non-empty string name");
        }
        Pass pass(object["name"].get<std::string>());
        pass_name_ = pass.name();
        pointers_.try_emplace(pass_name_, path);
        auto side_effect = boolean(object, path, "side_effect");
        if (!side_effect) return side_effect.take_error();
        pass.set_side_effect(*side_effect);
        auto pinned = boolean(object, path, "keep_declared_order");
        if (!pinned) return pinned.take_error();
        pass.keep_declared_order(*pinned);
        if (object.contains("kind")) {
            const json& kind = object["kind"];
            static constexpr std::array<PassKind, 3> kKinds{PassKind::Graphics, PassKind::Compute, PassKind::Copy};
            const auto found = std::find_if(kKinds.begin(), kKinds.end(), [&](PassKind k) {
                return kind.is_string() && kind.get<std::string>() == pass_kind_name(k);
            });
            if (found == kKinds.end()) {
                return fail(path + "/kind", "must be one of graphics, compute, copy, not " + excerpt(kind));
            }
            pass.set_kind(*found);
        }
        if (object.contains("queue")) {
            const json& queue = object["queue"];
            static constexpr std::array<Queue, 2> kQueues{Queue::Graphics, Queue::AsyncCompute};
            const auto found = std::find_if(kQueues.begin(), kQueues.end(), [&](Queue q) {
                return queue.is_string() && queue.get<std::string>() == queue_name(q);
            });
            if (found == kQueues.end()) {
                return fail(path + "/queue", "must be one of graphics, async_compute, not " + excerpt(queue));
            }
            pass.set_queue(*found);
        }

        // The pass's own ports first, then each port set of "parts", as Pass::add composes them.
        auto own = read_port_set(object, path, pass.name());
        if (!own) return own.take_error();
        pass.add(*own);
        if (object.contains("parts")) {
            const json& parts = object["parts"];
            if (!parts.is_array()) return fail(path + "/parts", "must be an array of port sets");
            for (std::size_t i = 0; i < parts.size(); ++i) {
                const std::string set_path = path + "/parts/" + std::to_string(i);
                const json& set = parts[i];
                if (!set.is_object()) return fail(set_path, "a port set must be an object");
                LOOM_TRY(only_keys(set, set_path, {"name", "inputs", "outputs", "inouts"}));
                if (!set.contains("name") || !set["name"].is_string()) {
                    return fail(set_path + "/name", "a port set needs a string name");
                }
                auto read = read_port_set(set, set_path, set["name"].get<std::string>());
                if (!read) return read.take_error();
                pass.add(*read);
            }
        }
        if (auto status = pass.status(); !status) return at(path, status.take_error());
        return pass;
    }

    Result<PortSet> read_port_set(const json& object, const std::string& path, std::string name) {
        PortSet ports(std::move(name));
        static constexpr std::array<std::pair<const char*, PortKind>, 3> kLists{
            {{"inputs", PortKind::Input}, {"outputs", PortKind::Output}, {"inouts", PortKind::InOut}}};
        for (const auto& [key, kind] : kLists) {
            if (!object.contains(key)) continue;
            const json& list = object[key];
            const std::string list_path = path + "/" + key;
            if (!list.is_array()) return fail(list_path, "must be an array of ports");
            for (std::size_t i = 0; i < list.size(); ++i) {
                const std::string port_path = list_path + "/" + std::to_string(i);
                auto port = read_port(list[i], port_path);
                if (!port) return port.take_error();
                if (port->type == ResourceType::Buffer) {
                    ports.declare_buffer(port->name, kind, port->buffer, port->optional, port->bytes);
                } else {
                    ports.declare(port->name, kind, port->spec, port->optional, port->range);
                }
                // A port declared by the pass and its port sets is located where it is first
                // declared.
                pointers_.try_emplace(pass_name_ + "." + port->name, port_path);
            }
        }
        return ports;
    }

    Result<Port> read_port(const json& object, const std::string& path) const {
        if (!object.is_object()) return fail(path, "a port must be an object with a \"name\"");
        auto type = read_type(object, path);
        if (!type) return type.take_error();
        if (*type == ResourceType::Buffer) return read_buffer_port(object, path);
        // A buffer property on a texture port most likely means a forgotten "type": say so
        // rather than list the texture keys.
        if (object.contains("alignment")) {
            return fail(path + "/alignment", "\"alignment\" is a property of buffer ports; a texture port takes none "
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
            const json& size = object["size"];
            const bool pair = size.is_array() && size.size() == 2 &&
                              std::all_of(size.begin(), size.end(), [](const json& v) { return v.is_number_integer(); });
            if (!pair) {
                // A byte count or a per-pixel/per-tile object is a buffer's size.
                const std::string hint = size.is_number_integer() || size.is_object()
                                             ? " (a buffer's size needs \"type\": \"buffer\")"
                                             : "";
                return fail(path + "/size", "must be [width, height] in texels, not " + excerpt(size) + hint);
            }
            const bool in_range = std::all_of(size.begin(), size.end(), [](const json& v) {
                if (v.is_number_unsigned()) return v.get<uint64_t>() >= 1 && v.get<uint64_t>() <= kMaxTextureExtent;
                return v.get<int64_t>() >= 1 && v.get<int64_t>() <= int64_t{kMaxTextureExtent};
            });
            if (!in_range) {
                return fail(path + "/size", "each side must be in 1.." + std::to_string(kMaxTextureExtent) + ", not " +
                                                excerpt(size));
            }
            spec.size = SizeSpec::absolute(size[0].get<uint32_t>(), size[1].get<uint32_t>());
        }
        if (object.contains("scale")) {
            const json& scale = object["scale"];
            auto valid_scale = [](const json& v) { return v.is_number() && v.get<double>() > 0.0 && v.get<double>() <= 16.0; };
            if (valid_scale(scale)) {
                spec.size = SizeSpec::relative(scale.get<float>());
            } else if (scale.is_array() && scale.size() == 2 && valid_scale(scale[0]) && valid_scale(scale[1])) {
                spec.size = SizeSpec::relative(scale[0].get<float>(), scale[1].get<float>());
            } else {
                return fail(path + "/scale", "must be a number in (0, 16] or [sx, sy], not " + excerpt(scale));
            }
        }
        // The limits of texture_spec.hpp, refused here with a JSON pointer rather than later by
        // resolve(); mips also depend on the resolved size, which resolve() checks.
        auto samples = positive(object, path, "samples", false, kMaxTextureSamples);
        if (!samples) return samples.take_error();
        if (*samples) {
            if (!std::has_single_bit(**samples)) {
                return fail(path + "/samples", "must be one of 1, 2, 4, 8, 16, 32, 64, not " + excerpt(object["samples"]));
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
            auto range = read_texture_range(object["range"], path + "/range");
            if (!range) return range.take_error();
            port.range = *range;
        }
        auto optional = boolean(object, path, "optional");
        if (!optional) return optional.take_error();
        port.optional = *optional;

        if (object.contains("usage")) {
            const json& usage = object["usage"];
            if (!usage.is_array()) return fail(path + "/usage", "must be an array of usage names");
            for (std::size_t i = 0; i < usage.size(); ++i) {
                const std::string where = path + "/usage/" + std::to_string(i);
                if (!usage[i].is_string()) return fail(where, "must be a usage name, not " + excerpt(usage[i]));
                auto flag = parse_usage_flag(usage[i].get<std::string>());
                if (!flag) {
                    return fail(where, "unknown usage \"" + usage[i].get<std::string>() +
                                           "\" (sampled, color_attachment, depth_stencil_attachment, storage, "
                                           "copy_src, copy_dst)");
                }
                spec.usage |= *flag;
            }
        }
        return port;
    }

    Result<std::string> port_name(const json& object, const std::string& path) const {
        if (!object.contains("name") || !object["name"].is_string() || object["name"].get<std::string>().empty()) {
            return fail(path + "/name", "a port needs a non-empty string name");
        }
        return object["name"].get<std::string>();
    }

    // "type": "texture" (the default) or "buffer".
    Result<ResourceType> read_type(const json& object, const std::string& path) const {
        if (!object.contains("type")) return ResourceType::Texture;
        const json& type = object["type"];
        for (ResourceType t : {ResourceType::Texture, ResourceType::Buffer}) {
            if (type.is_string() && type.get<std::string>() == resource_type_name(t)) return t;
        }
        return fail(path + "/type", "must be \"texture\" or \"buffer\", not " + excerpt(type));
    }

    // An integer in [min, max] (up to 2^40, a buffer's limit, so 64 bits).
    Result<uint64_t> whole_number(const json& value, const std::string& where, uint64_t min, uint64_t max) const {
        const std::string wanted = min == 0 ? "a non-negative integer" : "a positive integer";
        if (!value.is_number_integer()) return fail(where, "must be " + wanted + ", not " + excerpt(value));
        if (!value.is_number_unsigned() && value.get<int64_t>() < 0) {
            return fail(where, "must be " + wanted + ", not " + excerpt(value));
        }
        const auto number = value.get<uint64_t>();
        if (number < min) return fail(where, "must be " + wanted + ", not " + excerpt(value));
        if (number > max) return fail(where, "must be at most " + std::to_string(max) + ", not " + excerpt(value));
        return number;
    }

    // "range" of a texture port: {"mip": k} or {"mips": [base, count]} ([base]: to the last
    // level), and likewise "layer" / "layers"; what is not given is every level (layer).
    Result<SubresourceRange> read_texture_range(const json& value, const std::string& path) const {
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
                auto index = whole_number(value[one], path + "/" + one, 0, limit - 1);
                if (!index) return index.take_error();
                base = static_cast<uint32_t>(*index);
                count = 1;
            } else if (value.contains(many)) {
                const json& pair = value[many];
                const std::string where = path + "/" + many;
                if (!pair.is_array() || pair.empty() || pair.size() > 2) {
                    return fail(where, "must be [base, count] or [base] (from base to the last), not " + excerpt(pair));
                }
                auto first = whole_number(pair[0], where + "/0", 0, limit - 1);
                if (!first) return first.take_error();
                base = static_cast<uint32_t>(*first);
                count = rhi::kRemainingSubresources;
                if (pair.size() == 2) {
                    auto n = whole_number(pair[1], where + "/1", 1, limit - base);
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
    Result<Port> read_buffer_port(const json& object, const std::string& path) const {
        // Texture properties on a buffer port: name the key and what a buffer port takes.
        static constexpr std::array<std::string_view, 12> kTextureKeys{
            "format", "channels", "bits", "kind", "srgb", "depth", "stencil", "scale", "samples", "mips", "layers", "cube"};
        for (std::string_view key : kTextureKeys) {
            if (!object.contains(key)) continue;
            return fail(path + "/" + std::string(key),
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
            auto size = read_buffer_size(object["size"], path + "/size");
            if (!size) return size.take_error();
            spec.size = *size;
        }
        if (object.contains("alignment")) {
            auto alignment = whole_number(object["alignment"], path + "/alignment", 1, kMaxBufferAlignment);
            if (!alignment) return alignment.take_error();
            if (!std::has_single_bit(*alignment)) {
                return fail(path + "/alignment", "must be a power of two, not " + excerpt(object["alignment"]));
            }
            spec.alignment = *alignment;
        }
        if (object.contains("range")) {
            const json& range = object["range"];
            const std::string where = path + "/range";
            if (!range.is_object()) {
                return fail(where, "must be {\"offset\": bytes, \"size\": bytes} (no size: to the end), not " +
                                       excerpt(range));
            }
            LOOM_TRY(only_keys(range, where, {"offset", "size"}));
            if (range.contains("offset")) {
                auto offset = whole_number(range["offset"], where + "/offset", 0, kMaxBufferBytes - 1);
                if (!offset) return offset.take_error();
                port.bytes.offset = *offset;
            }
            if (range.contains("size")) {
                auto size = whole_number(range["size"], where + "/size", 1, kMaxBufferBytes - port.bytes.offset);
                if (!size) return size.take_error();
                port.bytes.size = *size;
            }
        }
        auto optional = boolean(object, path, "optional");
        if (!optional) return optional.take_error();
        port.optional = *optional;

        if (object.contains("usage")) {
            const json& usage = object["usage"];
            if (!usage.is_array()) return fail(path + "/usage", "must be an array of buffer usage names");
            for (std::size_t i = 0; i < usage.size(); ++i) {
                const std::string where = path + "/usage/" + std::to_string(i);
                if (!usage[i].is_string()) return fail(where, "must be a usage name, not " + excerpt(usage[i]));
                auto flag = parse_buffer_usage_flag(usage[i].get<std::string>());
                if (!flag) {
                    return fail(where, "unknown buffer usage \"" + usage[i].get<std::string>() +
                                           "\" (vertex, index, uniform, storage, indirect, copy_src, copy_dst)");
                }
                spec.usage |= *flag;
            }
        }
        return port;
    }

    // A buffer's "size": a byte count, {"per_pixel": bytes, "scale": s} (scale 1 by default)
    // or {"per_tile": bytes, "tile": [w, h]}.
    Result<BufferSize> read_buffer_size(const json& value, const std::string& path) const {
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
        auto bytes = whole_number(value[unit], path + "/" + unit, 1, kMaxBufferBytes);
        if (!bytes) return bytes.take_error();
        if (per_pixel) {
            if (value.contains("tile")) return fail(path + "/tile", "goes with \"per_tile\", not \"per_pixel\"");
            float scale = 1.0f;
            if (value.contains("scale")) {
                const json& s = value["scale"];
                if (!s.is_number() || !(s.get<double>() > 0.0 && s.get<double>() <= 16.0)) {
                    return fail(path + "/scale", "must be a number in (0, 16], not " + excerpt(s));
                }
                scale = s.get<float>();
            }
            return BufferSize::per_pixel(*bytes, scale);
        }
        if (value.contains("scale")) return fail(path + "/scale", "goes with \"per_pixel\", not \"per_tile\"");
        if (!value.contains("tile")) return fail(path, "missing \"tile\": [width, height] in pixels");
        const json& tile = value["tile"];
        if (!tile.is_array() || tile.size() != 2) {
            return fail(path + "/tile", "must be [width, height] in pixels, not " + excerpt(tile));
        }
        auto width = whole_number(tile[0], path + "/tile/0", 1, kMaxTextureExtent);
        if (!width) return width.take_error();
        auto height = whole_number(tile[1], path + "/tile/1", 1, kMaxTextureExtent);
        if (!height) return height.take_error();
        return BufferSize::per_tile(static_cast<uint32_t>(*width), static_cast<uint32_t>(*height), *bytes);
    }

    Result<std::optional<rhi::FormatFeatures>> read_format(const json& object, const std::string& path) const {
        const bool partial_color = object.contains("channels") || object.contains("bits") || object.contains("kind") ||
                                   object.contains("srgb");
        const bool partial_depth = object.contains("depth") || object.contains("stencil");
        if (object.contains("format")) {
            if (partial_color || partial_depth) {
                return fail(path, "give \"format\" or partial constraints (channels, bits, kind, srgb, depth, "
                                  "stencil), not both");
            }
            const json& value = object["format"];
            if (!value.is_string()) return fail(path + "/format", "must be a format name, not " + excerpt(value));
            auto format = parse_format_alias(value.get<std::string>());
            if (!format) return fail(path + "/format", "unknown format \"" + value.get<std::string>() + "\"");
            return std::optional(rhi::format_info(*format).features);
        }
        if (!partial_color && !partial_depth) return std::optional<rhi::FormatFeatures>{};

        std::optional<rhi::ChannelKind> kind;
        if (object.contains("kind")) {
            static constexpr std::array<rhi::ChannelKind, 5> kKinds{rhi::ChannelKind::Unorm, rhi::ChannelKind::Snorm,
                                                                    rhi::ChannelKind::Float, rhi::ChannelKind::Uint,
                                                                    rhi::ChannelKind::Sint};
            const json& value = object["kind"];
            for (rhi::ChannelKind k : kKinds) {
                if (value.is_string() && value.get<std::string>() == rhi::channel_kind_name(k)) kind = k;
            }
            if (!kind) return fail(path + "/kind", "must be one of unorm, snorm, float, uint, sint, not " + excerpt(value));
        }
        auto bits_of = [&](const char* key, uint32_t max) -> Result<std::optional<uint32_t>> {
            auto bits = positive(object, path, key);
            if (!bits) return bits.take_error();
            if (*bits && **bits > max) {
                return fail(path + "/" + key, "must be at most " + std::to_string(max) + ", not " +
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
                return fail(path + "/kind", "depth is unorm or float");
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

    std::string_view source_;
    std::string pass_name_;  // the pass being read
    std::unordered_map<std::string, std::string> pointers_;
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
    if (auto problem = check_json_structure(text, kMaxGraphFileDepth)) {
        return make_error(ErrorCode::Parse, std::string(source) + ":" + std::to_string(problem->line) + ":" +
                                                std::to_string(problem->column) + ": " + problem->message);
    }
    json root;
    try {
        root = json::parse(text.begin(), text.end());
    } catch (const json::parse_error& error) {
        // Turn the byte offset into a line and column.
        const std::size_t offset = std::min<std::size_t>(error.byte == 0 ? 0 : error.byte - 1, text.size());
        std::size_t line = 1;
        std::size_t column = 1;
        for (std::size_t i = 0; i < offset; ++i) {
            if (text[i] == '\n') {
                ++line;
                column = 1;
            } else {
                ++column;
            }
        }
        std::string what = error.what();
        if (auto colon = what.rfind(": "); colon != std::string::npos) what = what.substr(colon + 2);
        return make_error(ErrorCode::Parse, std::string(source) + ":" + std::to_string(line) + ":" +
                                                std::to_string(column) + ": invalid JSON: " + what);
    } catch (const json::exception& error) {
        // Any other refusal of the parser (the structure check above catches the known ones).
        std::string what = error.what();
        if (auto bracket = what.find("] "); bracket != std::string::npos) what = what.substr(bracket + 2);
        return make_error(ErrorCode::Parse, std::string(source) + ": invalid JSON: " + what);
    }
    return GraphReader(source).read(root);
}

Result<GraphFile> load_graph_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(ErrorCode::Io, "cannot read graph file " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return make_error(ErrorCode::Io, "error while reading graph file " + path.string());
    return parse_graph_json(text.str(), path.string());
}

Error locate_in_graph_file(const GraphFile& file, Error error) {
    // The subjects' JSON pointers, in the order the error names them, each once.
    std::vector<std::string> pointers;
    for (const std::string& subject : error.subjects) {
        auto it = file.pointers.find(subject);
        if (it == file.pointers.end()) continue;
        if (std::find(pointers.begin(), pointers.end(), it->second) == pointers.end()) pointers.push_back(it->second);
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
