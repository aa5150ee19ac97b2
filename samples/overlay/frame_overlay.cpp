#include "frame_overlay.hpp"

#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "imgui_renderer.hpp"
#include "loom/framegraph/export.hpp"

namespace loom::overlay {
namespace {

/// Makes `context` current for a scope and restores the application's afterwards.
class ContextScope {
public:
    explicit ContextScope(ImGuiContext* context) : ContextScope(context, ImGui::GetCurrentContext()) {}
    ContextScope(ImGuiContext* context, ImGuiContext* previous) : previous_(previous) { ImGui::SetCurrentContext(context); }
    ~ContextScope() { ImGui::SetCurrentContext(previous_); }
    ContextScope(const ContextScope&) = delete;
    ContextScope& operator=(const ContextScope&) = delete;

private:
    ImGuiContext* previous_;
};

int key_index(rhi::Key key) { return static_cast<int>(key); }

std::string milliseconds(std::optional<double> ms) {
    if (!ms) return "n/a";
    char text[32];
    std::snprintf(text, sizeof(text), "%.3f", *ms);
    return text;
}

}  // namespace

// Out of line: ImGuiRenderer is complete here.
FrameOverlay::FrameOverlay() = default;

Result<std::unique_ptr<FrameOverlay>> FrameOverlay::create(rhi::Device& device, rhi::Format target_format) {
    std::unique_ptr<FrameOverlay> overlay(new FrameOverlay());
    LOOM_TRY(overlay->build(device, target_format));
    return overlay;
}

Status FrameOverlay::build(rhi::Device& device, rhi::Format target_format) {
    // CreateContext makes the new context current when none was; the scope restores either way.
    ImGuiContext* previous = ImGui::GetCurrentContext();
    context_ = ImGui::CreateContext();
    ContextScope scope(context_, previous);
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the overlay's layout is not the user's to keep between runs
    io.LogFilename = nullptr;
    io.BackendPlatformName = "loom rhi::WindowInput";
    io.BackendRendererName = "loom rhi";
    using rhi::Key;
    io.KeyMap[ImGuiKey_Tab] = key_index(Key::Tab);
    io.KeyMap[ImGuiKey_LeftArrow] = key_index(Key::Left);
    io.KeyMap[ImGuiKey_RightArrow] = key_index(Key::Right);
    io.KeyMap[ImGuiKey_UpArrow] = key_index(Key::Up);
    io.KeyMap[ImGuiKey_DownArrow] = key_index(Key::Down);
    io.KeyMap[ImGuiKey_PageUp] = key_index(Key::PageUp);
    io.KeyMap[ImGuiKey_PageDown] = key_index(Key::PageDown);
    io.KeyMap[ImGuiKey_Home] = key_index(Key::Home);
    io.KeyMap[ImGuiKey_End] = key_index(Key::End);
    io.KeyMap[ImGuiKey_Insert] = key_index(Key::Insert);
    io.KeyMap[ImGuiKey_Delete] = key_index(Key::Delete);
    io.KeyMap[ImGuiKey_Backspace] = key_index(Key::Backspace);
    io.KeyMap[ImGuiKey_Space] = key_index(Key::Space);
    io.KeyMap[ImGuiKey_Enter] = key_index(Key::Enter);
    io.KeyMap[ImGuiKey_Escape] = key_index(Key::Escape);
    io.KeyMap[ImGuiKey_KeyPadEnter] = key_index(Key::Enter);
    io.KeyMap[ImGuiKey_A] = key_index(Key::A);
    io.KeyMap[ImGuiKey_C] = key_index(Key::C);
    io.KeyMap[ImGuiKey_V] = key_index(Key::V);
    io.KeyMap[ImGuiKey_X] = key_index(Key::X);
    io.KeyMap[ImGuiKey_Y] = key_index(Key::Y);
    io.KeyMap[ImGuiKey_Z] = key_index(Key::Z);
    ImGui::StyleColorsDark();
    auto renderer = ImGuiRenderer::create(device, target_format);
    if (!renderer) return renderer.take_error();
    renderer_ = std::move(*renderer);
    return {};
}

FrameOverlay::~FrameOverlay() {
    renderer_.reset();
    if (!context_) return;
    ImGuiContext* previous = ImGui::GetCurrentContext();
    ImGui::DestroyContext(context_);  // leaves no context current if it was current
    if (previous != context_) ImGui::SetCurrentContext(previous);
}

void FrameOverlay::feed(const rhi::WindowInput& input, rhi::Extent3D size, double seconds) {
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(std::max(size.width, 1u)), static_cast<float>(std::max(size.height, 1u)));
    io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);  // WindowInput's cursor is in framebuffer pixels already
    io.DeltaTime = seconds > 0.0 ? static_cast<float>(seconds) : 1.0f / 60.0f;
    io.MousePos = input.cursor_inside ? ImVec2(input.cursor_x, input.cursor_y) : ImVec2(-FLT_MAX, -FLT_MAX);
    for (std::size_t b = 0; b < rhi::kMouseButtonCount; ++b) {
        // A click shorter than a poll: down now, up in the next update.
        const bool tapped = input.buttons_pressed[b] && !input.buttons_down[b];
        io.MouseDown[b] = input.buttons_down[b] || (tapped && !release_next_[b]);
        release_next_[b] = tapped && !release_next_[b];
    }
    io.MouseWheel = input.scroll_y;
    io.MouseWheelH = input.scroll_x;
    std::bitset<rhi::kKeyCount> tapped_keys;
    for (rhi::Key key : input.key_presses) {
        if (!input.down(key)) tapped_keys.set(static_cast<std::size_t>(key));
    }
    for (std::size_t k = 0; k < rhi::kKeyCount; ++k) {
        const bool tapped = tapped_keys.test(k) && !keys_release_next_.test(k);
        io.KeysDown[k] = input.keys_down.test(k) || tapped;
        keys_release_next_.set(k, tapped);
    }
    io.KeyShift = input.shift;
    io.KeyCtrl = input.ctrl;
    io.KeyAlt = input.alt;
    io.KeySuper = input.super;
    for (char32_t c : input.text) io.AddInputCharacter(static_cast<unsigned int>(c));
}

