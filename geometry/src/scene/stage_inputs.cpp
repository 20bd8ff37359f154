#include "scene/stage_inputs.hpp"

namespace kiri::geometry {

ControlMeshInput control_mesh_input(std::uint64_t terrain, std::uint64_t placement, const FogSpec& spec)
{
    return {terrain, placement, spec.footprint, spec.margin, spec.surface, spec.patch_size};
}

LayerBaseInput layer_base_input(std::uint64_t tessellation, const LayerOptions& layers)
{
    return {tessellation, layers.texture, layers.base_offset};
}

MediumInput medium_input(std::uint64_t source, bool placed, const MediumOptions& medium, const LayerOptions& layers)
{
    return {source, placed, medium, placed ? 0.0 : layers.thickness};
}

ParticlesInput particles_input(std::uint64_t medium, ParticleSet set, const ParticleOptions& options,
                               const FogPartition& partition)
{
    ParticlesInput in{medium, set, options, set == ParticleSet::top_band ? partition : FogPartition{}};
    const ParticleOptions defaults;
    in.options.resolution = defaults.resolution;
    in.options.half_float = defaults.half_float;
    in.options.frame = defaults.frame;
    in.options.soft_edge = defaults.soft_edge;
    in.options.near_scale = defaults.near_scale;
    in.options.near_pixels = defaults.near_pixels;
    in.options.near_field = defaults.near_field;
    return in;
}

SurfaceSummary summarise(const BaseSurface& surface, const FitReport& fit)
{
    SurfaceSummary s;
    s.fit = fit;
    s.kind = surface.kind();
    s.patches = surface.num_patches();
    s.control_vertices = surface.control().num_vertices();
    s.snapped_boundary_vertices = surface.control().snapped_vertices;
    s.boundary_vertices = surface.control().boundary_vertices;
    return s;
}

}  // namespace kiri::geometry
