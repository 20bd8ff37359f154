#pragma once
//! \file gregory_patch.hpp
//! The bicubic Gregory patch of 20 control points ([Chiyokura83]; [Thesis] (2.1)-(2.5) with the
//! corrected Bernstein basis B^3_i(t) = C(3,i) t^i (1-t)^(3-i), docs/references.md):
//!
//!     S(u,v) = sum_{i,j=0..3} B_i(u) B_j(v) Q_ij(u,v),   Q_ij = P_ij0 on the boundary,
//!     Q11 = (u P110 + v P111) / (u + v),          Q21 = ((1-u) P210 + v P211) / ((1-u) + v),
//!     Q12 = (u P120 + (1-v) P121) / (u + (1-v)),  Q22 = ((1-u) P220 + (1-v) P221) / ((1-u) + (1-v)).
//!
//! i runs along u, j along v; P000 sits at (0,0), P300 at (1,0), P330 at (1,1), P030 at (0,1).
//! P_ij0 sets the cross-boundary derivative of the edges v = 0 and v = 1, P_ij1 that of the
//! edges u = 0 and u = 1. Every function here is defined on the closed unit square and returns
//! the limit at the four singular corners (never NaN); position and first derivatives are
//! exact (the rational weights are differentiated, unlike OpenSubdiv's GREGORY_BASIS, whose
//! derivatives hold them constant).
#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace kiri::geometry {

//! 20 control points. Storage order (`index`): the 16 points P_ij0 of the 4 x 4 net row by
//! row, index j*4 + i (the 12 boundary points and the k = 0 interior points), then the four
//! k = 1 interior points P111, P211, P121, P221 at 16, 17, 18, 19. With points 16..19 equal
//! to 5, 6, 9, 10 the patch is the bicubic Bezier patch of the first 16.
class GregoryPatch {
public:
    static constexpr int num_points = 20;
    using Points = std::array<glm::dvec3, num_points>;

    //! Storage index of P_ijk (i, j in 0..3; k in 0..1, only meaningful for i, j in {1, 2}).
    static constexpr int index(int i, int j, int k)
    {
        return (k == 0 || i == 0 || i == 3 || j == 0 || j == 3) ? j * 4 + i : 16 + (j - 1) * 2 + (i - 1);
    }

    GregoryPatch() = default;
    //! \param points in the storage order above (see `index`).
    explicit GregoryPatch(const Points& points);

    const glm::dvec3& point(int i, int j, int k = 0) const { return points_[index(i, j, k)]; }
    const Points& points() const { return points_; }
    //! Local origin (P000): evaluation works on points relative to it, so coordinates far
    //! from the world origin (1e7 m) lose nothing in the derivatives and only the final
    //! rounding in the position.
    const glm::dvec3& origin() const { return origin_; }
    //! Control points minus origin(), as structure of arrays (the batch path reads these).
    const std::array<double, num_points>& local_x() const { return x_; }
    const std::array<double, num_points>& local_y() const { return y_; }
    const std::array<double, num_points>& local_z() const { return z_; }

private:
    Points points_{};
    glm::dvec3 origin_{0.0};
    std::array<double, num_points> x_{}, y_{}, z_{};
};

//! One evaluated point.
struct PatchPoint {
    glm::dvec3 position{0.0};
    glm::dvec3 du{0.0}, dv{0.0};       //!< exact dS/du, dS/dv
    glm::dvec3 normal{0.0, 0.0, 1.0};  //!< unit normal, see unit_normal()
};

//! Unit normal from the first derivatives: normalize(du x dv). Where du x dv vanishes (a
//! collapsed edge at a corner, a zero-area patch) the normal is that of the patch evaluated
//! at `nudge` (a point moved 1e-7 towards the centre; the limit of the normal along that
//! path), and where that vanishes too, that of the control net (P330 - P000) x (P030 - P300),
//! and finally +z. Always finite and of unit length.
glm::dvec3 unit_normal(const GregoryPatch& patch, double u, double v, const glm::dvec3& du, const glm::dvec3& dv);

//! Position, exact first derivatives and unit normal at (u, v) in [0,1]^2. Parameters are
//! clamped to [0,1]; NaN parameters give the patch centre.
PatchPoint evaluate(const GregoryPatch& patch, double u, double v);

//! The 20 Gregory weights at (u, v) in storage order ([Thesis] (2.1)-(2.5)) and their exact first
//! derivatives: S = sum_k w[k] P_k. Sums to 1 (partition of unity); wu, wv sum to 0.
void gregory_weights(double u, double v, std::span<double, 20> w, std::span<double, 20> wu, std::span<double, 20> wv);

//! Structure-of-arrays views of a batch's results. Position and first-derivative spans must
//! all be at least the batch size; the normal spans may be empty (not computed).
struct PatchSampleSpans {
    std::span<double> px, py, pz;
    std::span<double> dux, duy, duz;
    std::span<double> dvx, dvy, dvz;
    std::span<double> nx, ny, nz;
};

//! Owning batch results (the convenient form; the `_into` form is the fast path).
struct PatchSamples {
    std::vector<double> px, py, pz, dux, duy, duz, dvx, dvy, dvz, nx, ny, nz;
    std::size_t size() const { return px.size(); }
    void resize(std::size_t n, bool normals);
    PatchSampleSpans spans();
    glm::dvec3 position(std::size_t i) const { return {px[i], py[i], pz[i]}; }
    glm::dvec3 du(std::size_t i) const { return {dux[i], duy[i], duz[i]}; }
    glm::dvec3 dv(std::size_t i) const { return {dvx[i], dvy[i], dvz[i]}; }
    glm::dvec3 normal(std::size_t i) const { return {nx[i], ny[i], nz[i]}; }
};

//! Batch evaluation at (u[i], v[i]): position and exact first derivatives (and unit normals
//! if out.nx is not empty). Allocates nothing. Points go in vector lanes (4 with AVX2+FMA,
//! chosen at run time on x86-64, else 2) through the tensor form: the four rational blends,
//! the bicubic Bezier sums over the 4 x 4 net, plus the terms of the blends' derivatives.
//! Parameters are clamped to [0,1]. \throw InputError if u and v differ in size or an
//! output span is shorter than u.
void evaluate_into(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v,
                   const PatchSampleSpans& out);

//! Convenient wrapper of evaluate_into that allocates the results.
PatchSamples evaluate(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v,
                      bool normals = true);

}  // namespace kiri::geometry
