// The pieces both finite-sphere references share (internal to validation/reference): the bipolar
// mesh of the meridian half-disc, the axisymmetric 9-node element matrices, and the small
// unilateral-contact (linear complementarity) solver on the contact candidates. The quasi-static
// model (finite_sphere.cpp) and the dynamic one (finite_sphere_dynamic.cpp) differ only in what
// they do with these: a body force and a pinned pole, or a mass matrix and Newmark steps.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <array>
#include <vector>

#include "validation/reference/finite_sphere.hpp"

namespace asperity::reference::detail {

// The library's callers are tests and gates: a bad argument is a programming error, named.
void require(bool ok, const char* name, double value, const char* range);

double effective_modulus(double E, double nu);

struct Mesh {
  std::vector<double> r, z;                  // node coordinates (z = 0 at the centre)
  std::vector<std::array<int, 9>> elements;  // tensor order: node (a, b) at 3a + b
  std::vector<int> surface;                  // surface nodes, by distance from P, P excluded
  int pole = -1;                             // P, the contact pole (z = −R)
};

// The bipolar (conformal) grid of finite_sphere.hpp's FiniteSphereMesh, fans at both poles.
Mesh make_mesh(const FiniteSphereMesh& spec, double R);

// The assembled axisymmetric model (small strain, isotropic, 3 × 3 Gauss points per element).
// Degrees of freedom (u_r, u_z) per node, u_r = 0 on the axis; eq[2n + c] is node n's equation
// for component c, −1 where fixed.
struct Assembly {
  std::vector<int> eq;
  int n_eq = 0;
  Eigen::SparseMatrix<double> K;     // stiffness (N/m)
  Eigen::SparseMatrix<double> mass;  // consistent mass per unit density, ∫ N_i N_j dV (m³)
  Eigen::VectorXd body;              // ∫ N_i dV on each u_z equation (m³)
  double volume = 0;                 // of the meshed half-disc revolved (m³)
};
// `pin_pole`: the pole's u_z fixed (the quasi-static model's rigid translation); `with_mass`:
// assemble the consistent mass too.
Assembly assemble(const Mesh& mesh, double E, double nu, bool pin_pole, bool with_mass);

// The candidates for contact: surface nodes within `reach` of the axis, nearest the pole first
// (the pole itself first when `with_pole`).
std::vector<int> contact_candidates(const Mesh& mesh, double reach, bool with_pole);

// Unilateral frictionless contact on the candidates: reactions R ≥ 0, gaps w = q + D R ≥ 0,
// R·w = 0, D symmetric positive definite (the candidates' compliance). `active` is the starting
// guess (empty: from the sign of q) and returns the contact set. Throws if it does not settle.
struct Complementarity {
  Eigen::VectorXd reaction, gap;
};
Complementarity solve_complementarity(const Eigen::MatrixXd& D, const Eigen::VectorXd& q,
                                      std::vector<char>& active);

}  // namespace asperity::reference::detail
