#include "accessor_reader.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <span>

#include "checked_math.hpp"
#include "gltf_constants.hpp"
#include "gltf_validate.hpp"

namespace loom::gltf::detail {

using namespace loom::scene;  // the importer builds the scene model's types

namespace {

static_assert(std::endian::native == std::endian::little, "glTF data is little-endian; big-endian hosts need byte swaps");

template <class T>
T load(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
}

// One component, converted as glTF defines for normalised integers (KHR_mesh_quantization
// and the core specification use the same rules).
double load_component(const unsigned char* bytes, int type, bool normalized) {
    switch (type) {
        case component_type::kByte: {
            const double value = load<int8_t>(bytes);
            return normalized ? std::max(value / 127.0, -1.0) : value;
        }
        case component_type::kUnsignedByte: {
            const double value = load<uint8_t>(bytes);
            return normalized ? value / 255.0 : value;
        }
        case component_type::kShort: {
            const double value = load<int16_t>(bytes);
            return normalized ? std::max(value / 32767.0, -1.0) : value;
        }
        case component_type::kUnsignedShort: {
            const double value = load<uint16_t>(bytes);
            return normalized ? value / 65535.0 : value;
        }
        case component_type::kUnsignedInt: {
            const double value = load<uint32_t>(bytes);
            return normalized ? value / 4294967295.0 : value;
        }
        case component_type::kFloat: return load<float>(bytes);
        default: return 0.0;
    }
}

uint32_t type_components(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

// The bytes of buffer view `view` as actually loaded, or an empty span when the view or its
// buffer is missing or does not fit.
std::span<const unsigned char> view_bytes(const tinygltf::Model& model, int view) {
    if (view < 0 || static_cast<std::size_t>(view) >= model.bufferViews.size()) return {};
    const tinygltf::BufferView& buffer_view = model.bufferViews[static_cast<std::size_t>(view)];
    if (buffer_view.buffer < 0 || static_cast<std::size_t>(buffer_view.buffer) >= model.buffers.size()) return {};
    const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(buffer_view.buffer)].data;
    if (!range_fits(buffer_view.byteOffset, buffer_view.byteLength, data.size())) return {};
    return std::span<const unsigned char>(data).subspan(buffer_view.byteOffset, buffer_view.byteLength);
}

template <class T>
T convert(double value) {
    return static_cast<T>(value);
}

}  // namespace

Error AccessorReader::error(const JsonPointer& where, const std::string& what) const {
    return make_error(ErrorCode::Parse, located_message(file_label_, where.str(), what));
}

uint32_t AccessorReader::components(int index) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) return 0;
    return type_components(model_.accessors[static_cast<std::size_t>(index)].type);
}

