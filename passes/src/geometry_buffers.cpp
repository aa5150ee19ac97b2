#include "loom/passes/geometry_buffers.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "loom/passes/mesh_object.hpp"

namespace loom::passes {
namespace {

std::atomic<uint64_t> next_geometry_id{1};

/// Bytes to write at an offset of one buffer.
struct Write {
    uint64_t offset = 0;
    std::span<const std::byte> data;
};

/// Writes `writes` into `buffer`: sorted by offset, and those that touch each other joined into
/// one write_buffer.
Status write_runs(rhi::Device& device, rhi::BufferHandle buffer, std::vector<Write>& writes, UploadStats& stats) {
    std::sort(writes.begin(), writes.end(), [](const Write& a, const Write& b) { return a.offset < b.offset; });
    std::vector<std::byte> staging;
    for (std::size_t i = 0; i < writes.size();) {
        std::size_t end = i + 1;
        uint64_t run_end = writes[i].offset + writes[i].data.size();
        while (end < writes.size() && writes[end].offset == run_end) run_end += writes[end++].data.size();
        if (end == i + 1) {
            LOOM_TRY(device.write_buffer(buffer, writes[i].offset, writes[i].data));
        } else {
            staging.resize(run_end - writes[i].offset);
            for (std::size_t k = i; k < end; ++k) {
                std::memcpy(staging.data() + (writes[k].offset - writes[i].offset), writes[k].data.data(),
                            writes[k].data.size());
            }
            LOOM_TRY(device.write_buffer(buffer, writes[i].offset, staging));
        }
        ++stats.writes;
        stats.bytes += run_end - writes[i].offset;
        i = end;
    }
    return {};
}

Result<rhi::BufferHandle> make_buffer(rhi::Device& device, std::string name, uint64_t size, rhi::BufferUsage usage) {
    rhi::BufferDesc desc;
    desc.name = std::move(name);
    desc.size = std::max<uint64_t>(size, 4);
    desc.usage = usage;
    return device.create_buffer(desc);
}

std::span<const std::byte> index_bytes(const Geometry& geometry) { return std::as_bytes(std::span(geometry.indices())); }

}  // namespace

// ---- Geometry --------------------------------------------------------------------------------

Result<std::shared_ptr<const Geometry>> Geometry::create(std::string name, std::vector<rhi::VertexBufferLayout> layouts,
                                                         std::vector<std::vector<std::byte>> streams,
                                                         uint32_t vertex_count, std::vector<uint32_t> indices) {
    const std::string what = "geometry '" + name + "': ";
    if (vertex_count == 0 || indices.empty() || indices.size() % 3 != 0) {
        return make_error(ErrorCode::InvalidArgument, what + "needs vertices and a triangle list (" +
                                                          std::to_string(vertex_count) + " vertices, " +
                                                          std::to_string(indices.size()) + " indices)");
    }
    if (layouts.empty() || layouts.size() != streams.size()) {
        return make_error(ErrorCode::InvalidArgument, what + std::to_string(layouts.size()) + " vertex layouts but " +
                                                          std::to_string(streams.size()) + " streams");
    }
    for (std::size_t slot = 0; slot < layouts.size(); ++slot) {
        if (layouts[slot].step != rhi::VertexStepMode::PerVertex || layouts[slot].stride == 0) {
            return make_error(ErrorCode::InvalidArgument,
                              what + "vertex layout " + std::to_string(slot) + " is per-instance or has stride 0");
        }
        const uint64_t expected = uint64_t{vertex_count} * layouts[slot].stride;
        if (streams[slot].size() != expected) {
            return make_error(ErrorCode::InvalidArgument, what + "stream " + std::to_string(slot) + " has " +
                                                              std::to_string(streams[slot].size()) + " bytes, " +
                                                              std::to_string(vertex_count) + " vertices of stride " +
                                                              std::to_string(layouts[slot].stride) + " need " +
                                                              std::to_string(expected));
        }
    }
    for (std::size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertex_count) {
            return make_error(ErrorCode::InvalidArgument, what + "index " + std::to_string(i) + " is " +
                                                              std::to_string(indices[i]) + ", but there are only " +
                                                              std::to_string(vertex_count) + " vertices");
        }
    }
    std::shared_ptr<Geometry> geometry(new Geometry());
    geometry->name_ = std::move(name);
    geometry->id_ = next_geometry_id++;
    geometry->layouts_ = std::move(layouts);
    geometry->streams_ = std::move(streams);
    geometry->vertex_count_ = vertex_count;
    geometry->indices_ = std::move(indices);
    return std::shared_ptr<const Geometry>(std::move(geometry));
}

