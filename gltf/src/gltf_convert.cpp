#include "gltf_convert.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <utility>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "accessor_reader.hpp"
#include "gltf_constants.hpp"
#include "gltf_validate.hpp"
#include "image_decode.hpp"
#include "json_pointer.hpp"
#include "loom/scene/geometry.hpp"

namespace loom::gltf::detail {

using namespace loom::scene;  // the importer builds the scene model's types

namespace {

// A vector element by a tinygltf index, or nullptr when the index is out of range (the
// validator makes that impossible; this keeps the converter safe on its own).
template <class T>
const T* element(const std::vector<T>& items, int index) {
    if (index < 0 || static_cast<std::size_t>(index) >= items.size()) return nullptr;
    return &items[static_cast<std::size_t>(index)];
}

uint64_t as_index(std::size_t index) { return static_cast<uint64_t>(index); }

glm::vec4 to_vec4(const std::vector<double>& values, const glm::vec4& fallback) {
    if (values.size() != 4) return fallback;
    return glm::vec4(static_cast<float>(values[0]), static_cast<float>(values[1]), static_cast<float>(values[2]),
                     static_cast<float>(values[3]));
}

glm::vec3 to_vec3(const std::vector<double>& values, const glm::vec3& fallback) {
    if (values.size() != 3) return fallback;
    return glm::vec3(static_cast<float>(values[0]), static_cast<float>(values[1]), static_cast<float>(values[2]));
}

// The node's transform: its matrix, or its translation, rotation and scale (the rotation
// normalised) and their product.
void set_transform(const tinygltf::Node& source, Node& node) {
    node.has_matrix = source.matrix.size() == 16;
    if (node.has_matrix) {
        for (int column = 0; column < 4; ++column) {
            for (int row = 0; row < 4; ++row) {
                node.local[column][row] = static_cast<float>(source.matrix[static_cast<std::size_t>(column * 4 + row)]);
            }
        }
        return;
    }
    node.translation = to_vec3(source.translation, glm::vec3(0.0f));
    node.scale = to_vec3(source.scale, glm::vec3(1.0f));
    if (source.rotation.size() == 4) {
        // glTF stores (x, y, z, w); glm::quat's constructor takes (w, x, y, z).
        const glm::quat rotation(static_cast<float>(source.rotation[3]), static_cast<float>(source.rotation[0]),
                                 static_cast<float>(source.rotation[1]), static_cast<float>(source.rotation[2]));
        const float length = glm::length(rotation);
        node.rotation = length > 0.0f ? rotation / length : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    }
    node.local = trs_matrix(node.translation, node.rotation, node.scale);
}

rhi::Filter filter_of(int gltf_filter) {
    switch (gltf_filter) {
        case filter::kNearest:
        case filter::kNearestMipmapNearest:
        case filter::kNearestMipmapLinear: return rhi::Filter::Nearest;
        default: return rhi::Filter::Linear;
    }
}

rhi::AddressMode address_of(int gltf_wrap) {
    switch (gltf_wrap) {
        case wrap::kClampToEdge: return rhi::AddressMode::ClampToEdge;
        case wrap::kMirroredRepeat: return rhi::AddressMode::MirroredRepeat;
        default: return rhi::AddressMode::Repeat;
    }
}

class Converter {
public:
    Converter(const tinygltf::Model& model, const std::string& file_label, const LoadOptions& options,
              const std::set<uint64_t>& unavailable_buffers, std::vector<std::string>& warnings)
        : model_(model), file_label_(file_label), options_(options), unavailable_buffers_(unavailable_buffers),
          warnings_(warnings), reader_(model, file_label, options.max_accessor_elements, unavailable_buffers) {}

    Result<Scene> run() {
        scene_.source = file_label_;
        LOOM_TRY(convert_materials());
        LOOM_TRY(convert_meshes());
        LOOM_TRY(convert_nodes());
        LOOM_TRY(convert_skins());
        LOOM_TRY(flatten_scene());
        check_unused_images();
        check_accessor_bounds();
        convert_animations();
        check_skinning_attributes();
        return std::move(scene_);
    }

private:
    Error error(const JsonPointer& where, const std::string& what) const {
        return make_error(ErrorCode::Parse, located_message(file_label_, where.str(), what));
    }
    void warn(const JsonPointer& where, const std::string& what) {
        warnings_.push_back(located_message(file_label_, where.str(), what));
    }

    // ---- data the importer does not use ------------------------------------------------------
    //
    // Values the importer does not use (and skinning data it uses only in part): what the
    // specification forbids in them is a warning naming the accessor's user (the validator
    // checked their formats and counts and warned about those; only accessors of the right format
    // are read here).

    // Accessor `index` as floats when it has `components` per element, else nullopt; a read
    // error (missing data) is a warning at `where`.
    std::optional<std::vector<float>> read_unused(int index, uint32_t components, const JsonPointer& where) {
        if (reader_.components(index) != components) return std::nullopt;
        auto values = reader_.read_floats(index, components);
        if (!values) {
            warn(where, "cannot be checked: " + values.error().message);
            return std::nullopt;
        }
        return std::move(*values);
    }

    // Images no material uses are not part of the scene, but their data must still be an image:
    // each is decoded once to find out (a warning names the image when it does not decode).
    void check_unused_images() {
        for (std::size_t i = 0; i < model_.images.size(); ++i) {
            const int image = static_cast<int>(i);
            if (images_.count({image, false}) != 0 || images_.count({image, true}) != 0) continue;
            const tinygltf::Image& source = model_.images[i];
            if (const tinygltf::BufferView* view = element(model_.bufferViews, source.bufferView);
                view != nullptr && view->buffer >= 0 && unavailable_buffers_.count(static_cast<uint64_t>(view->buffer)) != 0) {
                continue;  // no data to check (the buffer's warning says so)
            }
            // WebP (EXT_texture_webp, whose images the importer does not decode) is not checked.
            const std::vector<unsigned char>& bytes = source.image;
            if (bytes.size() >= 12 && std::equal(bytes.begin(), bytes.begin() + 4, "RIFF") &&
                std::equal(bytes.begin() + 8, bytes.begin() + 12, "WEBP")) {
                continue;
            }
            auto decoded = decode_image(source.image, rhi::Format::RGBA8Unorm, options_.max_image_dimension);
            if (!decoded) warn(JsonPointer{} / "images" / as_index(i), "no material uses it, and it does not decode: " + decoded.error().message);
        }
    }

