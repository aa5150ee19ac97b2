#pragma once
// Reading accessor data out of a loaded tinygltf model: every component type, normalised
// integers, byte strides and sparse substitution, with every byte range checked against the
// data actually loaded (the validator checked the declared sizes; this checks the real ones).

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "json_pointer.hpp"
#include "loom/rhi/result.hpp"

namespace loom::gltf::detail {


/// Reads accessors of one model; errors name the file and the accessor's JSON pointer.
class AccessorReader {
public:
    AccessorReader(const tinygltf::Model& model, std::string file_label, uint64_t max_elements,
                   const std::set<uint64_t>& unavailable_buffers)
        : model_(model), file_label_(std::move(file_label)), max_elements_(max_elements),
          unavailable_buffers_(unavailable_buffers) {}

    /// Accessor `index` as floats, `components` per element (the accessor's type must have
    /// exactly that many): normalised integers mapped to [0,1] / [-1,1] as glTF defines,
    /// other integers converted, sparse values substituted. Non-finite values are an error.
    [[nodiscard]] Result<std::vector<float>> read_floats(int index, uint32_t components) const;

    /// Accessor `index`'s components as stored (normalised integers not mapped, non-finite
    /// floats kept), for checks of values the importer does not read; every type but matrices
    /// whose columns are padded (MAT2/MAT3 of bytes or shorts).
    [[nodiscard]] Result<std::vector<double>> read_stored(int index) const;

    /// Index accessor `index` (SCALAR, unsigned integer components) as u32 values.
    [[nodiscard]] Result<std::vector<uint32_t>> read_indices(int index) const;

    /// Number of components of accessor `index`'s type (1 for SCALAR ... 16 for MAT4), 0 if
    /// the accessor does not exist.
    [[nodiscard]] uint32_t components(int index) const;

private:
    template <class T>
    Result<std::vector<T>> read(int index, uint32_t components, bool as_stored = false) const;

    Error error(const JsonPointer& where, const std::string& what) const;

    const tinygltf::Model& model_;
    std::string file_label_;
    uint64_t max_elements_;
    const std::set<uint64_t>& unavailable_buffers_;  ///< buffers without data (see ValidationOutput)
};

}  // namespace loom::gltf::detail
