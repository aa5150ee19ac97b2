// The side-by-side compile benchmark's graphs in skaarj1989/FrameGraph (its own headers; built
// only when LOOM_SKAARJ_FRAMEGRAPH_DIR points at its sources).
#include "compile_libraries.hpp"

#include "fg/FrameGraph.hpp"

namespace loom::bench {
namespace {

// A texture as skaarj's graph wants it: a description and create/destroy (never called here:
// the benchmark compiles, it does not execute).
struct SkaarjTexture {
    struct Desc {
        uint32_t width = 0;
        uint32_t height = 0;
        uint32_t format = 0;
    };
    void create(const Desc&, void*) {}
    void destroy(const Desc&, void*) {}
};

}  // namespace

uint64_t compile_in_skaarj(const CompileGraph& graph, const CompileNames& names) {
    FrameGraph frame_graph;
    // skaarj's own way to avoid growing its arrays: passes and resources known up front.
    frame_graph.reserve(static_cast<uint32_t>(graph.passes.size()), static_cast<uint32_t>(graph.textures.size()));
    std::vector<FrameGraphResource> handles(graph.textures.size());
    struct NoData {};
    for (std::size_t index = 0; index < graph.passes.size(); ++index) {
        const CompilePass& pass = graph.passes[index];
        frame_graph.addCallbackPass<NoData>(
            names.passes[index],
            [&](FrameGraph::Builder& builder, NoData&) {
                for (uint32_t r = 0; r < pass.read_count; ++r) builder.read(handles[graph.reads[pass.first_read + r]]);
                for (uint32_t t = pass.first_texture; t < pass.first_texture + pass.create_count; ++t) {
                    const CompileTexture& texture = graph.textures[t];
                    const uint32_t shift = texture.halved;
                    handles[t] = builder.write(builder.create<SkaarjTexture>(
                        names.textures[t], SkaarjTexture::Desc{1920u >> shift, 1080u >> shift, texture.format}));
                }
                if (pass.side_effect) builder.setSideEffect();
            },
            [](const NoData&, FrameGraphPassResources&, void*) {});
    }
    frame_graph.compile();
    return static_cast<uint64_t>(handles.back());
}

}  // namespace loom::bench
