// Scattered points -> heightfield (CGAL Delaunay TIN), against analytic surfaces.
#include <gtest/gtest.h>

#include "temp_path.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/terrain/point_files.hpp"
#include "kiri/geometry/terrain/scattered_points.hpp"

namespace fs = std::filesystem;
using namespace kiri::geometry;

namespace {

// Jittered grid: one uniform point in each s x s square of [0, k s]^2, plus the four corners
// so that the convex hull is the whole box.
std::vector<glm::dvec3> jittered(int k, double s, double ox, double oy, double (*f)(double, double), unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<glm::dvec3> pts;
    for (int b = 0; b < k; ++b)
        for (int a = 0; a < k; ++a) {
            const double x = (a + u(rng)) * s, y = (b + u(rng)) * s;
            pts.emplace_back(ox + x, oy + y, f(x, y));
        }
    for (const double x : {0.0, k * s})
        for (const double y : {0.0, k * s})
            pts.emplace_back(ox + x, oy + y, f(x, y));
    return pts;
}

double plane(double x, double y) { return 3.0 + 0.1 * x - 0.05 * y; }

constexpr double A = 50.0, a = 150.0, b = 200.0;
double wave(double x, double y) { return A * std::sin(x / a) * std::cos(y / b); }

class TempDir : public ::testing::Test {
protected:
    fs::path dir;
    void SetUp() override
    {
        dir = kiri::test::temp_path("xyz_test_" +
                                    std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    fs::path write(const std::string& name, const std::string& text)
    {
        std::ofstream(dir / name) << text;
        return dir / name;
    }
};

}  // namespace

TEST(HeightfieldFromPoints, ReproducesAPlaneFarFromTheOrigin)
{
    // UTM-sized coordinates: the plane must survive them to ~1e-9 m.
    const double ox = 500000.0, oy = 4000000.0;
    const auto pts = jittered(20, 50.0, ox, oy, plane, 1);
    const Heightfield hf = heightfield_from_points(pts, 10.0);
    ASSERT_EQ(hf.nx, 101);
    ASSERT_EQ(hf.ny, 101);
    EXPECT_DOUBLE_EQ(hf.dx, 10.0);
    EXPECT_DOUBLE_EQ(hf.georef.origin_x, ox + 500.0);
    EXPECT_DOUBLE_EQ(hf.georef.origin_y, oy + 500.0);
    EXPECT_DOUBLE_EQ(hf.x0, -500.0);
    double worst = 0.0;
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            ASSERT_EQ(hf.valid[j * hf.nx + i], 1);  // the corners make the hull the whole box
            // Local x_of(i) + origin = input coordinate.
            const double x = hf.x_of(i) + hf.georef.origin_x - ox, y = hf.y_of(j) + hf.georef.origin_y - oy;
            worst = std::max(worst, std::abs(hf.at(i, j) - plane(x, y)));
        }
    EXPECT_LT(worst, 1e-9);
}

TEST(HeightfieldFromPoints, SmoothSurfaceErrorShrinksWithDensity)
{
    // On a jittered grid of spacing s every empty Delaunay circle has radius < sqrt(2) s, so
    // linear interpolation is off by at most |D^2 f| R^2 / 2 <= A (1/a^2 + 1/b^2) s^2
    // (interior triangles; samples within 2 s of the box edge are left out).
    double previous = INFINITY;
    for (const int k : {16, 32, 64}) {
        const double s = 1024.0 / k;
        const auto pts = jittered(k, s, 0.0, 0.0, wave, 2);
        const Heightfield hf = heightfield_from_points(pts, 8.0);
        double worst = 0.0;
        for (int j = 0; j < hf.ny; ++j)
            for (int i = 0; i < hf.nx; ++i) {
                const double x = i * 8.0, y = j * 8.0;
                if (x < 2 * s || y < 2 * s || x > 1024.0 - 2 * s || y > 1024.0 - 2 * s)
                    continue;
                worst = std::max(worst, std::abs(hf.at(i, j) - wave(x, y)));
            }
        const double bound = A * (1.0 / (a * a) + 1.0 / (b * b)) * s * s;
        EXPECT_LT(worst, bound) << "k = " << k;
        EXPECT_LT(worst, 0.5 * previous) << "k = " << k;  // ~s^2: quarters when s halves
        std::printf("k = %d, s = %g m: max |error| %.4f m (bound %.4f m)\n", k, s, worst, bound);
        previous = worst;
    }
}

TEST(HeightfieldFromPoints, SamplesOutsideTheHullAreMaskedAndFilled)
{
    // A triangle of points over a plane: the box corners outside it are filled, finite.
    const std::vector<glm::dvec3> pts = {{0, 0, plane(0, 0)}, {100, 0, plane(100, 0)}, {0, 100, plane(0, 100)}};
    const Heightfield hf = heightfield_from_points(pts, 10.0);
    ASSERT_EQ(hf.nx, 11);
    EXPECT_EQ(hf.valid[0], 1);
    EXPECT_EQ(hf.valid[hf.z.size() - 1], 0);  // (100, 100) lies outside
    for (int j = 0; j < hf.ny; ++j)
        for (int i = 0; i < hf.nx; ++i) {
            EXPECT_TRUE(std::isfinite(hf.at(i, j)));
            EXPECT_EQ(hf.valid[j * hf.nx + i], i + j <= 10 ? 1 : 0) << i << "," << j;
            if (i + j <= 10) {
                EXPECT_NEAR(hf.at(i, j), plane(10.0 * i, 10.0 * j), 1e-9);
            }
        }
}

TEST(HeightfieldFromPoints, BadArgumentsAreRefused)
{
    const std::vector<glm::dvec3> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 5}};
    EXPECT_THROW(heightfield_from_points(line, 1.0), kiri::InputError);
    const std::vector<glm::dvec3> tri = {{0, 0, 0}, {1, 0, 1}, {0, 1, 5}};
    EXPECT_THROW(heightfield_from_points(tri, 0.0), kiri::InputError);
    EXPECT_THROW(heightfield_from_points(tri, NAN), kiri::InputError);
    EXPECT_THROW(heightfield_from_points({{0, 0, 0}, {1, 0, 1}}, 1.0), kiri::InputError);
    EXPECT_THROW(heightfield_from_points({{0, 0, 0}, {1, 0, NAN}, {0, 1, 1}}, 1.0), kiri::InputError);
    EXPECT_THROW(heightfield_from_points(tri, 1e-6), kiri::LimitError);
}

