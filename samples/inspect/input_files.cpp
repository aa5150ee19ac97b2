#include "input_files.hpp"

#include <fstream>
#include <sstream>
#include <unordered_set>

#include "inspect_input.hpp"

namespace loom::inspect {
namespace {

using nlohmann::json;

Error parse_error(const std::filesystem::path& path, const std::string& pointer, const std::string& message) {
    return make_error(ErrorCode::Parse, path.string() + ": " + (pointer.empty() ? "/" : pointer) + ": " + message);
}

Result<std::string> read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(ErrorCode::Io, "cannot read " + path.string());
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) return make_error(ErrorCode::Io, "cannot read " + path.string());
    return std::move(text).str();
}

Result<json> read_json(const std::filesystem::path& path) {
    auto text = read_text(path);
    if (!text) return text.take_error();
    json document = json::parse(*text, nullptr, false);
    if (document.is_discarded()) return make_error(ErrorCode::Parse, path.string() + ": not valid JSON");
    return document;
}

// Checks the members the page reads, each with its JSON type, and reports the first one that
// is missing or of the wrong type by its JSON pointer.
class Checker {
public:
    explicit Checker(const std::filesystem::path& path) : path_(path) {}

    /// The member `key` of the object at `pointer` must exist and be of `type`.
    bool need(const json& object, const std::string& pointer, const char* key, json::value_t type) {
        const std::string where = pointer + "/" + key;
        if (!object.is_object() || !object.contains(key)) return fail(where, "missing");
        return expect(object.at(key), where, type);
    }

    /// `value` at `pointer` must be of `type` (unsigned integers also pass as numbers).
    bool expect(const json& value, const std::string& pointer, json::value_t type) {
        const bool ok = value.type() == type ||
                        (type == json::value_t::number_float && value.is_number()) ||
                        (type == json::value_t::number_integer && value.is_number_integer());
        if (!ok) return fail(pointer, std::string("expected ") + name(type) + ", not " + value.type_name());
        return true;
    }

    /// A member that is either null or an unsigned integer.
    bool index_or_null(const json& object, const std::string& pointer, const char* key) {
        const std::string where = pointer + "/" + key;
        if (!object.contains(key)) return fail(where, "missing");
        if (object.at(key).is_null()) return true;
        return expect(object.at(key), where, json::value_t::number_unsigned);
    }

    /// An index below `count`.
    bool index_below(const json& value, const std::string& pointer, std::size_t count, const char* what) {
        if (!expect(value, pointer, json::value_t::number_unsigned)) return false;
        if (value.get<uint64_t>() >= count) {
            return fail(pointer, std::to_string(value.get<uint64_t>()) + " is not a " + what + " index (" +
                                     std::to_string(count) + " " + what + "s)");
        }
        return true;
    }

    bool fail(const std::string& pointer, const std::string& message) {
        if (!error_) error_ = parse_error(path_, pointer, message);
        return false;
    }

    [[nodiscard]] bool failed() const { return error_.has_value(); }
    Error take() { return std::move(*error_); }

private:
    static const char* name(json::value_t type) {
        switch (type) {
            case json::value_t::object: return "an object";
            case json::value_t::array: return "an array";
            case json::value_t::string: return "a string";
            case json::value_t::boolean: return "true or false";
            case json::value_t::number_unsigned: return "a non-negative integer";
            case json::value_t::number_integer: return "an integer";
            default: return "a number";
        }
    }

    std::filesystem::path path_;
    std::optional<Error> error_;
};

constexpr auto kObject = json::value_t::object;
constexpr auto kArray = json::value_t::array;
constexpr auto kString = json::value_t::string;
constexpr auto kBool = json::value_t::boolean;
constexpr auto kCount = json::value_t::number_unsigned;
constexpr auto kNumber = json::value_t::number_float;

