#include "gltf_validate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <string_view>
#include <system_error>

#include "checked_math.hpp"
#include "gltf_constants.hpp"
#include "json_pointer.hpp"
#include "uri.hpp"

namespace loom::gltf::detail {

using namespace loom::scene;  // the importer builds the scene model's types


std::string located_message(const std::string& file_label, const std::string& pointer, const std::string& what) {
    if (pointer.empty()) return file_label + ": " + what;
    return file_label + ": " + pointer + ": " + what;
}

namespace {

using json = nlohmann::json;

// Largest integer JSON can carry exactly (2^53 - 1); sizes and offsets above it are rejected.
constexpr uint64_t kMaxSafeInteger = (uint64_t{1} << 53) - 1;
// tinygltf keeps some values (references, sparse counts and offsets, texCoord) in an int.
constexpr uint64_t kMaxInt = static_cast<uint64_t>(std::numeric_limits<int32_t>::max());
// Deeper JSON (only possible in extras and extensions) would overflow the stack of tinygltf's
// recursive conversion of those values.
constexpr std::size_t kMaxJsonDepth = 256;

constexpr std::array<std::string_view, 3> kSupportedExtensions = {"KHR_mesh_quantization", "KHR_materials_emissive_strength",
                                                                   "KHR_texture_transform"};

/// The top-level arrays of a glTF document that other objects refer to by index.
enum class Collection : uint8_t {
    Accessors, Animations, Buffers, BufferViews, Cameras, Images, Materials, Meshes, Nodes, Samplers, Scenes, Skins,
    Textures,
};
constexpr std::size_t kCollectionCount = static_cast<std::size_t>(Collection::Textures) + 1;

struct CollectionInfo {
    const char* key;       // top-level property
    const char* singular;  // for messages
};

constexpr std::array<CollectionInfo, kCollectionCount> kCollections = {{
    {"accessors", "accessor"},
    {"animations", "animation"},
    {"buffers", "buffer"},
    {"bufferViews", "buffer view"},
    {"cameras", "camera"},
    {"images", "image"},
    {"materials", "material"},
    {"meshes", "mesh"},
    {"nodes", "node"},
    {"samplers", "sampler"},
    {"scenes", "scene"},
    {"skins", "skin"},
    {"textures", "texture"},
}};

const CollectionInfo& info(Collection collection) { return kCollections[static_cast<std::size_t>(collection)]; }

// What later checks need to know about a validated buffer view / accessor.
struct ViewInfo {
    uint64_t buffer = 0;
    uint64_t byte_offset = 0;
    uint64_t byte_length = 0;
    std::optional<uint64_t> byte_stride;
    std::optional<uint64_t> target;  ///< 34962 ARRAY_BUFFER or 34963 ELEMENT_ARRAY_BUFFER
};

struct AccessorInfo {
    ElementType type;
    int component_type = 0;
    bool normalized = false;
    uint64_t count = 0;
    std::optional<uint64_t> buffer_view;
    uint64_t byte_offset = 0;
    bool has_bounds = false;  ///< both min and max are present
};

constexpr uint64_t kArrayBuffer = 34962;
constexpr uint64_t kElementArrayBuffer = 34963;

// glTF attribute semantics: the core ones (indexed ones as <NAME>_<decimal without leading
// zeros>) or application-specific ones starting with an underscore.
bool is_valid_semantic(std::string_view semantic, bool morph_target) {
    if (!semantic.empty() && semantic.front() == '_') return true;
    if (semantic == "POSITION" || semantic == "NORMAL" || semantic == "TANGENT") return true;
    for (const std::string_view prefix : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
        if (semantic.substr(0, prefix.size()) != prefix) continue;
        if (morph_target && (prefix == "JOINTS_" || prefix == "WEIGHTS_")) return false;
        const std::string_view digits = semantic.substr(prefix.size());
        if (digits.empty() || (digits.size() > 1 && digits.front() == '0')) return false;
        return std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; });
    }
    return false;
}

std::string short_dump(const json& value) {
    std::string text = value.dump();
    if (text.size() > 40) text = text.substr(0, 37) + "...";
    return text;
}

std::string format_number(double value) {
    std::string text = json(value).dump();
    return text;
}

// Whether a node matrix (16 numbers, column-major, already checked) is a translation, rotation
// and scale: its last row 0 0 0 1 and its three axes orthogonal (no shear, no projection).
bool decomposable_to_trs(const json& matrix) {
    std::array<double, 16> m{};
    for (std::size_t i = 0; i < 16; ++i) m[i] = matrix[i].get<double>();
    constexpr double kTolerance = 1e-5;
    if (std::abs(m[3]) > kTolerance || std::abs(m[7]) > kTolerance || std::abs(m[11]) > kTolerance ||
        std::abs(m[15] - 1.0) > kTolerance) {
        return false;
    }
    const auto axis = [&](std::size_t c) { return std::array<double, 3>{m[4 * c], m[4 * c + 1], m[4 * c + 2]}; };
    const auto dot = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    };
    for (std::size_t a = 0; a < 3; ++a) {
        for (std::size_t b = a + 1; b < 3; ++b) {
            const double scale = std::sqrt(dot(axis(a), axis(a)) * dot(axis(b), axis(b)));
            if (std::abs(dot(axis(a), axis(b))) > 1e-4 * scale) return false;
        }
    }
    return true;
}

// A finite number in [min, max] (bounds exclusive when asked).
struct Range {
    double min = -std::numeric_limits<double>::infinity();
    double max = std::numeric_limits<double>::infinity();
    bool min_exclusive = false;
    bool max_exclusive = false;
};

class Validator {
public:
    Validator(const json& root, const ValidationInput& input, ValidationOutput& output)
        : root_(root), input_(input), output_(output) {}

    Status run() {
        if (!root_.is_object()) return parse_error(JsonPointer{}, "the JSON root is not an object");
        LOOM_TRY(check_depth());
        LOOM_TRY(check_asset());
        LOOM_TRY(check_extensions());
        LOOM_TRY(check_collections());
        LOOM_TRY(check_buffers());
        LOOM_TRY(check_buffer_views());
        LOOM_TRY(check_accessors());
        LOOM_TRY(check_images());
        LOOM_TRY(check_samplers());
        LOOM_TRY(check_textures());
        LOOM_TRY(check_materials());
        LOOM_TRY(check_meshes());
        LOOM_TRY(check_cameras());
        LOOM_TRY(check_skins());
        LOOM_TRY(check_nodes());
        LOOM_TRY(check_scenes());
        LOOM_TRY(check_animations());
        check_unused_data();
        return {};
    }

private:
    // ---- messages ------------------------------------------------------------------------

    Error parse_error(const JsonPointer& where, const std::string& what) const {
        return make_error(ErrorCode::Parse, located_message(input_.file_label, where.str(), what));
    }
    Error io_error(const JsonPointer& where, const std::string& what) const {
        return make_error(ErrorCode::Io, located_message(input_.file_label, where.str(), what));
    }
    void warn(const JsonPointer& where, const std::string& what) {
        output_.warnings.push_back(located_message(input_.file_label, where.str(), what));
    }

    // ---- typed access to JSON properties ---------------------------------------------------

    static const json* find(const json& object, std::string_view key) {
        const auto it = object.find(key);
        return it == object.end() ? nullptr : &*it;
    }

    Result<const json*> member(const json& object, std::string_view key, const JsonPointer& where, bool required,
                               json::value_t kind, const char* kind_name) const {
        const json* value = find(object, key);
        if (value == nullptr) {
            if (required) return parse_error(where, "required property '" + std::string(key) + "' is missing");
            return static_cast<const json*>(nullptr);
        }
        if (value->type() != kind) {
            return parse_error(where / key, std::string("must be ") + kind_name + ", got " + short_dump(*value));
        }
        return value;
    }
    Result<const json*> object_member(const json& object, std::string_view key, const JsonPointer& where, bool required) const {
        return member(object, key, where, required, json::value_t::object, "an object");
    }
    Result<const json*> array_member(const json& object, std::string_view key, const JsonPointer& where, bool required) const {
        return member(object, key, where, required, json::value_t::array, "an array");
    }

    // An array that, when present, has at least one element (glTF's minItems: 1).
    Result<const json*> non_empty_array_member(const json& object, std::string_view key, const JsonPointer& where,
                                               bool required) const {
        auto array = array_member(object, key, where, required);
        if (!array) return array.take_error();
        if (*array != nullptr && (*array)->empty()) return parse_error(where / key, "must not be empty (omit it instead)");
        return array;
    }

    Result<std::optional<std::string>> string_member(const json& object, std::string_view key, const JsonPointer& where,
                                                     bool required) const {
        auto value = member(object, key, where, required, json::value_t::string, "a string");
        if (!value) return value.take_error();
        if (*value == nullptr) return std::optional<std::string>{};
        return std::optional<std::string>{(*value)->get<std::string>()};
    }

    Result<std::optional<bool>> bool_member(const json& object, std::string_view key, const JsonPointer& where) const {
        auto value = member(object, key, where, false, json::value_t::boolean, "a boolean");
        if (!value) return value.take_error();
        if (*value == nullptr) return std::optional<bool>{};
        return std::optional<bool>{(*value)->get<bool>()};
    }

    // An integer JSON value (not 3.0, not 1e300) in [min, max].
    Result<uint64_t> integer_value(const json& value, const JsonPointer& where, uint64_t min, uint64_t max) const {
        uint64_t result = 0;
        if (value.is_number_unsigned()) {
            result = value.get<uint64_t>();
        } else if (value.is_number_integer()) {
            const int64_t signed_value = value.get<int64_t>();
            if (signed_value < 0) {
                return parse_error(where, "must be at least " + std::to_string(min) + ", got " + std::to_string(signed_value));
            }
            result = static_cast<uint64_t>(signed_value);
        } else if (const double number = value.is_number_float() ? value.get<double>() : 0.5;
                   std::floor(number) == number && std::abs(number) <= static_cast<double>(kMaxSafeInteger)) {
            // An integer written with a fraction ("1.0"): JSON has one number type, and the
            // validator reads it as the integer. tinygltf is handed the integer (ValidationOutput).
            if (number < 0) {
                return parse_error(where, "must be at least " + std::to_string(min) + ", got " + format_number(number));
            }
            result = static_cast<uint64_t>(number);
            output_.integers_written_as_floats.push_back(where.str());
        } else {
            return parse_error(where, "must be an integer, got " + short_dump(value));
        }
        if (result < min) return parse_error(where, "must be at least " + std::to_string(min) + ", got " + std::to_string(result));
        if (result > max) {
            return parse_error(where, "must be at most " + std::to_string(max) + ", got " + std::to_string(result));
        }
        return result;
    }

