#pragma once
// Small Dear ImGui helpers over doubles (the scene is in double; ImGui edits floats) and the
// sun's direction widget.
#include <glm/vec3.hpp>

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

}  // namespace kiri::preview
