#pragma once
//! \file gregory_opensubdiv.hpp
//! An independent implementation of the same Gregory patch: OpenSubdiv's GREGORY_BASIS
//! patch basis ([OpenSubdiv]: same surface, its own point order, approximate derivatives; see
//! docs/references.md).
//! For tests (an oracle) and for `kiri bench` (a side-by-side rival); not a fast path.
#include <span>

#include "kiri/geometry/surface/gregory_patch.hpp"

namespace kiri::geometry {

//! OpenSubdiv's GREGORY_BASIS weights at (u, v), permuted into GregoryPatch's storage order.
//! Its derivative weights hold the rational blends constant: approximate.
void opensubdiv_gregory_weights(double u, double v, std::span<double, 20> w, std::span<double, 20> wu,
                                std::span<double, 20> wv);

//! The batch of evaluate_into(), computed point by point the way OpenSubdiv evaluates a patch
//! (PatchTable::EvaluateBasis's basis, then the weighted sum of the 20 points). Normals are
//! not computed. \throw InputError as evaluate_into().
void evaluate_into_opensubdiv(const GregoryPatch& patch, std::span<const double> u, std::span<const double> v,
                              const PatchSampleSpans& out);

}  // namespace kiri::geometry