TEST_F(TempDir, ReadsRowsCommentsAndCommas)
{
    const auto path = write("pts.xyz", "# survey\n1 2 3\n\n  4.5\t-6 7e2  # a comment\n8,9,10\r\n");
    const auto pts = read_xyz_points(path);
    ASSERT_EQ(pts.size(), 3u);
    EXPECT_EQ(pts[1], glm::dvec3(4.5, -6.0, 700.0));
    EXPECT_EQ(pts[2], glm::dvec3(8.0, 9.0, 10.0));
}

TEST_F(TempDir, ErrorsNameTheFileAndLine)
{
    const auto expect_error = [](const fs::path& p, const std::string& field, const std::string& part) {
        try {
            read_xyz_points(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const kiri::InputError& e) {
            EXPECT_EQ(e.file(), p.string());
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expect_error(write("short.xyz", "1 2 3\n# ok\n4 5\n"), "line 3", "found 2");
    expect_error(write("word.xyz", "1 2 3\n1 two 3\n"), "line 2", "'two'");
    expect_error(write("nan.xyz", "1 2 nan\n"), "line 1", "'nan'");
    expect_error(write("huge.xyz", "1 2 1e999\n"), "line 1", "'1e999'");
    expect_error(write("empty.xyz", "# nothing\n\n"), "", "no points");
    expect_error(dir / "missing.xyz", "file", "no such file");
}

// ---- Point files: CSV with a header, PLY (point_files.hpp) ---------------------------------

namespace {

std::string ply_binary(const std::string& properties, const std::string& body, int count)
{
    return "ply\nformat binary_little_endian 1.0\ncomment test\nelement vertex " + std::to_string(count) + "\n" +
        properties + "element face 0\nproperty list uchar int vertex_indices\nend_header\n" + body;
}

template <class T>
std::string bytes(T v)
{
    return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}

}  // namespace

TEST_F(TempDir, CsvColumnsAreNamedInAnyOrder)
{
    const auto path = write("pts.csv", "# survey\nid,Z,\"y\",x,quality\n1,300.5,20,10,good\n2,310,21.5,11,fair\n");
    const auto pts = read_points(path);
    ASSERT_EQ(pts.size(), 2u);
    EXPECT_EQ(pts[0], glm::dvec3(10.0, 20.0, 300.5));
    EXPECT_EQ(pts[1], glm::dvec3(11.0, 21.5, 310.0));
    // Without a header: x,y,z rows, as before.
    EXPECT_EQ(read_points(write("plain.csv", "1,2,3\n4,5,6\n"))[1], glm::dvec3(4.0, 5.0, 6.0));
}

TEST_F(TempDir, PlyVerticesAsciiAndBinary)
{
    const auto ascii = write("pts.ply",
                             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                             "property uchar red\nproperty double z\nend_header\n"
                             "0 0 255 100\n10 0 0 101.5\n0 10 7 -3e2\n");
    const auto a = read_points(ascii);
    ASSERT_EQ(a.size(), 3u);
    EXPECT_EQ(a[1], glm::dvec3(10.0, 0.0, 101.5));
    EXPECT_EQ(a[2], glm::dvec3(0.0, 10.0, -300.0));
    const std::string props = "property double x\nproperty double y\nproperty short intensity\nproperty float z\n";
    std::string body;
    for (const glm::dvec3& p : a)
        body += bytes(p.x) + bytes(p.y) + bytes(std::int16_t(-7)) + bytes(float(p.z));
    const auto b = read_points(write("bin.ply", ply_binary(props, body, 3)));
    ASSERT_EQ(b.size(), 3u);
    for (std::size_t k = 0; k < 3; ++k)
        EXPECT_EQ(b[k], a[k]);
}

TEST_F(TempDir, PointFileErrorsNameTheFileAndWhere)
{
    const auto expect_error = [](const fs::path& p, const std::string& field, const std::string& part) {
        try {
            read_points(p);
            ADD_FAILURE() << "no error for " << p;
        } catch (const kiri::InputError& e) {
            EXPECT_EQ(e.file(), p.string());
            EXPECT_EQ(e.field(), field) << e.what();
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expect_error(write("names.csv", "lon,lat,elev\n1,2,3\n"), "line 1", "needs columns x, y, z; found lon, lat, elev");
    expect_error(write("short.csv", "x,y,z\n1,2,3\n4,5\n"), "line 3", "found 2");
    expect_error(write("nan.csv", "z,y,x\nnan,1,2\n"), "line 2", "column z");
    const std::string props = "property float x\nproperty float y\nproperty float z\n";
    expect_error(write("cut.ply", ply_binary(props, std::string(20, '\0'), 2)), "element vertex", "truncated");
    expect_error(write("huge.ply", ply_binary(props, "", 1000000000)), "element vertex", "truncated");
    expect_error(write("list.ply",
                       "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\n"
                       "property float y\nproperty float z\nend_header\n1 0 0 0\n"),
                 "property x", "is a list");
    expect_error(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\nend_header\n"),
                 "property x", "unknown type 'real'");
    expect_error(write("noz.ply",
                       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                       "end_header\n1 2\n"),
                 "element vertex", "has no property z");
    expect_error(write("nan.ply", ply_binary(props, bytes(1.0f) + bytes(NAN) + bytes(3.0f), 1)), "vertex 0",
                 "not finite");
    expect_error(write("big.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 0\nend_header\n"), "format",
                 "binary_big_endian");
    expect_error(write("text.ply", "solid cube\n"), "header", "not a PLY file");
    expect_error(write("ascii_cut.ply", "ply\nformat ascii 1.0\nelement vertex 3\n" + props + "end_header\n1 2 3\n"),
                 "element vertex", "3 vertices declared, 1 found");
}
