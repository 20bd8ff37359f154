#pragma once
// The camera's mouse drags, gathered from the window's events as they come rather than from the
// cursor's position once a frame: on a software GL a frame can take a second, and a drag that
// starts and ends within one (or ends between two) would otherwise lose the motion the frame did
// not see, or take the motion before the press as part of it.

#include <array>

#include <glm/vec2.hpp>

namespace kiri::preview {

class MouseDrags {
public:
    static constexpr int buttons = 3;  //!< left, right, middle (GLFW's and ImGui's order)

    //! A button went down at the cursor's last position; `panel_has_it` (ImGui wanted the mouse
    //! then) keeps that drag from the camera until the button comes up.
    void press(int button, bool panel_has_it);
    void release(int button);
    //! The cursor moved to (x, y) window pixels: each button held for the camera gathers the step.
    void move(double x, double y);
    //! The motion gathered for `button` since the last take, in window pixels; then zero. A
    //! button released since the last take still gives what it gathered while it was down.
    glm::dvec2 take(int button);
    bool held(int button) const;  //!< down, and for the camera

private:
    struct Button {
        bool down = false, for_camera = false;
        glm::dvec2 gathered{0.0};
    };
    std::array<Button, buttons> button_{};
    glm::dvec2 cursor_{0.0};
    bool cursor_known_ = false;
};

}  // namespace kiri::preview
