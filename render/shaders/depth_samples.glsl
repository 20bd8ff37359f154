// Library: a multisampled pixel's depth samples (depth_resolve.frag, froxel_edges.comp): the
// plane they lie on, and whether they see one surface or two.
uniform int u_samples;      // at most ds_max
uniform vec2 u_offsets[8];  // each sample's offset from the pixel's centre (pixels)

// Loops over the samples run to this constant and stop at u_samples: a bound the compiler can
// see lets it unroll them and keep ds in registers; an array indexed at run time lives in local
// memory on NVIDIA (as the height fog's runs did, docs/speed.md "On a GPU").
const int ds_max = 8;

// The pixel's samples' window depths, written before anything reads them; initialised so that
// Mesa's compiler, which cannot see that from ds_plane_at_centre, does not warn of it on every
// start.
float ds[ds_max] = float[ds_max](1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0);

// The least-squares plane through the samples whose depth lies in [lo, hi], read at the centre
// (`at`), and whether they lie on it: at least three samples, none off it by more than 5 % of
// their spread.
bool ds_plane_at_centre(float lo, float hi, out float at)
{
    mat3 normal = mat3(0.0);
    vec3 rhs = vec3(0.0);
    int count = 0;
    for (int s = 0; s < ds_max && s < u_samples; ++s)
        if (ds[s] >= lo && ds[s] <= hi) {
            vec3 row = vec3(1.0, u_offsets[s]);
            normal += outerProduct(row, row);
            rhs += row * ds[s];
            ++count;
        }
    at = lo;
    if (count < 3 || abs(determinant(normal)) < 1e-9)
        return false;
    vec3 plane = inverse(normal) * rhs;
    float residual = 0.0, low = 1.0, high = 0.0;
    for (int s = 0; s < ds_max && s < u_samples; ++s)
        if (ds[s] >= lo && ds[s] <= hi) {
            residual = max(residual, abs(ds[s] - dot(plane, vec3(1.0, u_offsets[s]))));
            low = min(low, ds[s]);
            high = max(high, ds[s]);
        }
    at = clamp(plane.x, low, high);
    return residual <= 0.05 * (high - low) + 4e-7;
}

// Reads pixel px's samples into ds, their range into lo and hi, and whether they see two
// surfaces (the resolve then splits them at (lo + hi) / 2): a jump (four samples cannot tell a
// jump split two and two across the diagonals from a steep plane: a spread of more than a
// quarter of the nearest depth over less than a pixel is one), or not on one plane; `centre`
// their plane's depth at the centre where they lie on one.
bool ds_read(sampler2DMS depth, ivec2 px, float near_plane, float far_plane, out float lo, out float hi,
             out float centre)
{
    lo = 1.0;
    hi = 0.0;
    for (int s = 0; s < ds_max && s < u_samples; ++s) {
        ds[s] = texelFetch(depth, px, s).r;
        lo = min(lo, ds[s]);
        hi = max(hi, ds[s]);
    }
    centre = lo;
    bool jump = hi < 1.0 ? view_depth(hi, near_plane, far_plane) > 1.25 * view_depth(lo, near_plane, far_plane)
                         : lo < 1.0;
    return u_samples < 3 || jump || !ds_plane_at_centre(lo, hi, centre);
}
