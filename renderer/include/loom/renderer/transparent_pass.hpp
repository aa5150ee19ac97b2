#pragma once
// The transparent pass: draws blended surfaces (glTF alphaMode BLEND) over the lit frame after
// the opaque ones, farthest first, each "over" what lies behind it (colour × alpha + behind ×
// (1 - alpha)). It lights like the forward pass — "camera" + "blend-render", and like the lit
// passes optionally "shadow-render" and "high-pass-render" — and works after the deferred pass
// and after the forward pass alike:
//
//   in/out color, high_pass (the lit pass's outputs, blended in place)
//   in/out depth (the opaque depth: tested, not written, so blended surfaces hide behind opaque
//          ones but not behind each other)
//   in     shadow_map
//
// Objects are sorted by the distance of their bounds' centre along the view direction, every
// frame (bounds given as a function are read again, so objects may move); surfaces that interpenetrate or overlap within one object are not sorted further.
// Objects must provide object_alpha() in their material part ("gltf-material" does).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "loom/passes/deferred_pass.hpp"
#include "loom/passes/shader_pass.hpp"
#include "loom/passes/view.hpp"

namespace loom::renderer {

class TransparentPass final : public passes::ShaderPass {
public:
    explicit TransparentPass(const passes::PassConfig& config = {}, passes::LightingParts parts = {},
                             std::string name = "transparent");

    /// Registers `object` (as ShaderPass::register_object) with the world bounds it is sorted by.
    Status register_object(std::shared_ptr<const passes::Object> object, const scene::Bounds& world_bounds);
    /// The same for an object that moves: `world_bounds` is called at every frame's sort. An
    /// empty function is an InvalidArgument error naming the object.
    Status register_object(std::shared_ptr<const passes::Object> object, std::function<scene::Bounds()> world_bounds);
    /// Refused: the pass needs bounds to sort by (an InvalidArgument error naming the object).
    Status register_object(std::shared_ptr<const passes::Object> object) override;
    /// Drops every registered object and its bounds (hides ShaderPass::clear_objects, which
    /// would keep the bounds: execute() then reports the mismatch as an error).
    void clear_objects();

    void set_view(const passes::SceneView& view) { view_ = view; }
    /// Luminance above which colour goes to the high-pass output (as the lit passes).
    void set_threshold(float threshold) { threshold_ = threshold; }
    [[nodiscard]] const passes::LightingParts& parts() const { return parts_; }

    /// The registered objects in the order the latest frame drew them (farthest first).
    [[nodiscard]] std::vector<std::string> draw_order() const;

    Status execute(fg::PassContext& context) override;

private:
    /// Indices into objects(), farthest first from the current view.
    [[nodiscard]] std::vector<std::size_t> sorted() const;

    passes::LightingParts parts_;
    passes::SceneView view_;
    float threshold_ = 1.0f;
    std::vector<std::function<scene::Bounds()>> bounds_;  ///< parallel to objects()
    std::vector<std::size_t> last_order_;
};

}  // namespace loom::renderer
