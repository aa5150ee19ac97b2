#pragma once
// Objects and object kinds: the object side of the pass/object protocol (Hafner, ELS 2019, §4).
//
// An ObjectKind is what a CLOS class is to the paper: the shader parts shared by every object of
// the kind (how to fetch and place a vertex, how to evaluate a material) and the vertex layout
// they read. Passes compose one program per (pass, object kind), so objects of one kind share
// it. An Object is an instance: geometry, material data, a transform, and render(), which
// records its draw with the program the pass chose for it.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "loom/passes/shader_part.hpp"
#include "loom/rhi/descriptions.hpp"
#include "loom/rhi/device.hpp"
#include "loom/rhi/result.hpp"

namespace loom::passes {

class Program;

/// The shader parts and vertex layout shared by all objects of a kind. Kinds are compared by
/// name: two different kinds must not share one (registering them with one pass is an error).
class ObjectKind {
public:
    ObjectKind(std::string name, std::vector<ShaderPart> parts, std::vector<rhi::VertexBufferLayout> vertex_buffers);

    [[nodiscard]] const std::string& name() const { return name_; }
    /// Parts in composition order (their resources are numbered in this order in set 1).
    [[nodiscard]] const std::vector<ShaderPart>& parts() const { return parts_; }
    /// Vertex buffer slots as objects of this kind bind them (slot i = vertex_buffers()[i]).
    [[nodiscard]] const std::vector<rhi::VertexBufferLayout>& vertex_buffers() const { return vertex_buffers_; }

    friend bool operator==(const ObjectKind&, const ObjectKind&) = default;

private:
    std::string name_;
    std::vector<ShaderPart> parts_;
    std::vector<rhi::VertexBufferLayout> vertex_buffers_;
};

/// What an object's render() gets: where to record and the program the pass bound for it
/// (its pipeline is already set, the pass's resources in set 0 are bound).
struct DrawContext {
    rhi::CommandList& commands;
    const Program& program;
};

/// A thing passes can draw.
class Object {
public:
    virtual ~Object() = default;

    /// The kind (shared by every object of the kind).
    [[nodiscard]] virtual const std::shared_ptr<const ObjectKind>& kind() const = 0;
    /// Rasterisation the object needs (e.g. no culling for double-sided surfaces, clockwise
    /// front faces for mirrored transforms). Default: back faces culled, counter-clockwise front.
    [[nodiscard]] virtual rhi::RasterState raster() const;
    /// A name for messages.
    [[nodiscard]] virtual std::string name() const { return kind()->name(); }

    /// Records the object's draw: binds its resources (set 1) and vertex data, draws. The
    /// paper's `render`; passes call it through render_with().
    virtual Status render(DrawContext& context) const = 0;
};

}  // namespace loom::passes
