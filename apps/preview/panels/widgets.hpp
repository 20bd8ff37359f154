#pragma once
// Small Dear ImGui helpers over doubles (the scene is in double; ImGui edits floats), the
// scene's options edited by their field lists (geometry/core/fields.hpp: the slider's range
// and a tooltip with the unit, the range and the meaning) and the sun's direction widget.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/core/fields.hpp"

namespace kiri::preview {

bool slider(const char* label, double& value, double lo, double hi, const char* format = "%.1f", bool log = false);
bool slider(const char* label, int& value, int lo, int hi);
//! Unbounded drag for coordinates (metres).
bool drag(const char* label, double& value, double speed, const char* format = "%.0f");
bool color_edit(const char* label, glm::dvec3& rgb);
//! The sky seen from above, north up: the centre is the zenith, the rim 10 degrees below the
//! horizon; dragging sets the direction (a unit vector, z >= sin(-10 deg)).
bool direction_widget(const char* label, glm::dvec3& direction, float radius = 70.0f);
//! A horizontal colour bar of the map `color(t)` for t in [t0, t1], with end labels.
void color_legend(const char* low, const char* high, bool diverging);

//! The field's unit, range and meaning when the last item is hovered.
void field_tooltip(const geometry::FieldInfo& info, bool integer = false);
//! A slider over the field's widget range (its range where it has no narrower one), shown in
//! the field's unit divided by `per_shown` (3600: seconds shown as hours).
bool field_slider(const char* label, double& value, const geometry::FieldInfo& info, const char* format = "%.2f",
                  double per_shown = 1.0);
bool field_slider(const char* label, int& value, const geometry::FieldInfo& info);
//! Both components over the field's widget range.
bool field_slider(const char* label, glm::dvec2& value, const geometry::FieldInfo& info, const char* format = "%.1f");
//! An unbounded field: dragged.
bool field_drag(const char* label, double& value, const geometry::FieldInfo& info, double speed,
                const char* format = "%.0f");
//! A checkbox with the field's tooltip.
bool field_checkbox(const char* label, bool& value, const geometry::FieldInfo& info);
//! A combo of the field's choices (an enumeration).
template <class E>
bool field_combo(const char* label, E& value, const geometry::FieldInfo& info);
bool choice_combo(const char* label, int& value, const geometry::FieldInfo& info);

template <class E>
bool field_combo(const char* label, E& value, const geometry::FieldInfo& info)
{
    int v = int(value);
    if (!choice_combo(label, v, info))
        return false;
    value = E(v);
    return true;
}

//! member of options o, edited by its field (the format applies to numbers).
template <class O, class T>
bool edit(const char* label, O& o, T& member, const char* format = "%.2f")
{
    const geometry::FieldInfo info = geometry::field_of(o, member);
    if constexpr (std::is_same_v<T, bool>)
        return field_checkbox(label, member, info);
    else if constexpr (std::is_enum_v<T>)
        return field_combo(label, member, info);
    else if constexpr (std::is_same_v<T, int>)
        return field_slider(label, member, info);
    else
        return field_slider(label, member, info, format);
}

}  // namespace kiri::preview
