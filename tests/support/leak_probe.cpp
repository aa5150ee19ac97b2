// loom-leak-probe --backend gl|vulkan [--leak]
//
// Shows that the sanitizer build still reports a leak in loom's own code although
// scripts/lsan.supp suppresses the graphics drivers' allocations: it creates a device on one
// backend (loading the GL or Vulkan driver, the loader and, on Vulkan, the validation layer,
// whose allocations the suppressions cover), reads back a texture,
// then either destroys everything (no report expected) or, with --leak, forgets the device, as
// an application that leaks it would (LeakSanitizer must report the device allocated by
// loom::rhi::create_device). Registered as tests only in sanitizer builds (tests/support).
#include <cstdio>
#include <cstring>
#include <memory>

#include "loom/rhi/device.hpp"

int main(int argc, char** argv) {
    loom::rhi::DeviceDesc desc;
    bool leak = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--leak") == 0) {
            leak = true;
        } else if (std::strcmp(argv[i], "--backend") == 0 && i + 1 < argc) {
            ++i;
            desc.backend = std::strcmp(argv[i], "vulkan") == 0 ? loom::rhi::Backend::Vulkan : loom::rhi::Backend::OpenGL;
        } else {
            std::fprintf(stderr, "usage: loom-leak-probe --backend gl|vulkan [--leak]\n");
            return 2;
        }
    }
    auto device = loom::rhi::create_device(desc);
    if (!device) {
        std::fprintf(stderr, "loom-leak-probe: %s\n", device.error().to_string().c_str());
        return 1;
    }
    std::unique_ptr<loom::rhi::Device> owned = std::move(*device);
    // Some driver work, so that the driver's own allocations are made and then suppressed.
    loom::rhi::TextureDesc texture_desc;
    texture_desc.name = "probe";
    texture_desc.width = 16;
    texture_desc.height = 16;
    auto texture = owned->create_texture(texture_desc);
    if (!texture) {
        std::fprintf(stderr, "loom-leak-probe: %s\n", texture.error().to_string().c_str());
        return 1;
    }
    auto image = owned->read_texture(*texture);
    if (!image) {
        std::fprintf(stderr, "loom-leak-probe: %s\n", image.error().to_string().c_str());
        return 1;
    }
    if (leak) {
        // The deliberate leak: nothing refers to the device any more when the process exits.
        owned.release();  // NOLINT(bugprone-unused-return-value)
        std::printf("loom-leak-probe: device leaked\n");
        return 0;
    }
    owned.reset();
    std::printf("loom-leak-probe: device destroyed\n");
    return 0;
}