    // Every accessor's values against its declared min and max, and float values for finiteness
    // (the importer reads neither min nor max; the accessors it reads were checked for finite
    // values as they were read). One warning per accessor, at the first value at fault; an
    // accessor whose data cannot be read was reported where it is used, or is not used.
    void check_accessor_bounds() {
        for (std::size_t a = 0; a < model_.accessors.size(); ++a) {
            const tinygltf::Accessor& accessor = model_.accessors[a];
            const bool is_float = accessor.componentType == component_type::kFloat;
            const bool bounded = !accessor.minValues.empty() || !accessor.maxValues.empty();
            // An accessor the conversion read is finite (read_floats refuses anything else).
            if (!bounded && (!is_float || read_as_floats_.count(static_cast<int>(a)) != 0)) continue;
            // Without a bufferView the values are zeros (and any sparse ones): the validator checks
            // the data a file carries, not those zeros.
            if (accessor.bufferView < 0 && !accessor.sparse.isSparse) continue;
            const auto values = reader_.read_stored(static_cast<int>(a));
            if (!values) continue;
            const JsonPointer where = JsonPointer{} / "accessors" / as_index(a);
            const auto components = static_cast<std::size_t>(reader_.components(static_cast<int>(a)));
            check_bounds(*values, components, accessor, is_float, where);
        }
    }
    // Warns at the first value of `values` that is not finite (at the accessor), or at the first
    // component whose declared min or max is not the data's (at that bound).
    void check_bounds(const std::vector<double>& values, std::size_t components, const tinygltf::Accessor& accessor,
                      bool is_float, const JsonPointer& where) {
        // Declared bounds are compared as the component type stores them (floats as floats).
        const auto stored = [&](double v) { return is_float ? static_cast<double>(static_cast<float>(v)) : v; };
        for (std::size_t i = 0; i < values.size(); ++i) {
            if (!std::isfinite(values[i])) {
                return warn(where, "element " + std::to_string(i / components) + " component " +
                                       std::to_string(i % components) + " is not a finite number");
            }
        }
        if (values.empty()) return;
        for (std::size_t c = 0; c < components; ++c) {
            double low = std::numeric_limits<double>::infinity();
            double high = -std::numeric_limits<double>::infinity();
            for (std::size_t i = c; i < values.size(); i += components) {
                low = std::min(low, values[i]);
                high = std::max(high, values[i]);
            }
            if (c < accessor.minValues.size() && stored(accessor.minValues[c]) != low) {
                return warn(where / "min" / as_index(c), "the declared minimum " + format_value(accessor.minValues[c]) +
                                                             " is not the data's, " + format_value(low));
            }
            if (c < accessor.maxValues.size() && stored(accessor.maxValues[c]) != high) {
                return warn(where / "max" / as_index(c), "the declared maximum " + format_value(accessor.maxValues[c]) +
                                                             " is not the data's, " + format_value(high));
            }
        }
    }
    static std::string format_value(double value) {
        std::ostringstream out;
        out << value;
        return out.str();
    }

    // ---- animations ------------------------------------------------------------------------
    //
    // Each animation with its channels that drive a node's translation, rotation or scale, and
    // the samplers they use. A channel is left out when the validator warned about it (its
    // output's format or count, a node with a matrix, a second channel on the same target) or
    // when its sampler's data breaks the specification (times negative or not increasing,
    // rotations not unit quaternions: a warning here names them); channels of morph target
    // weights are left out too (morph targets are not imported), and channels without a node,
    // as the specification says.
    void convert_animations() {
        for (std::size_t a = 0; a < model_.animations.size(); ++a) {
            const tinygltf::Animation& source = model_.animations[a];
            const JsonPointer where = JsonPointer{} / "animations" / as_index(a);
            Animation animation;
            animation.name = source.name.empty() ? "animation " + std::to_string(a) : source.name;
            // Per source sampler, the converted one (or none: it breaks the specification).
            std::map<std::size_t, std::optional<uint32_t>> converted;
            std::set<std::pair<int, AnimatedProperty>> targets;
            for (std::size_t c = 0; c < source.channels.size(); ++c) {
                const tinygltf::AnimationChannel& channel = source.channels[c];
                const std::optional<AnimatedProperty> property = animated_property(channel.target_path);
                if (!property || *property == AnimatedProperty::Weights || channel.target_node < 0 ||
                    static_cast<std::size_t>(channel.target_node) >= scene_.nodes.size() || channel.sampler < 0 ||
                    static_cast<std::size_t>(channel.sampler) >= source.samplers.size() ||
                    scene_.nodes[static_cast<std::size_t>(channel.target_node)].has_matrix ||
                    !targets.insert({channel.target_node, *property}).second) {
                    continue;
                }
                const auto s = static_cast<std::size_t>(channel.sampler);
                const auto [it, inserted] = converted.try_emplace(s);
                if (inserted) {
                    it->second = convert_sampler(source.samplers[s], *property, animation, where / "samplers" / as_index(s),
                                                 where / "channels" / as_index(c) / "sampler");
                }
                if (!it->second) continue;
                if (animation.samplers[*it->second].components != (*property == AnimatedProperty::Rotation ? 4u : 3u)) continue;
                animation.channels.push_back(
                    AnimationChannel{static_cast<uint32_t>(channel.target_node), *it->second, *property});
            }
            // Samplers no channel plays: their times are still checked.
            for (std::size_t s = 0; s < source.samplers.size(); ++s) {
                if (converted.count(s) == 0) read_times(source.samplers[s].input, where / "samplers" / as_index(s) / "input");
            }
            scene_.animations.push_back(std::move(animation));
        }
    }

    static std::optional<AnimatedProperty> animated_property(const std::string& path) {
        if (path == "translation") return AnimatedProperty::Translation;
        if (path == "rotation") return AnimatedProperty::Rotation;
        if (path == "scale") return AnimatedProperty::Scale;
        if (path == "weights") return AnimatedProperty::Weights;
        return std::nullopt;
    }

    // Keyframe times of input accessor `index`: non-negative and increasing, else a warning at
    // `where` and nullopt.
    std::optional<std::vector<float>> read_times(int index, const JsonPointer& where) {
        auto times = read_unused(index, 1, where);
        if (!times) return std::nullopt;
        if (times->empty()) {
            warn(where, "has no keyframes");
            return std::nullopt;
        }
        for (std::size_t k = 0; k < times->size(); ++k) {
            if ((*times)[k] < 0.0f) {
                warn(where, "keyframe " + std::to_string(k) + " has a negative time");
                return std::nullopt;
            }
            if (k > 0 && !((*times)[k] > (*times)[k - 1])) {
                warn(where, "keyframe times must increase, keyframe " + std::to_string(k) + " is not after keyframe " +
                                std::to_string(k - 1));
                return std::nullopt;
            }
        }
        return times;
    }

