#pragma once
// The windowed samples' live frame inspector: a Dear ImGui overlay, shown and hidden with F1,
// with the frame's passes and their GPU and CPU times, the transient memory against naive
// allocation and the lower bound, and controls (allocator, switches that add or remove passes)
// whose changes the sample applies by re-planning. Drawn through loom's RHI (imgui_renderer.hpp),
// so it is the same on every backend. docs/inspector.md, "Live overlay".

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "loom/framegraph/allocator.hpp"
#include "loom/framegraph/executor.hpp"
#include "loom/framegraph/plan.hpp"
#include "loom/rhi/device.hpp"

struct ImGuiContext;

namespace loom::overlay {

class ImGuiRenderer;

/// A control that adds passes to the graph when on and removes them when off (or, with no
/// passes, any other choice of the application's that re-plans the frame).
struct OverlaySwitch {
    std::string label;
    /// The passes it stands for: their rows in the pass table carry its checkbox, and while it
    /// is off they are listed as switched off.
    std::vector<std::string> passes;
    bool on = true;

    friend bool operator==(const OverlaySwitch&, const OverlaySwitch&) = default;
};

/// What the overlay's controls set; the application re-plans when update() returns a change.
struct OverlayControls {
    fg::AllocatorKind allocator = fg::AllocatorKind::Interval;
    std::vector<OverlaySwitch> switches;

    /// The switch labelled `label`; null when there is none.
    [[nodiscard]] const OverlaySwitch* find(std::string_view label) const {
        for (const OverlaySwitch& s : switches) {
            if (s.label == label) return &s;
        }
        return nullptr;
    }

    friend bool operator==(const OverlayControls&, const OverlayControls&) = default;
};

/// What the overlay shows of the latest frame.
struct OverlayFrame {
    /// First line: backend, device, frame size.
    std::string title;
    /// The plan of the frame (null: none yet).
    const fg::Plan* plan = nullptr;
    std::vector<fg::PassTiming> timings;
    /// Everything alive on the device (fg::ExecutionStats::device).
    uint64_t device_bytes = 0;
    /// CPU time of the whole latest frame, in milliseconds.
    double frame_ms = 0.0;
    /// Shown highlighted under the controls (why the last change was refused); empty: nothing.
    std::string message;
};

class FrameOverlay {
public:
    /// An overlay drawing into `target_format` textures on `device`, hidden until F1 (or
    /// set_visible). Its ImGui context is its own: it writes no imgui.ini and leaves any
    /// context the application uses current again.
    static Result<std::unique_ptr<FrameOverlay>> create(rhi::Device& device, rhi::Format target_format);
    ~FrameOverlay();
    FrameOverlay(const FrameOverlay&) = delete;
    FrameOverlay& operator=(const FrameOverlay&) = delete;

    [[nodiscard]] bool visible() const { return visible_; }
    void set_visible(bool visible) { visible_ = visible; }

    /// One frame of the UI: F1 in `input` toggles the overlay; while shown, the pointer and
    /// keys drive it. Lays out `frame` for a target of `size` and returns the controls as the
    /// user left them (equal to `controls` when nothing changed). `seconds` is the time since
    /// the previous update.
    OverlayControls update(const rhi::WindowInput& input, rhi::Extent3D size, double seconds, const OverlayFrame& frame,
                           const OverlayControls& controls);

    /// Draws what the latest update laid out over `target`'s contents (nothing while hidden).
    /// Call once per frame: it uploads the frame's vertices, which replaces the previous ones.
    Status record(rhi::CommandList& commands, rhi::TextureHandle target);

    /// Where the latest update placed a control, in target pixels: "allocator:<name>" (the
    /// allocator's radio button), "switch:<label>" (a switch's checkbox, in the pass table on its
    /// first pass's row or below the table), "window" (the whole overlay). For tests and scripted
    /// clicks; none while hidden or for unknown names.
    [[nodiscard]] std::optional<rhi::Rect> control_rect(std::string_view name) const;

    /// True while the pointer is over the overlay (the application should ignore its clicks).
    [[nodiscard]] bool wants_pointer() const { return wants_pointer_; }

private:
    FrameOverlay();
    Status build(rhi::Device& device, rhi::Format target_format);
    void feed(const rhi::WindowInput& input, rhi::Extent3D size, double seconds);
    void layout(const OverlayFrame& frame, OverlayControls& controls);
    void remember(std::string name);

    ImGuiContext* context_ = nullptr;
    std::unique_ptr<ImGuiRenderer> renderer_;
    bool visible_ = false;
    bool wants_pointer_ = false;
    /// Buttons and keys pressed and released between two polls are held down for one update,
    /// then released in the next, so that ImGui sees the click or tap.
    std::array<bool, rhi::kMouseButtonCount> release_next_{};
    std::bitset<rhi::kKeyCount> keys_release_next_;
    std::map<std::string, rhi::Rect, std::less<>> rects_;
};

}  // namespace loom::overlay
