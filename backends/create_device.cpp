// rhi::create_device for the backends compiled into this build.
#include "loom/rhi/device.hpp"

#if defined(LOOM_HAS_GL)
#include "loom/gl/gl_device.hpp"
#endif
#if defined(LOOM_HAS_VULKAN)
#include "loom/vulkan/vulkan_device.hpp"
#endif

namespace loom::rhi {

namespace {
// The trailing entry keeps the array non-empty when no backend is compiled in; it is not
// part of the list.
constexpr Backend kCompiled[] = {
#if defined(LOOM_HAS_GL)
    Backend::OpenGL,
#endif
#if defined(LOOM_HAS_VULKAN)
    Backend::Vulkan,
#endif
    Backend::OpenGL,
};
}  // namespace

std::span<const Backend> compiled_backends() { return {std::begin(kCompiled), std::size(kCompiled) - 1}; }

Result<std::unique_ptr<Device>> create_device(const DeviceDesc& desc) {
    switch (desc.backend) {
        case Backend::OpenGL:
#if defined(LOOM_HAS_GL)
            return gl::create_gl_device(desc);
#else
            return Error{ErrorCode::Unsupported, "the OpenGL backend is not compiled into this build (LOOM_WITH_GL=OFF)"};
#endif
        case Backend::Vulkan:
#if defined(LOOM_HAS_VULKAN)
            return vulkan::create_vulkan_device(desc);
#else
            return Error{ErrorCode::Unsupported, "the Vulkan backend is not compiled into this build (LOOM_WITH_VULKAN=OFF)"};
#endif
    }
    return Error{ErrorCode::InvalidArgument, "unknown backend"};
}

}  // namespace loom::rhi