    Result<std::optional<uint64_t>> integer_member(const json& object, std::string_view key, const JsonPointer& where,
                                                   bool required, uint64_t min = 0, uint64_t max = kMaxSafeInteger) const {
        const json* value = find(object, key);
        if (value == nullptr) {
            if (required) return parse_error(where, "required property '" + std::string(key) + "' is missing");
            return std::optional<uint64_t>{};
        }
        auto result = integer_value(*value, where / key, min, max);
        if (!result) return result.take_error();
        return std::optional<uint64_t>{*result};
    }

    std::size_t count(Collection collection) const { return counts_[static_cast<std::size_t>(collection)]; }

    Result<uint64_t> reference_value(const json& value, const JsonPointer& where, Collection collection) const {
        auto index = integer_value(value, where, 0, kMaxInt);
        if (!index) return index.take_error();
        if (*index >= count(collection)) {
            const std::size_t available = count(collection);
            return parse_error(where, std::string(info(collection).singular) + " " + std::to_string(*index) +
                                          " does not exist (the file has " + std::to_string(available) + " " +
                                          info(collection).key + ")");
        }
        return *index;
    }

    // An index into a top-level collection; an error names the missing object.
    Result<std::optional<uint64_t>> reference_member(const json& object, std::string_view key, const JsonPointer& where,
                                                     Collection collection, bool required) const {
        const json* value = find(object, key);
        if (value == nullptr) {
            if (required) return parse_error(where, "required property '" + std::string(key) + "' is missing");
            return std::optional<uint64_t>{};
        }
        auto index = reference_value(*value, where / key, collection);
        if (!index) return index.take_error();
        return std::optional<uint64_t>{*index};
    }


    Result<double> number_value(const json& value, const JsonPointer& where, const Range& range) const {
        if (!value.is_number()) return parse_error(where, "must be a number, got " + short_dump(value));
        const double number = value.get<double>();
        // Every number the importer keeps ends up in a float.
        if (!(std::abs(number) <= static_cast<double>(std::numeric_limits<float>::max()))) {
            return parse_error(where, "must be a finite number within the range of a 32-bit float, got " + format_number(number));
        }
        const bool below = range.min_exclusive ? !(number > range.min) : !(number >= range.min);
        const bool above = range.max_exclusive ? !(number < range.max) : !(number <= range.max);
        if (below || above) {
            std::string bounds;
            if (std::isfinite(range.min)) bounds += (range.min_exclusive ? "> " : ">= ") + format_number(range.min);
            if (std::isfinite(range.max)) {
                if (!bounds.empty()) bounds += " and ";
                bounds += (range.max_exclusive ? "< " : "<= ") + format_number(range.max);
            }
            return parse_error(where, "must be " + bounds + ", got " + format_number(number));
        }
        return number;
    }

    Result<std::optional<double>> number_member(const json& object, std::string_view key, const JsonPointer& where,
                                                bool required, const Range& range = {}) const {
        const json* value = find(object, key);
        if (value == nullptr) {
            if (required) return parse_error(where, "required property '" + std::string(key) + "' is missing");
            return std::optional<double>{};
        }
        auto number = number_value(*value, where / key, range);
        if (!number) return number.take_error();
        return std::optional<double>{*number};
    }

    // An array of exactly `size` numbers in `range` (or of any size when size == 0).
    Status number_array_member(const json& object, std::string_view key, const JsonPointer& where, std::size_t size,
                               const Range& range = {}) const {
        auto array = array_member(object, key, where, false);
        if (!array) return array.take_error();
        if (*array == nullptr) return {};
        const json& values = **array;
        if (size != 0 && values.size() != size) {
            return parse_error(where / key, "must have " + std::to_string(size) + " elements, has " +
                                                std::to_string(values.size()));
        }
        for (std::size_t i = 0; i < values.size(); ++i) {
            auto number = number_value(values[i], where / key / i, range);
            if (!number) return number.take_error();
        }
        return {};
    }

    // Checks that every element of root[key] is an object and calls check(element, pointer, index).
    template <class Check>
    Status for_each(Collection collection, Check&& check) {
        const json* array = find(root_, info(collection).key);
        if (array == nullptr) return {};
        const JsonPointer base = JsonPointer{} / info(collection).key;
        for (std::size_t i = 0; i < array->size(); ++i) LOOM_TRY(check((*array)[i], base / i, i));
        return {};
    }

    // ---- the document ---------------------------------------------------------------------

    // The nesting depth of the whole document, walked without recursion.
    Status check_depth() const {
        std::vector<std::pair<const json*, std::size_t>> stack{{&root_, 1}};
        while (!stack.empty()) {
            const auto [value, depth] = stack.back();
            stack.pop_back();
            if (depth > kMaxJsonDepth) {
                return parse_error(JsonPointer{}, "JSON nesting is deeper than " + std::to_string(kMaxJsonDepth) + " levels");
            }
            if (value->is_structured()) {
                for (const json& child : *value) {
                    if (child.is_structured()) stack.emplace_back(&child, depth + 1);
                }
            }
        }
        return {};
    }

