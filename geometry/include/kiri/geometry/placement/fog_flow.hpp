#pragma once
//! \file fog_flow.hpp
//! Fog moved by the wind over the terrain ([ValleyFog], "cloud waterfalls"). The fog
//! pooled under the inversion (the fill's connected bodies) keeps a plane top, tilted by the
//! wind's set-up; where the tilted top rises above the pool's rim (its lowest passes downwind)
//! fog spills over, and the spilt fog is a thin stream advected over the terrain, pouring down
//! the lee slopes and evaporating as it descends and warms.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "kiri/geometry/core/fields.hpp"
#include "kiri/geometry/placement/fog_columns.hpp"
#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

struct FlowOptions {
    glm::dvec2 wind{0.0};  //!< towards (x east, y north)
    double duration = 3600.0;
    double time_step = 60.0;  //!< any value is stable (accuracy only)
    double coupling = 0.5;
    //! Inversion strength (K): the potential temperature jump at the fog top. The wind's stress
    //! tilts a pool's top by s = C_d |wind|^2 / (g' H) (C_d = 1.5e-3, g' = 9.81 dtheta / 280 K,
    //! H the pool's mean depth): about 2 m per km for 5 m/s over 100 m of fog under 5 K.
    double inversion_strength = 5.0;
    //! Gravity flow of the stream down the terrain: spread * slope m/s, at most max_speed.
    double spread = 10.0;
    double max_speed = 3.0;
    //! Metres of descent that evaporate all but 1/e of the stream (it warms as it sinks, so its
    //! liquid water evaporates: about LWC / (9.8 K/km * 0.45 g/m^3/K), 45 m for 0.2 g/m^3;
    //! fog_placement.hpp derives it from the medium's extinction); 0 = no evaporation.
    double evaporation_depth = 45.0;
    double min_thickness = 1.0;
    bool operator==(const FlowOptions&) const = default;
};

//! The "flow" object of the scene's "fog" section. The wind is at most 100 m/s; the duration
//! takes at most a million time steps.
template <fields_of<FlowOptions> O, class V>
void visit_fields(O& o, V&& v)
{
    v(o.wind,
      {.key = "wind",
       .unit = "m/s",
       .doc = "above the inversion (at most 100 m/s)",
       .widget = closed(-15, 15),
       .required = "missing: the wind [east, north] in m/s",
       .shape = "[east, north]"});
    v(o.duration,
      {.key = "duration",
       .unit = "s",
       .range = closed(0, 2592000),
       .doc = "of flow (at most 30 days)",
       .widget = closed(0, 43200)});
    v(o.time_step,
      {.key = "time_step",
       .unit = "s",
       .range = left_open(0, 86400),
       .doc = "any step is stable (accuracy only); at most 10^6 steps"});
    v(o.coupling,
      {.key = "coupling",
       .range = closed(0, 1),
       .doc = "share of the wind the fog's top layer and the stream move with"});
    v(o.inversion_strength,
      {.key = "inversion_strength",
       .unit = "K",
       .range = open_range(0, 50),
       .doc = "the temperature jump at the fog top: a weaker inversion tilts the pools more"});
    v(o.spread,
      {.key = "spread", .unit = "m/s", .range = closed(0, 1e6), .doc = "gravity flow of the stream: spread * slope"});
    v(o.max_speed, {.key = "max_speed", .unit = "m/s", .range = open_range(0, 100), .doc = "cap of the gravity flow"});
    v(o.evaporation_depth,
      {.key = "evaporation_depth",
       .unit = "m",
       .range = closed(0, 1e6),
       .doc = "of descent that leave 1/e of the stream; 0 = none",
       .shown_default = "from the medium"});
    v(o.min_thickness,
      {.key = "min_thickness", .unit = "m", .range = at_least(0), .doc = "thinner fog counts as gone in the result"});
}

