#pragma once
// glTF 2.0 enumeration values, the sizes derived from them and the validator's tolerances,
// shared by the validator and the converter.

#include <cstdint>
#include <string_view>

namespace loom::gltf::detail {


namespace component_type {
inline constexpr int kByte = 5120;
inline constexpr int kUnsignedByte = 5121;
inline constexpr int kShort = 5122;
inline constexpr int kUnsignedShort = 5123;
inline constexpr int kUnsignedInt = 5125;
inline constexpr int kFloat = 5126;
}  // namespace component_type

namespace filter {
inline constexpr int kNearest = 9728;
inline constexpr int kLinear = 9729;
inline constexpr int kNearestMipmapNearest = 9984;
inline constexpr int kLinearMipmapNearest = 9985;
inline constexpr int kNearestMipmapLinear = 9986;
inline constexpr int kLinearMipmapLinear = 9987;
}  // namespace filter

namespace wrap {
inline constexpr int kClampToEdge = 33071;
inline constexpr int kMirroredRepeat = 33648;
inline constexpr int kRepeat = 10497;
}  // namespace wrap

/// Bytes of one component of `type`, or 0 for an invalid component type.
[[nodiscard]] constexpr uint32_t component_size(int type) {
    switch (type) {
        case component_type::kByte:
        case component_type::kUnsignedByte: return 1;
        case component_type::kShort:
        case component_type::kUnsignedShort: return 2;
        case component_type::kUnsignedInt:
        case component_type::kFloat: return 4;
        default: return 0;
    }
}

/// The name glTF gives a component type ("UNSIGNED_SHORT"), for messages.
[[nodiscard]] constexpr std::string_view component_type_name(int type) {
    switch (type) {
        case component_type::kByte: return "BYTE";
        case component_type::kUnsignedByte: return "UNSIGNED_BYTE";
        case component_type::kShort: return "SHORT";
        case component_type::kUnsignedShort: return "UNSIGNED_SHORT";
        case component_type::kUnsignedInt: return "UNSIGNED_INT";
        case component_type::kFloat: return "FLOAT";
        default: return "invalid";
    }
}

/// An accessor `type` ("VEC3"): its component count and, for matrices, its column count.
struct ElementType {
    std::string_view name;
    uint32_t components = 0;
    uint32_t columns = 0;  ///< 0 for scalars and vectors
};

/// The element type named `name`, or one with components == 0 for an invalid name.
[[nodiscard]] constexpr ElementType element_type(std::string_view name) {
    constexpr ElementType kTypes[] = {{"SCALAR", 1, 0}, {"VEC2", 2, 0}, {"VEC3", 3, 0}, {"VEC4", 4, 0},
                                      {"MAT2", 4, 2},   {"MAT3", 9, 3}, {"MAT4", 16, 4}};
    for (const ElementType& type : kTypes) {
        if (type.name == name) return type;
    }
    return {};
}

/// Bytes of one element, including the padding glTF requires at the end of each matrix column
/// so that every column starts at a multiple of 4 bytes.
[[nodiscard]] constexpr uint32_t element_size(const ElementType& type, int component) {
    const uint32_t size = component_size(component);
    if (type.columns == 0) return type.components * size;
    const uint32_t rows = type.components / type.columns;
    const uint32_t column_bytes = (rows * size + 3u) / 4u * 4u;
    return column_bytes * type.columns;
}

/// Bytes the last element of an accessor needs: the element without the padding after its
/// last matrix column (nothing follows it), e.g. 6 for a MAT2 of bytes, 11 for a MAT3.
[[nodiscard]] constexpr uint32_t last_element_size(const ElementType& type, int component) {
    if (type.columns == 0) return element_size(type, component);
    const uint32_t rows = type.components / type.columns;
    return element_size(type, component) / type.columns * (type.columns - 1) + rows * component_size(component);
}

/// How far from 1 the length of a unit quaternion (node rotations, rotation keyframes) or of a
/// unit vector (normals, tangents) may be: a little more than the error of 8-bit signed
/// quantisation, as glTF-Validator allows.
inline constexpr double kUnitQuaternionTolerance = 0.00769;
inline constexpr double kUnitVectorTolerance = 0.00674;

}  // namespace loom::gltf::detail
