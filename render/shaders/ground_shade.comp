#version 450 core
// The fog's shade on the ground (GroundShade): terrain.frag lights the ground with the sun's
// e^-tau through the fog, as the reference does. Phase 0, per vertex of the terrain's mesh:
// (the Medium's tau_sun, 0, the height fog's) (sun_volume.glsl: the Medium's marched, the height
// fog's in closed form).
// Phase 1, per vertex of the DEM's grid (u_grid: its samples, its row in the mesh, the
// surround's rings before it): refine 1 where the Medium's share of the sun's transmittance
// bends between the vertex's neighbours (the second difference along a row, a column or a
// diagonal over u_bend): a fog's shore or wall crosses the cell within metres, and interpolated
// between the vertices the shade would spill over the sunlit ground beside it. Phase 2, per
// texel of the fine map (u_fine samples a cell) in the cells around a marked vertex: tau_sun at
// the mesh's ground there, the Medium's part and the height fog's; ground_shade.glsl reads it in
// their triangles. Phases 0 and 2 carry the Medium's part on below 0 above a fog's top in its
// own column (medium_shade_below_zero). Phase 3, per texel still at 0 out of the Medium's shade
// (outside its columns: beside a wall, beyond the DEM's edge): the Medium's part carried on
// below 0 as its neighbours' run (2 a - b from the texels a and b beyond it in a row or a
// column), so that filtered between the texels it meets 0 where the shade ends. A fog's shore on
// a slope or its wall casts a shade that grows along the ground at a steady rate from that
// line; read as 0 beyond it, the filter drew the line at the next texel, and the shade spilled
// over the sunlit ground up to a texel out (a dense fog's: nearly black).
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer Vertices { float vertices[]; };  // u_stride floats each, the position first
layout(std430, binding = 1) buffer Shade { vec4 shade[]; };  // the Medium's tau_sun (signed), refine, the height fog's
layout(std430, binding = 2) buffer Refined {  // phase 1: the vertices marked (their grid index i + nx j)
    uint refined;
    uint marked_vertices[];
};
layout(rg32f, binding = 0) uniform image2D io_fine;  // the Medium's tau_sun (signed: phase 3), the height fog's
uniform vec3 u_sun_direction;
uniform int u_vertices;
uniform int u_stride;
uniform int u_phase;
uniform int u_row;     // phase 0: invocations a row (GroundShade's phase0_row)
uniform ivec4 u_grid;  // the DEM's samples across and down, the mesh's row, the rings before the grid
uniform int u_fine;
uniform float u_bend;

int mesh_vertex(int i, int j) { return (j + u_grid.w) * u_grid.z + i + u_grid.w; }

vec3 position(int v)
{
    int k = u_stride * v;
    return vec3(vertices[k], vertices[k + 1], vertices[k + 2]);
}

// The Medium's share of the sun's transmittance at grid sample (i, j) (the height fog's closed
// form is smooth and interpolates well).
float medium_through(int i, int j)
{
    int v = mesh_vertex(i, j);
    return exp(-max(shade[v].x, 0.0));
}

// Phases 2 and 3: id.y a marked vertex, id.x a texel of the fine map in the four cells around it
// (2 u_fine + 1 a side); the block's first texel and this one's place in it, false past the ends.
bool fine_block_texel(ivec2 id, out ivec2 corner, out ivec2 local)
{
    int side = 2 * u_fine + 1;
    corner = local = ivec2(0);
    if (id.y >= int(refined) || id.x >= side * side)
        return false;
    int vertex = int(marked_vertices[id.y]);
    corner = (ivec2(vertex % u_grid.x, vertex / u_grid.x) - 1) * u_fine;
    local = ivec2(id.x % side, id.x / side);
    return true;
}

// Whether phase 2 wrote fine texel t: it lies in the four cells around a marked vertex (phase 1
// marks them in `shade`, y = 1).
bool fine_written(ivec2 t)
{
    ivec2 lo = max((t + u_fine - 1) / u_fine - 1, ivec2(1)), hi = min(t / u_fine + 1, u_grid.xy - 2);
    bool written = false;
    for (int j = lo.y; j <= hi.y; ++j)
        for (int i = lo.x; i <= hi.x; ++i)
            written = written || shade[mesh_vertex(i, j)].y > 0.0;
    return written;
}

// Where the sun's path from p crosses no fog and p lies above its column's top: the Medium's
// tau_sun carried on below 0 at the rate it grows with depth just under the top, sigma d_top /
// sin(elevation) (the noise at its mean), so that blended between samples on either side of a
// fog's shore it meets 0 where the ground crosses the top, wherever the shore turns. Read as 0
// there, the blend drew the shore at the next sample out, and the shade of a dense fog spilled
// over the sunlit ground beside it; carried on along a row or a column of the fine map (phase
// 3), it met 0 where the ground ran on a plane, not where the shore bent within a cell (the
// bundled lake at 10 m of visibility: 327 of 35,253 pixels of sunlit ground more than 0.3 off
// the reference's sunlight there). 0 out of the Medium's columns (a wall's, the DEM's edge):
// there phase 3's runs.
float medium_shade_below_zero(vec3 p, vec3 s)
{
    if (u_md_on == 0 || !(s.z > 1e-3) || !shell_covers(p.xy))
        return 0.0;
    vec4 c = shell_column(p.xy);  // floor, bottom, top, coverage
    if (!(c.w > 0.0 && p.z > c.z && c.z > c.y))
        return 0.0;
    float d = c.w * u_md_top_density * (1.0 - 0.5 * u_md_detail) * medium_dissipation(1.0);
    return -u_md_extinction * d * (p.z - c.z) / s.z;
}