template <class T>
Result<std::vector<T>> AccessorReader::read(int index, uint32_t components, bool as_stored) const {
    const JsonPointer where = JsonPointer{} / "accessors" / static_cast<uint64_t>(std::max(index, 0));
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size()) {
        return error(where, "accessor " + std::to_string(index) + " does not exist");
    }
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
    const uint32_t size = component_size(accessor.componentType);
    if (size == 0 || type_components(accessor.type) != components) {
        return error(where, "accessor has an unexpected type or component type");
    }
    if (accessor.count > max_elements_) return error(where, "accessor count exceeds the importer's limit");
    const int sparse_views[] = {accessor.sparse.isSparse ? accessor.sparse.indices.bufferView : -1,
                                accessor.sparse.isSparse ? accessor.sparse.values.bufferView : -1};
    for (const int view : {accessor.bufferView, sparse_views[0], sparse_views[1]}) {
        if (view < 0 || static_cast<std::size_t>(view) >= model_.bufferViews.size()) continue;
        const int buffer = model_.bufferViews[static_cast<std::size_t>(view)].buffer;
        if (buffer >= 0 && unavailable_buffers_.count(static_cast<uint64_t>(buffer)) != 0) {
            return error(where, "reads buffer view " + std::to_string(view) + " of buffer " + std::to_string(buffer) +
                                    ", whose data is unavailable (no uri outside a GLB, or a URI with a scheme)");
        }
    }
    const std::optional<uint64_t> value_count = checked_mul(accessor.count, components);
    if (!value_count) return error(where, "accessor count overflows");
    const uint32_t element = size * components;  // scalars and vectors only: no column padding

    std::vector<T> values(static_cast<std::size_t>(*value_count), T{});
    auto store = [&](uint64_t element_index, const unsigned char* bytes) -> Status {
        for (uint32_t c = 0; c < components; ++c) {
            const double value =
                load_component(bytes + uint64_t{c} * size, accessor.componentType, accessor.normalized && !as_stored);
            if (!as_stored && !std::isfinite(value)) {
                return error(where, "element " + std::to_string(element_index) + " component " + std::to_string(c) +
                                        " is not a finite number");
            }
            values[static_cast<std::size_t>(element_index * components + c)] = convert<T>(value);
        }
        return {};
    };

    if (accessor.bufferView >= 0) {
        const std::span<const unsigned char> bytes = view_bytes(model_, accessor.bufferView);
        if (bytes.empty()) return error(where, "buffer view " + std::to_string(accessor.bufferView) + " has no loaded data");
        const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
        const uint64_t stride = view.byteStride != 0 ? view.byteStride : element;
        if (stride < element) return error(where, "byteStride is smaller than the element size");
        if (!range_fits(accessor.byteOffset, strided_span(accessor.count, stride, element).value_or(UINT64_MAX),
                        bytes.size())) {
            return error(where, "accessor does not fit in its buffer view's loaded data");
        }
        for (uint64_t e = 0; e < accessor.count; ++e) {
            LOOM_TRY(store(e, bytes.data() + accessor.byteOffset + e * stride));
        }
    }

    if (accessor.sparse.isSparse) {
        const JsonPointer sparse_where = where / "sparse";
        const auto& sparse = accessor.sparse;
        if (sparse.count < 1 || static_cast<uint64_t>(sparse.count) > accessor.count) {
            return error(sparse_where / "count", "sparse count is out of range");
        }
        const uint64_t count = static_cast<uint64_t>(sparse.count);
        const uint32_t index_size = component_size(sparse.indices.componentType);
        const std::span<const unsigned char> index_bytes = view_bytes(model_, sparse.indices.bufferView);
        const std::span<const unsigned char> value_bytes = view_bytes(model_, sparse.values.bufferView);
        if (index_size == 0 || sparse.indices.byteOffset < 0 ||
            !range_fits(static_cast<uint64_t>(sparse.indices.byteOffset), count * index_size, index_bytes.size())) {
            return error(sparse_where / "indices", "sparse indices do not fit in their buffer view's loaded data");
        }
        if (sparse.values.byteOffset < 0 ||
            !range_fits(static_cast<uint64_t>(sparse.values.byteOffset), count * element, value_bytes.size())) {
            return error(sparse_where / "values", "sparse values do not fit in their buffer view's loaded data");
        }
        const unsigned char* index_base = index_bytes.data() + sparse.indices.byteOffset;
        const unsigned char* value_base = value_bytes.data() + sparse.values.byteOffset;
        uint64_t previous = 0;
        for (uint64_t k = 0; k < count; ++k) {
            const auto target = static_cast<uint64_t>(load_component(index_base + k * index_size, sparse.indices.componentType, false));
            if (target >= accessor.count) {
                return error(sparse_where / "indices", "sparse index " + std::to_string(target) + " (element " +
                                                           std::to_string(k) + ") is past the accessor's count " +
                                                           std::to_string(accessor.count));
            }
            if (k > 0 && target <= previous) {
                return error(sparse_where / "indices", "sparse indices are not strictly increasing (element " +
                                                           std::to_string(k) + " is " + std::to_string(target) +
                                                           ", after " + std::to_string(previous) + ")");
            }
            previous = target;
            LOOM_TRY(store(target, value_base + k * element));
        }
    }
    return values;
}

Result<std::vector<float>> AccessorReader::read_floats(int index, uint32_t components) const {
    return read<float>(index, components);
}

Result<std::vector<double>> AccessorReader::read_stored(int index) const {
    const uint32_t count = components(index);
    if (count == 0) return error(JsonPointer{} / "accessors" / static_cast<uint64_t>(std::max(index, 0)), "accessor does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
    const bool padded_columns = (accessor.type == TINYGLTF_TYPE_MAT2 || accessor.type == TINYGLTF_TYPE_MAT3) &&
                                component_size(accessor.componentType) < 4;
    if (padded_columns) return error(JsonPointer{} / "accessors" / static_cast<uint64_t>(index), "padded matrix columns are not read");
    return read<double>(index, count, true);
}

Result<std::vector<uint32_t>> AccessorReader::read_indices(int index) const {
    if (index >= 0 && static_cast<std::size_t>(index) < model_.accessors.size()) {
        const int type = model_.accessors[static_cast<std::size_t>(index)].componentType;
        if (type != component_type::kUnsignedByte && type != component_type::kUnsignedShort &&
            type != component_type::kUnsignedInt) {
            return error(JsonPointer{} / "accessors" / static_cast<uint64_t>(index), "index accessor is not unsigned");
        }
    }
    return read<uint32_t>(index, 1);
}

}  // namespace loom::gltf::detail