    // Whether rotation keyframes are unit quaternions (a cubic spline's elements are in-tangent,
    // value, out-tangent: only values are rotations); else a warning at `where`.
    bool unit_rotations(const std::vector<float>& values, bool cubic, const JsonPointer& where) {
        for (std::size_t e = cubic ? 1 : 0; e * 4 + 3 < values.size(); e += cubic ? 3 : 1) {
            const float* q = values.data() + e * 4;
            const double length =
                std::sqrt(double{q[0]} * q[0] + double{q[1]} * q[1] + double{q[2]} * q[2] + double{q[3]} * q[3]);
            if (std::abs(length - 1.0) > kUnitQuaternionTolerance) {
                warn(where, "output element " + std::to_string(e) + " is not a unit quaternion (length " +
                                std::to_string(length) + ")");
                return false;
            }
        }
        return true;
    }

    // `source` as the sampler of a channel on `property`, appended to `animation`: its index,
    // or nullopt when its data breaks the specification (a warning at `where`, or for
    // rotations at the channel's `channel_where`) or does not fit the property.
    std::optional<uint32_t> convert_sampler(const tinygltf::AnimationSampler& source, AnimatedProperty property,
                                            Animation& animation, const JsonPointer& where,
                                            const JsonPointer& channel_where) {
        AnimationSampler sampler;
        sampler.interpolation = source.interpolation == "STEP"          ? Interpolation::Step
                                : source.interpolation == "CUBICSPLINE" ? Interpolation::CubicSpline
                                                                        : Interpolation::Linear;
        sampler.components = property == AnimatedProperty::Rotation ? 4 : 3;
        const bool cubic = sampler.interpolation == Interpolation::CubicSpline;
        // Times and values are checked each on its own, so that every rule they break is named.
        auto times = read_times(source.input, where / "input");
        auto values = read_unused(source.output, sampler.components, channel_where);  // nullopt: a format the validator warned about
        if (values && property == AnimatedProperty::Rotation && !unit_rotations(*values, cubic, channel_where)) {
            return std::nullopt;
        }
        if (!times || !values) return std::nullopt;
        const std::size_t expected = times->size() * sampler.components * (cubic ? 3 : 1);
        if (values->size() != expected || (cubic && times->size() < 2)) return std::nullopt;  // the validator warned
        sampler.times = std::move(*times);
        sampler.values = std::move(*values);
        animation.samplers.push_back(std::move(sampler));
        return static_cast<uint32_t>(animation.samplers.size() - 1);
    }

    // JOINTS_n / WEIGHTS_n of every primitive (JOINTS_0 / WEIGHTS_0 are imported): weights non-negative and
    // summing to 1 per vertex over all sets, no joint twice in a vertex with weight, joint
    // indices inside the smallest skin of the nodes that draw the mesh. One warning per check.
    void check_skinning_attributes() {
        std::vector<std::size_t> joints_of_mesh(model_.meshes.size(), SIZE_MAX);  // smallest skin's joint count
        for (const tinygltf::Node& node : model_.nodes) {
            if (node.mesh < 0 || node.skin < 0 || static_cast<std::size_t>(node.skin) >= model_.skins.size() ||
                static_cast<std::size_t>(node.mesh) >= model_.meshes.size()) {
                continue;
            }
            std::size_t& joints = joints_of_mesh[static_cast<std::size_t>(node.mesh)];
            joints = std::min(joints, model_.skins[static_cast<std::size_t>(node.skin)].joints.size());
        }
        for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
            for (std::size_t p = 0; p < model_.meshes[m].primitives.size(); ++p) {
                check_skinning_attributes(model_.meshes[m].primitives[p], joints_of_mesh[m],
                                          JsonPointer{} / "meshes" / as_index(m) / "primitives" / as_index(p) / "attributes");
            }
        }
    }
    void check_skinning_attributes(const tinygltf::Primitive& primitive, std::size_t joint_count, const JsonPointer& where) {
        struct Set {
            std::string joints_name, weights_name;
            std::vector<double> joints, weights;
        };
        std::vector<Set> sets;
        for (std::size_t n = 0;; ++n) {
            const auto joints = primitive.attributes.find("JOINTS_" + std::to_string(n));
            const auto weights = primitive.attributes.find("WEIGHTS_" + std::to_string(n));
            if (joints == primitive.attributes.end() || weights == primitive.attributes.end()) break;
            auto joint_values = reader_.read_stored(joints->second);
            auto weight_values = reader_.read_floats(weights->second, 4);
            if (!joint_values || !weight_values || reader_.components(joints->second) != 4 ||
                joint_values->size() != weight_values->size()) {
                return;  // formats and counts are the validator's; data it cannot read is not checked
            }
            sets.push_back({joints->first, weights->first, std::move(*joint_values),
                            std::vector<double>(weight_values->begin(), weight_values->end())});
        }
        if (sets.empty()) return;
        const std::size_t vertices = sets[0].joints.size() / 4;
        bool negative = false, unnormalized = false, duplicate = false, outside = false;
        for (std::size_t v = 0; v < vertices; ++v) {
            double sum = 0.0;
            std::vector<double> used;
            for (const Set& set : sets) {
                if (set.joints.size() != vertices * 4) return;
                for (std::size_t c = 0; c < 4; ++c) {
                    const double joint = set.joints[v * 4 + c];
                    const double weight = set.weights[v * 4 + c];
                    sum += weight;
                    if (weight < 0.0 && !negative) {
                        negative = true;
                        warn(where / set.weights_name, "vertex " + std::to_string(v) + " has a negative weight");
                    }
                    if (weight == 0.0) continue;
                    if (joint >= static_cast<double>(joint_count) && !outside) {
                        outside = true;
                        warn(where / set.joints_name, "vertex " + std::to_string(v) + " uses joint " +
                                                          std::to_string(static_cast<uint64_t>(joint)) + " of a skin with " +
                                                          std::to_string(joint_count) + " joints");
                    }
                    if (std::find(used.begin(), used.end(), joint) != used.end() && !duplicate) {
                        duplicate = true;
                        warn(where / set.joints_name, "vertex " + std::to_string(v) + " uses joint " +
                                                          std::to_string(static_cast<uint64_t>(joint)) + " twice");
                    }
                    used.push_back(joint);
                }
            }
            // Normalised weights may be off by their quantisation step per component.
            if (std::abs(sum - 1.0) > 2e-3 * static_cast<double>(sets.size() * 4) && !unnormalized) {
                unnormalized = true;
                warn(where / sets[0].weights_name, "vertex " + std::to_string(v) + "'s weights sum to " + std::to_string(sum) +
                                                       ", not 1");
            }
        }
    }