// A lifetime or occupancy: [first, last], positions in the order.
bool check_span(Checker& check, const json& object, const std::string& pointer, const char* key, std::size_t passes) {
    if (!check.need(object, pointer, key, kArray)) return false;
    const json& span = object.at(key);
    const std::string where = pointer + "/" + key;
    if (span.size() != 2) return check.fail(where, "expected [first, last]");
    if (!check.index_below(span[0], where + "/0", passes, "pass") || !check.index_below(span[1], where + "/1", passes, "pass")) {
        return false;
    }
    if (span[0].get<uint64_t>() > span[1].get<uint64_t>()) return check.fail(where, "first is after last");
    return true;
}

// The plan members the page reads (docs/framegraph.md describes them all). `pointer` is where
// the plan sits in its file ("" for a plan file, "/plan" in an inspector input).
Status check_plan(const json& plan, const std::filesystem::path& path, const std::string& pointer) {
    Checker check(path);
    if (!check.expect(plan, pointer, kObject)) return check.take();
    for (const char* key : {"passes", "resources", "textures", "buffers", "heaps", "edges", "culled", "order",
                            "queue_syncs", "ownership_transfers", "graph_outputs"}) {
        if (!check.need(plan, pointer, key, kArray)) return check.take();
    }
    for (const char* key : {"allocator", "hash", "sharing", "pass_order"}) {
        if (!check.need(plan, pointer, key, kString)) return check.take();
    }
    if (!check.need(plan, pointer, "summary", kObject) || !check.need(plan, pointer, "frame", kObject)) return check.take();
    for (const char* key : {"bytes", "naive_bytes", "lower_bound_bytes", "textures", "naive_textures",
                            "lower_bound_textures", "buffers", "buffer_bytes"}) {
        if (!check.need(plan.at("summary"), pointer + "/summary", key, kCount)) return check.take();
    }
    const std::size_t passes = plan.at("passes").size();
    const std::size_t resources = plan.at("resources").size();
    const std::size_t textures = plan.at("textures").size();
    const std::size_t buffers = plan.at("buffers").size();
    const std::size_t heaps = plan.at("heaps").size();
    for (std::size_t i = 0; i < passes && !check.failed(); ++i) {
        const json& pass = plan.at("passes")[i];
        const std::string at = pointer + "/passes/" + std::to_string(i);
        if (!check.need(pass, at, "name", kString) || !check.need(pass, at, "kind", kString) ||
            !check.need(pass, at, "queue", kString) || !check.need(pass, at, "side_effect", kBool) ||
            !check.need(pass, at, "ports", kArray)) {
            break;
        }
        for (std::size_t p = 0; p < pass.at("ports").size(); ++p) {
            const json& port = pass.at("ports")[p];
            const std::string port_at = at + "/ports/" + std::to_string(p);
            if (!check.need(port, port_at, "name", kString) || !check.need(port, port_at, "kind", kString) ||
                !check.need(port, port_at, "type", kString) || !check.index_or_null(port, port_at, "resource")) {
                break;
            }
            if (!port.at("resource").is_null()) check.index_below(port.at("resource"), port_at + "/resource", resources, "resource");
        }
    }
    for (std::size_t i = 0; i < resources && !check.failed(); ++i) {
        const json& r = plan.at("resources")[i];
        const std::string at = pointer + "/resources/" + std::to_string(i);
        if (!check.need(r, at, "name", kString) || !check.need(r, at, "type", kString) ||
            !check.need(r, at, "bytes", kCount) || !check.need(r, at, "ports", kArray) ||
            !check_span(check, r, at, "lifetime", passes) || !check_span(check, r, at, "occupancy", passes)) {
            break;
        }
        const bool buffer = r.at("type") == "buffer";
        const char* physical = buffer ? "buffer" : "texture";
        if (check.need(r, at, physical, kCount)) {
            check.index_below(r.at(physical), at + "/" + physical, buffer ? buffers : textures, physical);
        }
    }
    for (const char* list : {"textures", "buffers"}) {
        const json& objects = plan.at(list);
        for (std::size_t i = 0; i < objects.size() && !check.failed(); ++i) {
            const json& object = objects[i];
            const std::string at = pointer + "/" + list + "/" + std::to_string(i);
            if (!check.need(object, at, "name", kString) || !check.need(object, at, "bytes", kCount) ||
                !check.need(object, at, "resources", kArray)) {
                break;
            }
            for (std::size_t k = 0; k < object.at("resources").size(); ++k) {
                if (!check.index_below(object.at("resources")[k], at + "/resources/" + std::to_string(k), resources, "resource")) break;
            }
            if (object.contains("heap") && check.index_below(object.at("heap"), at + "/heap", heaps, "heap")) {
                check.need(object, at, "offset", kCount);
            }
        }
    }
    for (std::size_t i = 0; i < plan.at("edges").size() && !check.failed(); ++i) {
        const json& edge = plan.at("edges")[i];
        const std::string at = pointer + "/edges/" + std::to_string(i);
        if (check.need(edge, at, "from", kString) && check.need(edge, at, "to", kString)) {
            check.index_below(edge.contains("resource") ? edge.at("resource") : json(), at + "/resource", resources, "resource");
        }
    }
    for (std::size_t i = 0; i < heaps && !check.failed(); ++i) {
        check.expect(plan.at("heaps")[i], pointer + "/heaps/" + std::to_string(i), kCount);
    }
    for (std::size_t i = 0; i < plan.at("culled").size() && !check.failed(); ++i) {
        check.expect(plan.at("culled")[i], pointer + "/culled/" + std::to_string(i), kString);
    }
    if (check.failed()) return check.take();
    return {};
}

