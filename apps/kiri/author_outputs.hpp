#pragma once
// What `kiri author` writes: the formats a user picks with --formats, what each would weigh
// before anything is computed, and the refusal above a limit.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "kiri/geometry/scene/author_estimate.hpp"

namespace kiri::cli {

//! One kind of output file of `kiri author`.
enum class AuthorFormat {
    glb,        //!< layers.glb: the layer stack (compact, morph target + alpha per layer) and the terrain
    vdb,        //!< medium.vdb: the Medium's extinction as an OpenVDB fog volume
    particles,  //!< particles.ply
    maps,       //!< GeoTIFF and PNG maps of fog placed by the terrain (none otherwise)
    surface,    //!< base_surface.obj and base_surface.ply: the fitted base surface's triangles
    obj,        //!< layers.obj: every layer's triangles (large)
    ply,        //!< layers.ply: every layer's triangles (large)
};

//! glb, vdb, particles and maps; report.json is always written.
std::set<AuthorFormat> default_author_formats();
//! "glb,vdb" or "all"; \throw InputError naming --formats and the unknown name.
std::set<AuthorFormat> parse_author_formats(const std::string& list);
const char* to_string(AuthorFormat format);

//! Upper bounds of the files' sizes, from the authoring estimate (before anything is made).
struct OutputEstimate {
    std::vector<std::pair<AuthorFormat, double>> mib;  //!< per chosen format
    double total_mib() const;
    //! "about 41 MiB (glb 18, vdb 22, particles 1)"
    std::string summary() const;
};
//! terrain_cells: the DEM's; particles: the scene's count.
OutputEstimate estimate_outputs(const geometry::AuthorEstimate& estimate, double terrain_cells, double particles,
                                const std::set<AuthorFormat>& formats);

//! The default limit of --max-output (MiB).
inline constexpr double default_output_limit_mib = 2048.0;
//! \throw LimitError(scene, the key or flag that drives the largest file, "...") above limit_mib.
void check_output_estimate(const OutputEstimate& estimate, double limit_mib, const std::string& scene);

}  // namespace kiri::cli
