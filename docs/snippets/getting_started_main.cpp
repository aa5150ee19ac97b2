// docs/getting-started.md: the first program (loom-docs-first-graph, run by ctest).
#include <cstdio>
#include <string>

#include "snippets.hpp"

#include "loom/image_io/image_io.hpp"

// [docs:main]
int main(int argc, char** argv) {
    using namespace loom;
    const std::string backend = argc > 1 ? argv[1] : "gl";
    rhi::DeviceDesc desc;
    desc.backend = rhi::parse_backend(backend).value_or(rhi::Backend::OpenGL);
    desc.headless = true;  // no window: render offscreen
    desc.debug = true;     // GL debug output / Vulkan validation, logged through loom::log
    auto device = rhi::create_device(desc);
    if (!device) {
        std::fprintf(stderr, "%s\n", device.error().to_string().c_str());
        return 1;
    }
    auto image = docs::render_first_graph(**device);
    if (!image) {
        std::fprintf(stderr, "%s\n", image.error().to_string().c_str());
        return 1;
    }
    const std::string path = "first_graph_" + backend + ".png";
    if (auto written = image_io::write_png(*image, path); !written) return 1;
    std::printf("wrote %s (%ux%u)\n", path.c_str(), image->width, image->height);
    return 0;
}
// [/docs:main]