// The schedule of an inspector input: one entry per pass, with lists of transitions.
Status check_schedule(const json& input, const std::filesystem::path& path) {
    if (!input.contains("schedule")) return {};
    Checker check(path);
    const json& schedule = input.at("schedule");
    if (!check.expect(schedule, "/schedule", kArray)) return check.take();
    if (schedule.size() != input.at("plan").at("passes").size()) {
        check.fail("/schedule", std::to_string(schedule.size()) + " entries for " +
                                    std::to_string(input.at("plan").at("passes").size()) + " passes");
        return check.take();
    }
    for (std::size_t i = 0; i < schedule.size() && !check.failed(); ++i) {
        const std::string at = "/schedule/" + std::to_string(i);
        for (const char* key : {"ports", "before", "after", "buffers_before", "buffers_after", "copies"}) {
            if (!check.need(schedule[i], at, key, kArray)) break;
        }
    }
    if (check.failed()) return check.take();
    return {};
}

std::unordered_set<std::string> pass_names(const json& input) {
    std::unordered_set<std::string> names;
    for (const json& pass : input.at("plan").at("passes")) names.insert(pass.at("name").get<std::string>());
    return names;
}

// The member `member` of a file that holds it, or the file's document itself when that is of
// `type` (a timings array, an allocations object without the wrapper).
Result<std::pair<json, std::string>> member_of(const std::filesystem::path& path, const char* member, json::value_t type) {
    auto document = read_json(path);
    if (!document) return document.take_error();
    if (document->is_object() && document->contains(member)) {
        return std::pair<json, std::string>{document->at(member), std::string("/") + member};
    }
    if (document->type() == type) return std::pair<json, std::string>{std::move(*document), ""};
    return parse_error(path, "", std::string("expected \"") + member + "\" or the " + member + " alone");
}

}  // namespace

Result<json> read_input(const std::filesystem::path& path, const GraphPlanning& planning) {
    auto text = read_text(path);
    if (!text) return text.take_error();
    return parse_input(*text, path, planning);
}

