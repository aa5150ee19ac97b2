#pragma once
// Seeded random frame graphs for property tests and benchmarks. The same seed and options give
// the same graph on every platform (the generator uses its own SplitMix64, not <random>'s
// distributions, whose results differ between standard libraries).

#include <cstdint>

#include "loom/framegraph/graph.hpp"

namespace loom::fg::testing {

struct RandomGraphOptions {
    uint32_t passes = 16;
    uint32_t max_inputs = 3;        ///< inputs per pass: 0..max (the first pass has none)
    uint32_t max_outputs = 3;       ///< outputs per pass: 1..max
    uint32_t window = 6;            ///< inputs read outputs of the previous `window` passes
    uint32_t inout_percent = 15;    ///< chance that a pass also modifies a texture in place
    uint32_t side_effect_percent = 5;
    uint32_t graph_output_percent = 5;     ///< chance that a pass's first output is a graph output
    uint32_t optional_output_percent = 10;
    bool shuffle_declarations = true;      ///< declare passes in random order, not topological
    /// Chance that an output is a buffer (0: texture-only graphs, as the benchmarks use).
    uint32_t buffer_percent = 0;
    /// Chance that a texture output is a mip chain or a layer array whose readers and in-place
    /// writers use single mips or layers (a pass may then read one mip and write another).
    uint32_t subresource_percent = 0;
    /// Chance that a pass is a compute pass on the async compute queue (0: every pass is a
    /// graphics pass, as the benchmarks use).
    uint32_t async_percent = 0;
    /// With async_percent: false keeps those passes compute passes on the graphics queue, so
    /// that the same graph can be planned with and without async compute.
    bool async_queue = true;
    /// The pass (by generation order, p<n>) whose outputs drawn from the texture palette take
    /// the next palette spec instead, inputs that repeat their source's spec with them: the
    /// same graph but for texture specs. UINT32_MAX: none.
    uint32_t respecified_pass = UINT32_MAX;
};

/// The seeded corpora the property tests plan: texture-only graphs, graphs with buffers and
/// subresource ranges, graphs with async compute passes.
enum class Corpus { Textures, Mixed, Async };

/// The options of the corpus graph of `seed`: 2 to 40 passes and windows of 2 to 8 passes by
/// seed, with the corpus's buffers, subresources or async passes.
RandomGraphOptions corpus_options(uint64_t seed, Corpus corpus);

/// A random DAG: passes named p0, p1, ... in generation (topological) order, each with inputs
/// (i0, ...), outputs (o0, ...) and at most one inout (io); the last pass's first output is a
/// graph output. Output specs come from a small palette of colour and depth formats at full,
/// half and quarter size; inputs are unconstrained or repeat their source's spec. With
/// buffer_percent, some outputs are buffers (absolute, per-pixel and per-tile sizes) read by
/// buffer inputs; with subresource_percent, some textures have mips or layers that ports use
/// one at a time.
FrameGraph random_graph(uint64_t seed, const RandomGraphOptions& options = {});
/// random_graph declared into `graph` (empty: new, cleared or redeclared).
void declare_random_graph(FrameGraph& graph, uint64_t seed, const RandomGraphOptions& options = {});

/// SplitMix64: a tiny, portable, seeded generator.
class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next();
    /// Uniform-enough integer in [0, bound) for small bounds.
    uint32_t below(uint32_t bound) { return bound == 0 ? 0 : static_cast<uint32_t>(next() % bound); }
    bool percent(uint32_t chance) { return below(100) < chance; }

private:
    uint64_t state_;
};

}  // namespace loom::fg::testing
