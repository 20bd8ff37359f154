#include "scene/field_json.hpp"

#include <sstream>

namespace kiri::geometry {
namespace {

using json = nlohmann::json;

std::string with_unit(const FieldInfo& info)
{
    return info.unit.empty() ? std::string() : " (" + std::string(info.unit) + ")";
}

std::string shown(double v)
{
    std::ostringstream s;
    s << v;
    return s.str();
}

// An integer of the field's range, compared as a double: a huge unsigned value must not wrap into it.
double integer_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info)
{
    if (!j.is_number_integer())
        r.fail(ptr, "expected an integer");
    const double v = j.get<double>();
    if (std::string why = range_error(info.range, v, true, j.dump()); !why.empty())
        r.fail(ptr, why);
    return v;
}

template <class Vec>
void read_vector(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, Vec& out)
{
    constexpr int n = Vec::length();
    bool numbers = j.is_array() && j.size() == std::size_t(n);
    for (int k = 0; numbers && k < n; ++k)
        numbers = j[k].is_number();
    if (!numbers)
        r.fail(ptr, "expected an array of " + std::to_string(n) + " numbers" + with_unit(info));
    for (int k = 0; k < n; ++k) {
        const std::string component = ptr + "/" + std::to_string(k);
        out[k] = r.number(j[k], component);
        if (std::string why = range_error(info.range, out[k], false); !why.empty())
            r.fail(component, why);
    }
}

}  // namespace

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, double& out)
{
    const double v = r.number(j, ptr);
    if (std::string why = range_error(info.range, v, false, shown(v)); !why.empty())
        r.fail(ptr, why);
    out = v;
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, int& out)
{
    out = int(integer_value(r, j, ptr, info));
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, std::uint64_t& out)
{
    out = std::uint64_t(integer_value(r, j, ptr, info));
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, bool& out)
{
    out = info.choices.empty() ? r.boolean(j, ptr) : read_choice(r, j, ptr, info) != 0;
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo&, std::string& out)
{
    out = r.string(j, ptr);
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, glm::dvec2& out)
{
    read_vector(r, j, ptr, info, out);
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info, glm::dvec3& out)
{
    read_vector(r, j, ptr, info, out);
}

void read_value(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo&,
                std::filesystem::path& out, const std::filesystem::path& base_dir)
{
    const std::string path = r.string(j, ptr);
    if (path.empty())
        r.fail(ptr, "must not be empty");
    out = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : base_dir / path;
}

int read_choice(const JsonReader& r, const json& j, const std::string& ptr, const FieldInfo& info)
{
    if (j.is_string())
        for (const Choice& c : info.choices)
            if (j.get<std::string>() == c.name)
                return c.value;
    std::ostringstream expected;
    expected << "expected ";
    for (std::size_t k = 0; k < info.choices.size(); ++k)
        expected << (k == 0 ? "" : k + 1 == info.choices.size() ? " or " : ", ") << '"' << info.choices[k].name << '"';
    if (j.is_string())
        expected << ", got \"" << j.get<std::string>() << '"';
    r.fail(ptr, expected.str());
}

json choice_json(const FieldInfo& info, int value)
{
    for (const Choice& c : info.choices)
        if (c.value == value)
            return std::string(c.name);
    return std::string(info.choices.empty() ? std::string_view() : info.choices.front().name);
}

std::string array_shape_error(const FieldInfo& info, bool integers)
{
    return "expected an array of " + std::to_string(info.elements) + (integers ? " integers " : " numbers ") +
        std::string(info.shape) + with_unit(info);
}

}  // namespace kiri::geometry
