// What kiri chose for the user: the terrain's repairs and the derived keys, on stderr so that the
// printed output paths stay the only stdout lines of render.
#include <cstdio>

#include "commands.hpp"

namespace kiri::cli {

void print_derived(const geometry::DerivedDefaults& derived, const geometry::Heightfield& terrain)
{
    for (const std::string& w : terrain.warnings)
        std::fprintf(stderr, "kiri: warning: %s\n", w.c_str());
    if (const std::string line = derived.summary(); !line.empty())
        std::fprintf(stderr, "kiri: derived: %s\n", line.c_str());
}

}  // namespace kiri::cli