    // "2.0" → {2, 0}; nullopt for anything that is not "<digits>.<digits>".
    static std::optional<std::pair<uint64_t, uint64_t>> parse_version(const std::string& text) {
        const std::size_t dot = text.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == text.size() || dot > 9 || text.size() - dot - 1 > 9) {
            return std::nullopt;
        }
        uint64_t major = 0;
        uint64_t minor = 0;
        for (std::size_t i = 0; i < text.size(); ++i) {
            if (i == dot) continue;
            if (text[i] < '0' || text[i] > '9') return std::nullopt;
            uint64_t& part = i < dot ? major : minor;
            part = part * 10 + static_cast<uint64_t>(text[i] - '0');
        }
        return std::pair{major, minor};
    }

    Status check_asset() {
        const JsonPointer root;
        auto asset = object_member(root_, "asset", root, true);
        if (!asset) return asset.take_error();
        const JsonPointer where = root / "asset";
        auto version = string_member(**asset, "version", where, true);
        if (!version) return version.take_error();
        const auto parsed = parse_version(**version);
        if (!parsed) {
            return parse_error(where / "version", "'" + **version + "' is not a glTF version (expected \"2.0\")");
        }
        if (parsed->first != 2) {
            return parse_error(where / "version",
                               "glTF version " + **version + " is not supported (only glTF 2.x can be loaded)");
        }
        auto min_version = string_member(**asset, "minVersion", where, false);
        if (!min_version) return min_version.take_error();
        if (*min_version) {
            const auto min_parsed = parse_version(**min_version);
            if (!min_parsed) {
                return parse_error(where / "minVersion", "'" + **min_version + "' is not a glTF version");
            }
            if (*min_parsed > std::pair<uint64_t, uint64_t>{2, 0}) {
                return parse_error(where / "minVersion",
                                   "the file requires glTF " + **min_version + ", this importer supports glTF 2.0");
            }
        }
        return {};
    }

    Status check_extensions() {
        const JsonPointer root;
        std::set<std::string> used;
        for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
            auto array = array_member(root_, key, root, false);
            if (!array) return array.take_error();
            if (*array == nullptr) continue;
            for (std::size_t i = 0; i < (*array)->size(); ++i) {
                const json& name = (**array)[i];
                if (!name.is_string()) return parse_error(root / key / i, "must be a string, got " + short_dump(name));
                used.insert(name.get<std::string>());
                const bool supported_extension =
                    std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(),
                              name.get<std::string>()) != kSupportedExtensions.end();
                if (std::string_view(key) == "extensionsUsed" && !supported_extension) {
                    warn(root / key / i, "extension '" + name.get<std::string>() + "' is not supported; its data is ignored");
                }
                if (std::string_view(key) == "extensionsRequired" && !supported_extension) {
                    return parse_error(root / key / i, "required extension '" + name.get<std::string>() +
                                                           "' is not supported (supported: KHR_mesh_quantization, KHR_materials_emissive_strength, KHR_texture_transform)");
                }
            }
        }
        mesh_quantization_ = used.count("KHR_mesh_quantization") != 0;
        // EXT_texture_webp (not decoded): its WebP images are allowed, and textures draw with
        // their `source`, the PNG or JPEG fallback the extension requires when it is not required.
        webp_images_allowed_ = used.count("EXT_texture_webp") != 0;
        return check_extension_objects(root_, root, used);
    }

    // Every "extensions" object of the document (outside the application's "extras"): an object
    // of objects, each named in extensionsUsed (an undeclared one is a warning: the importer
    // reads only the extensions it supports, declared or not).
    Status check_extension_objects(const json& value, const JsonPointer& where, const std::set<std::string>& declared) {
        if (value.is_array()) {
            for (std::size_t i = 0; i < value.size(); ++i) {
                if (value[i].is_structured()) LOOM_TRY(check_extension_objects(value[i], where / i, declared));
            }
            return {};
        }
        for (const auto& [key, member] : value.items()) {
            if (key == "extras") continue;
            if (key == "extensions") {
                if (!member.is_object()) return parse_error(where / key, "must be an object, got " + short_dump(member));
                for (const auto& [name, extension] : member.items()) {
                    if (!extension.is_object()) {
                        return parse_error(where / key / name, "must be an object, got " + short_dump(extension));
                    }
                    if (declared.count(name) == 0) {
                        warn(where / key / name, "extension '" + name + "' is not declared in extensionsUsed");
                    }
                }
            }
            if (member.is_structured()) LOOM_TRY(check_extension_objects(member, where / key, declared));
        }
        return {};
    }

    // Every top-level collection that is present is an array of objects; remember the sizes
    // so that references can be checked in any order.
    Status check_collections() {
        const JsonPointer root;
        for (std::size_t c = 0; c < kCollectionCount; ++c) {
            const Collection collection = static_cast<Collection>(c);
            auto array = array_member(root_, info(collection).key, root, false);
            if (!array) return array.take_error();
            if (*array == nullptr) continue;
            if ((*array)->empty()) return parse_error(root / info(collection).key, "must not be empty (omit it instead)");
            for (std::size_t i = 0; i < (*array)->size(); ++i) {
                if (!(**array)[i].is_object()) {
                    return parse_error(root / info(collection).key / i, "must be an object, got " + short_dump((**array)[i]));
                }
            }
            counts_[c] = (*array)->size();
        }
        auto scene = reference_member(root_, "scene", root, Collection::Scenes, false);
        if (!scene) return scene.take_error();
        return {};
    }

    // ---- resources ---------------------------------------------------------------------------

    // The name tinygltf asks the file callbacks for when a buffer's uri is `name` (plain ASCII).
    std::string store_key(const std::string& name) const {
        std::string key = input_.tinygltf_base_dir;
        if (!key.empty() && key.back() != '/') key += '/';
        return key + name;
    }

    // tinygltf copies every image's bytes while it loads, before the converter can refuse an
    // image whose buffer has no data: the stand-in of such a buffer must cover the image's
    // view (zeros), or tinygltf would read past it. Images too large to stand in are refused here.
    Status cover_unavailable_image(uint64_t view_index, const JsonPointer& where) {
        const json& view = root_["bufferViews"][view_index];
        const auto buffer = view["buffer"].get<uint64_t>();
        if (output_.unavailable_buffers.count(buffer) == 0) return {};
        const uint64_t offset = view.contains("byteOffset") ? view["byteOffset"].get<uint64_t>() : 0;
        const uint64_t end = offset + view["byteLength"].get<uint64_t>();  // both validated: no overflow
        constexpr uint64_t kMaxStandIn = uint64_t{64} << 20;
        if (end > kMaxStandIn) {
            return parse_error(where, "reads buffer view " + std::to_string(view_index) + " of buffer " + std::to_string(buffer) +
                                          ", whose data is unavailable");
        }
        auto& rewrite = output_.buffer_rewrites[buffer];
        if (end <= rewrite.second) return {};
        rewrite.second = end;
        output_.files[store_key(rewrite.first)].resize(end, 0);
        return {};
    }

    // A buffer without data: tinygltf gets a one-byte stand-in, the converter the index.
    void mark_unavailable(uint64_t index) {
        const std::string name = "__loom_unavailable_buffer_" + std::to_string(index) + ".bin";
        output_.files.emplace(store_key(name), std::vector<unsigned char>(1, 0));
        output_.buffer_rewrites[index] = {name, 1};
        output_.unavailable_buffers.insert(index);
    }

    // Reads the file a relative URI names; stores it for tinygltf under the name tinygltf will
    // ask for, cut to `keep_bytes` when given. Returns the file's full size.
    Result<uint64_t> load_file(const std::string& uri, const JsonPointer& where, std::optional<uint64_t> keep_bytes) {
        if (uri.empty()) return parse_error(where, "URI is empty");
        if (has_uri_scheme(uri)) {
            return parse_error(where, "URI '" + uri + "' has a scheme; only relative file paths and data URIs are supported");
        }
        auto decoded = percent_decode(uri);
        if (!decoded) return parse_error(where, "invalid URI '" + uri + "': " + decoded.error().message);
        if (decoded->empty() || decoded->front() == '/' || decoded->find('\0') != std::string::npos) {
            return parse_error(where, "URI '" + uri + "' is not a relative file path");
        }
        const std::filesystem::path path = input_.base_dir / std::filesystem::path(*decoded);
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) {
            return io_error(where, "file '" + *decoded + "' not found (looked for " + path.string() + ")");
        }
        std::ifstream stream(path, std::ios::binary);
        std::vector<unsigned char> bytes;
        if (stream) {
            stream.seekg(0, std::ios::end);
            const std::streamoff size = stream.tellg();
            stream.seekg(0, std::ios::beg);
            if (size >= 0) {
                bytes.resize(static_cast<std::size_t>(size));
                stream.read(reinterpret_cast<char*>(bytes.data()), size);
            }
        }
        if (!stream) return io_error(where, "cannot read file '" + path.string() + "'");
        const uint64_t full_size = bytes.size();
        if (keep_bytes && *keep_bytes < bytes.size()) bytes.resize(static_cast<std::size_t>(*keep_bytes));
        std::string key = input_.tinygltf_base_dir;
        if (!key.empty() && key.back() != '/') key += '/';
        key += tinygltf_url_decode(uri);
        output_.files.emplace(std::move(key), std::move(bytes));
        return full_size;
    }

    // Decodes a data URI strictly.
    Result<DataUri> decoded_data_uri(const std::string& uri, const JsonPointer& where) const {
        auto data = decode_data_uri(uri);
        if (!data) return parse_error(where, data.error().message);
        return data;
    }
    // That tinygltf will recognise a base64 data URI as one (the others are served to it as files).
    Status check_tinygltf_decodes(const std::string& uri, const DataUri& data, const JsonPointer& where) const {
        if (!data.base64) return {};
        if (!tinygltf_decodes_media_type(data.media_type) ||
            uri.compare(0, 5 + data.media_type.size(), "data:" + data.media_type) != 0) {
            return parse_error(where, "data URI media type '" + data.media_type + "' is not supported (supported: " +
                                          std::string(tinygltf_media_types()) + ")");
        }
        return {};
    }

    // An embedded image's media type is image/png or image/jpeg, and its bytes are what the
    // mimeType (or the URI) declares. Images are decoded by their content, so a mismatch is a
    // warning.
    void check_image_media_type(const DataUri& image, const std::optional<std::string>& mime, const JsonPointer& where) {
        const std::string declared = mime ? *mime : image.media_type;
        if (declared != "image/png" && declared != "image/jpeg") {
            warn(where, "declares media type '" + declared + "'; glTF images are image/png or image/jpeg (decoded by their content)");
            return;
        }
        const auto& d = image.data;
        const bool png = d.size() >= 4 && d[0] == 0x89 && d[1] == 'P' && d[2] == 'N' && d[3] == 'G';
        const bool jpeg = d.size() >= 3 && d[0] == 0xFF && d[1] == 0xD8 && d[2] == 0xFF;
        if ((png && declared != "image/png") || (jpeg && declared != "image/jpeg")) {
            warn(where, "holds a " + std::string(png ? "PNG" : "JPEG") + " image but declares '" + declared +
                            "' (decoded by its content)");
        }
    }

    Status check_buffers() {
        return for_each(Collection::Buffers, [&](const json& buffer, const JsonPointer& where, std::size_t index) -> Status {
            auto byte_length = integer_member(buffer, "byteLength", where, true, 1);
            if (!byte_length) return byte_length.take_error();
            const uint64_t declared = **byte_length;
            auto uri = string_member(buffer, "uri", where, false);
            if (!uri) return uri.take_error();
            if (!*uri && input_.is_glb && index == 0) {
                if (!input_.glb_bin) return parse_error(where, "buffer has no uri and the GLB file has no BIN chunk");
                if (input_.glb_bin->size() < declared) {
                    return parse_error(where / "byteLength", "byteLength " + std::to_string(declared) +
                                                                 " exceeds the GLB BIN chunk's " +
                                                                 std::to_string(input_.glb_bin->size()) + " bytes");
                }
                // tinygltf reads the document as JSON text: the BIN chunk becomes a file.
                const std::string name = "__loom_glb_bin_chunk.bin";
                output_.files.emplace(store_key(name), std::vector<unsigned char>(input_.glb_bin->begin(),
                                                                                  input_.glb_bin->begin() + static_cast<std::ptrdiff_t>(declared)));
                output_.buffer_rewrites[index] = {name, declared};
            } else if (!*uri || (!is_data_uri(**uri) && has_uri_scheme(**uri))) {
                // Legal (a placeholder, or data elsewhere) as long as nothing reads it.
                warn(!*uri ? where : where / "uri",
                     !*uri ? "buffer has no uri (and is not a GLB's BIN chunk): its data is unavailable"
                           : "URI '" + **uri + "' has a scheme; only relative file paths and data URIs are fetched, so "
                             "the buffer's data is unavailable");
                mark_unavailable(index);
            } else if (is_data_uri(**uri)) {
                auto data = decoded_data_uri(**uri, where / "uri");
                if (!data) return data.take_error();
                LOOM_TRY(check_tinygltf_decodes(**uri, *data, where / "uri"));
                if (data->data.size() != declared) {
                    return parse_error(where / "uri", "data URI holds " + std::to_string(data->data.size()) +
                                                          " bytes, but the buffer's byteLength is " + std::to_string(declared));
                }
                if (!data->base64) {
                    const std::string name = "__loom_data_uri_buffer_" + std::to_string(index) + ".bin";
                    output_.files[store_key(name)] = std::move(data->data);
                    output_.buffer_rewrites[index] = {name, declared};
                }
            } else {
                auto size = load_file(**uri, where / "uri", declared);
                if (!size) return size.take_error();
                if (*size < declared) {
                    return parse_error(where / "byteLength", "byteLength " + std::to_string(declared) + " exceeds the " +
                                                                 std::to_string(*size) + " bytes of file '" + **uri + "'");
                }
            }
            buffer_lengths_.push_back(declared);
            return {};
        });
    }

    Status check_buffer_views() {
        return for_each(Collection::BufferViews, [&](const json& view, const JsonPointer& where, std::size_t) -> Status {
            ViewInfo result;
            auto buffer = reference_member(view, "buffer", where, Collection::Buffers, true);
            if (!buffer) return buffer.take_error();
            result.buffer = **buffer;
            auto offset = integer_member(view, "byteOffset", where, false);
            if (!offset) return offset.take_error();
            result.byte_offset = offset->value_or(0);
            auto length = integer_member(view, "byteLength", where, true, 1);
            if (!length) return length.take_error();
            result.byte_length = **length;
            auto stride = integer_member(view, "byteStride", where, false, 4, 252);
            if (!stride) return stride.take_error();
            if (*stride && **stride % 4 != 0) {
                return parse_error(where / "byteStride", "must be a multiple of 4, got " + std::to_string(**stride));
            }
            result.byte_stride = *stride;
            auto target = integer_member(view, "target", where, false, 0, kMaxInt);
            if (!target) return target.take_error();
            if (*target && **target != kArrayBuffer && **target != kElementArrayBuffer) {
                return parse_error(where / "target", std::to_string(**target) + " is not 34962 (ARRAY_BUFFER) or 34963 "
                                                                                "(ELEMENT_ARRAY_BUFFER)");
            }
            result.target = *target;
            if (*stride && *target && **target == kElementArrayBuffer) {
                return parse_error(where / "byteStride", "an index buffer view (target 34963) must not have a byteStride");
            }
            if (*stride && **stride > result.byte_length) {
                return parse_error(where / "byteStride", "byteStride " + std::to_string(**stride) +
                                                             " exceeds the view's byteLength " +
                                                             std::to_string(result.byte_length));
            }
            const uint64_t buffer_length = buffer_lengths_[result.buffer];
            if (!range_fits(result.byte_offset, result.byte_length, buffer_length)) {
                return parse_error(where, "byteOffset " + std::to_string(result.byte_offset) + " + byteLength " +
                                              std::to_string(result.byte_length) + " exceeds the byteLength " +
                                              std::to_string(buffer_length) + " of buffer " + std::to_string(result.buffer));
            }
            views_.push_back(result);
            return {};
        });
    }

    // A range of `size` bytes at `offset` inside buffer view `view`, for messages of the form
    // "<what> needs bytes [a, b) but buffer view N has byteLength L".
    Status check_in_view(uint64_t view, uint64_t offset, std::optional<uint64_t> size, const JsonPointer& where,
                         const std::string& what) const {
        const uint64_t length = views_[view].byte_length;
        if (!size) return parse_error(where, what + " has a size that overflows 64 bits");
        if (!range_fits(offset, *size, length)) {
            const auto end = checked_add(offset, *size);
            return parse_error(where, what + " needs bytes [" + std::to_string(offset) + ", " +
                                          (end ? std::to_string(*end) : std::string("overflow")) +
                                          ") of buffer view " + std::to_string(view) + ", which has byteLength " +
                                          std::to_string(length));
        }
        return {};
    }

    Status check_accessors() {
        const uint64_t max_elements = input_.options->max_accessor_elements;
        return for_each(Collection::Accessors, [&](const json& accessor, const JsonPointer& where, std::size_t) -> Status {
            AccessorInfo result;
            auto component = integer_member(accessor, "componentType", where, true, 0, kMaxInt);
            if (!component) return component.take_error();
            result.component_type = static_cast<int>(**component);
            if (component_size(result.component_type) == 0) {
                return parse_error(where / "componentType", std::to_string(**component) + " is not a valid component type");
            }
            auto type = string_member(accessor, "type", where, true);
            if (!type) return type.take_error();
            result.type = element_type(**type);
            if (result.type.components == 0) return parse_error(where / "type", "'" + **type + "' is not a valid accessor type");
            auto normalized = bool_member(accessor, "normalized", where);
            if (!normalized) return normalized.take_error();
            result.normalized = normalized->value_or(false);
            if (result.normalized && (result.component_type == component_type::kFloat ||
                                      result.component_type == component_type::kUnsignedInt)) {
                return parse_error(where / "normalized", "only 8- and 16-bit integer components can be normalized");
            }
            auto count = integer_member(accessor, "count", where, true, 1);
            if (!count) return count.take_error();
            result.count = **count;
            if (result.count > max_elements) {
                return parse_error(where / "count", "count " + std::to_string(result.count) + " exceeds the importer's limit " +
                                                        std::to_string(max_elements) +
                                                        " (LoadOptions::max_accessor_elements)");
            }
            for (const char* key : {"min", "max"}) {
                LOOM_TRY(number_array_member(accessor, key, where, result.type.components));
            }
            result.has_bounds = find(accessor, "min") != nullptr && find(accessor, "max") != nullptr;
            auto offset = integer_member(accessor, "byteOffset", where, false);
            if (!offset) return offset.take_error();
            const uint64_t byte_offset = offset->value_or(0);
            result.byte_offset = byte_offset;
            auto view = reference_member(accessor, "bufferView", where, Collection::BufferViews, false);
            if (!view) return view.take_error();
            result.buffer_view = *view;
            const uint32_t size = component_size(result.component_type);
            const uint32_t element = element_size(result.type, result.component_type);
            if (*view) {
                const ViewInfo& view_info = views_[**view];
                if ((view_info.byte_offset + byte_offset) % size != 0) {
                    return parse_error(where / "byteOffset", "the accessor's offset in its buffer (" +
                                                                 std::to_string(view_info.byte_offset + byte_offset) +
                                                                 ") is not a multiple of its component size " +
                                                                 std::to_string(size));
                }
                // Matrix columns start at multiples of 4 bytes, so the matrix must too.
                if (result.type.columns != 0 && size < 4 && byte_offset % 4 != 0) {
                    return parse_error(where / "byteOffset", "a matrix accessor of " + std::to_string(size) +
                                                                 "-byte components must start at a multiple of 4 bytes, got " +
                                                                 std::to_string(byte_offset));
                }
                const uint64_t stride = view_info.byte_stride.value_or(element);
                if (stride < element) {
                    return parse_error(where, "element size " + std::to_string(element) + " exceeds the byteStride " +
                                                  std::to_string(stride) + " of buffer view " + std::to_string(**view));
                }
                // The last element needs no padding after its last column.
                const auto span = strided_span(result.count, stride, last_element_size(result.type, result.component_type));
                LOOM_TRY(check_in_view(**view, byte_offset, span, where,
                                       "accessor (" + std::to_string(result.count) + " elements of " +
                                           std::to_string(element) + " bytes, stride " + std::to_string(stride) + ")"));
            } else if (offset->has_value()) {
                return parse_error(where / "byteOffset", "byteOffset needs a bufferView");
            }
            LOOM_TRY(check_sparse(accessor, where, result, element));
            accessors_.push_back(result);
            return {};
        });
    }

    Status check_sparse(const json& accessor, const JsonPointer& accessor_where, const AccessorInfo& info_,
                        uint32_t element) const {
        auto sparse = object_member(accessor, "sparse", accessor_where, false);
        if (!sparse) return sparse.take_error();
        if (*sparse == nullptr) return {};
        const JsonPointer where = accessor_where / "sparse";
        auto count = integer_member(**sparse, "count", where, true, 1, std::min<uint64_t>(info_.count, kMaxInt));
        if (!count) return count.take_error();

        auto indices = object_member(**sparse, "indices", where, true);
        if (!indices) return indices.take_error();
        const JsonPointer indices_where = where / "indices";
        auto indices_view = reference_member(**indices, "bufferView", indices_where, Collection::BufferViews, true);
        if (!indices_view) return indices_view.take_error();
        auto indices_offset = integer_member(**indices, "byteOffset", indices_where, false, 0, kMaxInt);
        if (!indices_offset) return indices_offset.take_error();
        auto index_component = integer_member(**indices, "componentType", indices_where, true, 0, kMaxInt);
        if (!index_component) return index_component.take_error();
        const int index_type = static_cast<int>(**index_component);
        if (index_type != component_type::kUnsignedByte && index_type != component_type::kUnsignedShort &&
            index_type != component_type::kUnsignedInt) {
            return parse_error(indices_where / "componentType",
                               std::to_string(index_type) + " is not an index component type (5121, 5123 or 5125)");
        }
        if (views_[**indices_view].byte_stride) {
            return parse_error(indices_where / "bufferView", "buffer view " + std::to_string(**indices_view) +
                                                                 " of sparse indices must not have a byteStride");
        }
        const uint64_t index_offset = indices_offset->value_or(0);
        if ((views_[**indices_view].byte_offset + index_offset) % component_size(index_type) != 0) {
            return parse_error(indices_where / "byteOffset", "sparse indices are not aligned to their component size");
        }
        LOOM_TRY(check_in_view(**indices_view, index_offset, checked_mul(**count, component_size(index_type)), indices_where,
                               "sparse indices"));

        auto values = object_member(**sparse, "values", where, true);
        if (!values) return values.take_error();
        const JsonPointer values_where = where / "values";
        auto values_view = reference_member(**values, "bufferView", values_where, Collection::BufferViews, true);
        if (!values_view) return values_view.take_error();
        auto values_offset = integer_member(**values, "byteOffset", values_where, false, 0, kMaxInt);
        if (!values_offset) return values_offset.take_error();
        if (views_[**values_view].byte_stride) {
            return parse_error(values_where / "bufferView", "buffer view " + std::to_string(**values_view) +
                                                                " of sparse values must not have a byteStride");
        }
        const uint64_t value_offset = values_offset->value_or(0);
        if ((views_[**values_view].byte_offset + value_offset) % component_size(info_.component_type) != 0) {
            return parse_error(values_where / "byteOffset", "sparse values are not aligned to their component size");
        }
        return check_in_view(**values_view, value_offset, checked_mul(**count, element), values_where, "sparse values");
    }

    Status check_images() {
        return for_each(Collection::Images, [&](const json& image, const JsonPointer& where, std::size_t index) -> Status {
            auto uri = string_member(image, "uri", where, false);
            if (!uri) return uri.take_error();
            auto view = reference_member(image, "bufferView", where, Collection::BufferViews, false);
            if (!view) return view.take_error();
            auto mime = string_member(image, "mimeType", where, false);
            if (!mime) return mime.take_error();
            if (uri->has_value() == view->has_value()) {
                return parse_error(where, "an image needs exactly one of 'uri' and 'bufferView'");
            }
            if (*view) {
                if (!*mime) return parse_error(where, "required property 'mimeType' is missing (the image uses a bufferView)");
                const bool webp = webp_images_allowed_ && **mime == "image/webp";
                if (**mime != "image/png" && **mime != "image/jpeg" && !webp) {
                    return parse_error(where / "mimeType", "'" + **mime + "' is not a glTF image type (image/png, image/jpeg)");
                }
                if (**view < views_.size() && views_[**view].byte_stride) {
                    return parse_error(where / "bufferView", "buffer view " + std::to_string(**view) +
                                                                 " holds image data and must not define byteStride");
                }
                return cover_unavailable_image(**view, where);
            }
            if (is_data_uri(**uri)) {
                auto data = decoded_data_uri(**uri, where / "uri");
                if (!data) return data.take_error();
                // A WebP data URI (EXT_texture_webp) is not one tinygltf takes either: served as a file.
                const bool webp = webp_images_allowed_ && data->media_type == "image/webp";
                if (!webp) {
                    LOOM_TRY(check_tinygltf_decodes(**uri, *data, where / "uri"));
                    check_image_media_type(*data, *mime, where / "uri");
                }
                if (webp || !data->base64) {
                    const std::string name = "__loom_data_uri_image_" + std::to_string(index);
                    output_.files[store_key(name)] = std::move(data->data);
                    output_.image_rewrites[index] = name;
                }
                return {};
            }
            auto size = load_file(**uri, where / "uri", std::nullopt);
            if (!size) return size.take_error();
            if (*size == 0) return parse_error(where / "uri", "image file '" + **uri + "' is empty");
            return {};
        });
    }

    Status check_samplers() {
        return for_each(Collection::Samplers, [&](const json& sampler, const JsonPointer& where, std::size_t) -> Status {
            struct Allowed {
                const char* key;
                std::vector<uint64_t> values;
            };
            const Allowed checks[] = {
                {"magFilter", {filter::kNearest, filter::kLinear}},
                {"minFilter",
                 {filter::kNearest, filter::kLinear, filter::kNearestMipmapNearest, filter::kLinearMipmapNearest,
                  filter::kNearestMipmapLinear, filter::kLinearMipmapLinear}},
                {"wrapS", {wrap::kClampToEdge, wrap::kMirroredRepeat, wrap::kRepeat}},
                {"wrapT", {wrap::kClampToEdge, wrap::kMirroredRepeat, wrap::kRepeat}},
            };
            for (const Allowed& check : checks) {
                auto value = integer_member(sampler, check.key, where, false, 0, kMaxInt);
                if (!value) return value.take_error();
                if (*value && std::find(check.values.begin(), check.values.end(), **value) == check.values.end()) {
                    return parse_error(where / check.key, std::to_string(**value) + " is not a valid " + check.key);
                }
            }
            return {};
        });
    }

    Status check_textures() {
        return for_each(Collection::Textures, [&](const json& texture, const JsonPointer& where, std::size_t) -> Status {
            auto sampler = reference_member(texture, "sampler", where, Collection::Samplers, false);
            if (!sampler) return sampler.take_error();
            auto source = reference_member(texture, "source", where, Collection::Images, false);
            if (!source) return source.take_error();
            if (const json* extensions = find(texture, "extensions"); extensions != nullptr && extensions->is_object()) {
                if (const json* webp = find(*extensions, "EXT_texture_webp"); webp != nullptr && webp->is_object()) {
                    auto webp_source = reference_member(*webp, "source", where / "extensions" / "EXT_texture_webp",
                                                        Collection::Images, true);
                    if (!webp_source) return webp_source.take_error();
                }
            }
            return {};
        });
    }

    // A textureInfo (or normal/occlusion textureInfo) object.
    // Also records in material_uv_sets_[material] the UV sets the reference samples.
    Status check_texture_info(const json& parent, const char* key, const JsonPointer& parent_where, std::size_t material) {
        auto texture_info = object_member(parent, key, parent_where, false);
        if (!texture_info) return texture_info.take_error();
        if (*texture_info == nullptr) return {};
        const JsonPointer where = parent_where / key;
        auto index = reference_member(**texture_info, "index", where, Collection::Textures, true);
        if (!index) return index.take_error();
        auto tex_coord = integer_member(**texture_info, "texCoord", where, false, 0, kMaxInt);
        if (!tex_coord) return tex_coord.take_error();
        if (std::string_view(key) == "normalTexture") {
            auto scale = number_member(**texture_info, "scale", where, false);
            if (!scale) return scale.take_error();
        }
        if (std::string_view(key) == "occlusionTexture") {
            auto strength = number_member(**texture_info, "strength", where, false, Range{0.0, 1.0});
            if (!strength) return strength.take_error();
        }
        // KHR_texture_transform: offset and scale of two numbers, a rotation, an optional UV set.
        auto extensions = object_member(**texture_info, "extensions", where, false);
        if (!extensions) return extensions.take_error();
        if (*extensions) {
            auto transform = object_member(**extensions, "KHR_texture_transform", where / "extensions", false);
            if (!transform) return transform.take_error();
            if (*transform) {
                const JsonPointer transform_where = where / "extensions" / "KHR_texture_transform";
                LOOM_TRY(number_array_member(**transform, "offset", transform_where, 2));
                LOOM_TRY(number_array_member(**transform, "scale", transform_where, 2));
                auto rotation = number_member(**transform, "rotation", transform_where, false);
                if (!rotation) return rotation.take_error();
                auto coordinates = integer_member(**transform, "texCoord", transform_where, false, 0, kMaxInt);
                if (!coordinates) return coordinates.take_error();
                if (*coordinates) *tex_coord = *coordinates;  // replaces the reference's own
            }
        }
        material_uv_sets_[material] = std::max(material_uv_sets_[material], tex_coord->value_or(0) + 1);
        return {};
    }

    Status check_materials() {
        material_uv_sets_.assign(count(Collection::Materials), 0);
        return for_each(Collection::Materials, [&](const json& material, const JsonPointer& where, std::size_t index) -> Status {
            const Range unit{0.0, 1.0};
            auto pbr = object_member(material, "pbrMetallicRoughness", where, false);
            if (!pbr) return pbr.take_error();
            if (*pbr) {
                const JsonPointer pbr_where = where / "pbrMetallicRoughness";
                LOOM_TRY(number_array_member(**pbr, "baseColorFactor", pbr_where, 4, unit));
                auto metallic = number_member(**pbr, "metallicFactor", pbr_where, false, unit);
                if (!metallic) return metallic.take_error();
                auto roughness = number_member(**pbr, "roughnessFactor", pbr_where, false, unit);
                if (!roughness) return roughness.take_error();
                LOOM_TRY(check_texture_info(**pbr, "baseColorTexture", pbr_where, index));
                LOOM_TRY(check_texture_info(**pbr, "metallicRoughnessTexture", pbr_where, index));
            }
            LOOM_TRY(check_texture_info(material, "normalTexture", where, index));
            LOOM_TRY(check_texture_info(material, "occlusionTexture", where, index));
            LOOM_TRY(check_texture_info(material, "emissiveTexture", where, index));
            LOOM_TRY(number_array_member(material, "emissiveFactor", where, 3, unit));
            // KHR_materials_emissive_strength: a non-negative multiplier of emissiveFactor (HDR emission).
            auto extensions = object_member(material, "extensions", where, false);
            if (!extensions) return extensions.take_error();
            if (*extensions) {
                const JsonPointer extensions_where = where / "extensions";
                auto strength = object_member(**extensions, "KHR_materials_emissive_strength", extensions_where, false);
                if (!strength) return strength.take_error();
                if (*strength) {
                    auto value = number_member(**strength, "emissiveStrength", extensions_where / "KHR_materials_emissive_strength",
                                               false, Range{0.0});
                    if (!value) return value.take_error();
                }
            }
            auto alpha_mode = string_member(material, "alphaMode", where, false);
            if (!alpha_mode) return alpha_mode.take_error();
            if (*alpha_mode && **alpha_mode != "OPAQUE" && **alpha_mode != "MASK" && **alpha_mode != "BLEND") {
                return parse_error(where / "alphaMode", "'" + **alpha_mode + "' is not OPAQUE, MASK or BLEND");
            }
            auto cutoff = number_member(material, "alphaCutoff", where, false, Range{0.0});
            if (!cutoff) return cutoff.take_error();
            auto double_sided = bool_member(material, "doubleSided", where);
            if (!double_sided) return double_sided.take_error();
            return {};
        });
    }

    // Whether `semantic` may use this accessor format (core glTF, plus KHR_mesh_quantization
    // when the file uses it). Unknown semantics accept anything.
    bool attribute_format_allowed(std::string_view semantic, const AccessorInfo& accessor) const {
        using namespace component_type;
        const int c = accessor.component_type;
        const bool n = accessor.normalized;
        const uint32_t k = accessor.type.columns == 0 ? accessor.type.components : 0;
        const bool q = mesh_quantization_;
        const bool is_float = c == kFloat;
        const bool unorm = (c == kUnsignedByte || c == kUnsignedShort) && n;
        const bool snorm = (c == kByte || c == kShort) && n;
        const bool small_int = c == kByte || c == kUnsignedByte || c == kShort || c == kUnsignedShort;
        if (semantic == "POSITION") return k == 3 && (is_float || (q && small_int));
        if (semantic == "NORMAL") return k == 3 && (is_float || (q && snorm));
        if (semantic == "TANGENT") return k == 4 && (is_float || (q && snorm));
        if (semantic.substr(0, 9) == "TEXCOORD_") return k == 2 && (is_float || unorm || (q && small_int));
        if (semantic.substr(0, 6) == "COLOR_") return (k == 3 || k == 4) && (is_float || unorm);
        if (semantic.substr(0, 7) == "JOINTS_") return k == 4 && (c == kUnsignedByte || c == kUnsignedShort) && !n;
        if (semantic.substr(0, 8) == "WEIGHTS_") return k == 4 && (is_float || unorm);
        return true;
    }

    static std::string describe(const AccessorInfo& accessor) {
        return std::string(accessor.type.name) + " " + std::string(component_type_name(accessor.component_type)) +
               (accessor.normalized ? " normalized" : "");
    }

    // The UV sets a primitive's material samples (check_texture_info recorded them) exist on the
    // primitive: a texture without its set reads (0, 0), a warning, as the importer draws it so.
    void check_material_uv_sets(const json& primitive, const JsonPointer& where) {
        const std::optional<uint64_t> material = index_in(primitive, "material");
        if (!material) return;
        uint64_t sets = 0;
        const json& attributes = primitive.at("attributes");
        while (attributes.contains("TEXCOORD_" + std::to_string(sets))) ++sets;
        if (const uint64_t needed = material_uv_sets_[*material]; needed > sets) {
            warn(where / "material", "material " + std::to_string(*material) + " samples TEXCOORD_" +
                                         std::to_string(needed - 1) + ", which the primitive does not have (it reads (0, 0))");
        }
    }

    Status check_primitive(const json& primitive, const JsonPointer& where) {
        auto attributes = object_member(primitive, "attributes", where, true);
        if (!attributes) return attributes.take_error();
        if ((*attributes)->empty()) return parse_error(where / "attributes", "must not be empty");
        // Counts are compared with POSITION's (else with the first attribute's).
        std::optional<std::pair<std::string, uint64_t>> first_count;
        if (const json* position = find(**attributes, "POSITION")) {
            auto accessor = reference_value(*position, where / "attributes" / "POSITION", Collection::Accessors);
            if (!accessor) return accessor.take_error();
            first_count = {"POSITION", accessors_[*accessor].count};
        }
        for (const auto& [semantic, value] : (*attributes)->items()) {
            const JsonPointer attribute_where = where / "attributes" / semantic;
            auto accessor = reference_value(value, attribute_where, Collection::Accessors);
            if (!accessor) return accessor.take_error();
            const AccessorInfo& accessor_info = accessors_[*accessor];
            if (!is_valid_semantic(semantic, false)) {
                return parse_error(attribute_where, "'" + semantic + "' is not a glTF attribute semantic (application-"
                                                    "specific attributes must start with an underscore)");
            }
            if (accessor_info.component_type == component_type::kUnsignedInt) {
                return parse_error(attribute_where, "accessor " + std::to_string(*accessor) +
                                                        " is UNSIGNED_INT, which no vertex attribute may use");
            }
            if (semantic == "POSITION" && !accessor_info.has_bounds) {
                return parse_error(attribute_where, "POSITION accessor " + std::to_string(*accessor) +
                                                        " must have 'min' and 'max'");
            }
            LOOM_TRY(check_vertex_view(*accessor, attribute_where));
            if (!attribute_format_allowed(semantic, accessor_info)) {
                return parse_error(attribute_where, "accessor " + std::to_string(*accessor) + " is " +
                                                        describe(accessor_info) + ", which " + semantic + " cannot use" +
                                                        (mesh_quantization_ ? "" : " (without KHR_mesh_quantization)"));
            }
            if (!first_count) {
                first_count = {semantic, accessor_info.count};
            } else if (first_count->second != accessor_info.count) {
                return parse_error(attribute_where, "accessor " + std::to_string(*accessor) + " has " +
                                                        std::to_string(accessor_info.count) + " elements, but " +
                                                        first_count->first + " has " + std::to_string(first_count->second) +
                                                        " (all attributes of a primitive need the same count)");
            }
        }
        auto indices = reference_member(primitive, "indices", where, Collection::Accessors, false);
        if (!indices) return indices.take_error();
        if (*indices) {
            const AccessorInfo& accessor = accessors_[**indices];
            const int c = accessor.component_type;
            if (accessor.type.components != 1 || accessor.type.columns != 0 || accessor.normalized ||
                (c != component_type::kUnsignedByte && c != component_type::kUnsignedShort &&
                 c != component_type::kUnsignedInt)) {
                return parse_error(where / "indices", "accessor " + std::to_string(**indices) + " is " + describe(accessor) +
                                                          "; indices must be SCALAR UNSIGNED_BYTE, UNSIGNED_SHORT or "
                                                          "UNSIGNED_INT");
            }
            if (accessor.buffer_view) LOOM_TRY(use_view(*accessor.buffer_view, kElementArrayBuffer, where / "indices"));
            if (!accessor.buffer_view) {
                // All zeros by the specification; tinygltf needs a view, so one is made for it.
                const std::string name = "__loom_zero_indices_" + std::to_string(**indices) + ".bin";
                const uint64_t bytes = accessor.count * component_size(c);
                output_.files.emplace(store_key(name), std::vector<unsigned char>(static_cast<std::size_t>(bytes), 0));
                output_.zero_index_accessors[**indices] = {name, bytes};
            }
            if (accessor.buffer_view && views_[*accessor.buffer_view].byte_stride) {
                return parse_error(where / "indices", "accessor " + std::to_string(**indices) + " uses buffer view " +
                                                          std::to_string(*accessor.buffer_view) +
                                                          ", which has a byteStride (indices must be tightly packed)");
            }
        }
        auto material = reference_member(primitive, "material", where, Collection::Materials, false);
        if (!material) return material.take_error();
        auto mode = integer_member(primitive, "mode", where, false, 0, 6);
        if (!mode) return mode.take_error();
        auto targets = non_empty_array_member(primitive, "targets", where, false);
        if (!targets) return targets.take_error();
        if (*targets) {
            for (std::size_t t = 0; t < (*targets)->size(); ++t) {
                const json& target = (**targets)[t];
                if (!target.is_object()) return parse_error(where / "targets" / t, "must be an object");
                for (const auto& [semantic, value] : target.items()) {
                    const JsonPointer target_where = where / "targets" / t / semantic;
                    auto accessor = reference_value(value, target_where, Collection::Accessors);
                    if (!accessor) return accessor.take_error();
                    if (!is_valid_semantic(semantic, true)) {
                        return parse_error(target_where, "'" + semantic + "' is not a morph target attribute semantic");
                    }
                    const json* base = find(**attributes, semantic);
                    if (base == nullptr) {
                        return parse_error(target_where, "the primitive has no " + semantic + " attribute for this target to morph");
                    }
                    const AccessorInfo& target_accessor = accessors_[*accessor];
                    if (semantic == "POSITION" && !target_accessor.has_bounds) {
                        return parse_error(target_where, "POSITION accessor " + std::to_string(*accessor) +
                                                             " must have 'min' and 'max'");
                    }
                    if (first_count && target_accessor.count != first_count->second) {
                        return parse_error(target_where, "accessor " + std::to_string(*accessor) + " has " +
                                                             std::to_string(target_accessor.count) + " elements, the primitive's vertices " +
                                                             std::to_string(first_count->second));
                    }
                    LOOM_TRY(check_vertex_view(*accessor, target_where));
                }
            }
            if (!(*targets)->empty()) warn(where / "targets", "morph targets are not imported (the base shape is used)");
        }
        return {};
    }

    // A buffer view serves vertices or indices, never both (its target, when given, says which).
    Status use_view(uint64_t view, uint64_t usage, const JsonPointer& where) {
        const auto [it, inserted] = view_usage_.emplace(view, views_[view].target.value_or(usage));
        if (it->second != usage) {
            const auto name = [](uint64_t u) { return u == kArrayBuffer ? std::string("vertex") : std::string("index"); };
            return parse_error(where, "buffer view " + std::to_string(view) + " holds " + name(it->second) +
                                          " data and cannot also be used for " + name(usage) + " data");
        }
        return {};
    }

    // Vertex attribute data: 4-byte aligned, and a view several attributes share needs a stride.
    Status check_vertex_view(uint64_t accessor_index, const JsonPointer& where) {
        const AccessorInfo& accessor = accessors_[accessor_index];
        if (!accessor.buffer_view) return {};
        const uint64_t view = *accessor.buffer_view;
        LOOM_TRY(use_view(view, kArrayBuffer, where));
        if ((views_[view].byte_offset + accessor.byte_offset) % 4 != 0) {
            return parse_error(where, "accessor " + std::to_string(accessor_index) + " starts at byte " +
                                          std::to_string(views_[view].byte_offset + accessor.byte_offset) +
                                          " of its buffer; vertex attribute data must be aligned to 4 bytes");
        }
        std::set<uint64_t>& users = vertex_view_accessors_[view];
        users.insert(accessor_index);
        if (users.size() > 1 && !views_[view].byte_stride) {
            return parse_error(where, "buffer view " + std::to_string(view) + " is used by several vertex attribute "
                                                                            "accessors and must define byteStride");
        }
        return {};
    }

    Status check_meshes() {
        mesh_targets_.assign(count(Collection::Meshes), 0);
        mesh_has_joints_.assign(count(Collection::Meshes), false);
        return for_each(Collection::Meshes, [&](const json& mesh, const JsonPointer& where, std::size_t index) -> Status {
            auto primitives = array_member(mesh, "primitives", where, true);
            if (!primitives) return primitives.take_error();
            if ((*primitives)->empty()) return parse_error(where / "primitives", "a mesh needs at least one primitive");
            for (std::size_t p = 0; p < (*primitives)->size(); ++p) {
                const json& primitive = (**primitives)[p];
                if (!primitive.is_object()) return parse_error(where / "primitives" / p, "must be an object");
                LOOM_TRY(check_primitive(primitive, where / "primitives" / p));
                check_material_uv_sets(primitive, where / "primitives" / p);
            }
            // Every primitive of a mesh has the same number of morph targets; weights, one each.
            auto target_count = [](const json& primitive) -> std::size_t {
                const auto targets = primitive.find("targets");
                return targets == primitive.end() ? 0 : targets->size();
            };
            const std::size_t targets = target_count((**primitives)[0]);
            for (std::size_t p = 1; p < (*primitives)->size(); ++p) {
                if (target_count((**primitives)[p]) != targets) {
                    return parse_error(where / "primitives" / p / "targets",
                                       "has " + std::to_string(target_count((**primitives)[p])) + " morph targets, primitive 0 " +
                                           std::to_string(targets) + " (all primitives of a mesh need the same number)");
                }
            }
            mesh_targets_[index] = targets;
            for (const json& primitive : **primitives) {
                const auto attributes = primitive.find("attributes");
                if (attributes != primitive.end() && attributes->is_object() && attributes->contains("JOINTS_0")) {
                    mesh_has_joints_[index] = true;
                }
            }
            LOOM_TRY(number_array_member(mesh, "weights", where, 0));
            if (const json* weights = find(mesh, "weights"); weights != nullptr && weights->size() != targets) {
                return parse_error(where / "weights", "has " + std::to_string(weights->size()) + " weights for " +
                                                          std::to_string(targets) + " morph targets");
            }
            return {};
        });
    }

    Status check_cameras() {
        return for_each(Collection::Cameras, [&](const json& camera, const JsonPointer& where, std::size_t) -> Status {
            auto type = string_member(camera, "type", where, true);
            if (!type) return type.take_error();
            if (**type != "perspective" && **type != "orthographic") {
                return parse_error(where / "type", "'" + **type + "' is not 'perspective' or 'orthographic'");
            }
            const std::string other = **type == "perspective" ? "orthographic" : "perspective";
            if (find(camera, other) != nullptr) {
                return parse_error(where / other, "a " + **type + " camera must not have '" + other + "' properties");
            }
            auto parameters = object_member(camera, **type, where, true);
            if (!parameters) return parameters.take_error();
            const JsonPointer p_where = where / **type;
            const json& p = **parameters;
            Range positive;
            positive.min = 0.0;
            positive.min_exclusive = true;
            if (**type == "perspective") {
                auto yfov = number_member(p, "yfov", p_where, true, positive);
                if (!yfov) return yfov.take_error();
                auto znear = number_member(p, "znear", p_where, true, positive);
                if (!znear) return znear.take_error();
                auto aspect = number_member(p, "aspectRatio", p_where, false, positive);
                if (!aspect) return aspect.take_error();
                Range beyond_near;
                beyond_near.min = **znear;
                beyond_near.min_exclusive = true;
                auto zfar = number_member(p, "zfar", p_where, false, beyond_near);
                if (!zfar) return zfar.take_error();
            } else {
                for (const char* key : {"xmag", "ymag"}) {
                    auto mag = number_member(p, key, p_where, true);
                    if (!mag) return mag.take_error();
                    if (**mag == 0.0) return parse_error(p_where / key, "must not be zero");
                }
                auto znear = number_member(p, "znear", p_where, true, Range{0.0});
                if (!znear) return znear.take_error();
                Range beyond_near;
                beyond_near.min = **znear;
                beyond_near.min_exclusive = true;
                auto zfar = number_member(p, "zfar", p_where, true, beyond_near);
                if (!zfar) return zfar.take_error();
            }
            return {};
        });
    }

    Status check_skins() {
        if (Status status = for_each(Collection::Skins, [&](const json& skin, const JsonPointer& where, std::size_t) -> Status {
            auto matrices = reference_member(skin, "inverseBindMatrices", where, Collection::Accessors, false);
            if (!matrices) return matrices.take_error();
            auto skeleton = reference_member(skin, "skeleton", where, Collection::Nodes, false);
            if (!skeleton) return skeleton.take_error();
            auto joints = non_empty_array_member(skin, "joints", where, true);
            if (!joints) return joints.take_error();
            for (std::size_t j = 0; j < (*joints)->size(); ++j) {
                auto joint = reference_value((**joints)[j], where / "joints" / j, Collection::Nodes);
                if (!joint) return joint.take_error();
            }
            return {};
        }); !status) {
            return status;
        }
        return {};
    }

    Status check_nodes() {
        const std::size_t node_count = count(Collection::Nodes);
        parents_.assign(node_count, std::nullopt);
        if (Status status = for_each(Collection::Nodes, [&](const json& node, const JsonPointer& where, std::size_t index) -> Status {
            auto children = non_empty_array_member(node, "children", where, false);
            if (!children) return children.take_error();
            if (*children) {
                for (std::size_t k = 0; k < (*children)->size(); ++k) {
                    const JsonPointer child_where = where / "children" / k;
                    auto child = reference_value((**children)[k], child_where, Collection::Nodes);
                    if (!child) return child.take_error();
                    std::optional<uint64_t>& parent = parents_[*child];
                    if (parent) {
                        return parse_error(child_where, "node " + std::to_string(*child) + " is already a child of node " +
                                                            std::to_string(*parent) + " (a node can have only one parent)");
                    }
                    parent = index;
                }
            }
            for (const auto& [key, collection] : {std::pair{"mesh", Collection::Meshes}, std::pair{"camera", Collection::Cameras},
                                                  std::pair{"skin", Collection::Skins}}) {
                auto reference = reference_member(node, key, where, collection, false);
                if (!reference) return reference.take_error();
            }
            const Range unit{-1.0, 1.0};
            LOOM_TRY(number_array_member(node, "matrix", where, 16));
            LOOM_TRY(number_array_member(node, "translation", where, 3));
            LOOM_TRY(number_array_member(node, "rotation", where, 4, unit));
            LOOM_TRY(number_array_member(node, "scale", where, 3));
            LOOM_TRY(number_array_member(node, "weights", where, 0));
            if (find(node, "matrix") != nullptr &&
                (find(node, "translation") != nullptr || find(node, "rotation") != nullptr || find(node, "scale") != nullptr)) {
                return parse_error(where / "matrix", "a node must not have both 'matrix' and translation/rotation/scale");
            }
            if (const json* rotation = find(node, "rotation")) {
                double squares = 0.0;
                for (const json& value : *rotation) squares += value.get<double>() * value.get<double>();
                if (std::abs(std::sqrt(squares) - 1.0) > kUnitQuaternionTolerance) {
                    return parse_error(where / "rotation", "must be a unit quaternion, its length is " +
                                                               format_number(std::sqrt(squares)));
                }
            }
            if (const json* matrix = find(node, "matrix"); matrix != nullptr && !decomposable_to_trs(*matrix)) {
                return parse_error(where / "matrix", "must be decomposable into translation, rotation and scale (last row "
                                                     "0 0 0 1, orthogonal axes)");
            }
            return {};
        }); !status) {
            return status;
        }
        return check_node_cycles();
    }

    // With at most one parent per node, a cycle is found by walking up the parent links: a
    // walk that meets a node of its own path has gone round a cycle.
    Status check_node_cycles() const {
        const std::size_t node_count = parents_.size();
        enum class Mark : uint8_t { Unvisited, OnPath, Done };
        std::vector<Mark> marks(node_count, Mark::Unvisited);
        for (std::size_t start = 0; start < node_count; ++start) {
            std::vector<uint64_t> path;
            std::optional<uint64_t> node = start;
            while (node && marks[*node] != Mark::Done) {
                if (marks[*node] == Mark::OnPath) {
                    // The cycle is the part of the path from `node` on; print it in child
                    // order, starting at its smallest node.
                    std::vector<uint64_t> cycle(std::find(path.begin(), path.end(), *node), path.end());
                    std::reverse(cycle.begin(), cycle.end());
                    std::rotate(cycle.begin(), std::min_element(cycle.begin(), cycle.end()), cycle.end());
                    std::string chain;
                    for (const uint64_t n : cycle) chain += std::to_string(n) + " -> ";
                    chain += std::to_string(cycle.front());
                    return parse_error(JsonPointer{} / "nodes" / cycle.front(), "node " + std::to_string(cycle.front()) +
                                                                                    " is part of a cycle of children (" +
                                                                                    chain + ")");
                }
                marks[*node] = Mark::OnPath;
                path.push_back(*node);
                node = parents_[*node];
            }
            for (const uint64_t visited : path) marks[visited] = Mark::Done;
        }
        return {};
    }

    Status check_scenes() {
        return for_each(Collection::Scenes, [&](const json& scene, const JsonPointer& where, std::size_t) -> Status {
            auto nodes = non_empty_array_member(scene, "nodes", where, false);
            if (!nodes) return nodes.take_error();
            if (*nodes == nullptr) return {};
            std::set<uint64_t> seen;
            for (std::size_t k = 0; k < (*nodes)->size(); ++k) {
                const JsonPointer node_where = where / "nodes" / k;
                auto node = reference_value((**nodes)[k], node_where, Collection::Nodes);
                if (!node) return node.take_error();
                if (parents_[*node]) {
                    return parse_error(node_where, "node " + std::to_string(*node) + " is not a root node (it is a child of node " +
                                                       std::to_string(*parents_[*node]) + ")");
                }
                if (!seen.insert(*node).second) {
                    return parse_error(node_where, "node " + std::to_string(*node) + " is listed twice");
                }
            }
            return {};
        });
    }

    Status check_animations() {
        if (Status status = for_each(Collection::Animations, [&](const json& animation, const JsonPointer& where, std::size_t) -> Status {
            auto samplers = non_empty_array_member(animation, "samplers", where, true);
            if (!samplers) return samplers.take_error();
            for (std::size_t s = 0; s < (*samplers)->size(); ++s) {
                const json& sampler = (**samplers)[s];
                const JsonPointer sampler_where = where / "samplers" / s;
                if (!sampler.is_object()) return parse_error(sampler_where, "must be an object");
                for (const char* key : {"input", "output"}) {
                    auto accessor = reference_member(sampler, key, sampler_where, Collection::Accessors, true);
                    if (!accessor) return accessor.take_error();
                }
            }
            auto channels = non_empty_array_member(animation, "channels", where, true);
            if (!channels) return channels.take_error();
            for (std::size_t c = 0; c < (*channels)->size(); ++c) {
                const json& channel = (**channels)[c];
                const JsonPointer channel_where = where / "channels" / c;
                if (!channel.is_object()) return parse_error(channel_where, "must be an object");
                auto sampler = integer_member(channel, "sampler", channel_where, true, 0, kMaxInt);
                if (!sampler) return sampler.take_error();
                if (**sampler >= (*samplers)->size()) {
                    return parse_error(channel_where / "sampler", "sampler " + std::to_string(**sampler) +
                                                                      " does not exist (the animation has " +
                                                                      std::to_string((*samplers)->size()) + " samplers)");
                }
                auto target = object_member(channel, "target", channel_where, true);
                if (!target) return target.take_error();
                auto node = reference_member(**target, "node", channel_where / "target", Collection::Nodes, false);
                if (!node) return node.take_error();
            }
            return {};
        }); !status) {
            return status;
        }
        return {};
    }

    // ---- data the importer does not use -----------------------------------------------------
    //
    // Animations, skins and morph weights are not imported, so what the specification forbids in
    // them is a warning naming its place (the file still loads), not an error. The references
    // were checked above; this checks how they fit together. (Their values are checked by the
    // converter, which reads the data.)

    // "{VEC4, FLOAT}", or "{VEC4, normalized UNSIGNED_BYTE}".
    std::string format_of(const AccessorInfo& accessor) const {
        return "{" + std::string(accessor.type.name) + ", " + (accessor.normalized ? "normalized " : "") +
               std::string(component_type_name(accessor.component_type)) + "}";
    }
    bool has_stride(const AccessorInfo& accessor) const {
        return accessor.buffer_view && *accessor.buffer_view < views_.size() && views_[*accessor.buffer_view].byte_stride;
    }
    static bool is_float(const AccessorInfo& accessor) {
        return accessor.component_type == component_type::kFloat && !accessor.normalized;
    }
    // FLOAT, or a normalized (unsigned) byte or short: what rotations and weights may be stored as.
    static bool is_float_or_normalized(const AccessorInfo& accessor) {
        if (is_float(accessor)) return true;
        const int c = accessor.component_type;
        return accessor.normalized && (c == component_type::kByte || c == component_type::kUnsignedByte ||
                                       c == component_type::kShort || c == component_type::kUnsignedShort);
    }
    // The node at the top of `node`'s hierarchy.
    uint64_t root_of(uint64_t node) const {
        while (parents_[node]) node = *parents_[node];
        return node;
    }
    bool is_ancestor_or_self(uint64_t ancestor, uint64_t node) const {
        for (std::optional<uint64_t> at = node; at; at = parents_[*at]) {
            if (*at == ancestor) return true;
        }
        return false;
    }
    // A reference checked above (so a non-negative integer, "-0" included), or nullopt when absent.
    std::optional<uint64_t> index_in(const json& object, std::string_view key) const {
        const json* value = find(object, key);
        if (value == nullptr || !value->is_number_integer() || value->get<int64_t>() < 0) return std::nullopt;
        return value->get<uint64_t>();
    }

    void check_unused_data() {
        check_animation_use();
        check_skin_use();
        check_node_use();
    }

    void check_animation_use() {
        const json* animations = find(root_, "animations");
        const json* nodes = find(root_, "nodes");
        if (animations == nullptr) return;
        for (std::size_t a = 0; a < animations->size(); ++a) {
            const json& animation = (*animations)[a];
            const JsonPointer where = JsonPointer{} / "animations" / a;
            const json& samplers = animation.at("samplers");
            for (std::size_t s = 0; s < samplers.size(); ++s) {
                const JsonPointer sampler_where = where / "samplers" / s;
                const std::optional<uint64_t> input_index = index_in(samplers[s], "input");
                const std::optional<uint64_t> output_index = index_in(samplers[s], "output");
                if (!input_index || !output_index) continue;  // checked above: never
                const AccessorInfo& input = accessors_[*input_index];
                const AccessorInfo& output = accessors_[*output_index];
                if (input.type.components != 1 || input.type.columns != 0 || !is_float(input)) {
                    warn(sampler_where / "input", "an animation's input accessor must be {SCALAR, FLOAT}, got " + format_of(input));
                } else if (!input.has_bounds) {
                    warn(sampler_where / "input", "an animation's input accessor must define min and max");
                }
                for (const auto& [key, accessor] : {std::pair{"input", &input}, std::pair{"output", &output}}) {
                    if (has_stride(*accessor)) {
                        warn(sampler_where / key, "the buffer view of an animation sampler's accessor must not define byteStride");
                    }
                }
                if (cubic(samplers[s]) && input.count < 2) {
                    warn(sampler_where / "input", "a CUBICSPLINE sampler needs at least 2 keyframes, its input has " +
                                                      std::to_string(input.count));
                }
            }
            const json& channels = animation.at("channels");
            std::map<std::pair<uint64_t, std::string>, std::size_t> first_channel_of_target;
            for (std::size_t c = 0; c < channels.size(); ++c) {
                const JsonPointer channel_where = where / "channels" / c;
                const json& channel = channels[c];
                const std::optional<uint64_t> sampler_index = index_in(channel, "sampler");
                if (!sampler_index) continue;  // checked above: never
                const json& sampler = samplers[*sampler_index];
                const json& target = channel.at("target");
                const json* path_value = find(target, "path");
                if (path_value == nullptr || !path_value->is_string()) continue;
                const std::string path = path_value->get<std::string>();
                if (path != "translation" && path != "rotation" && path != "scale" && path != "weights") continue;
                const std::optional<uint64_t> node = index_in(target, "node");
                std::optional<std::size_t> targets;  // morph targets of the node's mesh
                if (node) {
                    const json& node_object = (*nodes)[*node];
                    const std::optional<uint64_t> mesh = index_in(node_object, "mesh");
                    targets = mesh ? mesh_targets_[*mesh] : 0;
                    if (path == "weights" && *targets == 0) {
                        warn(channel_where / "target", "animates the morph weights of node " + std::to_string(*node) +
                                                           ", whose mesh has no morph targets");
                    }
                    if (path != "weights" && find(node_object, "matrix") != nullptr) {
                        warn(channel_where / "target", "animates the " + path + " of node " + std::to_string(*node) +
                                                           ", which has a matrix instead of translation/rotation/scale");
                    }
                    const auto [first, inserted] = first_channel_of_target.try_emplace({*node, path}, c);
                    if (!inserted) {
                        warn(where / "channels" / first->second / "target",
                             "has the same target as channel " + std::to_string(c) + " (node " + std::to_string(*node) +
                                 ", " + path + ")");
                    }
                }
                const std::optional<uint64_t> input_index = index_in(sampler, "input");
                const std::optional<uint64_t> output_index = index_in(sampler, "output");
                if (!input_index || !output_index) continue;
                const AccessorInfo& input = accessors_[*input_index];
                const AccessorInfo& output = accessors_[*output_index];
                const bool vec3 = path == "translation" || path == "scale";
                const bool format_ok = vec3 ? output.type.components == 3 && is_float(output)
                                       : path == "rotation"
                                           ? output.type.components == 4 && output.type.columns == 0 && is_float_or_normalized(output)
                                           : output.type.components == 1 && is_float_or_normalized(output);
                if (!format_ok) {
                    warn(channel_where / "sampler", "the output accessor's format " + format_of(output) + " does not fit path '" +
                                                        path + "'");
                    continue;
                }
                const uint64_t per_key = (cubic(sampler) ? 3 : 1) * (path == "weights" ? targets.value_or(0) : 1);
                if ((path != "weights" || targets.value_or(0) != 0) && output.count != input.count * per_key) {
                    warn(channel_where / "sampler", "the output accessor has " + std::to_string(output.count) +
                                                        " elements, " + std::to_string(input.count * per_key) +
                                                        " expected from the input's " + std::to_string(input.count) +
                                                        " keyframes");
                }
            }
        }
    }
    bool cubic(const json& sampler) const {
        const json* interpolation = find(sampler, "interpolation");
        return interpolation != nullptr && interpolation->is_string() && *interpolation == "CUBICSPLINE";
    }

    void check_skin_use() {
        const json* skins = find(root_, "skins");
        if (skins == nullptr) return;
        for (std::size_t s = 0; s < skins->size(); ++s) {
            const json& skin = (*skins)[s];
            const JsonPointer where = JsonPointer{} / "skins" / s;
            const json& joints = skin.at("joints");
            if (const std::optional<uint64_t> matrices = index_in(skin, "inverseBindMatrices")) {
                const AccessorInfo& accessor = accessors_[*matrices];
                if (accessor.type.columns != 4 || !is_float(accessor)) {
                    warn(where / "inverseBindMatrices", "must be a {MAT4, FLOAT} accessor, got " + format_of(accessor));
                } else if (accessor.count < joints.size()) {
                    warn(where / "inverseBindMatrices", "has " + std::to_string(accessor.count) + " matrices for " +
                                                            std::to_string(joints.size()) + " joints");
                }
                if (has_stride(accessor)) {
                    warn(where / "inverseBindMatrices", "the buffer view of inverse bind matrices must not define byteStride");
                }
            }
            const uint64_t root = root_of(joints[0].get<uint64_t>());
            bool common_root = true;
            for (const json& joint : joints) common_root = common_root && root_of(joint.get<uint64_t>()) == root;
            if (!common_root) warn(where / "joints", "the joints do not have a common root");
            if (const std::optional<uint64_t> skeleton = index_in(skin, "skeleton")) {
                bool above_all = true;
                for (const json& joint : joints) above_all = above_all && is_ancestor_or_self(*skeleton, joint.get<uint64_t>());
                if (!above_all) warn(where / "skeleton", "node " + std::to_string(*skeleton) + " is not a common root of the joints");
            }
        }
    }

    void check_node_use() {
        const json* nodes = find(root_, "nodes");
        if (nodes == nullptr) return;
        const json* skins = find(root_, "skins");
        for (std::size_t n = 0; n < nodes->size(); ++n) {
            const json& node = (*nodes)[n];
            const JsonPointer where = JsonPointer{} / "nodes" / n;
            const std::optional<uint64_t> mesh = index_in(node, "mesh");
            const std::optional<uint64_t> skin = index_in(node, "skin");
            if (skin && !mesh) warn(where / "skin", "a node with a skin needs a mesh");
            if (find(node, "weights") != nullptr) {
                if (!mesh) {
                    warn(where / "weights", "a node with morph weights needs a mesh");
                } else if ((*nodes)[n].at("weights").size() != mesh_targets_[*mesh]) {
                    warn(where / "weights", "has " + std::to_string(node.at("weights").size()) + " weights for the " +
                                                std::to_string(mesh_targets_[*mesh]) + " morph targets of mesh " +
                                                std::to_string(*mesh));
                }
            }
            if (!skin || !mesh) continue;
            if (!mesh_has_joints_[*mesh]) {
                warn(where, "has a skin, but mesh " + std::to_string(*mesh) + " has no JOINTS_0 attribute");
                continue;
            }
            // A scene that holds the skinned node must hold a joint too (under any of its roots:
            // the skeleton and the mesh are often siblings at the top of a scene).
            const uint64_t root = root_of(n);
            const std::set<uint64_t> roots = scene_roots_beside(root);
            bool joint_in_its_scene = false;
            for (const json& joint : (*skins)[*skin].at("joints")) {
                joint_in_its_scene = joint_in_its_scene || roots.count(root_of(joint.get<uint64_t>())) != 0;
            }
            if (!joint_in_its_scene && in_a_scene(root)) {
                warn(where, "is skinned, but no joint of skin " + std::to_string(*skin) + " is in its scene");
            }
        }
    }
    // The roots of every scene that lists `root` among its nodes.
    std::set<uint64_t> scene_roots_beside(uint64_t root) const {
        std::set<uint64_t> beside;
        const json* scenes = find(root_, "scenes");
        if (scenes == nullptr) return beside;
        for (const json& scene : *scenes) {
            const json* roots = find(scene, "nodes");
            if (roots == nullptr) continue;
            bool lists_it = false;
            for (const json& r : *roots) lists_it = lists_it || r.get<uint64_t>() == root;
            if (!lists_it) continue;
            for (const json& r : *roots) beside.insert(r.get<uint64_t>());
        }
        return beside;
    }

    bool in_a_scene(uint64_t root) const {
        const json* scenes = find(root_, "scenes");
        if (scenes == nullptr) return false;
        for (const json& scene : *scenes) {
            const json* roots = find(scene, "nodes");
            if (roots == nullptr) continue;
            for (const json& r : *roots) {
                if (r.get<uint64_t>() == root) return true;
            }
        }
        return false;
    }

    const json& root_;
    const ValidationInput& input_;
    ValidationOutput& output_;
    std::array<std::size_t, kCollectionCount> counts_{};
    bool mesh_quantization_ = false;
    bool webp_images_allowed_ = false;
    std::vector<uint64_t> buffer_lengths_;
    std::vector<ViewInfo> views_;
    std::vector<AccessorInfo> accessors_;
    std::vector<std::optional<uint64_t>> parents_;
    std::vector<std::size_t> mesh_targets_;  // per mesh: its morph targets
    std::vector<bool> mesh_has_joints_;      // per mesh: a primitive has JOINTS_0
    std::vector<uint64_t> material_uv_sets_;  // per material: the UV sets its textures sample (highest + 1)
    std::map<uint64_t, uint64_t> view_usage_;                   // buffer view -> kArrayBuffer / kElementArrayBuffer
    std::map<uint64_t, std::set<uint64_t>> vertex_view_accessors_;  // buffer view -> vertex attribute accessors
};

}  // namespace

Result<ValidationOutput> validate_document(const nlohmann::json& root, const ValidationInput& input) {
    ValidationOutput output;
    Validator validator(root, input, output);
    LOOM_TRY(validator.run());
    return output;
}

}  // namespace loom::gltf::detail
