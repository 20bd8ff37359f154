#pragma once
//! \file author_report.hpp
//! report.json of `kiri author`, and the optics written into exported maps.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "kiri/geometry/scene/pipeline.hpp"

namespace kiri::geometry {

//! report.json of `kiri author` for `scene` authored as `products` (a pipeline run that reached
//! the layer base): the fog section, the fit figures (FitReport), counts, the tessellation's
//! error, each stage's time (`stages`), then "optics" (the medium's extinction, visibility,
//! liquid water content, albedo, g, and the engines' equivalents, engine_fog in medium.hpp)
//! and, for fog placed by the terrain, "placement" (per region, the fog, the valleys, the
//! outline, flow, burn-off, timings). Heights and thicknesses are metres of the DEM (the
//! exaggeration taken out).
std::string author_report_json(const Scene& scene, const PipelineProducts& products,
                               const std::array<StageRecord, stage_count>& stages);

//! The optics as (name, value) pairs for the metadata of exported maps.
std::vector<std::pair<std::string, std::string>> optics_metadata(const MediumOptions& medium);

}  // namespace kiri::geometry