void FrameOverlay::remember(std::string name) {
    const ImVec2 min = ImGui::GetItemRectMin();
    const ImVec2 max = ImGui::GetItemRectMax();
    rects_[std::move(name)] = rhi::Rect{static_cast<int32_t>(min.x), static_cast<int32_t>(min.y),
                                        static_cast<uint32_t>(std::max(0.0f, max.x - min.x)),
                                        static_cast<uint32_t>(std::max(0.0f, max.y - min.y))};
}

OverlayControls FrameOverlay::update(const rhi::WindowInput& input, rhi::Extent3D size, double seconds,
                                     const OverlayFrame& frame, const OverlayControls& controls) {
    if (input.pressed(rhi::Key::F1)) visible_ = !visible_;
    ContextScope scope(context_);
    feed(input, size, seconds);
    ImGui::NewFrame();
    rects_.clear();
    OverlayControls result = controls;
    if (visible_) layout(frame, result);
    ImGui::Render();
    wants_pointer_ = visible_ && ImGui::GetIO().WantCaptureMouse;
    return result;
}

void FrameOverlay::layout(const OverlayFrame& frame, OverlayControls& controls) {
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowBgAlpha(0.92f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings;
    if (!ImGui::Begin("loom frame inspector", nullptr, flags)) {
        ImGui::End();
        return;
    }
    ImGui::TextUnformatted(frame.title.c_str());
    const fg::Plan* plan = frame.plan;
    if (plan) {
        ImGui::Text("%zu passes, %zu resources; CPU %.2f ms per frame", plan->order.size(), plan->resources.size(),
                    frame.frame_ms);
        ImGui::Separator();
        const fg::PlanSummary& s = plan->summary;
        ImGui::Text("transient memory %s (naive %s, lower bound %s)", fg::format_bytes(s.bytes).c_str(),
                    fg::format_bytes(s.naive_bytes).c_str(), fg::format_bytes(s.lower_bound_bytes).c_str());
        const float used = s.naive_bytes ? static_cast<float>(static_cast<double>(s.bytes) / static_cast<double>(s.naive_bytes)) : 0.0f;
        char share[32];
        std::snprintf(share, sizeof(share), "%.0f%% of naive", used * 100.0f);
        ImGui::ProgressBar(used, ImVec2(-1.0f, 0.0f), share);
        ImGui::Text("aliasing saves %s; textures %u (naive %u, lower bound %u)",
                    fg::format_bytes(s.naive_bytes > s.bytes ? s.naive_bytes - s.bytes : 0).c_str(), s.textures,
                    s.naive_textures, s.lower_bound_textures);
        ImGui::Text("device total %s", fg::format_bytes(frame.device_bytes).c_str());
    }
    ImGui::Separator();
    ImGui::TextUnformatted("allocator:");
    const auto names = fg::allocator_names();
    for (std::string_view name : names) {
        auto kind = fg::parse_allocator(name);
        if (!kind) continue;
        ImGui::SameLine();
        const std::string label(name);
        if (ImGui::RadioButton(label.c_str(), controls.allocator == *kind)) controls.allocator = *kind;
        remember("allocator:" + label);
    }
    // Switches that stand for no pass, and why the last change was refused, above the pass table
    // (which may be long): always in view.
    for (OverlaySwitch& s : controls.switches) {
        if (!s.passes.empty()) continue;
        const std::string id = s.label + "##switch";
        ImGui::Checkbox(id.c_str(), &s.on);
        remember("switch:" + s.label);
    }
    if (!frame.message.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
        ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.35f, 1.0f), "%s", frame.message.c_str());
        ImGui::PopTextWrapPos();
    }

    // Which switch a pass belongs to, and which passes show a switch's checkbox.
    auto switch_of = [&](std::string_view pass) -> OverlaySwitch* {
        for (OverlaySwitch& s : controls.switches) {
            if (std::find(s.passes.begin(), s.passes.end(), pass) != s.passes.end()) return &s;
        }
        return nullptr;
    };
    std::map<std::string, bool, std::less<>> checkbox_shown;
    auto checkbox = [&](OverlaySwitch& s) {
        if (checkbox_shown[s.label]) return;
        checkbox_shown[s.label] = true;
        const std::string id = "##switch:" + s.label;
        ImGui::Checkbox(id.c_str(), &s.on);
        remember("switch:" + s.label);
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.label.c_str());
    };

    std::map<std::string_view, const fg::PassTiming*> timing_of;
    double max_gpu = 0.0;
    for (const fg::PassTiming& t : frame.timings) {
        timing_of[t.pass] = &t;
        if (t.gpu_ms) max_gpu = std::max(max_gpu, *t.gpu_ms);
    }
    // A plan taller than the space left scrolls inside the table, so the rest stays on screen.
    std::size_t rows = 1;  // the header
    if (plan) rows += plan->order.size() + plan->culled.size();
    for (const OverlaySwitch& s : controls.switches) rows += s.on ? 0 : s.passes.size();
    const ImGuiStyle& style = ImGui::GetStyle();
    const float row_height = ImGui::GetFrameHeight() + 2.0f * style.CellPadding.y;
    const float space = ImGui::GetIO().DisplaySize.y - ImGui::GetCursorScreenPos().y - 6.0f * ImGui::GetTextLineHeightWithSpacing();
    const float table_height = std::max(space, 6.0f * row_height);
    ImGuiTableFlags table_flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingFixedFit;
    ImVec2 outer(0.0f, 0.0f);
    if (static_cast<float>(rows) * row_height > table_height) {
        table_flags |= ImGuiTableFlags_ScrollY;
        outer.y = table_height;
    }
    if (ImGui::BeginTable("passes", 5, table_flags, outer)) {
        ImGui::TableSetupScrollFreeze(0, 1);
        ImGui::TableSetupColumn("on");
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableSetupColumn("CPU ms");
        ImGui::TableSetupColumn("GPU time", ImGuiTableColumnFlags_WidthFixed, 120.0f);
        ImGui::TableHeadersRow();
        if (plan) {
            for (const fg::PlanPass& pass : plan->order) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                if (OverlaySwitch* s = switch_of(pass.name)) checkbox(*s);
                ImGui::TableNextColumn();
                if (pass.queue == fg::Queue::AsyncCompute) {
                    ImGui::TextColored(ImVec4(0.55f, 0.8f, 1.0f, 1.0f), "%s (async compute)", pass.name.c_str());
                } else {
                    ImGui::TextUnformatted(pass.name.c_str());
                }
                const auto t = timing_of.find(pass.name);
                const fg::PassTiming* timing = t == timing_of.end() ? nullptr : t->second;
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(milliseconds(timing ? timing->gpu_ms : std::nullopt).c_str());
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(milliseconds(timing ? std::optional<double>(timing->cpu_ms) : std::nullopt).c_str());
                ImGui::TableNextColumn();
                const float share = timing && timing->gpu_ms && max_gpu > 0.0 ? static_cast<float>(*timing->gpu_ms / max_gpu) : 0.0f;
                ImGui::ProgressBar(share, ImVec2(-1.0f, 0.0f), "");
            }
            for (const std::string& culled : plan->culled) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::TableNextColumn();
                ImGui::TextDisabled("%s (culled)", culled.c_str());
            }
        }
        // Switched-off passes are not in the plan; their rows keep the checkbox that restores them.
        for (OverlaySwitch& s : controls.switches) {
            if (s.on) continue;
            for (const std::string& pass : s.passes) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                checkbox(s);
                ImGui::TableNextColumn();
                ImGui::TextDisabled("%s (off)", pass.c_str());
            }
        }
        ImGui::EndTable();
    }
    // A switch whose passes are all absent from the plan while on (e.g. culled) still needs a box.
    for (OverlaySwitch& s : controls.switches) {
        if (s.passes.empty() || checkbox_shown[s.label]) continue;
        const std::string id = s.label + "##switch";
        ImGui::Checkbox(id.c_str(), &s.on);
        remember("switch:" + s.label);
    }
    for (const OverlaySwitch& s : controls.switches) {
        if (s.passes.empty()) continue;
        std::string passes;
        for (const std::string& pass : s.passes) passes += (passes.empty() ? "" : " + ") + pass;
        ImGui::TextDisabled("[%s] %s: %s", s.on ? "x" : " ", passes.c_str(), s.label.c_str());
    }
    ImGui::TextDisabled("F1 hides this overlay; changes re-plan the frame");
    const ImVec2 pos = ImGui::GetWindowPos();
    const ImVec2 extent = ImGui::GetWindowSize();
    rects_["window"] = rhi::Rect{static_cast<int32_t>(pos.x), static_cast<int32_t>(pos.y), static_cast<uint32_t>(extent.x),
                                 static_cast<uint32_t>(extent.y)};
    ImGui::End();
}

Status FrameOverlay::record(rhi::CommandList& commands, rhi::TextureHandle target) {
    if (!visible_) return {};
    ContextScope scope(context_);
    const ImDrawData* data = ImGui::GetDrawData();
    if (!data || !data->Valid) return {};
    return renderer_->record(commands, target, *data);
}

std::optional<rhi::Rect> FrameOverlay::control_rect(std::string_view name) const {
    const auto found = rects_.find(name);
    if (found == rects_.end()) return std::nullopt;
    return found->second;
}

}  // namespace loom::overlay
