#include "loom/framegraph/executor.hpp"

namespace loom::fg {

Result<rhi::MemoryRequirements> DeviceMemoryModel::requirements(const rhi::TextureDesc& desc) {
    return device_->texture_memory_requirements(desc);
}

}  // namespace loom::fg
