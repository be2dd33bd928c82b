#pragma once
// The box-constrained QP both line optimisers solve (min_curvature.hpp, min_time.hpp).
// Framework-free.
#include <Eigen/Sparse>

#include <vector>

namespace brickyard::planning {

// min ½ αᵀHα + gᵀα, lo ≤ α ≤ hi: the primal active-set method. From a feasible α, solve with
// the bound variables held; step toward that solution until the first free variable meets its
// bound (which joins the bound set); once the full step is feasible, release the bound variable
// whose gradient most wants it inside, or stop when none does. Each round factors the reduced
// (sparse, banded) system anew. Returns the rounds taken.
// bound (when not null): the bound set to start from (0 free, -1 at lower, +1 at upper; a guess,
// e.g. the last solve's: the method corrects it) and, on return, the final one.
int box_qp(const Eigen::SparseMatrix<double>& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
           Eigen::VectorXd& alpha, std::vector<int>* bound = nullptr);

}  // namespace brickyard::planning
