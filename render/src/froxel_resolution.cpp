// FroxelPass in a frame drawn at a share of the still's resolution (the preview while the view
// moves, Renderer::set_froxel_resolution): its shell, its marches' steps and its tolerance.
#include "froxel_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace kiri::render::detail {

void FroxelPass::set_resolution(double scale)
{
    resolution_ = std::isfinite(scale) ? std::clamp(scale, 0.125, 1.0) : 1.0;
}

int FroxelPass::marched_steps() const
{
    return std::max(1, int(std::lround(options_.pixel_steps * std::cbrt(resolution_))));
}

float FroxelPass::upsample_tolerance() const
{
    const double shrink = std::cbrt(resolution_);
    return float(std::min(options_.upsample / (shrink * shrink), 1.0));
}

void FroxelPass::use_shell_for_resolution()
{
    // The step: 2^-k of the tiles across, k = 0..3. Its shell has a 4^-k share of the whole
    // shell's blocks, so its blocks stay about as many pixels wide on a frame as many times
    // smaller. Each coarse shell holds the whole one (build_shell_mesh's blocks are
    // conservative), so no fog is lost: the rays' stretches only take in more air. On llvmpipe
    // the whole shell's rasterisation was 14 ms of a 110 ms moving frame at 160x90, 2.6 ms at
    // the 1/8 step's.
    const int k = std::clamp(int(std::lround(-std::log2(resolution_))), 0, 3);
    if (k == drawn_shell_ || !medium_)
        return;
    if (k > 0 && !coarse_shells_[std::size_t(k - 1)])
        coarse_shells_[std::size_t(k - 1)] = build_shell_mesh(*medium_, shell_max_blocks >> (2 * k));
    tile_bounds_.set_shell(k == 0 ? shell_ : *coarse_shells_[std::size_t(k - 1)]);
    drawn_shell_ = k;
}

}  // namespace kiri::render::detail