struct FlowReport {
    int steps = 0;
    int pools = 0;
    double volume_before_m3 = 0.0, volume_after_m3 = 0.0;
    double outflow_m3 = 0.0;  //!< carried past the grid's border
    double evaporated_m3 = 0.0;
    double spilled_m3 = 0.0;           //!< over the pools' rims, in all
    double stream_m3 = 0.0;            //!< outside the pools at the end
    double max_tilt_m = 0.0;           //!< the largest rise of a pool's top above its mean (set-up)
    double evaporation_depth_m = 0.0;  //!< the depth used
};

//! A pool: a connected body of the initial fog (8-neighbours), its cells, rim and level.
struct FlowPool {
    std::vector<std::uint32_t> cells, rim;  //!< rim: cells outside, next to the pool
    glm::dvec2 centroid{0.0};
    double volume = 0.0;  //!< m^3
    double level = 0.0;   //!< top at the centroid (m)
    double slope = 0.0;   //!< set-up tilt along the wind (m/m)
};

//! The state of the flow between steps.
struct FlowState {
    std::vector<FlowPool> pools;
    std::vector<std::uint32_t> pool_of;  //!< per cell: pool index + 1, 0 outside the pools
    std::vector<double> stream;          //!< thickness of the moving fog outside the pools (m)
    double outflow_m3 = 0.0, evaporated_m3 = 0.0, spilled_m3 = 0.0, max_tilt_m = 0.0;
    std::vector<double> next, moved;  //!< scratch of flow_step (it allocates nothing else)
    std::vector<float> u, v;          //!< the stream's velocity per cell (terrain and wind only)
};

//! Pools from the fog columns (their thickness), an empty stream, the stream's velocities.
//! \throw InputError(label, "flow/<key>", reason) for options out of range.
FlowState make_flow_state(const Heightfield& terrain, const FogColumns& fog, const FlowOptions& options,
                          const std::string& label = {});

//! One step of dt seconds. (1) Each pool's top is the plane level + slope (x - centroid).w,
//! its level the one that holds the pool's volume exactly (thickness max(0, top - ground)
//! over its cells). (2) Where that plane stands above a rim cell's ground by d, the pool spills
//! d * coupling |wind| dt / cell of thickness into it. (3) The stream follows its velocity
//! (coupling * wind + the capped gravity flow down the terrain), sub-stepped so no sub-step
//! crosses more than a cell, losing exp(-descent / evaporation_depth) for the descent below the
//! inversion (the highest pool level: a run-up sliding back into its pool keeps its water),
//! and each column's volume
//! is spread bilinearly over the four cells around where it lands (forward semi-Lagrangian:
//! weights >= 0 summing to 1, so nothing turns negative and no time step is unstable); what
//! lands in a pool joins it, what leaves the grid is counted as outflow. (3b) Where the stream
//! piles up (a pit, a slope the wind pushes it against) four relaxation sweeps spread a tenth of
//! each column's excess over its neighbours' surfaces to them, where the ground drops less than
//! the column is thick: piles level into pools, thin fog on slopes is left to (3). Without evaporation
//! pools + stream + outflow keep the volume (to rounding). Serial: the same input gives the
//! same bytes.
void flow_step(const Heightfield& terrain, FlowState& state, const FlowOptions& options, double dt);

//! Thickness per cell (m): the pools' plane tops over the ground, plus the stream.
std::vector<double> flow_thickness(const Heightfield& terrain, const FlowState& state, const FlowOptions& options);

//! duration / time_step steps (the last one shorter) from the fog columns; the result's
//! columns stand on the ground (bottom = ground, top = ground + thickness, fog where the
//! thickness exceeds min_thickness). \throw InputError(label, "flow/<key>", reason).
FogColumns flow_fog(const Heightfield& terrain, const FogColumns& fog, const FlowOptions& options,
                    FlowReport* report = nullptr, const std::string& label = {});

}  // namespace kiri::geometry
