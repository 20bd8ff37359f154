#pragma once
// The inputs of the pipeline's stages (pipeline.hpp): what each stage reads, as a value compared
// with a defaulted operator==. Upstream products enter as the version of the stage that made
// them; options enter as the values the stage function reads, in world units, and nothing else,
// so an edit reruns exactly the stages that read it.
#include <cstdint>
#include <string>

#include "kiri/geometry/scene/pipeline.hpp"
#include "kiri/geometry/volume/height_fog.hpp"

namespace kiri::geometry {

struct TerrainInput {
    TerrainSpec terrain;
    bool exaggeration_given = true;  // else derived from the terrain on load
    bool operator==(const TerrainInput&) const = default;
};

struct PlacementInput {
    std::uint64_t terrain = 0;
    PlacementSpec placement;
    double patch_size = 0.0;  // the outline's defaults
    bool operator==(const PlacementInput&) const = default;
};

struct ControlMeshInput {
    std::uint64_t terrain = 0, placement = 0;
    Footprint footprint;
    double margin = 0.0;
    SurfaceKind surface = SurfaceKind::catmull_clark;
    double patch_size = 0.0;
    bool operator==(const ControlMeshInput&) const = default;
};
ControlMeshInput control_mesh_input(std::uint64_t terrain, std::uint64_t placement, const FogSpec& spec);

struct FitInput {
    std::uint64_t control = 0;
    FitOptions fit;
    bool operator==(const FitInput&) const = default;
};

struct TessellationInput {
    std::uint64_t fit = 0;
    TessellationOptions tessellation;
    bool operator==(const TessellationInput&) const = default;
};

struct LayerBaseInput {
    std::uint64_t tessellation = 0;
    LayerTextureOptions texture;
    double base_offset = 0.0;
    bool operator==(const LayerBaseInput&) const = default;
};
LayerBaseInput layer_base_input(std::uint64_t tessellation, const LayerOptions& layers);

struct MediumInput {
    std::uint64_t source = 0;  // the placement's version (fog placed by the terrain), else the layer base's
    bool placed = false;
    MediumOptions medium;    // its optics and its detail (medium_detail)
    double thickness = 0.0;  // the layer stack's slab (not placed)
    bool operator==(const MediumInput&) const = default;
};
MediumInput medium_input(std::uint64_t source, bool placed, const MediumOptions& medium, const LayerOptions& layers);

struct ParticlesInput {
    std::uint64_t medium = 0;
    ParticleSet set = ParticleSet::whole;
    ParticleOptions options;  // the sampling options (the buffer's and billboards' apply per frame)
    FogPartition partition;   // top band only
    bool operator==(const ParticlesInput&) const = default;
};
ParticlesInput particles_input(std::uint64_t medium, ParticleSet set, const ParticleOptions& options,
                               const FogPartition& partition);

struct LightInput {
    std::uint64_t medium = 0, terrain = 0;
    glm::dvec3 sun{0.0};  // towards the sun, as the scene gives it
    HeightFog haze;       // the froxels' height fog over the terrain, which the bake traces too
    bool surround = true;
    bool operator==(const LightInput&) const = default;
};

struct ExportsInput {
    std::uint64_t layer_base = 0;
    LayerOptions layers;
    glm::dvec3 eye{0.0};
    bool operator==(const ExportsInput&) const = default;
};

SurfaceSummary summarise(const BaseSurface& surface, const FitReport& fit);

}  // namespace kiri::geometry