    // ---- materials, textures, images ------------------------------------------------------

    Status convert_materials() {
        for (std::size_t m = 0; m < model_.materials.size(); ++m) {
            const tinygltf::Material& source = model_.materials[m];
            const JsonPointer where = JsonPointer{} / "materials" / as_index(m);
            const JsonPointer pbr_where = where / "pbrMetallicRoughness";
            const auto& pbr = source.pbrMetallicRoughness;
            Material material;
            material.name = source.name.empty() ? "material " + std::to_string(m) : source.name;
            material.base_color_factor = to_vec4(pbr.baseColorFactor, glm::vec4(1.0f));
            material.metallic_factor = static_cast<float>(pbr.metallicFactor);
            material.roughness_factor = static_cast<float>(pbr.roughnessFactor);
            material.emissive_factor = to_vec3(source.emissiveFactor, glm::vec3(0.0f));
            // KHR_materials_emissive_strength scales the factor past 1 (validated non-negative).
            if (auto ext = source.extensions.find("KHR_materials_emissive_strength"); ext != source.extensions.end()) {
                const tinygltf::Value& strength = ext->second.Get("emissiveStrength");
                if (strength.IsNumber()) material.emissive_factor *= static_cast<float>(strength.GetNumberAsDouble());
            }
            material.normal_scale = static_cast<float>(source.normalTexture.scale);
            material.occlusion_strength = static_cast<float>(source.occlusionTexture.strength);
            material.alpha_mode = source.alphaMode == "MASK"    ? AlphaMode::Mask
                                  : source.alphaMode == "BLEND" ? AlphaMode::Blend
                                                                : AlphaMode::Opaque;
            material.alpha_cutoff = static_cast<float>(source.alphaCutoff);
            material.double_sided = source.doubleSided;

            auto base_color = texture_ref(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions, true,
                                          pbr_where / "baseColorTexture");
            if (!base_color) return base_color.take_error();
            material.base_color_texture = *base_color;
            auto metallic_roughness = texture_ref(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                                                  pbr.metallicRoughnessTexture.extensions,
                                                  false, pbr_where / "metallicRoughnessTexture");
            if (!metallic_roughness) return metallic_roughness.take_error();
            material.metallic_roughness_texture = *metallic_roughness;
            auto normal = texture_ref(source.normalTexture.index, source.normalTexture.texCoord, source.normalTexture.extensions, false,
                                      where / "normalTexture");
            if (!normal) return normal.take_error();
            material.normal_texture = *normal;
            auto occlusion = texture_ref(source.occlusionTexture.index, source.occlusionTexture.texCoord,
                                         source.occlusionTexture.extensions, false,
                                         where / "occlusionTexture");
            if (!occlusion) return occlusion.take_error();
            material.occlusion_texture = *occlusion;
            auto emissive = texture_ref(source.emissiveTexture.index, source.emissiveTexture.texCoord, source.emissiveTexture.extensions, true,
                                        where / "emissiveTexture");
            if (!emissive) return emissive.take_error();
            material.emissive_texture = *emissive;
            scene_.materials.push_back(std::move(material));
        }
        return {};
    }

    Result<std::optional<TextureRef>> texture_ref(int texture, int tex_coord, const tinygltf::ExtensionMap& extensions, bool srgb,
                                                  const JsonPointer& where) {
        if (texture < 0) return std::optional<TextureRef>{};
        TextureRef ref;
        // KHR_texture_transform (validated): the transform, and a UV set that replaces texCoord.
        if (auto ext = extensions.find("KHR_texture_transform"); ext != extensions.end()) {
            const tinygltf::Value& value = ext->second;
            TextureTransform transform;
            auto pair = [&](const char* key, glm::vec2& out) {
                const tinygltf::Value& array = value.Get(key);
                if (array.IsArray() && array.ArrayLen() == 2) {
                    out = glm::vec2(static_cast<float>(array.Get(0).GetNumberAsDouble()),
                                    static_cast<float>(array.Get(1).GetNumberAsDouble()));
                }
            };
            pair("offset", transform.offset);
            pair("scale", transform.scale);
            if (value.Get("rotation").IsNumber()) transform.rotation = static_cast<float>(value.Get("rotation").GetNumberAsDouble());
            if (value.Get("texCoord").IsInt()) tex_coord = value.Get("texCoord").GetNumberAsInt();
            ref.transform = transform;
        }
        if (tex_coord == 0 || tex_coord == 1) {
            ref.uv_set = static_cast<uint32_t>(tex_coord);
        } else {
            warn(where / "texCoord", "TEXCOORD_" + std::to_string(tex_coord) + " is not imported; UV set 0 is used instead");
        }
        const tinygltf::Texture* source = element(model_.textures, texture);
        if (source == nullptr) return error(where / "index", "texture " + std::to_string(texture) + " does not exist");
        if (source->source < 0) {
            warn(where / "index", "texture " + std::to_string(texture) + " has no image source; the material ignores it");
            return std::optional<TextureRef>{};
        }
        const auto key = std::pair{texture, srgb};
        if (const auto cached = textures_.find(key); cached != textures_.end()) {
            ref.texture = cached->second;
            return std::optional<TextureRef>{ref};
        }
        const JsonPointer texture_where = JsonPointer{} / "textures" / static_cast<uint64_t>(texture);
        auto image = scene_image(source->source, srgb, texture_where / "source");
        if (!image) return image.take_error();
        Texture result;
        result.image = *image;
        result.sampler = sampler(source->sampler);
        result.name = !source->name.empty() ? source->name : scene_.images[*image].name;
        result.sampler.name = result.name;
        ref.texture = static_cast<uint32_t>(scene_.textures.size());
        scene_.textures.push_back(std::move(result));
        textures_.emplace(key, ref.texture);
        return std::optional<TextureRef>{ref};
    }

