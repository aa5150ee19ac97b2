#pragma once
// A program: the vertex and fragment stage a pass composed for one object kind (or for itself),
// compiled, with lookups of its resources by the names reflection reports.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "loom/rhi/result.hpp"
#include "loom/rhi/shader.hpp"

namespace loom::passes {

/// Where a resource of a program lives.
struct ResourceSlot {
    uint32_t set = 0;
    uint32_t binding = 0;
    /// Declared size in bytes of a uniform block or storage buffer (without a trailing array;
    /// 0 for textures).
    uint32_t size = 0;
    /// A storage buffer (its size is a minimum, not the exact size).
    bool storage_buffer = false;

    friend bool operator==(const ResourceSlot&, const ResourceSlot&) = default;
};

class Program {
public:
    Program(std::string pass, std::string kind, rhi::ShaderModule vertex, rhi::ShaderModule fragment);

    /// "pass/kind", or "pass" for a pass's own program.
    [[nodiscard]] std::string name() const;
    [[nodiscard]] const std::string& pass() const { return pass_; }
    /// The object kind it was composed for; empty for a pass's own program.
    [[nodiscard]] const std::string& kind() const { return kind_; }
    [[nodiscard]] const rhi::ShaderModule& vertex() const { return vertex_; }
    [[nodiscard]] const rhi::ShaderModule& fragment() const { return fragment_; }

    /// The slot of a uniform block or storage buffer (by block type name, e.g.
    /// "CameraUniforms") or of a sampled texture (by variable name) in either stage; nullopt when the program has none of that
    /// name (a part that was left out, or a resource the compiler found unused).
    [[nodiscard]] std::optional<ResourceSlot> find(std::string_view name) const;
    /// find(), or an InvalidArgument error naming the program and the resource.
    [[nodiscard]] Result<ResourceSlot> slot(std::string_view name) const;
    /// slot() of a uniform block, also checking that the block is `size` bytes (the C++ struct
    /// mirrors it): a mismatch is an InvalidArgument error naming both sizes.
    [[nodiscard]] Result<ResourceSlot> uniform_slot(std::string_view block, uint32_t size) const;

private:
    std::string pass_;
    std::string kind_;
    rhi::ShaderModule vertex_;
    rhi::ShaderModule fragment_;
};

}  // namespace loom::passes
