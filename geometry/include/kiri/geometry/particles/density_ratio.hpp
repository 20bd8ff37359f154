#pragma once
//! \file density_ratio.hpp
//! The Medium's extinction over the density the particles' balls add up to, on a grid that
//! follows the Medium's shell (docs/particles.md, "The balls' sum made the Medium's").
//!
//! A cloud of balls is a smoothed and lumpy copy of the fog it stands for: its sum thins where
//! the balls happen to lie apart, and spills out of a thread of fog narrower than a ball. A
//! billboard that weights its ball's density by this ratio along its ray draws, summed over every
//! ball, the Medium itself at the grid's resolution: sum_k rho_k(p) R(p) = sigma(p) wherever a
//! ball reaches. Where no ball reaches, the fog is lost as before; where the Medium has none,
//! R = 0 and the balls draw nothing.
#include <vector>

#include <glm/vec2.hpp>

namespace kiri::geometry {

class Medium;
struct ParticleCloud;

//! The balls' summed density (1/m), which is smooth at the balls' scale, on a grid; the Medium's
//! extinction, which is not (a thread's wall, the detail noise), is taken at the point itself.
//! Cell (i, j, l) holds the sum at (x0 + (i + 1/2) dx, y0 + (j + 1/2) dy) and shell height
//! h = (l + 1/2) / levels between the column's floor and top there (z = floor + h (top - floor)).
//! A column without fog takes the floor and top of the fog nearest it (within the largest
//! radius), so the sum beside a fog's wall is taken at the heights the fog's balls spill at.
struct DensityRatioGrid {
    int nx = 0, ny = 0, levels = 0;
    double x0 = 0.0, y0 = 0.0, dx = 1.0, dy = 1.0;
    std::vector<float> floor, top;  //!< per column (j nx + i), metres, top > floor
    std::vector<float> balls;       //!< (l ny + j) nx + i
    double max_ratio = 16.0;
    bool empty() const { return balls.empty(); }
};

struct DensityRatioOptions {
    //! Levels a column: one every fifth of the smallest radius down the thickest column (the
    //! balls' sum changes over a ball's Gaussian, 0.4 radii), from min_levels to max_levels.
    int min_levels = 4, max_levels = 16;
    //! The cells' side: the Medium's grid spacing, or half the smallest ball's radius where that
    //! is finer, but no more than max_side cells a side.
    int max_side = 1024;
    //! R is clamped to [0, max_ratio]: where the balls barely reach, the few that do are not
    //! made opaque (DensityRatioGrid::max_ratio).
    double max_ratio = 16.0;
    int threads = 0;  //!< 0: one per core
};

//! The grid for `cloud`, standing for `medium` (its extinction and albedo: a cloud with optics of
//! its own gets an empty grid). Balls are the ball_density of each particle times its seen gain
//! (mass_gain(above_ground)), cut at its floor's and top's planes, as the billboards draw them.
DensityRatioGrid density_ratio_grid(const ParticleCloud& cloud, const Medium& medium,
                                    const DensityRatioOptions& options = {});

//! The balls' sum at (x, y) and shell height h (cells' levels: (z - floor) / (top - floor) of
//! the column there), read as the GPU reads it (trilinear over the cells' centres, clamped to
//! the edge): 0 for an empty grid.
double ball_sum_at(const DensityRatioGrid& grid, double x, double y, double h);
//! R = the Medium's extinction over the balls' sum at p, in [0, max_ratio] (0 where the Medium
//! has none; max_ratio where it has some and no ball reaches); 0 for an empty grid. The sum is
//! read at the height in the Medium's own column (Medium::column: where the Medium has fog, the
//! grid's columns are the Medium's at the cells' centres).
double density_ratio_at(const DensityRatioGrid& grid, const Medium& medium, double x, double y, double z);

}  // namespace kiri::geometry
