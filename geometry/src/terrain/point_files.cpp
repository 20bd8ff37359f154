#include "kiri/geometry/terrain/point_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/terrain/scattered_points.hpp"

namespace kiri::geometry {
namespace {

std::string lower(std::string s)
{
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

std::string trim(const std::string& s, const char* blanks = " \t\r\"'")
{
    const std::size_t a = s.find_first_not_of(blanks);
    if (a == std::string::npos)
        return {};
    return s.substr(a, s.find_last_not_of(blanks) - a + 1);
}

bool parse_number(const std::string& token, double& value)
{
    errno = 0;
    char* end = nullptr;
    value = std::strtod(token.c_str(), &end);
    return !token.empty() && end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(value);
}

std::vector<std::string> split_commas(const std::string& line)
{
    std::vector<std::string> out;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');)
        out.push_back(trim(cell));
    if (!line.empty() && line.back() == ',')
        out.emplace_back();
    return out;
}

// PLY's scalar types and their sizes in bytes (0: unknown).
int ply_size(const std::string& type)
{
    static const std::array<std::pair<const char*, int>, 16> types = {{{"char", 1},
                                                                       {"uchar", 1},
                                                                       {"int8", 1},
                                                                       {"uint8", 1},
                                                                       {"short", 2},
                                                                       {"ushort", 2},
                                                                       {"int16", 2},
                                                                       {"uint16", 2},
                                                                       {"int", 4},
                                                                       {"uint", 4},
                                                                       {"int32", 4},
                                                                       {"uint32", 4},
                                                                       {"float", 4},
                                                                       {"float32", 4},
                                                                       {"double", 8},
                                                                       {"float64", 8}}};
    for (const auto& [name, size] : types)
        if (type == name)
            return size;
    return 0;
}

// A little-endian value of PLY type `type` at p (the host is little-endian: x86, ARM).
double ply_value(const std::string& type, const unsigned char* p)
{
    const auto as = [p](auto v) {
        std::memcpy(&v, p, sizeof v);
        return double(v);
    };
    if (type == "char" || type == "int8")
        return as(std::int8_t{});
    if (type == "uchar" || type == "uint8")
        return as(std::uint8_t{});
    if (type == "short" || type == "int16")
        return as(std::int16_t{});
    if (type == "ushort" || type == "uint16")
        return as(std::uint16_t{});
    if (type == "int" || type == "int32")
        return as(std::int32_t{});
    if (type == "uint" || type == "uint32")
        return as(std::uint32_t{});
    if (type == "float" || type == "float32")
        return as(float{});
    return as(double{});
}

}  // namespace

std::vector<glm::dvec3> read_points(const std::filesystem::path& path)
{
    const std::string ext = lower(path.extension().string());
    if (ext == ".ply")
        return read_ply_points(path);
    if (ext == ".csv")
        return read_csv_points(path);
    return read_xyz_points(path);
}

std::vector<glm::dvec3> read_csv_points(const std::filesystem::path& path)
{
    const std::string file = path.string();
    std::ifstream in(path);
    if (!in)
        throw InputError(file, "file", std::filesystem::exists(path) ? "cannot open for reading" : "no such file");
    std::string line;
    std::size_t number = 0;
    std::vector<std::string> header;
    while (std::getline(in, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        if (!trim(line).empty()) {
            header = split_commas(line);
            break;
        }
    }
    double v = 0.0;
    if (header.empty() ||
        std::all_of(header.begin(), header.end(), [&](const std::string& c) { return parse_number(c, v); }))
        return read_xyz_points(path);  // no header: "x,y,z" rows
    int column[3] = {-1, -1, -1};
    for (std::size_t c = 0; c < header.size(); ++c)
        for (int axis = 0; axis < 3; ++axis)
            if (lower(header[c]) == std::string(1, "xyz"[axis]) && column[axis] < 0)
                column[axis] = int(c);
    if (std::any_of(column, column + 3, [](int c) { return c < 0; })) {
        std::string found;
        for (const std::string& c : header)
            found += (found.empty() ? "" : ", ") + c;
        throw InputError(file, "line " + std::to_string(number), "the header needs columns x, y, z; found " + found);
    }
    const std::size_t needed = std::size_t(*std::max_element(column, column + 3)) + 1;
    std::vector<glm::dvec3> points;
    while (std::getline(in, line)) {
        ++number;
        if (const auto hash = line.find('#'); hash != std::string::npos)
            line.resize(hash);
        if (trim(line).empty())
            continue;
        const std::vector<std::string> cells = split_commas(line);
        const std::string field = "line " + std::to_string(number);
        if (cells.size() < needed)
            throw InputError(
                file, field,
                "expected " + std::to_string(header.size()) + " columns, found " + std::to_string(cells.size()));
        double p[3];
        for (int axis = 0; axis < 3; ++axis)
            if (!parse_number(cells[std::size_t(column[axis])], p[axis]))
                throw InputError(file, field,
                                 "'" + cells[std::size_t(column[axis])] + "' (column " + std::string(1, "xyz"[axis]) +
                                     ") is not a finite number");
        points.emplace_back(p[0], p[1], p[2]);
    }
    if (in.bad())
        throw IoError(file, "file", "read error");
    if (points.empty())
        throw InputError(file, "", "no points (expected rows of x, y, z under the header)");
    return points;
}

std::vector<glm::dvec3> read_ply_points(const std::filesystem::path& path)
{
    const std::string file = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw InputError(file, "file", std::filesystem::exists(path) ? "cannot open for reading" : "no such file");
    std::string line;
    if (!std::getline(in, line) || trim(line) != "ply")
        throw InputError(file, "header", "not a PLY file (it must start with \"ply\")");
    bool binary = false, in_vertex = false, seen_format = false;
    long long count = -1;
    int elements = 0;
    struct Property {
        std::string type, name;
    };
    std::vector<Property> properties;
    while (true) {
        if (!std::getline(in, line))
            throw InputError(file, "header", "truncated: no end_header");
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (word == "end_header")
            break;
        if (word == "format") {
            std::string format;
            words >> format;
            if (format == "binary_little_endian")
                binary = true;
            else if (format != "ascii")
                throw InputError(file, "format", "'" + format + "' is not supported (ascii or binary_little_endian)");
            seen_format = true;
        } else if (word == "element") {
            std::string name, n;
            words >> name >> n;
            ++elements;
            in_vertex = name == "vertex";
            if (in_vertex) {
                if (elements != 1)
                    throw InputError(file, "element vertex", "must be the first element");
                double c = 0.0;
                if (!parse_number(n, c) || c < 0 || c != std::floor(c) || c > 1e12)
                    throw InputError(file, "element vertex", "'" + n + "' is not a vertex count");
                count = (long long)c;
            }
        } else if (word == "property" && in_vertex) {
            std::string type, name;
            words >> type;
            if (type == "list") {
                std::string count_type, item_type;
                words >> count_type >> item_type >> name;
                if (name == "x" || name == "y" || name == "z")
                    throw InputError(file, "property " + name, "is a list; x, y and z must be numbers");
                throw InputError(file, "property " + name, "vertex lists are not supported");
            }
            words >> name;
            if (ply_size(type) == 0)
                throw InputError(file, "property " + name, "unknown type '" + type + "'");
            properties.push_back({type, name});
        }
    }
    if (!seen_format)
        throw InputError(file, "format", "missing");
    if (count < 0)
        throw InputError(file, "element vertex", "missing");
    int column[3] = {-1, -1, -1};
    for (std::size_t k = 0; k < properties.size(); ++k)
        for (int axis = 0; axis < 3; ++axis)
            if (properties[k].name == std::string(1, "xyz"[axis]))
                column[axis] = int(k);
    for (int axis = 0; axis < 3; ++axis)
        if (column[axis] < 0)
            throw InputError(file, "element vertex", std::string("has no property ") + "xyz"[axis]);
    std::vector<glm::dvec3> points;
    const auto finite_point = [&](const double p[3], long long k) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
            throw InputError(file, "vertex " + std::to_string(k), "is not finite");
        points.emplace_back(p[0], p[1], p[2]);
    };
    if (binary) {
        std::size_t stride = 0;
        std::vector<std::size_t> offset;
        for (const Property& p : properties) {
            offset.push_back(stride);
            stride += std::size_t(ply_size(p.type));
        }
        const auto body = in.tellg();
        in.seekg(0, std::ios::end);
        const auto left = std::uintmax_t(in.tellg() - body);
        in.seekg(body);
        if (std::uintmax_t(count) * stride > left)
            throw InputError(file, "element vertex",
                             "truncated: " + std::to_string(count) + " vertices of " + std::to_string(stride) +
                                 " bytes need " + std::to_string(std::uintmax_t(count) * stride) +
                                 " bytes, the file holds " + std::to_string(left));
        points.reserve(std::size_t(count));
        std::vector<unsigned char> row(stride);
        for (long long k = 0; k < count; ++k) {
            if (!in.read(reinterpret_cast<char*>(row.data()), std::streamsize(stride)))
                throw InputError(file, "vertex " + std::to_string(k), "truncated");
            double p[3];
            for (int axis = 0; axis < 3; ++axis)
                p[axis] = ply_value(properties[std::size_t(column[axis])].type,
                                    row.data() + offset[std::size_t(column[axis])]);
            finite_point(p, k);
        }
    } else {
        for (long long k = 0; k < count; ++k) {
            if (!std::getline(in, line))
                throw InputError(
                    file, "element vertex",
                    "truncated: " + std::to_string(count) + " vertices declared, " + std::to_string(k) + " found");
            std::istringstream words(line);
            std::vector<std::string> values;
            for (std::string w; words >> w;)
                values.push_back(w);
            if (values.size() < properties.size())
                throw InputError(file, "vertex " + std::to_string(k),
                                 "expected " + std::to_string(properties.size()) + " values, found " +
                                     std::to_string(values.size()));
            double p[3];
            for (int axis = 0; axis < 3; ++axis) {
                const std::string& token = values[std::size_t(column[axis])];
                errno = 0;
                char* end = nullptr;
                p[axis] = std::strtod(token.c_str(), &end);
                if (end != token.c_str() + token.size())
                    throw InputError(file, "vertex " + std::to_string(k), "'" + token + "' is not a number");
            }
            finite_point(p, k);
        }
    }
    if (points.empty())
        throw InputError(file, "element vertex", "no points");
    return points;
}

}  // namespace kiri::geometry