Result<std::shared_ptr<const Geometry>> make_mesh_geometry(std::string name, std::span<const MeshVertex> vertices,
                                                           std::span<const uint32_t> indices) {
    const auto bytes = std::as_bytes(vertices);
    std::vector<std::vector<std::byte>> streams{std::vector<std::byte>(bytes.begin(), bytes.end())};
    return Geometry::create(std::move(name), {mesh_vertex_layout()}, std::move(streams),
                            static_cast<uint32_t>(vertices.size()), std::vector<uint32_t>(indices.begin(), indices.end()));
}

bool same_vertex_layouts(std::span<const rhi::VertexBufferLayout> a, std::span<const rhi::VertexBufferLayout> b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
        if (a[i].stride != b[i].stride || a[i].step != b[i].step || a[i].attributes.size() != b[i].attributes.size()) {
            return false;
        }
        for (std::size_t j = 0; j < a[i].attributes.size(); ++j) {
            const rhi::VertexAttribute& x = a[i].attributes[j];
            const rhi::VertexAttribute& y = b[i].attributes[j];
            if (x.location != y.location || x.format != y.format || x.offset != y.offset) return false;
        }
    }
    return true;
}

// ---- GeometryBuffers -------------------------------------------------------------------------

GeometryBuffers::GeometryBuffers(uint32_t initial_vertices, uint32_t initial_indices)
    : initial_vertices_(std::max(initial_vertices, 1u)), initial_indices_(std::max(initial_indices, 3u)),
      indices_(initial_indices_) {}

GeometryBuffers::~GeometryBuffers() { release_gpu(); }

uint32_t GeometryBuffers::pool_for(std::span<const rhi::VertexBufferLayout> layouts) {
    for (uint32_t i = 0; i < vertex_pools_.size(); ++i) {
        if (same_vertex_layouts(vertex_pools_[i].layouts, layouts)) return i;
    }
    VertexPool pool;
    pool.layouts.assign(layouts.begin(), layouts.end());
    pool.vertices.grow(initial_vertices_);
    vertex_pools_.push_back(std::move(pool));
    return static_cast<uint32_t>(vertex_pools_.size() - 1);
}

Status GeometryBuffers::place(rhi::Device& device, std::span<const Geometry* const> geometries,
                              std::vector<GeometryPlacement>& placed,
                              std::span<const std::pair<const Geometry*, GeometryPlacement>> live, UploadStats& stats) {
    if (device_ && device_ != &device) {
        return make_error(ErrorCode::InvalidState, "shared geometry buffers hold buffers of another device");
    }
    device_ = &device;
    // Ranges first (growing the allocators as needed), then buffers large enough, then data.
    placed.clear();
    for (const Geometry* geometry : geometries) {
        GeometryPlacement p;
        p.vertex_pool = pool_for(geometry->layouts());
        RangeAllocator& vertices = vertex_pools_[p.vertex_pool].vertices;
        auto first_vertex = vertices.allocate(geometry->vertex_count());
        if (!first_vertex) {
            vertices.grow(std::max(vertices.capacity() * 2, vertices.capacity() + geometry->vertex_count()));
            first_vertex = vertices.allocate(geometry->vertex_count());
        }
        auto first_index = indices_.allocate(geometry->indices().size());
        if (!first_index) {
            indices_.grow(std::max(indices_.capacity() * 2, indices_.capacity() + geometry->indices().size()));
            first_index = indices_.allocate(geometry->indices().size());
        }
        if (*first_vertex + geometry->vertex_count() > uint64_t{INT32_MAX} || *first_index > UINT32_MAX) {
            return make_error(ErrorCode::OutOfMemory, "geometry '" + geometry->name() +
                                                          "': the shared buffers cannot address that many vertices");
        }
        p.first_vertex = static_cast<uint32_t>(*first_vertex);
        p.first_index = static_cast<uint32_t>(*first_index);
        p.index_count = static_cast<uint32_t>(geometry->indices().size());
        placed.push_back(p);
    }
    for (uint32_t pool = 0; pool < vertex_pools_.size(); ++pool) {
        if (vertex_pools_[pool].vertices.capacity() > vertex_pools_[pool].buffer_vertices) {
            LOOM_TRY(grow_vertices(device, pool, vertex_pools_[pool].vertices.capacity(), live, stats));
        }
    }
    if (indices_.capacity() > index_capacity_) LOOM_TRY(grow_indices(device, indices_.capacity(), live, stats));

    // The new data, grouped per buffer.
    std::vector<Write> index_writes;
    for (uint32_t pool = 0; pool < vertex_pools_.size(); ++pool) {
        const VertexPool& vp = vertex_pools_[pool];
        for (std::size_t slot = 0; slot < vp.layouts.size(); ++slot) {
            std::vector<Write> writes;
            for (std::size_t g = 0; g < geometries.size(); ++g) {
                if (placed[g].vertex_pool != pool) continue;
                writes.push_back({uint64_t{placed[g].first_vertex} * vp.layouts[slot].stride, geometries[g]->streams()[slot]});
            }
            LOOM_TRY(write_runs(device, vp.buffers[slot], writes, stats));
        }
    }
    for (std::size_t g = 0; g < geometries.size(); ++g) {
        index_writes.push_back({uint64_t{placed[g].first_index} * 4, index_bytes(*geometries[g])});
    }
    LOOM_TRY(write_runs(device, index_buffer_, index_writes, stats));
    stats.sets += geometries.size();
    return {};
}

