// The side-by-side compile benchmark's graphs in acdemiralp/fg (header-only; built only when
// LOOM_ACDEMIRALP_FG_DIR points at its sources).
#include "compile_libraries.hpp"

#include <cstddef>
#include <memory>

#include <fg/framegraph.hpp>

namespace loom::bench {
namespace {

struct AcdemiralpDescription {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t format = 0;
};
struct AcdemiralpTexture {};
using AcdemiralpResource = fg::resource<AcdemiralpDescription, AcdemiralpTexture>;

}  // namespace
}  // namespace loom::bench

namespace fg {
// acdemiralp/fg needs a way to realise each resource type (never called: nothing executes).
template <>
std::unique_ptr<loom::bench::AcdemiralpTexture> realize(const loom::bench::AcdemiralpDescription&) {
    return std::make_unique<loom::bench::AcdemiralpTexture>();
}
}  // namespace fg

namespace loom::bench {

uint64_t compile_in_acdemiralp(const CompileGraph& graph, const CompileNames& names) {
    fg::framegraph frame_graph;
    std::vector<AcdemiralpResource*> handles(graph.textures.size());
    struct NoData {};
    for (std::size_t index = 0; index < graph.passes.size(); ++index) {
        const CompilePass& pass = graph.passes[index];
        auto* task = frame_graph.add_render_task<NoData>(
            names.passes[index],
            [&](NoData&, fg::render_task_builder& builder) {
                for (uint32_t r = 0; r < pass.read_count; ++r) builder.read(handles[graph.reads[pass.first_read + r]]);
                for (uint32_t t = pass.first_texture; t < pass.first_texture + pass.create_count; ++t) {
                    const CompileTexture& texture = graph.textures[t];
                    const uint32_t shift = texture.halved;
                    handles[t] = builder.create<AcdemiralpResource>(
                        names.textures[t], AcdemiralpDescription{1920u >> shift, 1080u >> shift, texture.format});
                }
            },
            [](const NoData&) {});
        if (pass.side_effect) task->set_cull_immune(true);
    }
    frame_graph.compile();
    return reinterpret_cast<std::uintptr_t>(handles.back());
}

}  // namespace loom::bench
