#pragma once
// Internal: reads typed values out of a scene's JSON tree; every failure throws InputError
// naming the file and the JSON pointer (nlohmann stays out of public headers). Ranges are the
// field lists' (core/fields.hpp, read by scene/field_json.hpp).
#include <cmath>
#include <set>
#include <string>

#include <glm/vec2.hpp>
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
};

}  // namespace kiri::geometry
