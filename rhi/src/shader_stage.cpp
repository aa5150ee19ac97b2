#include "loom/rhi/shader.hpp"

#include <string_view>

namespace loom::rhi {

std::string_view shader_stage_name(ShaderStage stage) {
    switch (stage) {
        case ShaderStage::Vertex: return "vertex";
        case ShaderStage::Fragment: return "fragment";
        case ShaderStage::Compute: return "compute";
    }
    return "unknown";
}

}  // namespace loom::rhi
