#pragma once
//! \file ground.hpp
//! The ground every renderer draws (the GL terrain and sky, the reference ray marcher, the path
//! tracer): the DEM, the sea's surface over its sea, and the surround beyond the DEM's edge, so
//! that a tile does not float in a void. One definition, so that they all draw one terrain.
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "kiri/geometry/terrain/heightfield.hpp"

namespace kiri::geometry {

//! Height of the heightfield's triangles at (x, y): two per cell, split along
//! (i, j)-(i + 1, j + 1), as Terrain::height; points outside the grid take the nearest edge's.
double grid_height(const Heightfield& hf, double x, double y);

//! The sea level of a DEM that holds a sea, else empty. A sea is on a coast: 2 % of the valid
//! cells at or below 0 and 2 % above (as scene_defaults' coast), where either 1 % of them are
//! exactly 0 (SRTM writes the sea as a flat 0) or the grid reaches below -500 m (a bathymetric
//! grid: no dry land on Earth lies that low). Its level is 0. A flat plain at 0 is no sea.
std::optional<double> sea_level(const Heightfield& hf);

class Ground {
public:
    //! `surround` false: the bare tile, nothing beyond the grid's edge.
    explicit Ground(const Heightfield& hf, bool surround = true);

    const Heightfield& heightfield() const { return hf_; }
    bool surround() const { return surround_; }
    //! Sample (i, j)'s height, raised to the sea's surface where the sea covers it (the water's
    //! surface at the sea level over a bathymetric grid).
    double sample(int i, int j) const
    {
        const double z = hf_.at(i, j);
        return sea_ && z < *sea_ ? *sea_ : z;
    }
    //! Height at (x, y). Inside the grid: the triangles of sample(). Beyond it, with the surround:
    //! n + (base - n) * smoothstep(d / ease), d the distance to the grid and
    //! n = e + s d (1 - d / r)^2 for d < r: e and s the means, over the nearest edge's samples
    //! within d of the nearest edge point, of the edge's heights and of its outward slopes (in a
    //! corner, the two edges' means weighted by the direction), r four cells. So the surround
    //! meets the grid with the edge's height and slope (no crease), its detail widens and fades
    //! outwards instead of streaking, it is base() from ease() on, and flat to the horizon. On a
    //! coast the sea is the base: the easing heads a tenth of the relief below the sea and the
    //! sea's surface covers it, so the edge's land ends in a coast and the sea continues to the
    //! horizon. Without the surround: the nearest edge point's height (as Terrain::height).
    //! Finite for every input (NaN: base()).
    double height(double x, double y) const;
    //! Unit upward normal at (x, y): the triangle's inside the grid; beyond, central differences
    //! of height() over a hundredth of a cell (the surround has no triangles of its own).
    glm::dvec3 normal(double x, double y) const;
    //! Distance from (x, y) to the grid's rectangle (0 inside).
    double distance_outside(double x, double y) const;
    bool inside(double x, double y) const { return distance_outside(x, y) == 0.0; }

    std::optional<double> sea_level() const { return sea_; }
    //! Whether a point of the ground at height z is water: at the sea's surface (within a
    //! millionth of the relief, for float positions).
    bool is_water(double z) const { return sea_ && z <= *sea_ + water_tolerance(); }
    double water_tolerance() const { return 1e-6 * (1.0 + z_max_ - z_min_); }
    //! The surround's far level: the median of the grid's border samples; on a coast the sea's
    //! surface.
    double base() const { return base_; }
    //! How far beyond the edge the surround reaches base(): a quarter of the grid's longer side,
    //! at least two cells.
    double ease() const { return ease_; }
    //! The heights of sample() (the surround lies between them and base()).
    double z_min() const { return z_min_; }
    double z_max() const { return z_max_; }

private:
    // One edge of the grid, sample() along it, with its running integral (trapezoids: exact
    // for the piecewise linear profile), for means over windows in O(1).
    struct Edge {
        double start = 0.0, step = 1.0;
        std::vector<double> z, integral;
        double primitive(double s) const;  // integral of the profile from start to s
        double mean(double a, double b) const;
    };
    struct Side {
        Edge z, slope;  // heights, and outward slopes (rise per metre away from the grid)
    };
    Side south_, north_, west_, east_;
    double slope_reach_ = 1.0;  // how far out the edge's slope is continued
    const Heightfield& hf_;
    bool surround_ = true;
    std::optional<double> sea_;
    double base_ = 0.0, ease_ = 1.0, z_min_ = 0.0, z_max_ = 0.0;
    double drop_to_ = 0.0;  // where the easing heads: base_, or below the sea when the sea is the base
    double sample_height(double x, double y) const;  // the triangles of sample(), clamped to the grid
};

//! The albedo of water: a dark, slightly blue Lambertian surface (open water sends back a few
//! per cent of the light), shared by terrain.frag and the CPU renderers.
inline constexpr double water_albedo[3] = {0.02, 0.045, 0.09};

}  // namespace kiri::geometry
