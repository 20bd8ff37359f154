#pragma once
// Internal: the fit's least-squares solve. The normal matrix's sparsity is fixed by the
// topology: its pattern and the slot of every face-local entry are built once; each solve
// only scatters values and refactorises.
#include <vector>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "fog/fit_steps.hpp"

namespace kiri::geometry {

class FitSolver {
public:
    //! vertex_target: what a faint pull on each control height aims at (vertex_targets()).
    FitSolver(const FitLayout& layout, std::vector<double> vertex_target);
    //! The control heights minimising the faces' energies plus the pull.
    //! \throw InputError when the system is singular.
    std::vector<double> solve(const std::vector<FaceSystem>& faces);
    //! Solves so far (FitReport::iterations).
    int solves() const { return solves_; }

private:
    const FitLayout& layout_;
    std::vector<double> vertex_target_;
    Eigen::SparseMatrix<double> normal_;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> cholesky_;
    std::vector<std::vector<int>> face_slot_;  // per face, the value index of each (row, column) of its support
    std::vector<int> diagonal_slot_;
    int solves_ = 0;
};

}  // namespace kiri::geometry
