#pragma once
// Frame graphs described in JSON:
//
//   { "frame": {"width": 1920, "height": 1080},
//     "passes": [
//       {"name": "shadow", "outputs": [{"name": "shadow_map", "format": "Depth32F", "size": [2048, 2048]}]},
//       {"name": "deferred", "inputs": [{"name": "shadow_map"}],
//        "outputs": [{"name": "color", "format": "RGBA16F", "scale": 1.0}],
//        "parts": [{"name": "high_pass", "outputs": [{"name": "high_pass", "format": "RGBA16F"}]}]},
//       {"name": "tint", "inouts": [{"name": "color"}], "side_effect": false}],
//     "connections": [["shadow.shadow_map", "deferred.shadow_map"], ["deferred.color", "tint.color"]],
//     "outputs": ["tint.color"] }
//
// A pass's "parts" are port sets (fg::PortSet), added after the pass's own ports; its "kind"
// is "graphics" (the default), "compute" or "copy" (fg::PassKind).
// A port object has "name", "type" ("texture", the default, or "buffer") and, for a texture
// port, any of: "format" (an rhi::format_name or a short alias such as "RGBA16F", "RGBA8",
// "D32F"), or partial format constraints "channels" (1-4), "bits", "kind" (unorm, snorm, float,
// uint, sint), "srgb", "depth" (bits), "stencil" (bits); "size" [w, h] or "scale" (a number or
// [sx, sy]); "samples", "mips", "layers"; "range" (the mips and layers the port uses:
// {"mip": k} or {"mips": [base, count]}, {"layer": i} or {"layers": [base, count]}; [base]
// runs to the last); "optional"; "usage" (a list of sampled, color_attachment,
// depth_stencil_attachment, storage, copy_src, copy_dst).
// A buffer port takes "size" (bytes: N, {"per_pixel": N, "scale": s} or {"per_tile": N,
// "tile": [w, h]}), "usage" (vertex, index, uniform, storage, indirect, copy_src, copy_dst),
// "alignment" (a power of two), "range" ({"offset": N, "size": N}, no size: to the end) and
// "optional":
//
//       {"name": "cull", "kind": "compute",
//        "outputs": [{"name": "lights", "type": "buffer", "size": {"per_tile": 1024, "tile": [16, 16]}}]}
//
// The order of the passes (PlanOptions::order; loom-plan's --order overrides it) is the top-level
// "order": "declared" (the default) or "memory"; "order_constraints" lists pairs of pass names
// [earlier, later] (FrameGraph::require_order), and a pass's "keep_declared_order": true pins it
// (Pass::keep_declared_order):
//
//     "order": "memory", "order_constraints": [["tonemap", "ui"]],
//     "passes": [..., {"name": "ui", "keep_declared_order": true, ...}]
//
// Unknown keys and bad values are ErrorCode::Parse errors with the JSON pointer (RFC 6901), e.g.
// `graph.json: /passes/2/outputs/0/format: unknown format "RGBA17F"`.
//
// Before the document is read, the text is refused (with line and column) when it nests
// objects and arrays deeper than kMaxGraphFileDepth, repeats a key within one object, or holds
// a number beyond a double (1e400). Pass and port names may not contain '.' or control
// characters (see name_problem()). Values quoted in errors are cut to 60 characters.

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/graph.hpp"
#include "loom/rhi/format.hpp"
#include "loom/rhi/result.hpp"

namespace loom::fg {

/// How deeply a graph file may nest objects and arrays (graph files need nine: a tile size in a
/// port of a port set); deeper text is refused before a document is built from it.
inline constexpr std::size_t kMaxGraphFileDepth = 64;

/// A graph read from a file, with the frame size the file asks for (default 1920x1080).
struct GraphFile {
    FrameGraph graph;
    Extent2D frame{1920, 1080};
    /// The pass order the file asks for ("order"; default memory, kDefaultPassOrder).
    PassOrder order = kDefaultPassOrder;
    /// What the text was called in parse_graph_json (the file name for load_graph_file).
    std::string source;

    /// Where the pass `subject` ("pass") or port ("pass.port") is declared in the text, as a
    /// JSON pointer ("/passes/2", "/passes/2/outputs/0", "/passes/2/parts/1/inputs/0"; a port a
    /// pass and its port sets both declare: its first declaration); nullopt for a name the file
    /// does not declare. Written when asked for, from port_locations.
    [[nodiscard]] std::optional<std::string> pointer(std::string_view subject) const;

    /// Where a port is first declared: a list of the pass's own ports or of one of its "parts".
    struct PortLocation {
        static constexpr uint32_t kOwnPorts = ~uint32_t{0};
        uint32_t part = kOwnPorts;       ///< index in the pass's "parts", or kOwnPorts
        PortKind list = PortKind::Input;  ///< "inputs", "outputs" or "inouts"
        uint32_t index = 0;              ///< index in that list
    };
    /// Where the ports of the file's passes are declared, as parse_graph_json found them (read
    /// by pointer()): pass i's ports, in Pass::ports() order, are port_locations[
    /// first_port_location[i]] up to port_locations[first_port_location[i + 1]].
    std::vector<PortLocation> port_locations;
    std::vector<uint32_t> first_port_location;
};

/// Parses a JSON graph. `source` names the text in error messages (usually the file name).
Result<GraphFile> parse_graph_json(std::string_view text, std::string_view source = "graph");

/// Reads and parses a JSON graph file (ErrorCode::Io when it cannot be read).
Result<GraphFile> load_graph_file(const std::filesystem::path& path);

/// An error found later (by build_plan: a failed join, a cycle, an unconnected input) about
/// `file`'s graph, located in the file: "<source>: <JSON pointer of its first subject>:
/// <message>", with the pointers of its other subjects after it, e.g.
/// `g.json: /passes/1/inputs/0: required input b.in is not connected`. An error without known
/// subjects gets the source only.
Error locate_in_graph_file(const GraphFile& file, Error error);

/// A format by rhi name ("RGBA16Float") or short alias: a trailing "F" for Float ("RGBA16F",
/// "R11G11B10F"), no suffix for Unorm ("RGBA8", "R16"), "D16", "D24", "D32F", "D24S8",
/// "D32FS8", "S8"; names are also matched ignoring case.
std::optional<rhi::Format> parse_format_alias(std::string_view name);

}  // namespace loom::fg
