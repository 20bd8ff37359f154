#pragma once
// Dynamic resolution while the view moves: the preview draws a moving view at the scale that
// keeps its frame time within a budget (a frame rate the user picks), and the still view at the
// full scale once the camera stops, as game engines' dynamic resolution and DCC viewports'
// "lower while navigating" do.

namespace kiri::preview {

struct FrameBudget {
    double target_ms = 100.0;  //!< the moving frame's budget (10 frames a second)
    float min_scale = 0.125f;  //!< of the window's framebuffer: never coarser than this
    float max_scale = 1.0f;    //!< never finer than the still view's scale
};

//! The scale of the next moving frame, from the last one's scale and its measured time. A frame's
//! cost is part fixed (vertices, the fog's volume passes) and part per pixel (~ scale^2), and
//! which part dominates differs by mode and machine, so the step assumes all of it per pixel,
//! scale * sqrt(target / measured), and damps it to [0.7, 1.25] of the last scale a frame: a
//! fixed-cost-bound frame then walks down to min_scale in a few frames instead of oscillating, and
//! climbs back as the frame gets cheaper. Non-finite or non-positive inputs keep the scale,
//! clamped to the budget's range.
float next_moving_scale(float scale, double measured_ms, const FrameBudget& budget);

//! The froxel volume's, the terrain grid's and the particles' resolution
//! (Renderer::set_froxel_resolution, set_terrain_resolution, set_particle_resolution) for a
//! frame drawn at `ratio` of the still view's size: the largest
//! power of two no larger, in [1/8, 1]. So a moving frame keeps about the still's pixels per
//! froxel tile and per terrain cell (the volume's passes cost the square of it, the terrain's
//! vertices too), and the volume, rebuilt without history when it changes, changes only at
//! those steps while the frame's scale glides. Non-finite or non-positive: 1/8.
double resolution_step(float ratio);

//! A moving frame's width or height: `side` or the next larger size that is not a power of two,
//! nor is it divided by 2, 4, 8 or 16 and rounded up (the textures the passes size from the
//! frame: its reduced targets, the froxel apply's grids of pixels). llvmpipe keys its compiled programs by whether each texture's sides
//! are powers of two: moving frames 241 to 256 wide or 113 to 128 high (a 16th of them 16 or 8)
//! each compiled a new variant of the apply, 1.8 to 2.3 s in the middle of a camera move, until
//! its disk cache held it. At most 16 pixels more above 32 (31 below); sides below 2 or above
//! 2^24 are kept.
int off_power_of_two(int side);

}  // namespace kiri::preview