    Result<uint32_t> scene_image(int image, bool srgb, const JsonPointer& where) {
        const auto key = std::pair{image, srgb};
        if (const auto cached = images_.find(key); cached != images_.end()) return cached->second;
        const tinygltf::Image* source = element(model_.images, image);
        if (source == nullptr) return error(where, "image " + std::to_string(image) + " does not exist");
        const JsonPointer image_where = JsonPointer{} / "images" / static_cast<uint64_t>(image);
        if (const tinygltf::BufferView* view = element(model_.bufferViews, source->bufferView);
            view != nullptr && view->buffer >= 0 && unavailable_buffers_.count(static_cast<uint64_t>(view->buffer)) != 0) {
            return error(image_where, "reads buffer view " + std::to_string(source->bufferView) + " of buffer " +
                                          std::to_string(view->buffer) + ", whose data is unavailable");
        }
        auto decoded = decode_image(source->image, srgb ? rhi::Format::RGBA8Srgb : rhi::Format::RGBA8Unorm,
                                    options_.max_image_dimension);
        if (!decoded) return error(image_where, decoded.error().message);
        TextureImage result;
        result.source = static_cast<uint32_t>(image);
        if (!source->name.empty()) {
            result.name = source->name;
        } else if (!source->uri.empty() && source->uri.compare(0, 5, "data:") != 0) {
            result.name = source->uri;
        } else {
            result.name = "image " + std::to_string(image);
        }
        result.image = std::move(*decoded);
        const auto index = static_cast<uint32_t>(scene_.images.size());
        scene_.images.push_back(std::move(result));
        images_.emplace(key, index);
        return index;
    }

    // glTF sampler → rhi::SamplerDesc. Undefined filters mean "auto" in glTF; loom picks
    // trilinear filtering. Minification filters without mipmaps sample level 0 only.
    rhi::SamplerDesc sampler(int index) const {
        rhi::SamplerDesc desc;
        desc.address_u = rhi::AddressMode::Repeat;
        desc.address_v = rhi::AddressMode::Repeat;
        desc.address_w = rhi::AddressMode::Repeat;
        desc.mag_filter = rhi::Filter::Linear;
        desc.min_filter = rhi::Filter::Linear;
        desc.mipmap_filter = rhi::Filter::Linear;
        const tinygltf::Sampler* source = element(model_.samplers, index);
        if (source == nullptr) return desc;
        if (source->magFilter >= 0) desc.mag_filter = filter_of(source->magFilter);
        if (source->minFilter >= 0) {
            desc.min_filter = filter_of(source->minFilter);
            switch (source->minFilter) {
                case filter::kNearest:
                case filter::kLinear:
                    desc.mipmap_filter = rhi::Filter::Nearest;
                    desc.max_lod = 0.0f;
                    break;
                case filter::kNearestMipmapNearest:
                case filter::kLinearMipmapNearest: desc.mipmap_filter = rhi::Filter::Nearest; break;
                default: desc.mipmap_filter = rhi::Filter::Linear; break;
            }
        }
        desc.address_u = address_of(source->wrapS);
        desc.address_v = address_of(source->wrapT);
        return desc;
    }

    uint32_t default_material() {
        if (!default_material_) {
            Material material;
            material.name = "default";
            default_material_ = static_cast<uint32_t>(scene_.materials.size());
            scene_.materials.push_back(std::move(material));
        }
        return *default_material_;
    }

    // ---- meshes ------------------------------------------------------------------------------

    Status convert_meshes() {
        for (std::size_t m = 0; m < model_.meshes.size(); ++m) {
            const tinygltf::Mesh& source = model_.meshes[m];
            Mesh mesh;
            mesh.name = source.name.empty() ? "mesh " + std::to_string(m) : source.name;
            for (std::size_t p = 0; p < source.primitives.size(); ++p) {
                auto primitive = convert_primitive(source.primitives[p], JsonPointer{} / "meshes" / as_index(m) /
                                                                             "primitives" / as_index(p));
                if (!primitive) return primitive.take_error();
                if (*primitive) mesh.primitives.push_back(std::move(**primitive));
            }
            scene_.meshes.push_back(std::move(mesh));
        }
        return {};
    }

    // Reads a float attribute of `components` components into the vertices with `assign`.
    template <class Assign>
    Status read_attribute(const tinygltf::Primitive& source, const char* semantic, uint32_t components,
                          std::vector<Vertex>& vertices, Assign&& assign) {
        const auto found = source.attributes.find(semantic);
        if (found == source.attributes.end()) return {};
        auto values = reader_.read_floats(found->second, components);
        if (!values) return values.take_error();
        read_as_floats_.insert(found->second);
        if (values->size() != vertices.size() * components) {
            return error(JsonPointer{} / "accessors" / static_cast<uint64_t>(std::max(found->second, 0)),
                         std::string(semantic) + " count differs from POSITION's");
        }
        for (std::size_t v = 0; v < vertices.size(); ++v) assign(vertices[v], values->data() + v * components);
        return {};
    }

