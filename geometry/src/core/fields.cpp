#include "kiri/geometry/core/fields.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

namespace kiri::geometry {
namespace {

// As the scene's messages always showed numbers: six significant digits, integers whole.
std::string shown(double v, bool integer)
{
    std::ostringstream s;
    if (integer && std::abs(v) < 9.2e18)
        s << static_cast<long long>(v);
    else
        s << v;
    return s.str();
}

std::string bound_text(const Bound& b, bool integer)
{
    return b.name.empty() ? number_text(b.value, integer) : std::string(b.name);
}

}  // namespace

std::string number_text(double v, bool integer)
{
    if (integer || (v == std::floor(v) && std::abs(v) < 1e5))
        return std::to_string(static_cast<long long>(v));
    char buffer[32];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    std::string s(buffer, end);
    // 1e+06 reads 1e6 in the docs.
    if (const auto e = s.find("e+"); e != std::string::npos)
        s.erase(e + 1, 1);
    while (s.find("e0") != std::string::npos)
        s.erase(s.find("e0") + 1, 1);
    while (s.find("e-0") != std::string::npos)
        s.erase(s.find("e-0") + 2, 1);
    return s;
}

std::string range_text(const Range& r, bool integer)
{
    if (r.bounded())
        return "in " + std::string(r.lo_open ? "(" : "[") + bound_text(r.lo, integer) + ", " +
            bound_text(r.hi, integer) + (r.hi_open ? ")" : "]");
    if (r.has_lo())
        return (r.lo_open ? "> " : ">= ") + bound_text(r.lo, integer);
    if (r.has_hi())
        return (r.hi_open ? "< " : "<= ") + bound_text(r.hi, integer);
    return "";
}

bool Range::contains(double v) const
{
    if (!std::isfinite(v))
        return false;
    if (has_lo() && (lo_open ? !(v > lo.value) : !(v >= lo.value)))
        return false;
    return !(has_hi() && (hi_open ? !(v < hi.value) : !(v <= hi.value)));
}

std::string range_error(const Range& r, double v, bool integer, std::string_view got)
{
    if (r.contains(v))
        return {};
    if (r.bounded())
        return "must be in " + std::string(r.lo_open ? "(" : "[") + shown(r.lo.value, integer) + ", " +
            shown(r.hi.value, integer) + (r.hi_open ? ")" : "]") + ", got " +
            (got.empty() ? shown(v, integer) : std::string(got));
    if (!std::isfinite(v))
        return "must be a finite number";
    if (r.has_lo())
        return std::string(r.lo_open ? "must be > " : "must be >= ") + shown(r.lo.value, integer);
    return std::string(r.hi_open ? "must be < " : "must be <= ") + shown(r.hi.value, integer);
}

std::string field_pointer(std::string_view section, const FieldInfo& info)
{
    std::string p(section);
    p.append("/").append(info.key);
    if (info.element >= 0)
        p.append("/").append(std::to_string(info.element));
    return p;
}

void check_field(double value, const FieldInfo& info, bool integer, const std::string& label, std::string_view section)
{
    if (std::string why = range_error(info.range, value, integer); !why.empty())
        throw InputError(label, field_pointer(section, info), why);
}

namespace {

template <class Vec>
void check_components(const Vec& value, const FieldInfo& info, const std::string& label, std::string_view section)
{
    for (int k = 0; k < Vec::length(); ++k)
        if (std::string why = range_error(info.range, value[k], false); !why.empty())
            throw InputError(label, field_pointer(section, info) + "/" + std::to_string(k), why);
}

}  // namespace

void check_field(const glm::dvec2& value, const FieldInfo& info, const std::string& label, std::string_view section)
{
    check_components(value, info, label, section);
}

void check_field(const glm::dvec3& value, const FieldInfo& info, const std::string& label, std::string_view section)
{
    check_components(value, info, label, section);
}

}  // namespace kiri::geometry