Status GeometryBuffers::grow_vertices(rhi::Device& device, uint32_t pool, uint64_t needed,
                                      std::span<const std::pair<const Geometry*, GeometryPlacement>> live,
                                      UploadStats& stats) {
    VertexPool& vp = vertex_pools_[pool];
    std::vector<rhi::BufferHandle> buffers;
    for (std::size_t slot = 0; slot < vp.layouts.size(); ++slot) {
        auto buffer = make_buffer(device,
                                  "shared vertices (layout " + std::to_string(pool) + ", slot " + std::to_string(slot) + ")",
                                  needed * vp.layouts[slot].stride, rhi::BufferUsage::Vertex);
        if (!buffer) {
            for (rhi::BufferHandle made : buffers) (void)device.destroy(made);
            return buffer.take_error();
        }
        buffers.push_back(*buffer);
    }
    const bool refill = !vp.buffers.empty();
    for (rhi::BufferHandle old : vp.buffers) (void)device.destroy(old);
    vp.buffers = std::move(buffers);
    vp.buffer_vertices = needed;
    if (!refill) return {};
    ++stats.growths;
    const uint64_t before = stats.bytes;
    for (std::size_t slot = 0; slot < vp.layouts.size(); ++slot) {
        std::vector<Write> writes;
        for (const auto& [geometry, placement] : live) {
            if (placement.vertex_pool != pool) continue;
            writes.push_back({uint64_t{placement.first_vertex} * vp.layouts[slot].stride, geometry->streams()[slot]});
        }
        LOOM_TRY(write_runs(device, vp.buffers[slot], writes, stats));
    }
    stats.growth_bytes += stats.bytes - before;
    return {};
}

Status GeometryBuffers::grow_indices(rhi::Device& device, uint64_t needed,
                                     std::span<const std::pair<const Geometry*, GeometryPlacement>> live,
                                     UploadStats& stats) {
    auto buffer = make_buffer(device, "shared indices", needed * 4, rhi::BufferUsage::Index);
    if (!buffer) return buffer.take_error();
    const bool refill = static_cast<bool>(index_buffer_);
    if (index_buffer_) (void)device.destroy(index_buffer_);
    index_buffer_ = *buffer;
    index_capacity_ = needed;
    if (!refill) return {};
    ++stats.growths;
    const uint64_t before = stats.bytes;
    std::vector<Write> writes;
    for (const auto& [geometry, placement] : live) writes.push_back({uint64_t{placement.first_index} * 4, index_bytes(*geometry)});
    LOOM_TRY(write_runs(device, index_buffer_, writes, stats));
    stats.growth_bytes += stats.bytes - before;
    return {};
}

void GeometryBuffers::free(const Geometry& geometry, const GeometryPlacement& placement) {
    if (placement.vertex_pool < vertex_pools_.size()) {
        vertex_pools_[placement.vertex_pool].vertices.free(placement.first_vertex, geometry.vertex_count());
    }
    indices_.free(placement.first_index, placement.index_count);
}

void GeometryBuffers::release_gpu() {
    if (device_) {
        for (VertexPool& pool : vertex_pools_) {
            for (rhi::BufferHandle buffer : pool.buffers) (void)device_->destroy(buffer);
        }
        if (index_buffer_) (void)device_->destroy(index_buffer_);
    }
    vertex_pools_.clear();
    indices_ = RangeAllocator(initial_indices_);
    index_buffer_ = {};
    index_capacity_ = 0;
    device_ = nullptr;
}

}  // namespace loom::passes
