#include "loom/framegraph/executor.hpp"

namespace loom::fg {

Result<rhi::MemoryRequirements> DeviceMemoryModel::requirements(const rhi::TextureDesc& desc) {
    return device_->texture_memory_requirements(desc);
}

Result<rhi::MemoryRequirements> DeviceMemoryModel::buffer_requirements(const rhi::BufferDesc& desc) {
    return device_->buffer_memory_requirements(desc);
}

}  // namespace loom::fg
