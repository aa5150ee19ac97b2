#pragma once
// What an application brings to loom on GL: its own OpenGL 4.5 context (here an EGL
// surfaceless one, as a headless engine would make), and a record of the GL state it cares
// about, to check that loom leaves it as it was.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <epoxy/gl.h>

namespace loom::test {

/// The application's own context, current on the calling thread while it lives.
class AppGlContext {
public:
    /// A 4.5 core debug context on the Mesa surfaceless platform; null (with `error` set) when
    /// the machine has none.
    static std::unique_ptr<AppGlContext> create(std::string& error);
    ~AppGlContext();
    AppGlContext(const AppGlContext&) = delete;
    AppGlContext& operator=(const AppGlContext&) = delete;

    void make_current();
    /// Leaves no context current on this thread.
    void release();

private:
    AppGlContext() = default;
    void* display_ = nullptr;
    void* context_ = nullptr;
};

/// The application-visible GL state loom could disturb: bindings, fixed-function state, pixel
/// store, clip control. Two snapshots compare equal when loom restored everything.
struct GlStateSnapshot {
    std::vector<std::pair<std::string, std::vector<double>>> values;

    /// Reads the state of the current context (texture, sampler, buffer and image bindings of
    /// the first `units` units/points, blend and colour mask of the first 8 draw buffers).
    static GlStateSnapshot capture(unsigned units = 8);
    /// The entries that differ, one per line ("name: before -> after"); empty when equal.
    [[nodiscard]] std::string diff(const GlStateSnapshot& after) const;
};

}  // namespace loom::test