    // What the specification requires of vertex values the importer reads (normals and tangents
    // of unit length, a tangent's w of 1 or -1, colours in 0..1), made so with one warning per
    // attribute naming the first vertex at fault: the picture is the one the file means, and
    // the file still loads.
    void fix_vertex_values(std::vector<Vertex>& vertices, bool normals, bool tangents, bool colors,
                           const JsonPointer& where) {
        const auto off_unit = [](const glm::vec3& v) {
            return std::abs(static_cast<double>(glm::length(v)) - 1.0) > kUnitVectorTolerance;
        };
        const auto first = [&](auto&& faulty) -> std::optional<std::size_t> {
            for (std::size_t v = 0; v < vertices.size(); ++v) {
                if (faulty(vertices[v])) return v;
            }
            return std::nullopt;
        };
        if (normals) {
            if (const auto v = first([&](const Vertex& x) { return off_unit(x.normal); })) {
                warn(where / "NORMAL", "vertex " + std::to_string(*v) + "'s normal has length " +
                                           std::to_string(glm::length(vertices[*v].normal)) + ", not 1; normals are normalised");
                for (Vertex& x : vertices) {
                    if (glm::length(x.normal) > 0.0f) x.normal = glm::normalize(x.normal);
                }
            }
        }
        if (tangents) {
            if (const auto v = first([&](const Vertex& x) { return off_unit(glm::vec3(x.tangent)); })) {
                warn(where / "TANGENT", "vertex " + std::to_string(*v) + "'s tangent has length " +
                                            std::to_string(glm::length(glm::vec3(vertices[*v].tangent))) +
                                            ", not 1; tangents are normalised");
                for (Vertex& x : vertices) {
                    const glm::vec3 t(x.tangent);
                    if (glm::length(t) > 0.0f) x.tangent = glm::vec4(glm::normalize(t), x.tangent.w);
                }
            }
            if (const auto v = first([](const Vertex& x) { return x.tangent.w != 1.0f && x.tangent.w != -1.0f; })) {
                warn(where / "TANGENT", "vertex " + std::to_string(*v) + "'s tangent has w = " +
                                            std::to_string(vertices[*v].tangent.w) + ", not 1 or -1; w becomes its sign");
                for (Vertex& x : vertices) x.tangent.w = x.tangent.w < 0.0f ? -1.0f : 1.0f;
            }
        }
        if (colors) {
            const auto outside = [](const Vertex& x) {
                return glm::any(glm::lessThan(x.color, glm::vec4(0.0f))) || glm::any(glm::greaterThan(x.color, glm::vec4(1.0f)));
            };
            if (const auto v = first(outside)) {
                warn(where / "COLOR_0", "vertex " + std::to_string(*v) + "'s colour is outside 0..1; colours are clamped");
                for (Vertex& x : vertices) x.color = glm::clamp(x.color, glm::vec4(0.0f), glm::vec4(1.0f));
            }
        }
    }

    Result<std::optional<Primitive>> convert_primitive(const tinygltf::Primitive& source, const JsonPointer& where) {
        const int mode = source.mode < 0 ? TINYGLTF_MODE_TRIANGLES : source.mode;
        if (mode < TINYGLTF_MODE_TRIANGLES || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
            static constexpr const char* kNames[] = {"points", "lines", "line loop", "line strip"};
            warn(where / "mode", std::string("mode ") + std::to_string(mode) + " (" +
                                     (mode >= 0 && mode < 4 ? kNames[mode] : "unknown") +
                                     ") is not supported; the primitive is skipped");
            return std::optional<Primitive>{};
        }
        const auto position = source.attributes.find("POSITION");
        if (position == source.attributes.end()) {
            warn(where / "attributes", "primitive has no POSITION; it is skipped");
            return std::optional<Primitive>{};
        }
        for (const auto& [semantic, accessor] : source.attributes) {
            const bool extra_uv = semantic.rfind("TEXCOORD_", 0) == 0 && semantic != "TEXCOORD_0" && semantic != "TEXCOORD_1";
            const bool extra_color = semantic.rfind("COLOR_", 0) == 0 && semantic != "COLOR_0";
            const bool extra_skin = (semantic.rfind("JOINTS_", 0) == 0 && semantic != "JOINTS_0") ||
                                    (semantic.rfind("WEIGHTS_", 0) == 0 && semantic != "WEIGHTS_0");
            if (extra_uv || extra_color) warn(where / "attributes" / semantic, semantic + " is not imported");
            if (extra_skin) {
                warn(where / "attributes" / semantic, semantic + " is not imported (four joints per vertex are: JOINTS_0 and WEIGHTS_0)");
            }
        }

        Primitive primitive;
        auto positions = reader_.read_floats(position->second, 3);
        if (!positions) return positions.take_error();
        read_as_floats_.insert(position->second);
        const std::size_t vertex_count = positions->size() / 3;
        primitive.vertices.resize(vertex_count);
        for (std::size_t v = 0; v < vertex_count; ++v) {
            const float* p = positions->data() + v * 3;
            primitive.vertices[v].position = glm::vec3(p[0], p[1], p[2]);
            primitive.bounds.extend(primitive.vertices[v].position);
        }
        const auto has = [&](const char* semantic) { return source.attributes.count(semantic) != 0; };
        LOOM_TRY(read_attribute(source, "NORMAL", 3, primitive.vertices,
                                [](Vertex& v, const float* x) { v.normal = glm::vec3(x[0], x[1], x[2]); }));
        LOOM_TRY(read_attribute(source, "TANGENT", 4, primitive.vertices,
                                [](Vertex& v, const float* x) { v.tangent = glm::vec4(x[0], x[1], x[2], x[3]); }));
        LOOM_TRY(read_attribute(source, "TEXCOORD_0", 2, primitive.vertices,
                                [](Vertex& v, const float* x) { v.uv0 = glm::vec2(x[0], x[1]); }));
        LOOM_TRY(read_attribute(source, "TEXCOORD_1", 2, primitive.vertices,
                                [](Vertex& v, const float* x) { v.uv1 = glm::vec2(x[0], x[1]); }));
        if (has("COLOR_0")) {
            const uint32_t components = reader_.components(source.attributes.at("COLOR_0"));
            if (components == 3) {
                LOOM_TRY(read_attribute(source, "COLOR_0", 3, primitive.vertices,
                                        [](Vertex& v, const float* x) { v.color = glm::vec4(x[0], x[1], x[2], 1.0f); }));
            } else {
                LOOM_TRY(read_attribute(source, "COLOR_0", 4, primitive.vertices,
                                        [](Vertex& v, const float* x) { v.color = glm::vec4(x[0], x[1], x[2], x[3]); }));
            }
        }
        fix_vertex_values(primitive.vertices, has("NORMAL"), has("TANGENT"), has("COLOR_0"), where / "attributes");
        if (has("JOINTS_0") && has("WEIGHTS_0")) read_skin_influences(source, primitive, where / "attributes");
        if (has("NORMAL")) primitive.from_file |= kAttributeNormal;
        if (has("TANGENT")) primitive.from_file |= kAttributeTangent;
        if (has("TEXCOORD_0")) primitive.from_file |= kAttributeUv0;
        if (has("TEXCOORD_1")) primitive.from_file |= kAttributeUv1;
        if (has("COLOR_0")) primitive.from_file |= kAttributeColor;

        // Indices: from the file (every value checked against the vertex count) or implicit.
        std::vector<uint32_t> sequence;
        if (source.indices >= 0) {
            auto indices = reader_.read_indices(source.indices);
            if (!indices) return indices.take_error();
            sequence = std::move(*indices);
            for (std::size_t i = 0; i < sequence.size(); ++i) {
                // The largest value of the index type restarts strips on GPUs; glTF forbids it.
                const uint64_t restart = (uint64_t{1} << (8 * component_size(model_.accessors[static_cast<std::size_t>(source.indices)].componentType))) - 1;
                if (sequence[i] == restart) {
                    return error(where / "indices", "index " + std::to_string(sequence[i]) + " (element " + std::to_string(i) +
                                                        ") is the primitive restart value, which glTF index data must not contain");
                }
                if (sequence[i] >= vertex_count) {
                    return error(where / "indices", "index " + std::to_string(sequence[i]) + " (element " + std::to_string(i) +
                                                        ") is past the vertex count " + std::to_string(vertex_count));
                }
            }
        } else {
            sequence.resize(vertex_count);
            for (std::size_t i = 0; i < vertex_count; ++i) sequence[i] = static_cast<uint32_t>(i);
        }
        const auto topology = static_cast<Topology>(mode);
        if (topology == Topology::Triangles && sequence.size() % 3 != 0) {
            warn(source.indices >= 0 ? where / "indices" : where, std::to_string(sequence.size()) +
                                                                      " vertices do not form whole triangles; the last " +
                                                                      std::to_string(sequence.size() % 3) + " are ignored");
        }
        primitive.indices = triangle_list(topology, sequence);

        primitive.material = source.material >= 0 ? static_cast<uint32_t>(source.material) : default_material();
        if (primitive.material >= scene_.materials.size()) return error(where / "material", "material does not exist");
        const Material& material = scene_.materials[primitive.material];
        // (A material sampling a UV set the primitive lacks was reported by the validator.)

        if (!(primitive.from_file & kAttributeNormal)) {
            if (options_.normals == NormalGeneration::Flat) {
                generate_flat_normals(primitive);
            } else {
                generate_smooth_normals(primitive);
            }
        }
        const bool wants_tangents = options_.tangents == TangentGeneration::Always ||
                                    (options_.tangents == TangentGeneration::WhenNormalMapped && material.normal_texture);
        if (wants_tangents && !(primitive.from_file & kAttributeTangent)) {
            generate_tangents(primitive, material.normal_texture ? material.normal_texture->uv_set : 0);
        }
        return std::optional<Primitive>{std::move(primitive)};
    }

