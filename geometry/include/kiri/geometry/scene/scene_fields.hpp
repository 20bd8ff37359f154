#pragma once
//! \file scene_fields.hpp
//! The key tables of the docs, generated from the scene's field lists (core/fields.hpp): each
//! lies in docs/*.md between the HTML comments "fields: SECTION" and "/fields", and
//! tests/geometry/docs_fields_test.cpp fails when one differs from what the lists give
//! (KIRI_UPDATE_DOCS=1 rewrites them).
#include <string>
#include <string_view>
#include <vector>

namespace kiri::geometry {

//! "terrain", "cameras", "sun", "image", "fog", "fog/tessellation", "fog/fill",
//! "fog/fill/valleys", "fog/outline", "fog/flow", "fog/burn_off", "layers", "medium",
//! "particles", "froxel", "froxel/height_fog", "combined".
std::vector<std::string> documented_sections();
//! The markdown table of a section's keys: key, type and range, unit, default, meaning.
//! \throw std::invalid_argument for a section that is not one of documented_sections().
std::string fields_table(std::string_view section);

}  // namespace kiri::geometry
