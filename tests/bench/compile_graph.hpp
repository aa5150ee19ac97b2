#pragma once
// The seeded graphs of the side-by-side compile benchmark (compile_bench.cpp): one description
// that each library under test (loom and, when present, skaarj1989/FrameGraph and acdemiralp/fg)
// turns into its own graph, so that every library declares and compiles the same passes,
// textures and reads.
//
// Passes come in layers of kLayerWidth. Each pass creates 1-2 textures and reads 1-3 textures
// of the two layers before it; every texture of a layer is read by some pass of the next layer
// and the last layer's passes have side effects, so that no library culls anything and every
// texture lives at most two layers (the cost per pass cannot grow with the graph's size because
// lifetimes do).

#include <algorithm>
#include <cstdint>
#include <vector>

namespace loom::bench {

/// A texture: its producer (pass index, output index within the pass) and its description.
struct CompileTexture {
    uint32_t pass = 0;
    uint32_t output = 0;   ///< 0 or 1
    uint32_t format = 0;   ///< index into a small palette (each library maps it to its own format)
    uint32_t halved = 0;   ///< 0: frame size, 1: half the frame size
};

/// A pass: the textures it reads (indices into CompileGraph::reads) and creates.
struct CompilePass {
    uint32_t first_read = 0;
    uint32_t read_count = 0;      ///< 0 in the first layer, else 1..3
    uint32_t first_texture = 0;   ///< the textures it creates are first_texture, first_texture + 1, ...
    uint32_t create_count = 0;    ///< 1..2
    bool side_effect = false;     ///< the last layer: nothing reads its textures
};

struct CompileGraph {
    std::vector<CompilePass> passes;
    std::vector<uint32_t> reads;             ///< texture indices, grouped by pass
    std::vector<CompileTexture> textures;
};

inline constexpr uint32_t kLayerWidth = 8;
inline constexpr uint32_t kFormats = 3;

/// SplitMix64 (the benchmark's own generator, so that graphs are the same everywhere).
class CompileRandom {
public:
    explicit CompileRandom(uint64_t seed) : state_(seed) {}
    uint64_t next() {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    }
    uint32_t below(uint32_t bound) { return static_cast<uint32_t>(next() % bound); }

private:
    uint64_t state_;
};

/// The graph of `pass_count` passes for `seed`.
inline CompileGraph make_compile_graph(uint32_t pass_count, uint64_t seed = 7) {
    CompileGraph graph;
    graph.passes.reserve(pass_count);
    graph.textures.reserve(pass_count * 2);
    graph.reads.reserve(pass_count * 3);
    CompileRandom random(seed);
    // Textures of the previous layer and of the one before it.
    uint32_t previous_begin = 0, previous_end = 0, older_begin = 0;
    uint32_t layer_begin_texture = 0;
    for (uint32_t index = 0; index < pass_count; ++index) {
        const uint32_t in_layer = index % kLayerWidth;
        if (in_layer == 0 && index > 0) {
            older_begin = previous_begin;
            previous_begin = layer_begin_texture;
            previous_end = static_cast<uint32_t>(graph.textures.size());
            layer_begin_texture = previous_end;
        }
        CompilePass pass;
        pass.first_read = static_cast<uint32_t>(graph.reads.size());
        if (index >= kLayerWidth) {
            const uint32_t wanted = 1 + random.below(3);
            // Every texture of the previous layer gets a reader: pass k of a layer reads the
            // previous layer's textures k, k + width, ... (at most two: a layer creates at most
            // 2 × width textures).
            for (uint32_t t = previous_begin + in_layer; t < previous_end; t += kLayerWidth) graph.reads.push_back(t);
            // The rest at random among the two previous layers, each texture once.
            for (uint32_t tries = 0; graph.reads.size() - pass.first_read < wanted && tries < 8; ++tries) {
                const uint32_t t = older_begin + random.below(previous_end - older_begin);
                const auto begin = graph.reads.begin() + pass.first_read;
                if (std::find(begin, graph.reads.end(), t) == graph.reads.end()) graph.reads.push_back(t);
            }
        }
        pass.read_count = static_cast<uint32_t>(graph.reads.size()) - pass.first_read;
        pass.first_texture = static_cast<uint32_t>(graph.textures.size());
        pass.create_count = 1 + random.below(2);
        for (uint32_t o = 0; o < pass.create_count; ++o) {
            graph.textures.push_back({index, o, random.below(kFormats), random.below(2)});
        }
        pass.side_effect = index >= (pass_count - 1) / kLayerWidth * kLayerWidth;
        graph.passes.push_back(pass);
    }
    return graph;
}

}  // namespace loom::bench
