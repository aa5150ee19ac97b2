// docs/backends.md: capabilities, explicit states, accounting and debug output, compiled;
// describe_device() runs them on a device (snippets_test.cpp).
#include <sstream>

#include "loom/rhi/device.hpp"
#include "loom/rhi/log.hpp"
#include "snippets.hpp"

namespace loom::docs {

// [docs:debug]
/// Where loom's messages go: GL debug output and Vulkan validation arrive as LogLevel::Error
/// (source "gl" / "vulkan") when DeviceDesc::debug is on; the default sink prints warnings and
/// errors to stderr.
void route_messages_to(std::ostringstream& out) {
    set_log_level(LogLevel::Warning);
    set_log_sink([&out](LogLevel level, std::string_view source, std::string_view message) {
        out << log_level_name(level) << " [" << source << "] " << message << "\n";
    });
}
// [/docs:debug]

Result<std::string> describe_device(rhi::Device& device) {
    std::ostringstream text;
    // [docs:capabilities]
    const rhi::Capabilities& caps = device.capabilities();
    text << rhi::backend_name(caps.backend) << ": " << caps.device_name << " | " << caps.api_version << "\n";
    // What the device can do with a format decides what a plan may ask for.
    const rhi::FormatCapabilities& hdr = caps.format(rhi::Format::RGBA16Float);
    text << "RGBA16Float: " << (hdr.color_attachment ? "renderable" : "not renderable") << ", "
         << (hdr.blendable ? "blendable" : "not blendable") << ", " << (hdr.filterable ? "filterable" : "not filterable")
         << "\n";
    // Placed resources (memory aliasing) let the "heap" allocator share bytes between textures.
    text << "placed resources: " << (caps.placed_resources ? "yes" : "no") << ", timestamps: "
         << (caps.timestamps ? "yes" : "no") << "\n";
    // [/docs:capabilities]

    rhi::TextureDesc desc;
    desc.name = "target";
    desc.format = rhi::Format::RGBA8Unorm;
    desc.width = 64;
    desc.height = 64;
    desc.usage = rhi::TextureUsage::ColorAttachment | rhi::TextureUsage::Sampled | rhi::TextureUsage::CopySrc;
    auto created = device.create_texture(desc);
    if (!created) return created.take_error();
    const rhi::TextureHandle target = *created;

    // [docs:states]
    rhi::CommandList& cmd = device.begin_frame();
    cmd.begin_timer("clear");
    rhi::RenderPassDesc pass;
    pass.label = "clear";
    pass.colors.push_back({target, 0, 0, rhi::LoadOp::Clear, rhi::StoreOp::Store, {0.0, 0.5, 1.0, 1.0}});
    cmd.begin_render_pass(pass);  // moves `target` to RenderTarget itself
    cmd.end_render_pass();
    cmd.end_timer();
    // Before a shader samples it: Vulkan records a layout transition and a barrier; GL needs
    // nothing here (only storage writes need glMemoryBarrier), but the state is tracked the same.
    cmd.transition(target, rhi::ResourceState::ShaderRead);
    LOOM_TRY(device.end_frame());  // the first error recorded in the frame, if any
    // [/docs:states]

    // [docs:accounting]
    LOOM_TRY(device.wait_idle());  // timer results of the last frame are there after this
    const rhi::ResourceStats resources = device.resource_stats();
    const rhi::FrameStats frame = device.last_frame_stats();
    text << resources.textures << " texture(s), " << resources.texture_bytes << " bytes; last frame: " << frame.render_passes
         << " render pass(es), " << frame.api_calls << " API calls\n";
    for (const rhi::TimerResult& timer : device.timer_results()) text << timer.label << ": " << timer.gpu_ms << " ms\n";
    // [/docs:accounting]
    LOOM_TRY(device.destroy(target));
    return text.str();
}

}  // namespace loom::docs
