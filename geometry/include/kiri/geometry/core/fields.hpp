#pragma once
//! \file fields.hpp
//! Each scene option declared once: its JSON key, unit, range and one line of documentation
//! (FieldInfo), listed per options struct by a `visit_fields` function next to the struct:
//!
//!   template <fields_of<LayerOptions> O, class V> void visit_fields(O& o, V&& v)
//!   {
//!       v(o.count, {.key = "count", .range = closed(1, 1000), .doc = "..."});
//!       v(o.max_count, {.key = "max_count", .range = closed({double(o.count), "count"}, 1000), ...});
//!   }
//!
//! The scene's reader and writer (geometry/src/scene), the validators (check_fields), the
//! preview's widgets and the key tables of the docs all walk these lists, so a key, its range
//! and its default are typed once. Fields are visited in declaration order, so a range may
//! depend on a field visited before it, as the reader has read it. Defaults are the struct's
//! default member initialisers. A list visits the same fields whatever the values (no branches).
#include <concepts>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "kiri/geometry/core/error.hpp"

namespace kiri::geometry {

inline constexpr double unbounded_value = std::numeric_limits<double>::infinity();

//! One end of a Range; `name` says what it is when it follows another field ("count").
struct Bound {
    double value;
    std::string_view name{};
    constexpr Bound(double v, std::string_view n = {}) : value(v), name(n) {}
};

//! Allowed values: lo..hi, each end closed or open; an infinite end leaves that side unbounded.
struct Range {
    Bound lo{-unbounded_value}, hi{unbounded_value};
    bool lo_open = false, hi_open = false;

