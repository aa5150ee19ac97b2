#include "loom/sample_common/window_loop.hpp"

namespace loom::samples {

Status run_window_loop(rhi::Device& device, const FrameRecorder& record, uint64_t max_frames) {
    uint64_t frames = 0;
    while (device.poll_window()) {
        rhi::CommandList& list = device.begin_frame();
        const rhi::TextureHandle backbuffer = device.backbuffer();
        if (backbuffer.is_null()) {
            (void)device.end_frame();
            return Error{ErrorCode::InvalidState, "run_window_loop: the device has no window (it is headless)"};
        }
        record(list, backbuffer, device.window_size());
        LOOM_TRY(device.end_frame());
        if (max_frames != 0 && ++frames >= max_frames) break;
    }
    return device.wait_idle();
}

}  // namespace loom::samples
