#include "random_graph.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <string>
#include <vector>

namespace loom::fg::testing {
namespace {

using rhi::ChannelKind;
using rhi::Format;

TextureSpec palette(uint32_t index) {
    switch (index) {
        case 0: return TextureSpec::of(Format::RGBA8Unorm);
        case 1: return TextureSpec::of(Format::RGBA16Float);
        case 2: return TextureSpec::of(Format::RGBA16Float).with_scale(0.5f);
        case 3: return TextureSpec::of(Format::Depth32F);
        case 4: return TextureSpec::of(Format::R16Float);
        case 5: return TextureSpec::color(3, 16, ChannelKind::Float);  // resolves to RGBA16Float
        default: return TextureSpec::of(Format::RG16Float).with_scale(0.25f);
    }
}
constexpr uint32_t kPaletteSize = 7;

// prefix + number by appending (GCC 12 -O3 warns falsely about "literal" + std::to_string).
std::string numbered(std::string_view prefix, uint32_t number) {
    std::string out(prefix);
    out += std::to_string(number);
    return out;
}

// A port that produces a texture later passes may read.
struct Producer {
    uint32_t pass = 0;
    std::string port;
    uint32_t spec = 0;
    bool modified_in_place = false;  // once an inout modifies it, later passes read the inout
};

struct Connection {
    std::string from;
    std::string to;
};

}  // namespace

uint64_t SplitMix64::next() {
    state_ += 0x9e3779b97f4a7c15ull;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

FrameGraph random_graph(uint64_t seed, const RandomGraphOptions& options) {
    SplitMix64 rng(seed);
    std::vector<Pass> passes;
    std::vector<Connection> connections;
    std::vector<std::string> outputs;
    std::vector<Producer> producers;
    std::vector<uint32_t> first_producer;  // per pass, the index of its first producer
    passes.reserve(options.passes);

    for (uint32_t i = 0; i < options.passes; ++i) {
        Pass pass(numbered("p", i));
        first_producer.push_back(static_cast<uint32_t>(producers.size()));
        const uint32_t window_start = i > options.window ? i - options.window : 0;
        std::vector<uint32_t> candidates;  // indices into producers
        for (uint32_t p = first_producer[window_start]; p < producers.size(); ++p) {
            if (!producers[p].modified_in_place) candidates.push_back(p);
        }
        std::vector<uint32_t> read;  // producers this pass reads

        const uint32_t input_count = candidates.empty() ? 0 : rng.below(options.max_inputs + 1);
        for (uint32_t k = 0; k < input_count; ++k) {
            const uint32_t chosen = candidates[rng.below(static_cast<uint32_t>(candidates.size()))];
            const Producer& source = producers[chosen];
            const std::string name = numbered("i", k);
            pass.input(name, rng.percent(30) ? palette(source.spec) : TextureSpec{});
            connections.push_back({numbered("p", source.pass) + "." + source.port, pass.name() + "." + name});
            read.push_back(chosen);
        }

        std::optional<Producer> in_place;
        if (!candidates.empty() && rng.percent(options.inout_percent)) {
            std::vector<uint32_t> modifiable;
            for (uint32_t p : candidates) {
                if (std::find(read.begin(), read.end(), p) == read.end()) modifiable.push_back(p);
            }
            if (!modifiable.empty()) {
                Producer& source = producers[modifiable[rng.below(static_cast<uint32_t>(modifiable.size()))]];
                source.modified_in_place = true;
                pass.inout("io");
                connections.push_back({numbered("p", source.pass) + "." + source.port, pass.name() + ".io"});
                in_place = Producer{i, "io", source.spec, false};
            }
        }

        const uint32_t output_count = 1 + rng.below(options.max_outputs);
        for (uint32_t k = 0; k < output_count; ++k) {
            const std::string name = numbered("o", k);
            const uint32_t spec = rng.below(kPaletteSize);
            pass.declare(name, PortKind::Output, palette(spec), rng.percent(options.optional_output_percent));
            producers.push_back({i, name, spec, false});
        }
        if (in_place) producers.push_back(*in_place);
        if (rng.percent(options.side_effect_percent)) pass.set_side_effect();
        if (i + 1 == options.passes || rng.percent(options.graph_output_percent)) outputs.push_back(pass.name() + ".o0");
        passes.push_back(std::move(pass));
    }

    std::vector<uint32_t> declaration(passes.size());
    for (uint32_t i = 0; i < declaration.size(); ++i) declaration[i] = i;
    if (options.shuffle_declarations) {
        for (uint32_t i = static_cast<uint32_t>(declaration.size()); i > 1; --i) std::swap(declaration[i - 1], declaration[rng.below(i)]);
    }
    FrameGraph graph;
    for (uint32_t index : declaration) {
        [[maybe_unused]] auto added = graph.add_pass(std::move(passes[index]));
        assert(added.ok());
    }
    for (const Connection& c : connections) {
        [[maybe_unused]] auto connected = graph.connect(*parse_port_ref(c.from), *parse_port_ref(c.to));
        assert(connected.ok());
    }
    for (const std::string& output : outputs) {
        [[maybe_unused]] auto marked = graph.mark_output(*parse_port_ref(output));
        assert(marked.ok());
    }
    return graph;
}

}  // namespace loom::fg::testing
