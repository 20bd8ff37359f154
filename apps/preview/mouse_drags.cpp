#include "mouse_drags.hpp"

namespace kiri::preview {

void MouseDrags::press(int button, bool panel_has_it)
{
    if (button < 0 || button >= buttons)
        return;
    button_[button].down = true;
    button_[button].for_camera = !panel_has_it;
}

void MouseDrags::release(int button)
{
    if (button >= 0 && button < buttons)
        button_[button].down = false;
}

void MouseDrags::move(double x, double y)
{
    const glm::dvec2 to(x, y);
    if (cursor_known_)
        for (Button& b : button_)
            if (b.down && b.for_camera)
                b.gathered += to - cursor_;
    cursor_ = to;
    cursor_known_ = true;
}

glm::dvec2 MouseDrags::take(int button)
{
    if (button < 0 || button >= buttons)
        return glm::dvec2(0.0);
    const glm::dvec2 out = button_[button].gathered;
    button_[button].gathered = glm::dvec2(0.0);
    return out;
}

bool MouseDrags::held(int button) const
{
    return button >= 0 && button < buttons && button_[button].down && button_[button].for_camera;
}

}  // namespace kiri::preview