void main()
{
    ivec2 id = ivec2(gl_GlobalInvocationID.xy);
    // Phases 0 and 2 end in one march of the sun's optical depth (a second copy of it inlined
    // doubled the program's compile time on llvmpipe).
    vec3 p;
    int v = -1;  // phase 0's vertex; phase 2 writes texel ab
    ivec2 ab = ivec2(0);
    if (u_phase == 0) {
        v = id.y * u_row + id.x;
        if (!(id.x < u_row && v < u_vertices))
            return;
        p = position(v);
    }
    if (u_phase == 1) {
        int i = id.x, j = id.y;
        if (i < 1 || j < 1 || i + 1 >= u_grid.x || j + 1 >= u_grid.y)
            return;
        float t = 2.0 * medium_through(i, j), bend = 0.0;
        bend = max(bend, abs(medium_through(i - 1, j) + medium_through(i + 1, j) - t));
        bend = max(bend, abs(medium_through(i, j - 1) + medium_through(i, j + 1) - t));
        bend = max(bend, abs(medium_through(i - 1, j - 1) + medium_through(i + 1, j + 1) - t));
        bend = max(bend, abs(medium_through(i - 1, j + 1) + medium_through(i + 1, j - 1) - t));
        if (bend > u_bend) {
            shade[mesh_vertex(i, j)].y = 1.0;
            marked_vertices[atomicAdd(refined, 1u)] = uint(j * u_grid.x + i);
        }
        return;
    }
    if (u_phase == 3) {
        ivec2 corner, local;
        if (!fine_block_texel(id, corner, local))
            return;
        ab = corner + local;
        ivec2 size = imageSize(io_fine);
        if (any(lessThan(ab, ivec2(0))) || any(greaterThanEqual(ab, size)))
            return;
        vec2 own = imageLoad(io_fine, ab).rg;
        if (own.r != 0.0)
            return;  // in the shade, or carried on in its own column (medium_shade_below_zero)
        float carried = -3e38;  // the least shade beyond the line of those the runs give
        const ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
        for (int k = 0; k < 4; ++k) {
            // Runs over texels phase 2 wrote (beyond the marked vertices' cells a texel may be
            // unwritten): any marked vertex's, not only this block's, so that a texel two marked
            // vertices' blocks share gets the same value from either (read within its own block
            // alone, each wrote its own, and the picture changed from run to run).
            ivec2 b = ab + 2 * steps[k];
            if (any(greaterThanEqual(b, size)) || any(lessThan(b, ivec2(0))) || !fine_written(ab + steps[k]) ||
                !fine_written(b))
                continue;
            float ta = imageLoad(io_fine, ab + steps[k]).r;
            if (!(ta > 0.0))
                continue;
            float tb = imageLoad(io_fine, b).r;
            if (tb > ta)  // growing away from the line
                carried = max(carried, 2.0 * ta - tb);
        }
        if (carried > -3e38)
            imageStore(io_fine, ab, vec4(min(carried, 0.0), own.g, 0.0, 0.0));
        return;
    }
    if (u_phase == 2) {
        // Texel (a, b) lies on the cells' corners at every u_fine-th texel. Neighbours marked both
        // write their shared texels, with the same value.
        ivec2 corner, local;
        if (!fine_block_texel(id, corner, local))
            return;
        ab = corner + local;
        ivec2 cell = ab / u_fine;
        // The ground as the mesh draws it: two triangles a cell, split along (i, j)-(i + 1, j + 1).
        ivec2 c = min(cell, u_grid.xy - 2);
        vec2 f = vec2(ab - c * u_fine) / float(u_fine);
        vec3 p00 = position(mesh_vertex(c.x, c.y)), p10 = position(mesh_vertex(c.x + 1, c.y));
        vec3 p11 = position(mesh_vertex(c.x + 1, c.y + 1)), p01 = position(mesh_vertex(c.x, c.y + 1));
        p = f.x >= f.y ? p00 + f.x * (p10 - p00) + f.y * (p11 - p10) : p00 + f.x * (p11 - p01) + f.y * (p01 - p00);
    }
    float haze = height_fog_sun(p, u_sun_direction);
    float medium = sun_optical_depth(p, u_sun_direction, 0.5) - haze;
    if (!(medium > 0.0))
        medium = medium_shade_below_zero(p, u_sun_direction);
    if (v >= 0)
        shade[v] = vec4(medium, 0.0, haze, 0.0);
    else
        imageStore(io_fine, ab, vec4(medium, haze, 0.0, 0.0));
}
