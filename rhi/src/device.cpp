#include "loom/rhi/device.hpp"

#include <atomic>

#include "loom/rhi/handle_pool.hpp"
#include "loom/rhi/log.hpp"

namespace loom::rhi {

std::string_view backend_name(Backend backend) {
    switch (backend) {
        case Backend::OpenGL: return "gl";
        case Backend::Vulkan: return "vulkan";
    }
    return "unknown";
}

std::optional<Backend> parse_backend(std::string_view name) {
    if (name == "gl" || name == "opengl") return Backend::OpenGL;
    if (name == "vulkan" || name == "vk") return Backend::Vulkan;
    return std::nullopt;
}

void CommandList::draw_indexed_indirect(BufferHandle, uint64_t, uint32_t draw_count, uint32_t) {
    // A backend without indirect draws (Capabilities::draw_indirect false) cannot record an
    // error in its own list through this base class; say so loudly instead of drawing nothing.
    log_error("rhi", "draw_indexed_indirect of " + std::to_string(draw_count) +
                         " draws: this backend does not implement indirect draws (Capabilities::draw_indirect is false)");
}

uint16_t next_device_id() {
    static std::atomic<uint16_t> counter{0};
    uint16_t id = ++counter;
    if (id == 0) id = ++counter;  // 0 never names a device
    return id;
}

}  // namespace loom::rhi
