#pragma once
// Internal: any options struct read from and written to its section of the scene's JSON by its
// field list (core/fields.hpp), with the messages scenes have always given: unknown keys, types,
// ranges, each naming the file and the JSON pointer.
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "core/json_reader.hpp"
#include "kiri/geometry/core/fields.hpp"

namespace kiri::geometry {

// One value of a field, at pointer ptr, checked for its type and the field's range.
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                double& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info, int& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                std::uint64_t& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info, bool& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                std::string& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                glm::dvec2& out);
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                glm::dvec3& out);
//! A file name, resolved against base_dir when relative.
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info,
                std::filesystem::path& out, const std::filesystem::path& base_dir);
//! The value of the choice j names.
int read_choice(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info);
template <class E>
requires std::is_enum_v<E>
void read_value(const JsonReader& r, const nlohmann::json& j, const std::string& ptr, const FieldInfo& info, E& out)
{
    out = E(read_choice(r, j, ptr, info));
}

//! The name of the choice of `value`.
nlohmann::json choice_json(const FieldInfo& info, int value);

//! "expected an array of 3 integers [width, height, slices]": an array field's shape.
std::string array_shape_error(const FieldInfo& info, bool integers);

inline nlohmann::json field_json(double v, const FieldInfo&) { return v; }
inline nlohmann::json field_json(int v, const FieldInfo&) { return v; }
inline nlohmann::json field_json(std::uint64_t v, const FieldInfo&) { return v; }
inline nlohmann::json field_json(bool v, const FieldInfo& info)
{
    return info.choices.empty() ? nlohmann::json(v) : choice_json(info, int(v));
}
inline nlohmann::json field_json(const std::string& v, const FieldInfo&) { return v; }
inline nlohmann::json field_json(const std::filesystem::path& v, const FieldInfo&) { return v.string(); }
inline nlohmann::json field_json(const glm::dvec2& v, const FieldInfo&) { return nlohmann::json::array({v.x, v.y}); }
inline nlohmann::json field_json(const glm::dvec3& v, const FieldInfo&)
{
    return nlohmann::json::array({v.x, v.y, v.z});
}
template <class E>
requires std::is_enum_v<E> nlohmann::json field_json(E v, const FieldInfo& info) { return choice_json(info, int(v)); }

//! Reads the fields given in the object j (the section at pointer `section`) into o; a
//! required field that is absent is refused.
struct FieldReader {
    const JsonReader& r;
    const nlohmann::json& j;
    const std::string& section;
    const std::filesystem::path& base_dir;

    template <class T>
    void operator()(T& member, const FieldInfo& info) const
    {
        if constexpr (!std::is_same_v<std::remove_const_t<T>, HandWritten>) {
            const std::string key(info.key), ptr = section + "/" + key;
            if (!j.contains(key)) {
                if (!info.required.empty())
                    r.fail(ptr, std::string(info.required));
                return;
            }
            if (info.element < 0)
                return read(j[key], ptr, info, member);
            const nlohmann::json& a = j[key];
            if (!a.is_array() || a.size() != std::size_t(info.elements))
                r.fail(ptr, array_shape_error(info, std::is_integral_v<T>));
            read(a[info.element], ptr + "/" + std::to_string(info.element), info, member);
        }
    }

private:
    template <class T>
    void read(const nlohmann::json& v, const std::string& ptr, const FieldInfo& info, T& member) const
    {
        if constexpr (std::is_same_v<T, std::filesystem::path>)
            read_value(r, v, ptr, info, member, base_dir);
        else
            read_value(r, v, ptr, info, member);
    }
};

//! The keys of a list (hand-written ones included).
template <class O, class Fields = MainFields>
std::set<std::string> field_keys(O& o, Fields fields = {})
{
    std::set<std::string> keys;
    fields(o, [&](const auto&, const FieldInfo& info) { keys.insert(std::string(info.key)); });
    return keys;
}

//! Reads the section j at pointer `section` into o: keys outside the list and `extra` (what the
//! caller reads by hand) are refused, the given fields read and checked, hand-written keys left
//! to the caller. Relative file names are resolved against base_dir. \throw InputError.
template <class O, class Fields = MainFields>
void read_fields(const JsonReader& r, const nlohmann::json& j, const std::string& section, O& o,
                 const std::set<std::string>& extra = {}, const std::filesystem::path& base_dir = {},
                 Fields fields = {})
{
    std::set<std::string> keys = field_keys(o, fields);
    keys.insert(extra.begin(), extra.end());
    r.only(j, section, keys);
    fields(o, FieldReader{r, j, section, base_dir});
}

//! The section of o: every field but the hand-written ones and those at an omitted default (an
//! array field is left out when one of its values is).
template <class O, class Fields = MainFields>
nlohmann::json write_fields(const O& o, Fields fields = {})
{
    nlohmann::json out = nlohmann::json::object();
    std::set<std::string> incomplete;
    for_each_field(
        o,
        [&](const auto& m, const FieldInfo& info, const auto& fallback) {
            using T = std::remove_cvref_t<decltype(m)>;
            if constexpr (!std::is_same_v<T, HandWritten>) {
                const std::string key(info.key);
                if (info.omit_default && m == fallback) {
                    if (info.element >= 0)
                        incomplete.insert(key);
                    return;
                }
                if (info.element < 0)
                    out[key] = field_json(m, info);
                else
                    out[key][std::size_t(info.element)] = field_json(m, info);
            }
        },
        fields);
    for (const std::string& key : incomplete)
        out.erase(key);
    return out;
}

}  // namespace kiri::geometry
