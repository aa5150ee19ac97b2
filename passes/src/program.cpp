#include "loom/passes/program.hpp"

namespace loom::passes {
namespace {

std::optional<ResourceSlot> find_in(const rhi::ShaderReflection& reflection, std::string_view name) {
    for (const rhi::UniformBlock& block : reflection.uniform_blocks) {
        if (block.name == name) return ResourceSlot{block.set, block.binding, block.size};
    }
    for (const rhi::StorageBuffer& buffer : reflection.storage_buffers) {
        if (buffer.name == name) return ResourceSlot{buffer.set, buffer.binding, buffer.size, true};
    }
    for (const rhi::SampledTexture& texture : reflection.textures) {
        if (texture.name == name) return ResourceSlot{texture.set, texture.binding, 0};
    }
    return std::nullopt;
}

}  // namespace

Program::Program(std::string pass, std::string kind, rhi::ShaderModule vertex, rhi::ShaderModule fragment)
    : pass_(std::move(pass)), kind_(std::move(kind)), vertex_(std::move(vertex)), fragment_(std::move(fragment)) {}

std::string Program::name() const { return kind_.empty() ? pass_ : pass_ + "/" + kind_; }

std::optional<ResourceSlot> Program::find(std::string_view name) const {
    if (auto slot = find_in(vertex_.reflection, name)) return slot;
    return find_in(fragment_.reflection, name);
}

Result<ResourceSlot> Program::slot(std::string_view name) const {
    if (auto found = find(name)) return *found;
    return make_error(ErrorCode::InvalidArgument,
                      "program '" + this->name() + "' has no resource named '" + std::string(name) + "'");
}

Result<ResourceSlot> Program::uniform_slot(std::string_view block, uint32_t size) const {
    auto found = slot(block);
    if (!found) return found;
    if (found->size != size) {
        return make_error(ErrorCode::InvalidArgument,
                          "program '" + name() + "': uniform block '" + std::string(block) + "' is " +
                              std::to_string(found->size) + " bytes in the shader but " + std::to_string(size) +
                              " bytes on the CPU");
    }
    return found;
}

}  // namespace loom::passes