    // JOINTS_0 and WEIGHTS_0 as the primitive's skin influences, one per vertex. Data of another
    // shape (the validator reported it) leaves the primitive unskinned, with a warning.
    void read_skin_influences(const tinygltf::Primitive& source, Primitive& primitive, const JsonPointer& where) {
        const int joints_accessor = source.attributes.at("JOINTS_0");
        const int weights_accessor = source.attributes.at("WEIGHTS_0");
        auto joints = reader_.components(joints_accessor) == 4 ? reader_.read_stored(joints_accessor)
                                                               : Result<std::vector<double>>(std::vector<double>{});
        auto weights = reader_.components(weights_accessor) == 4 ? reader_.read_floats(weights_accessor, 4)
                                                                 : Result<std::vector<float>>(std::vector<float>{});
        const std::size_t count = primitive.vertices.size();
        if (!joints || !weights || joints->size() != count * 4 || weights->size() != count * 4) {
            warn(where / "JOINTS_0", "JOINTS_0 and WEIGHTS_0 are not four values per vertex; the primitive is not skinned");
            return;
        }
        primitive.skin.resize(count);
        for (std::size_t v = 0; v < count; ++v) {
            for (std::size_t c = 0; c < 4; ++c) {
                const double joint = (*joints)[v * 4 + c];
                primitive.skin[v].joints[static_cast<int>(c)] = joint >= 0.0 && joint < 4294967296.0 ? static_cast<uint32_t>(joint) : 0u;
                primitive.skin[v].weights[static_cast<int>(c)] = (*weights)[v * 4 + c];
            }
        }
    }

    // ---- nodes and the flattened scene ---------------------------------------------------

    Status convert_nodes() {
        const std::size_t count = model_.nodes.size();
        scene_.nodes.resize(count);
        for (std::size_t n = 0; n < count; ++n) {
            const tinygltf::Node& source = model_.nodes[n];
            Node& node = scene_.nodes[n];
            node.name = source.name.empty() ? "node " + std::to_string(n) : source.name;
            set_transform(source, node);
            if (source.mesh >= 0) node.mesh = static_cast<uint32_t>(source.mesh);
            if (source.camera >= 0) node.camera = static_cast<uint32_t>(source.camera);
            if (source.skin >= 0) node.skin = static_cast<uint32_t>(source.skin);
            for (const int child : source.children) {
                if (child < 0 || static_cast<std::size_t>(child) >= count) {
                    return error(JsonPointer{} / "nodes" / as_index(n) / "children", "child node does not exist");
                }
                node.children.push_back(static_cast<uint32_t>(child));
            }
        }
        for (std::size_t n = 0; n < count; ++n) {
            for (const uint32_t child : scene_.nodes[n].children) {
                if (scene_.nodes[child].parent) {
                    return error(JsonPointer{} / "nodes" / as_index(n) / "children", "node has several parents");
                }
                scene_.nodes[child].parent = static_cast<uint32_t>(n);
            }
        }
        std::vector<bool> every_node(count, true);
        if (update_world_matrices(scene_.nodes, every_node) != count) {
            return error(JsonPointer{} / "nodes", "the node hierarchy has a cycle");
        }
        return {};
    }

    Result<std::vector<uint32_t>> scene_roots() const {
        const tinygltf::Scene* chosen = nullptr;
        if (options_.scene) {
            chosen = element(model_.scenes, static_cast<int>(std::min<uint32_t>(*options_.scene, INT32_MAX)));
            if (chosen == nullptr) {
                return make_error(ErrorCode::InvalidArgument,
                                  file_label_ + ": LoadOptions::scene is " + std::to_string(*options_.scene) +
                                      ", but the file has " + std::to_string(model_.scenes.size()) + " scenes");
            }
        } else if (model_.defaultScene >= 0) {
            chosen = element(model_.scenes, model_.defaultScene);
        } else if (!model_.scenes.empty()) {
            chosen = &model_.scenes.front();
        }
        std::vector<uint32_t> roots;
        if (chosen != nullptr) {
            for (const int node : chosen->nodes) {
                if (node < 0 || static_cast<std::size_t>(node) >= scene_.nodes.size()) {
                    return error(JsonPointer{} / "scenes", "scene node does not exist");
                }
                roots.push_back(static_cast<uint32_t>(node));
            }
        } else {
            for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
                if (!scene_.nodes[n].parent) roots.push_back(static_cast<uint32_t>(n));
            }
        }
        return roots;
    }

