#pragma once
// Shared vertex and index buffers: the vertex and index data of many meshes sub-allocated in a
// few large buffers, so that objects with different meshes are drawn without binding other
// buffers (each draw names its range: first index and base vertex).
//
// Vertex data is kept per vertex layout: one VertexPool per distinct list of per-vertex buffer
// layouts, with one buffer per slot — one buffer for an interleaved layout, several for separate
// streams — and one allocator counting vertices, so that a mesh starts at the same vertex in
// every slot and one base vertex serves all. Indices of every mesh share one IndexPool. Freed
// ranges are reused; a pool that is full grows into larger buffers (the meshes keep their data
// on the CPU and are written into the new buffers at the same ranges).

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "loom/passes/range_allocator.hpp"
#include "loom/passes/uniform_set.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::passes {

struct MeshVertex;

/// A mesh's vertices (one stream of bytes per vertex buffer slot) and its triangle-list
/// indices, kept on the CPU: submitted objects share it, the scene uploads it into the shared
/// buffers once, and grown buffers are refilled from it.
class Geometry {
public:
    /// Checks and wraps the data. Errors (InvalidArgument, naming the geometry): no vertices or
    /// indices, an index count that is not a multiple of 3, an index out of range, a stream
    /// whose size is not vertex_count * its layout's stride, a per-instance layout.
    static Result<std::shared_ptr<const Geometry>> create(std::string name, std::vector<rhi::VertexBufferLayout> layouts,
                                                          std::vector<std::vector<std::byte>> streams,
                                                          uint32_t vertex_count, std::vector<uint32_t> indices);

    [[nodiscard]] const std::string& name() const { return name_; }
    /// Unique per geometry, increasing in creation order (sorting and state keys use it).
    [[nodiscard]] uint64_t id() const { return id_; }
    [[nodiscard]] const std::vector<rhi::VertexBufferLayout>& layouts() const { return layouts_; }
    [[nodiscard]] const std::vector<std::vector<std::byte>>& streams() const { return streams_; }
    [[nodiscard]] uint32_t vertex_count() const { return vertex_count_; }
    [[nodiscard]] const std::vector<uint32_t>& indices() const { return indices_; }

private:
    Geometry() = default;

    std::string name_;
    uint64_t id_ = 0;
    std::vector<rhi::VertexBufferLayout> layouts_;
    std::vector<std::vector<std::byte>> streams_;
    uint32_t vertex_count_ = 0;
    std::vector<uint32_t> indices_;
};

/// A mesh of MeshVertex (interleaved, mesh_vertex_layout()) and u32 triangle-list indices.
Result<std::shared_ptr<const Geometry>> make_mesh_geometry(std::string name, std::span<const MeshVertex> vertices,
                                                           std::span<const uint32_t> indices);

/// Equal vertex buffer layouts (stride, step, attributes).
bool same_vertex_layouts(std::span<const rhi::VertexBufferLayout> a, std::span<const rhi::VertexBufferLayout> b);

/// Where a placed geometry lives.
struct GeometryPlacement {
    uint32_t vertex_pool = 0;   ///< index of its VertexPool in GeometryBuffers
    uint32_t first_vertex = 0;  ///< base vertex of its draws
    uint32_t first_index = 0;   ///< in the index buffer
    uint32_t index_count = 0;
};

/// The shared vertex buffers of one vertex layout.
struct VertexPool {
    std::vector<rhi::VertexBufferLayout> layouts;
    RangeAllocator vertices;
    std::vector<rhi::BufferHandle> buffers;  ///< one per layout slot (empty until first upload)
    uint64_t buffer_vertices = 0;            ///< capacity of the buffers, in vertices
};

/// Every vertex pool and the index pool, on one device.
class GeometryBuffers {
public:
    /// Pools start with room for `initial_vertices` vertices (per layout) and
    /// `initial_indices` indices, and double when full.
    GeometryBuffers(uint32_t initial_vertices, uint32_t initial_indices);
    /// Destroys the buffers (the device must still be alive, or release_gpu()).
    ~GeometryBuffers();
    GeometryBuffers(const GeometryBuffers&) = delete;
    GeometryBuffers& operator=(const GeometryBuffers&) = delete;

    /// Allocates ranges for `geometries` and uploads them, adjacent ranges of one buffer in one
    /// write; grows (and refills) pools that are full. `placed` receives one placement per
    /// geometry. `live` lists every geometry placed before and still in use, with its
    /// placement, to refill grown buffers.
    Status place(rhi::Device& device, std::span<const Geometry* const> geometries, std::vector<GeometryPlacement>& placed,
                 std::span<const std::pair<const Geometry*, GeometryPlacement>> live, UploadStats& stats);
    /// Returns a geometry's ranges to the free lists.
    void free(const Geometry& geometry, const GeometryPlacement& placement);

    [[nodiscard]] const std::vector<VertexPool>& vertex_pools() const { return vertex_pools_; }
    [[nodiscard]] rhi::BufferHandle index_buffer() const { return index_buffer_; }
    /// Indices allocated now / the index buffer's capacity.
    [[nodiscard]] uint64_t indices_used() const { return indices_.used(); }
    [[nodiscard]] uint64_t index_capacity() const { return index_capacity_; }

    /// Destroys the buffers and forgets every range (the scene places everything again).
    void release_gpu();

private:
    uint32_t pool_for(std::span<const rhi::VertexBufferLayout> layouts);
    Status grow_vertices(rhi::Device& device, uint32_t pool, uint64_t needed,
                         std::span<const std::pair<const Geometry*, GeometryPlacement>> live, UploadStats& stats);
    Status grow_indices(rhi::Device& device, uint64_t needed,
                        std::span<const std::pair<const Geometry*, GeometryPlacement>> live, UploadStats& stats);

    uint32_t initial_vertices_;
    uint32_t initial_indices_;
    rhi::Device* device_ = nullptr;
    std::vector<VertexPool> vertex_pools_;
    RangeAllocator indices_;
    rhi::BufferHandle index_buffer_;
    uint64_t index_capacity_ = 0;
};

}  // namespace loom::passes
