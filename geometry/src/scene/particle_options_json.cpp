#include "scene/particle_options_json.hpp"

#include "scene/field_json.hpp"

namespace kiri::geometry {

using json = nlohmann::json;

ParticleOptions parse_particle_options(const json& j, const std::string& file)
{
    const JsonReader r{file};
    ParticleOptions o;
    read_fields(r, j, "/particles", o);
    if (j.contains(std::string(field_of(o, o.count).key)) && j.contains(std::string(field_of(o, o.spacing).key)))
        r.fail("/particles", "give count or spacing, not both (each sets the number of particles)");
    validate_particle_options(o, file);
    return o;
}

json particle_options_to_json(const ParticleOptions& o)
{
    json j = write_fields(o);
    if (o.spacing > 0.0)  // the spacing sets the count
        j.erase(std::string(field_of(o, o.count).key));
    return j;
}

}  // namespace kiri::geometry
