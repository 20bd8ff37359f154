#pragma once
// Internal: a field list (core/fields.hpp) as a markdown table of the docs: key, type (with its
// range), unit, default (the struct's own unless the field shows another) and meaning.
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include "kiri/geometry/core/fields.hpp"

namespace kiri::geometry {

//! One row; an array field's elements add to the row of its first.
struct FieldRow {
    std::string key, unit, meaning;
    std::vector<std::string> types, defaults;
    std::string shape;  //!< of an array field or a vector
    bool array = false;
};

std::string choices_text(const FieldInfo& info);
std::string choice_default(const FieldInfo& info, int value);
std::string markdown(const std::vector<FieldRow>& rows);

template <class T>
std::string type_text(const FieldInfo& info)
{
    const auto numbers = [&](const char* word) {
        const std::string r = range_text(info.range, std::is_integral_v<T>);
        return std::string(word) + (r.empty() ? "" : " " + r);
    };
    if constexpr (std::is_same_v<T, HandWritten>)
        return info.type.empty() ? numbers("number") : std::string(info.type);
    else if constexpr (std::is_same_v<T, bool>)
        return info.choices.empty() ? "true or false" : choices_text(info);
    else if constexpr (std::is_enum_v<T>)
        return choices_text(info);
    else if constexpr (std::is_integral_v<T>)
        return numbers("integer");
    else if constexpr (std::is_floating_point_v<T>)
        return numbers("number");
    else if constexpr (is_vector_field<T>) {
        const std::string r = range_text(info.range, false);
        return std::string(info.shape.empty() ? (T::length() == 2 ? "[x, y]" : "[x, y, z]") : info.shape) +
            (r.empty() ? "" : ", each " + r);
    } else if constexpr (std::is_same_v<T, std::filesystem::path>)
        return "path";
    else
        return "string";
}

template <class T>
std::string default_text(const T& value, const FieldInfo& info)
{
    if constexpr (std::is_same_v<T, HandWritten>)
        return "";
    else if constexpr (std::is_same_v<T, bool>)
        return info.choices.empty() ? (value ? "true" : "false") : choice_default(info, int(value));
    else if constexpr (std::is_enum_v<T>)
        return choice_default(info, int(value));
    else if constexpr (std::is_arithmetic_v<T>)
        return number_text(double(value), std::is_integral_v<T>);
    else if constexpr (is_vector_field<T>) {
        std::string s = "[";
        for (int k = 0; k < T::length(); ++k)
            s += (k ? ", " : "") + number_text(value[k], false);
        return s + "]";
    } else if constexpr (std::is_same_v<T, std::filesystem::path>)
        return value.string();
    else
        return "`\"" + value + "\"`";
}

//! The table of o's list (defaults from a default-constructed O).
template <class O, class Fields = MainFields>
std::string markdown_table(Fields fields = {})
{
    std::vector<FieldRow> rows;
    const O defaults{};
    fields(defaults, [&](const auto& m, const FieldInfo& info) {
        using T = std::remove_cvref_t<decltype(m)>;
        std::string shown = !info.required.empty() ? std::string("required")
            : !info.shown_default.empty()          ? std::string(info.shown_default)
                                                   : default_text(m, info);
        if (info.element > 0 && !rows.empty() && rows.back().array) {
            rows.back().types.push_back(type_text<T>(info));
            rows.back().defaults.push_back(shown);
            return;
        }
        FieldRow row{
            std::string(info.key),   std::string(info.unit), std::string(info.doc), {type_text<T>(info)}, {shown},
            std::string(info.shape), info.element == 0};
        rows.push_back(row);
    });
    return markdown(rows);
}

}  // namespace kiri::geometry