    Camera camera_instance(const Node& node) const {
        Camera camera;
        const tinygltf::Camera* source = element(model_.cameras, static_cast<int>(*node.camera));
        camera.world = node.world;
        if (source == nullptr) return camera;
        camera.name = !source->name.empty() ? source->name : node.name;
        if (source->type == "orthographic") {
            OrthographicProjection ortho;
            ortho.xmag = static_cast<float>(source->orthographic.xmag);
            ortho.ymag = static_cast<float>(source->orthographic.ymag);
            ortho.znear = static_cast<float>(source->orthographic.znear);
            ortho.zfar = static_cast<float>(source->orthographic.zfar);
            camera.projection = ortho;
        } else {
            PerspectiveProjection perspective;
            perspective.yfov = static_cast<float>(source->perspective.yfov);
            perspective.znear = static_cast<float>(source->perspective.znear);
            // tinygltf stores an absent aspect ratio / far plane as 0.
            if (source->perspective.aspectRatio > 0.0) perspective.aspect_ratio = static_cast<float>(source->perspective.aspectRatio);
            if (source->perspective.zfar > 0.0) perspective.zfar = static_cast<float>(source->perspective.zfar);
            camera.projection = perspective;
        }
        return camera;
    }

    // Skins: their joints and inverse bind matrices (the identity where the file gives none, or
    // gives matrices the validator reported: fewer than joints, or not MAT4 floats). A matrix
    // whose last row is not 0 0 0 1 is kept, with a warning.
    Status convert_skins() {
        for (std::size_t s = 0; s < model_.skins.size(); ++s) {
            const tinygltf::Skin& source = model_.skins[s];
            const JsonPointer where = JsonPointer{} / "skins" / as_index(s);
            Skin skin;
            skin.name = source.name.empty() ? "skin " + std::to_string(s) : source.name;
            for (std::size_t j = 0; j < source.joints.size(); ++j) {
                const int joint = source.joints[j];
                if (joint < 0 || static_cast<std::size_t>(joint) >= scene_.nodes.size()) {
                    return error(where / "joints" / as_index(j), "joint node does not exist");
                }
                skin.joints.push_back(static_cast<uint32_t>(joint));
            }
            skin.inverse_bind_matrices.assign(skin.joints.size(), glm::mat4(1.0f));
            if (source.inverseBindMatrices >= 0) {
                const auto matrices = read_unused(source.inverseBindMatrices, 16, where / "inverseBindMatrices");
                if (matrices) warn_unless_affine(*matrices, where / "inverseBindMatrices");
                if (matrices && matrices->size() >= skin.joints.size() * 16) {
                    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
                        skin.inverse_bind_matrices[j] = glm::make_mat4(matrices->data() + j * 16);  // column-major, as glTF
                    }
                } else {
                    warn(where / "inverseBindMatrices", "not one MAT4 per joint; the joints' inverse bind matrices are the identity");
                }
            }
            scene_.skins.push_back(std::move(skin));
        }
        for (std::size_t n = 0; n < scene_.nodes.size(); ++n) {
            const std::optional<uint32_t> skin = scene_.nodes[n].skin;
            if (skin && *skin >= scene_.skins.size()) return error(JsonPointer{} / "nodes" / as_index(n) / "skin", "skin does not exist");
        }
        return {};
    }

    // A warning at `where` naming the first of the column-major MAT4s in `matrices` whose last
    // row is not 0 0 0 1.
    void warn_unless_affine(const std::vector<float>& matrices, const JsonPointer& where) {
        for (std::size_t m = 0; m * 16 + 15 < matrices.size(); ++m) {
            const float* column_major = matrices.data() + m * 16;
            if (column_major[3] != 0.0f || column_major[7] != 0.0f || column_major[11] != 0.0f || column_major[15] != 1.0f) {
                warn(where, "matrix " + std::to_string(m) + " is not affine (its last row must be 0 0 0 1)");
                return;
            }
        }
    }

    Status flatten_scene() {
        auto roots = scene_roots();
        if (!roots) return roots.take_error();
        // Depth-first in file order: a node, then its children in the order they are listed.
        std::vector<uint32_t> stack(roots->rbegin(), roots->rend());
        while (!stack.empty()) {
            const uint32_t n = stack.back();
            stack.pop_back();
            const Node& node = scene_.nodes[n];
            if (node.mesh) {
                if (*node.mesh >= scene_.meshes.size()) return error(JsonPointer{} / "nodes" / uint64_t{n} / "mesh", "mesh does not exist");
                const Mesh& mesh = scene_.meshes[*node.mesh];
                for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
                    const Primitive& primitive = mesh.primitives[p];
                    DrawItem item;
                    item.node = n;
                    item.mesh = *node.mesh;
                    item.primitive = static_cast<uint32_t>(p);
                    item.material = primitive.material;
                    if (node.skin && !primitive.skin.empty()) {
                        item.skin = node.skin;
                        place_skinned_draw_item(item, scene_, primitive);
                    } else {
                        place_draw_item(item, node, primitive);
                    }
                    scene_.bounds.extend(item.world_bounds);
                    scene_.draw_items.push_back(std::move(item));
                }
            }
            if (node.camera) scene_.cameras.push_back(camera_instance(node));
            for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.push_back(*child);
        }
        return {};
    }

    const tinygltf::Model& model_;
    const std::string& file_label_;
    const LoadOptions& options_;
    const std::set<uint64_t>& unavailable_buffers_;  // buffers without data (see ValidationOutput)
    std::vector<std::string>& warnings_;
    AccessorReader reader_;
    Scene scene_;
    std::map<std::pair<int, bool>, uint32_t> textures_;  // (glTF texture, sRGB) → Scene::textures
    std::set<int> read_as_floats_;  // accessors the conversion read with read_floats (so finite)
    std::map<std::pair<int, bool>, uint32_t> images_;    // (glTF image, sRGB) → Scene::images
    std::optional<uint32_t> default_material_;
};

}  // namespace

Result<Scene> convert_model(const tinygltf::Model& model, const std::string& file_label, const LoadOptions& options,
                            const std::set<uint64_t>& unavailable_buffers, std::vector<std::string>& warnings) {
    Converter converter(model, file_label, options, unavailable_buffers, warnings);
    return converter.run();
}

}  // namespace loom::gltf::detail
