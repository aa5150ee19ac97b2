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

BufferSpec buffer_palette(uint32_t index) {
    switch (index) {
        case 0: return BufferSpec::of_size(64 * 1024);
        case 1: return BufferSpec::sized(BufferSize::per_pixel(4));
        case 2: return BufferSpec::sized(BufferSize::per_tile(16, 16, 1024));
        default: return BufferSpec::of_size(20).with_usage(rhi::BufferUsage::Indirect);
    }
}
constexpr uint32_t kBufferPaletteSize = 4;

// Textures whose subresources ports use one at a time: a mip chain, a layer array.
TextureSpec subresource_palette(uint32_t index) {
    return index == 0 ? TextureSpec::of(Format::RGBA16Float).with_size(256, 256).with_mips(5)
                      : TextureSpec::of(Format::Depth32F).with_size(512, 512).with_layers(4);
}
constexpr uint32_t kSubresourcePaletteSize = 2;
// Producer::spec values past the texture palettes name buffer and subresource specs.
constexpr uint32_t kBufferSpecBase = 100;
constexpr uint32_t kSubresourceSpecBase = 200;

// The single subresource number `k` of a subresource-palette texture: a mip of the chain, a
// layer of the array.
SubresourceRange single(uint32_t spec, uint32_t k) {
    return spec == kSubresourceSpecBase ? mip(k % 5) : layer(k % 4);
}

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

RandomGraphOptions corpus_options(uint64_t seed, Corpus corpus) {
    RandomGraphOptions options;
    options.passes = 2 + static_cast<uint32_t>(seed % 39);
    options.window = 2 + static_cast<uint32_t>(seed % 7);
    if (corpus == Corpus::Mixed) {
        options.buffer_percent = 25;
        options.subresource_percent = 20;
    }
    if (corpus == Corpus::Async) options.async_percent = 33;
    return options;
}

uint64_t SplitMix64::next() {
    state_ += 0x9e3779b97f4a7c15ull;
    uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

FrameGraph random_graph(uint64_t seed, const RandomGraphOptions& options) {
    FrameGraph graph;
    declare_random_graph(graph, seed, options);
    return graph;
}

void declare_random_graph(FrameGraph& graph, uint64_t seed, const RandomGraphOptions& options) {
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
            if (source.spec >= kSubresourceSpecBase) {
                pass.input(name, {}, single(source.spec, rng.below(5)));
            } else if (source.spec >= kBufferSpecBase) {
                pass.buffer_input(name, rng.percent(30) ? buffer_palette(source.spec - kBufferSpecBase) : BufferSpec{});
            } else {
                pass.input(name, rng.percent(30) ? palette(source.spec) : TextureSpec{});
            }
            connections.push_back({numbered("p", source.pass) + "." + source.port, pass.name() + "." + name});
            read.push_back(chosen);
        }

        std::optional<Producer> in_place;
        if (!candidates.empty() && rng.percent(options.inout_percent)) {
            std::vector<uint32_t> modifiable;
            for (uint32_t p : candidates) {
                if (std::find(read.begin(), read.end(), p) == read.end()) modifiable.push_back(p);
            }
            // A mip chain or array this pass reads one subresource of may be modified in another.
            std::vector<std::pair<uint32_t, uint32_t>> read_subresource;  // producer, input number
            for (uint32_t k = 0; k < read.size(); ++k) {
                // Read through one input only: the range after it is then disjoint from every read.
                const bool read_once = std::count(read.begin(), read.end(), read[k]) == 1;
                if (producers[read[k]].spec >= kSubresourceSpecBase && !producers[read[k]].modified_in_place && read_once) {
                    read_subresource.emplace_back(read[k], k);
                }
            }
            if (!read_subresource.empty() && rng.percent(50)) {
                const auto [chosen, input] = read_subresource[rng.below(static_cast<uint32_t>(read_subresource.size()))];
                Producer& source = producers[chosen];
                source.modified_in_place = true;
                const SubresourceRange read_range = pass.find_port(numbered("i", input))->range;
                // The next mip (or layer) after the one read, so the two never overlap.
                const uint32_t read_index = source.spec == kSubresourceSpecBase ? read_range.base_mip : read_range.base_layer;
                pass.inout("io", {}, single(source.spec, read_index + 1));
                connections.push_back({numbered("p", source.pass) + "." + source.port, pass.name() + ".io"});
                in_place = Producer{i, "io", source.spec, false};
            } else if (!modifiable.empty()) {
                Producer& source = producers[modifiable[rng.below(static_cast<uint32_t>(modifiable.size()))]];
                source.modified_in_place = true;
                if (source.spec >= kSubresourceSpecBase) {
                    pass.inout("io", {}, single(source.spec, rng.below(5)));
                } else if (source.spec >= kBufferSpecBase) {
                    pass.buffer_inout("io");
                } else {
                    pass.inout("io");
                }
                connections.push_back({numbered("p", source.pass) + "." + source.port, pass.name() + ".io"});
                in_place = Producer{i, "io", source.spec, false};
            }
        }

        const uint32_t output_count = 1 + rng.below(options.max_outputs);
        for (uint32_t k = 0; k < output_count; ++k) {
            const std::string name = numbered("o", k);
            // Draws only what the options ask for, so texture-only graphs stay the ones the
            // benchmarks have always measured. The first output stays a texture: it may be the
            // graph output.
            if (options.buffer_percent != 0 && k > 0 && rng.percent(options.buffer_percent)) {
                const uint32_t spec = rng.below(kBufferPaletteSize);
                pass.declare_buffer(name, PortKind::Output, buffer_palette(spec), rng.percent(options.optional_output_percent));
                producers.push_back({i, name, kBufferSpecBase + spec, false});
            } else if (options.subresource_percent != 0 && rng.percent(options.subresource_percent)) {
                const uint32_t spec = rng.below(kSubresourcePaletteSize);
                pass.declare(name, PortKind::Output, subresource_palette(spec), rng.percent(options.optional_output_percent),
                             single(kSubresourceSpecBase + spec, 0));
                producers.push_back({i, name, kSubresourceSpecBase + spec, false});
            } else {
                // Drawn as ever, then changed: the rest of the graph stays what the seed makes.
                const uint32_t drawn = rng.below(kPaletteSize);
                const uint32_t spec = i == options.respecified_pass ? (drawn + 1) % kPaletteSize : drawn;
                pass.declare(name, PortKind::Output, palette(spec), rng.percent(options.optional_output_percent));
                producers.push_back({i, name, spec, false});
            }
        }
        if (in_place) producers.push_back(*in_place);
        if (rng.percent(options.side_effect_percent)) pass.set_side_effect();
        // Drawn only when asked for, so that graphs without async passes stay what they were.
        if (options.async_percent != 0 && rng.percent(options.async_percent)) {
            pass.set_kind(PassKind::Compute).set_queue(options.async_queue ? Queue::AsyncCompute : Queue::Graphics);
        }
        if (i + 1 == options.passes || rng.percent(options.graph_output_percent)) outputs.push_back(pass.name() + ".o0");
        passes.push_back(std::move(pass));
    }

    std::vector<uint32_t> declaration(passes.size());
    for (uint32_t i = 0; i < declaration.size(); ++i) declaration[i] = i;
    if (options.shuffle_declarations) {
        for (uint32_t i = static_cast<uint32_t>(declaration.size()); i > 1; --i) std::swap(declaration[i - 1], declaration[rng.below(i)]);
    }
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
}

}  // namespace loom::fg::testing
