#pragma once
// Internal: reads typed values out of a scene's JSON tree; every failure throws InputError
// naming the file and the JSON pointer (nlohmann stays out of public headers).
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

struct JsonReader {
    using json = nlohmann::json;
    const std::string& file;

    [[noreturn]] void fail(const std::string& ptr, const std::string& why) const { throw InputError(file, ptr, why); }

    void only(const json& j, const std::string& ptr, const std::set<std::string>& keys) const
    {
        if (!j.is_object())
            fail(ptr.empty() ? "/" : ptr, "expected an object");
        for (const auto& item : j.items())
            if (!keys.count(item.key()))
                fail(ptr + "/" + item.key(), "unknown key (expected one of: " + join(keys) + ")");
    }
    static std::string join(const std::set<std::string>& keys)
    {
        std::string out;
        for (const std::string& k : keys)
            out += (out.empty() ? "" : ", ") + k;
        return out;
    }
    double number(const json& j, const std::string& ptr) const
    {
        if (!j.is_number())
            fail(ptr, "expected a number");
        const double v = j.get<double>();
        if (!std::isfinite(v))
            fail(ptr, "expected a finite number");
        return v;
    }
    double positive(const json& j, const std::string& ptr) const
    {
        const double v = number(j, ptr);
        if (!(v > 0.0))
            fail(ptr, "must be > 0");
        return v;
    }
    double non_negative(const json& j, const std::string& ptr) const
    {
        const double v = number(j, ptr);
        if (v < 0.0)
            fail(ptr, "must be >= 0");
        return v;
    }
    double in_range(const json& j, const std::string& ptr, double lo, double hi, bool open) const
    {
        const double v = number(j, ptr);
        if (open ? !(v > lo && v < hi) : !(v >= lo && v <= hi)) {
            std::ostringstream why;
            why << "must be in " << (open ? "(" : "[") << lo << ", " << hi << (open ? ")" : "]") << ", got " << v;
            fail(ptr, why.str());
        }
        return v;
    }
    int integer(const json& j, const std::string& ptr, int lo, int hi) const
    {
        if (!j.is_number_integer())
            fail(ptr, "expected an integer");
        // Compared as double: a huge unsigned value must not wrap into the range.
        const double v = j.get<double>();
        if (v < lo || v > hi) {
            std::ostringstream why;
            why << "must be in [" << lo << ", " << hi << "], got " << j.dump();
            fail(ptr, why.str());
        }
        return int(v);
    }
    bool boolean(const json& j, const std::string& ptr) const
    {
        if (!j.is_boolean())
            fail(ptr, "expected true or false");
        return j.get<bool>();
    }
    std::string string(const json& j, const std::string& ptr) const
    {
        if (!j.is_string())
            fail(ptr, "expected a string");
        return j.get<std::string>();
    }
    glm::dvec2 point(const json& j, const std::string& ptr) const
    {
        if (!j.is_array() || j.size() != 2)
            fail(ptr, "expected an array of 2 numbers [x, y] (local metres)");
        return {number(j[0], ptr + "/0"), number(j[1], ptr + "/1")};
    }
    glm::dvec3 vec3(const json& j, const std::string& ptr) const
    {
        if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
            fail(ptr, "expected an array of 3 numbers");
        return {number(j[0], ptr + "/0"), number(j[1], ptr + "/1"), number(j[2], ptr + "/2")};
    }
};

}  // namespace kiri::geometry