    constexpr bool has_lo() const { return lo.value > -unbounded_value; }
    constexpr bool has_hi() const { return hi.value < unbounded_value; }
    constexpr bool bounded() const { return has_lo() && has_hi(); }
    bool contains(double v) const;
};

constexpr Range unbounded() { return {}; }
constexpr Range closed(Bound lo, Bound hi) { return {lo, hi, false, false}; }    //!< [lo, hi]
constexpr Range open_range(Bound lo, Bound hi) { return {lo, hi, true, true}; }  //!< (lo, hi)
constexpr Range left_open(Bound lo, Bound hi) { return {lo, hi, true, false}; }  //!< (lo, hi]
constexpr Range greater_than(Bound lo) { return {lo, {unbounded_value}, true, false}; }
constexpr Range at_least(Bound lo) { return {lo, {unbounded_value}, false, false}; }

//! A value of an enumeration (or of a bool) as the scene names it.
struct Choice {
    std::string_view name;
    int value;
};

struct FieldInfo {
    std::string_view key;               //!< in its section of the scene
    std::string_view unit;              //!< "m", "1/m", "s", "m/s", ...; empty: dimensionless
    Range range{};                      //!< of a number (of each component of a vector)
    std::string_view doc;               //!< one line: what it does
    std::span<const Choice> choices{};  //!< the names of an enumeration's values
    //! The preview's slider, where the range is too wide to slide over (unbounded: the range).
    Range widget{};
    bool log_widget = false;  //!< the slider is logarithmic
    //! Non-empty: the key must be given, and this is the reason when it is not.
    std::string_view required{};
    //! The docs' default, where the struct's own default stands for something else ("the Medium's").
    std::string_view shown_default{};
    //! The default stands for "not given": left out of a written scene and not range-checked.
    bool omit_default = false;
    //! >= 0: the field is element `element` of the array `key` of `elements` values, `shape`
    //! names them ("[width, height, slices]").
    int element = -1, elements = 0;
    std::string_view shape{};
    //! The docs' type of a hand-written key (an object, alternatives, a list).
    std::string_view type{};
};

//! A key whose value is not one scalar (an object, a polymorphic value, an alternative way to
//! give another field): the section's reader and writer handle it by hand; the list still
//! declares it (the keys allowed, its docs, the range of its numbers).
struct HandWritten {
    bool operator==(const HandWritten&) const = default;
};
inline constexpr HandWritten hand_written{};

//! O is T or const T: visit_fields serves readers (T) and validators and writers (const T).
template <class O, class T>
concept fields_of = std::same_as<std::remove_const_t<O>, T>;

//! "" when v is in the range; otherwise the reason, e.g. "must be in [0, 1], got 2", "must be > 0".
//! `got` is how v is shown (empty: v itself); integer ranges show their ends as integers.
std::string range_error(const Range& range, double v, bool integer, std::string_view got = {});

//! The list of a struct: the main one (visit_fields) unless a section names another.
struct MainFields {
    template <class O, class V>
    void operator()(O& o, V&& v) const
    {
        visit_fields(o, v);
    }
};

template <class T>
inline constexpr bool is_vector_field = std::is_same_v<T, glm::dvec2> || std::is_same_v<T, glm::dvec3>;

//! The address of every visited member of o, in order (to pair o's fields with a default's).
template <class O, class Fields = MainFields>
std::vector<const void*> field_addresses(const O& o, Fields fields = {})
{
    std::vector<const void*> out;
    fields(o, [&](const auto& m, const FieldInfo&) { out.push_back(&m); });
    return out;
}

//! Calls f(member, info, default) for each field of o, the default from a default-constructed O.
template <class O, class F, class Fields = MainFields>
void for_each_field(O& o, F&& f, Fields fields = {})
{
    static const std::remove_const_t<O> defaults{};
    const std::vector<const void*> d = field_addresses(defaults, fields);
    std::size_t k = 0;
    fields(o, [&](auto& m, const FieldInfo& info) {
        using T = std::remove_cvref_t<decltype(m)>;
        f(m, info, *static_cast<const T*>(d.at(k++)));
    });
}

//! The info of o's field `member` (found by address: pass a member of o itself), its range
//! evaluated with o's values. \throw std::logic_error when the list has no such member.
template <class O, class T, class Fields = MainFields>
FieldInfo field_of(O& o, const T& member, Fields fields = {})
{
    const FieldInfo* found = nullptr;
    FieldInfo info;
    fields(o, [&](const auto& m, const FieldInfo& i) {
        if (!found && static_cast<const void*>(&m) == static_cast<const void*>(&member)) {
            info = i;
            found = &info;
        }
    });
    if (!found)
        throw std::logic_error("field_of: not a field of its list");
    return info;
}

//! The info of o's field (or hand-written key) `key`. \throw std::logic_error when there is none.
template <class O, class Fields = MainFields>
FieldInfo field_named(O& o, std::string_view key, Fields fields = {})
{
    bool found = false;
    FieldInfo info;
    fields(o, [&](const auto&, const FieldInfo& i) {
        if (!found && i.key == key) {
            info = i;
            found = true;
        }
    });
    if (!found)
        throw std::logic_error("field_named: no field " + std::string(key));
    return info;
}

//! The range as the docs read it: "in [0, 1]", "> 0", "in [count, 1000]" ("" when unbounded).
std::string range_text(const Range& range, bool integer);
//! A number as the docs write it: whole numbers below 1e5 in full, others shortest (1e6, 0.001).
std::string number_text(double v, bool integer);

//! The JSON pointer of a field in `section` ("/layers"): "/layers/count", "/froxel/size/2".
std::string field_pointer(std::string_view section, const FieldInfo& info);

//! Throws InputError(label, field_pointer(section, info), reason) when `value` breaks the
//! field's range (vectors: each component, named by its index).
void check_field(double value, const FieldInfo& info, bool integer, const std::string& label, std::string_view section);
void check_field(const glm::dvec2& value, const FieldInfo& info, const std::string& label, std::string_view section);
void check_field(const glm::dvec3& value, const FieldInfo& info, const std::string& label, std::string_view section);

//! The validator of a list: every number of o within its range (and finite), except those at an
//! omitted default. Cross-field rules are the caller's. \throw InputError naming section/key.
template <class O, class Fields = MainFields>
void check_fields(const O& o, const std::string& label, std::string_view section, Fields fields = {})
{
    for_each_field(
        o,
        [&](const auto& m, const FieldInfo& info, const auto& fallback) {
            using T = std::remove_cvref_t<decltype(m)>;
            if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
                if (info.omit_default && m == fallback)
                    return;
                check_field(double(m), info, std::is_integral_v<T>, label, section);
            } else if constexpr (is_vector_field<T>) {
                if (info.omit_default && m == fallback)
                    return;
                check_field(m, info, label, section);
            }
        },
        fields);
}

}  // namespace kiri::geometry
