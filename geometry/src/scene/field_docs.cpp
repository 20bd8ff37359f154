#include "scene/field_docs.hpp"

#include <algorithm>

namespace kiri::geometry {
namespace {

// A cell may not hold the table's column separator.
std::string cell(const std::string& s)
{
    std::string out;
    for (char c : s) {
        if (c == '|')
            out += '\\';
        out += c;
    }
    return out;
}

}  // namespace

std::string choices_text(const FieldInfo& info)
{
    std::string s;
    for (std::size_t k = 0; k < info.choices.size(); ++k)
        s += (k == 0                             ? ""
                  : k + 1 == info.choices.size() ? " or "
                                                 : ", ") +
            std::string("`\"") + std::string(info.choices[k].name) + "\"`";
    return s;
}

std::string choice_default(const FieldInfo& info, int value)
{
    for (const Choice& c : info.choices)
        if (c.value == value)
            return "`\"" + std::string(c.name) + "\"`";
    return "";
}

std::string markdown(const std::vector<FieldRow>& rows)
{
    std::string out = "| key | type | unit | default | meaning |\n|---|---|---|---|---|\n";
    for (const FieldRow& row : rows) {
        std::string type = row.types.front(), shown = row.defaults.front();
        if (row.array) {
            // One row for the array: its shape, its elements' types (once when they agree), its values.
            const bool same = std::all_of(row.types.begin(), row.types.end(),
                                          [&](const std::string& t) { return t == row.types.front(); });
            type = row.shape + ", " + (same ? row.types.front() : "");
            for (std::size_t k = 0; !same && k < row.types.size(); ++k)
                type += (k ? ", " : "") + row.types[k];
            const bool automatic = std::all_of(row.defaults.begin(), row.defaults.end(),
                                               [&](const std::string& d) { return d == row.defaults.front(); });
            if (!automatic || shown.empty() || std::isdigit(static_cast<unsigned char>(shown.front()))) {
                shown = "[";
                for (std::size_t k = 0; k < row.defaults.size(); ++k)
                    shown += (k ? ", " : "") + row.defaults[k];
                shown += "]";
            }
        }
        out += "| `" + row.key + "` | " + cell(type) + " | " + cell(row.unit) + " | " + cell(shown) + " | " +
            cell(row.meaning) + " |\n";
    }
    return out;
}

}  // namespace kiri::geometry
