// Library: the ground's albedo (terrain.frag, and sky.frag's ground beyond the surround): by
// height and slope as the CPU renderers' ground_albedo (geometry/src/reference/terrain_shading.hpp),
// water at the sea's surface (kiri/geometry/terrain/ground.hpp).
uniform float u_z_min;            // the grid's heights: the colours' range
uniform float u_z_max;
uniform int u_water;              // 1: the DEM holds a sea
uniform float u_sea_level;        // m, exaggeration applied
uniform float u_water_tolerance;  // m: float positions at the sea's surface
uniform float u_ground_albedo;    // 1, or 0 for a black ground (SunLight::black_ground)

vec3 terrain_albedo(float height01, float steepness)
{
    const vec3 valley = vec3(0.16, 0.26, 0.10);
    const vec3 slope = vec3(0.30, 0.32, 0.15);
    const vec3 upland = vec3(0.42, 0.40, 0.28);
    const vec3 rock = vec3(0.40, 0.36, 0.32);
    vec3 c = height01 < 0.5 ? mix(valley, slope, height01 * 2.0) : mix(slope, upland, height01 * 2.0 - 1.0);
    return mix(c, rock, smoothstep(0.18, 0.55, steepness));
}

vec3 ground_albedo(vec3 world, float normal_z)
{
    if (u_water != 0 && world.z <= u_sea_level + u_water_tolerance)
        return u_ground_albedo * vec3(0.02, 0.045, 0.09);  // geometry::water_albedo
    float height01 = clamp((world.z - u_z_min) / max(u_z_max - u_z_min, 1e-3), 0.0, 1.0);
    return u_ground_albedo * terrain_albedo(height01, 1.0 - normal_z);
}
