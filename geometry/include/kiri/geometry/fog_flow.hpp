#pragma once
//! \file fog_flow.hpp
//! Fog moved by the wind over the terrain (issue 10, REFERENCE 6 "cloud waterfalls"): the
//! thickness field advected in 2D, piling up against the slopes downwind until it tops the
//! lowest pass, pouring down the lee side and evaporating as it descends and warms.
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/heightfield.hpp"

namespace kiri::geometry {

struct FlowOptions {
    glm::dvec2 wind{0.0};        //!< m/s above the inversion, towards (x east, y north)
    double duration = 3600.0;    //!< seconds of flow, >= 0
    double time_step = 60.0;     //!< seconds, > 0; any value is stable (accuracy only)
    double coupling = 0.5;       //!< share of the wind the fog above the downwind ground moves with, [0, 1]
    //! Gravity: the fog flows down the slope of its own surface (ground + thickness) at this
    //! speed per unit slope (m/s), capped at max_speed. A flat top is at rest; under wind the
    //! top tilts by coupling * |wind| / spread (a few metres per km).
    double spread = 400.0;
    double max_speed = 3.0;      //!< m/s, > 0
    //! Metres of descent that evaporate all but 1/e of the fog (it warms as it sinks, so its
    //! liquid water evaporates: about LWC / (9.8 K/km * 0.45 g/m^3/K), 45 m for 0.2 g/m^3;
    //! fog_placement.hpp derives it from the medium's extinction);
    //! 0 = no evaporation (the volume is then conserved exactly).
    double evaporation_depth = 45.0;
    double min_thickness = 1.0;  //!< metres: thinner fog counts as gone in the result
};

struct FlowReport {
    int steps = 0;
    double volume_before_m3 = 0.0, volume_after_m3 = 0.0;
    double outflow_m3 = 0.0;       //!< carried past the grid's border
    double evaporated_m3 = 0.0;
    double moved_out_m3 = 0.0;     //!< now over cells that had no fog at the start (spilled)
    double max_speed_ms = 0.0;     //!< fastest column seen
};

//! Scratch buffers of flow_step, kept between steps (the step itself then allocates nothing).
struct FlowWork {
    std::vector<float> u, v;       //!< velocity per cell (m/s)
    std::vector<double> next;
};

//! One step of dt seconds: the velocity of each column (wind share where the fog's surface is
//! above the ground one cell downwind, scaled by the share of the column above it; plus the
//! capped gravity flow down its surface), then a forward semi-Lagrangian transport: each
//! column follows its velocity (sub-stepped so no sub-step crosses more than a cell) and its
//! volume, times exp(-descent / evaporation_depth), is spread bilinearly over the four cells
//! around where it lands. The weights are >= 0 and sum to 1, so thickness never turns
//! negative, no time step is unstable, and without evaporation the volume is conserved up to
//! what leaves the grid (returned through outflow_m3 / evaporated_m3, added). Serial: the same
//! input gives the same bytes.
void flow_step(const Heightfield& terrain, std::vector<double>& thickness, const FlowOptions& options, double dt,
               FlowWork& work, double* outflow_m3 = nullptr, double* evaporated_m3 = nullptr,
               double* max_speed_ms = nullptr);

//! options.duration / options.time_step steps (the last one shorter) from the thickness
//! field (metres, nx * ny, >= 0). \throw InputError(label, "flow/<key>", reason) for options
//! out of range or a field of the wrong size.
std::vector<double> flow_fog(const Heightfield& terrain, std::vector<double> thickness, const FlowOptions& options,
                             FlowReport* report = nullptr, const std::string& label = {});

}  // namespace kiri::geometry