Result<json> parse_input(const std::string& text, const std::filesystem::path& path, const GraphPlanning& planning) {
    json document = json::parse(text, nullptr, false);
    if (document.is_discarded()) return make_error(ErrorCode::Parse, path.string() + ": not valid JSON");

    if (document.is_object() && document.contains("format")) {
        if (document.at("format") != kInputFormat) {
            return parse_error(path, "/format", "expected \"" + std::string(kInputFormat) + "\"");
        }
        if (document.value("version", 0) != kInputVersion) {
            return parse_error(path, "/version", "this loom-inspect reads version " + std::to_string(kInputVersion));
        }
        if (!document.contains("plan")) return parse_error(path, "/plan", "missing");
        if (auto checked = check_plan(document.at("plan"), path, "/plan"); !checked) return checked.take_error();
        if (auto checked = check_schedule(document, path); !checked) return checked.take_error();
        return document;
    }
    // A plan JSON says which allocator made it and has a summary; a graph file has neither.
    if (document.is_object() && document.contains("summary") && document.contains("allocator")) {
        if (auto checked = check_plan(document, path, ""); !checked) return checked.take_error();
        return json{{"format", kInputFormat}, {"version", kInputVersion}, {"source", path.filename().string()},
                    {"plan", std::move(document)}};
    }

    auto file = fg::parse_graph_json(text, path.string());
    if (!file) return file.take_error();
    fg::PlanOptions options = planning.options;
    options.frame = planning.frame.value_or(file->frame);
    options.order = planning.order.value_or(file->order);
    auto plan = fg::build_plan(file->graph, options);
    if (!plan) return fg::locate_in_graph_file(*file, plan.take_error());
    RunRecord run;
    run.source = path.filename().string() + ", planned by loom-inspect";
    // The schedule with no imports or histories: a graph file binds none.
    auto schedule = fg::build_execution_schedule(*plan, {}, {});
    if (!schedule) return fg::locate_in_graph_file(*file, schedule.take_error());
    run.schedule = &*schedule;
    if (planning.compare) {
        auto rows = compare_allocators(file->graph, options);
        if (!rows) return fg::locate_in_graph_file(*file, rows.take_error());
        run.allocators = std::move(*rows);
    }
    std::ostringstream written;
    write_input(written, *plan, run);
    return json::parse(std::move(written).str());
}

Status add_timings(json& input, const std::filesystem::path& path) {
    auto found = member_of(path, "timings", kArray);
    if (!found) return found.take_error();
    auto& [timings, pointer] = *found;
    Checker check(path);
    if (!check.expect(timings, pointer, kArray)) return check.take();
    const auto names = pass_names(input);
    for (std::size_t i = 0; i < timings.size(); ++i) {
        const json& t = timings[i];
        const std::string at = pointer + "/" + std::to_string(i);
        if (!check.need(t, at, "pass", kString) || !check.need(t, at, "cpu_ms", kNumber)) return check.take();
        if (t.contains("gpu_ms") && !t.at("gpu_ms").is_null() && !check.expect(t.at("gpu_ms"), at + "/gpu_ms", kNumber)) {
            return check.take();
        }
        if (!names.contains(t.at("pass").get<std::string>())) {
            return parse_error(path, at + "/pass", "'" + t.at("pass").get<std::string>() + "' is not a pass that runs in the plan");
        }
    }
    input["timings"] = std::move(timings);
    return {};
}

Status add_allocations(json& input, const std::filesystem::path& path) {
    auto found = member_of(path, "allocations", kObject);
    if (!found) return found.take_error();
    auto& [allocations, pointer] = *found;
    Checker check(path);
    if (!check.expect(allocations, pointer, kObject)) return check.take();
    for (const auto& [key, value] : allocations.items()) {
        if (key == "device") {
            if (!check.expect(value, pointer + "/device", kObject)) return check.take();
            for (const auto& [device_key, count] : value.items()) {
                if (!check.expect(count, pointer + "/device/" + device_key, kCount)) return check.take();
            }
        } else if (!check.expect(value, pointer + "/" + key, kCount)) {
            return check.take();
        }
    }
    input["allocations"] = std::move(allocations);
    return {};
}

}  // namespace loom::inspect
