// Mouse and keys of the preview window (docs/preview.md "Controls"). ImGui's IO is read after
// its NewFrame: what the panel takes (WantCaptureMouse / Keyboard) the camera does not get.
#include <epoxy/gl.h>
// epoxy first: GLFW then skips its own GL header.
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <utility>

#include "preview_app.hpp"

namespace kiri::preview {

bool PreviewApp::handle_input(double seconds)
{
    const ImGuiIO& io = ImGui::GetIO();
    const glm::dvec3 before = camera_.eye(), target_before = camera_.target();
    // Each button's drag as gathered from the events (mouse_drags.hpp); a drag begun on the panel
    // gathers nothing.
    const glm::dvec2 left = drags_.take(GLFW_MOUSE_BUTTON_LEFT), right = drags_.take(GLFW_MOUSE_BUTTON_RIGHT),
                     middle = drags_.take(GLFW_MOUSE_BUTTON_MIDDLE);
    if (!io.WantCaptureMouse && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left))
        pivot_at_cursor();
    else if (left != glm::dvec2(0.0))
        ui_.fly_mode ? camera_.look_around(left.x, left.y) : camera_.orbit(left.x, left.y);
    if (middle != glm::dvec2(0.0))
        camera_.look_around(middle.x, middle.y);
    if (right != glm::dvec2(0.0))
        camera_.pan(right.x, right.y, io.DisplaySize.y);
    if (!io.WantCaptureMouse && io.MouseWheel != 0.0f)
        camera_.zoom(io.MouseWheel);
    if (!io.WantCaptureKeyboard) {
        if (!io.KeyCtrl) {  // Ctrl+S saves, it does not fly backwards
            GLFWwindow* w = window_->window();
            const auto key = [w](int k) { return glfwGetKey(w, k) == GLFW_PRESS ? 1.0 : 0.0; };
            // Half the distance to the target per second: slow near the ground, fast from afar.
            const double speed = std::clamp(0.5 * camera_.distance(), 5.0, 50000.0) * (io.KeyShift ? 4.0 : 1.0);
            camera_.fly(key(GLFW_KEY_W) - key(GLFW_KEY_S), key(GLFW_KEY_D) - key(GLFW_KEY_A),
                        key(GLFW_KEY_E) - key(GLFW_KEY_Q), seconds, speed);
        }
        handle_keys();
    }
    key_presses_.clear();  // typed into the panel
    return camera_.eye() != before || camera_.target() != target_before;
}

void PreviewApp::on_key(GLFWwindow* window, int key, int, int action, int mods)
{
    if (action == GLFW_PRESS)
        static_cast<PreviewApp*>(glfwGetWindowUserPointer(window))->key_presses_.push_back({key, mods});
}

void PreviewApp::on_mouse_button(GLFWwindow* window, int button, int action, int)
{
    auto* app = static_cast<PreviewApp*>(glfwGetWindowUserPointer(window));
    if (action == GLFW_PRESS)
        app->drags_.press(button, ImGui::GetIO().WantCaptureMouse);
    else if (action == GLFW_RELEASE)
        app->drags_.release(button);
}

void PreviewApp::on_cursor(GLFWwindow* window, double x, double y)
{
    static_cast<PreviewApp*>(glfwGetWindowUserPointer(window))->drags_.move(x, y);
}

void PreviewApp::handle_keys()
{
    for (const KeyPress& k : std::exchange(key_presses_, {}))
        handle_key(k.key, k.mods);
}

void PreviewApp::handle_key(int key, int mods)
{
    const auto pressed = [key](int k) { return key == k; };
    if (mods & GLFW_MOD_CONTROL) {
        ui_.save |= pressed(GLFW_KEY_S);
        return;
    }
    ui_.focus_fog |= pressed(GLFW_KEY_F);
    ui_.reset_camera |= pressed(GLFW_KEY_R);
    ui_.screenshot |= pressed(GLFW_KEY_F12) || pressed(GLFW_KEY_P);
    if (pressed(GLFW_KEY_TAB))
        ui_.fly_mode = !ui_.fly_mode;
    if (pressed(GLFW_KEY_H))
        ui_.view.show_panel = !ui_.view.show_panel;
    if (pressed(GLFW_KEY_T))
        ui_.view.show_stats = !ui_.view.show_stats;
    if (pressed(GLFW_KEY_M)) {  // the next render mode
        ui_.view.mode = next_fog_mode(ui_.view.mode);
        ui_.mode_changed = true;
    }
    for (int i = 0; i < 9 && i < int(scene_.cameras.size()); ++i)
        if (pressed(GLFW_KEY_1 + i))
            ui_.bookmark = i;
}

void PreviewApp::pivot_at_cursor()
{
    const ImGuiIO& io = ImGui::GetIO();
    if (last_width_ <= 0 || io.DisplaySize.x <= 0.0f || io.DisplaySize.y <= 0.0f)
        return;
    // Window pixels to the pixels of the last 3D frame (HiDPI and the render scale).
    const int x = int(io.MousePos.x / io.DisplaySize.x * float(last_width_));
    const int y = int(io.MousePos.y / io.DisplaySize.y * float(last_height_));
    if (const auto p = renderer_->pick(x, y))
        camera_.set_target(*p);
}

}  // namespace kiri::preview
