// The shared pieces of the finite-sphere references (finite_sphere_fe.hpp): mesh, element
// matrices and the contact complementarity solver.
#include "validation/reference/finite_sphere_fe.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace asperity::reference::detail {

namespace {

using Complex = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// The bipolar grid. With ζ = r + i(z + R) (the contact pole P at ζ = 0, the opposite pole T at
// ζ = 2iR), the inversion w = 1/ζ sends the sphere's circle |ζ − iR| = R to the line
// Im w = −1/(2R) and the axis to Re w = 0, so the meridian half-disc becomes the quadrant
// ω = w + i/(2R), Re ω ≥ 0, Im ω ≤ 0, and log ω the strip ℓ + iθ, θ ∈ [−π/2, 0]. A uniform
// grid in (ℓ, θ) is conformal: square cells whose size is (cell width in θ) × (distance to the
// nearer pole), the sphere's surface exactly the line θ = 0 and the axis θ = −π/2.
Complex zeta_of(double ell, double theta, double R) {
  const Complex omega = std::polar(std::exp(ell), theta);
  return 1.0 / (omega - Complex(0.0, 0.5 / R));
}

// A point of the sphere's circle (centre iR) at polar angle ψ about its centre; P is ψ = −π/2.
Complex on_circle(double psi, double R) {
  return Complex(0.0, R) + std::polar(R, psi);
}
double circle_angle(Complex zeta, double R) {
  return std::arg(zeta - Complex(0.0, R));
}

// 1D quadratic Lagrange on −1, 0, 1 and its derivative.
std::array<double, 3> lagrange(double x) {
  return {0.5 * x * (x - 1.0), 1.0 - x * x, 0.5 * x * (x + 1.0)};
}
std::array<double, 3> lagrange_derivative(double x) {
  return {x - 0.5, -2.0 * x, x + 0.5};
}

}  // namespace

double effective_modulus(double E, double nu) {
  return E / (1.0 - nu * nu);
}

void require(bool ok, const char* name, double value, const char* range) {
  if (!ok)
    throw std::invalid_argument(std::string("finite_sphere: ") + name + " = " +
                                std::to_string(value) + ", must be " + range);
}

Mesh make_mesh(const FiniteSphereMesh& spec, double R) {
  const int M = spec.angular_cells;
  const double dtheta = kPi / (2.0 * M);
  const double ell_max = std::log(1.0 / (spec.pole_fan * R));  // |ω| ≈ 1/|ζ| near P
  const double ell_min = std::log(spec.top_fan / (4.0 * R));  // |ω| ≈ |ζ − 2iR|/(4R²) near T
  const int L = static_cast<int>(std::ceil((ell_max - ell_min) / dtheta));
  const double dell = (ell_max - ell_min) / L;
  const int nj = 2 * M + 1, ni = 2 * L + 1;

  Mesh mesh;
  auto add = [&](Complex zeta) {
    mesh.r.push_back(std::max(0.0, zeta.real()));
    mesh.z.push_back(zeta.imag() - R);
    return static_cast<int>(mesh.r.size()) - 1;
  };
  for (int i = 0; i < ni; ++i) {
    for (int j = 0; j < nj; ++j) {
      Complex zeta = zeta_of(ell_min + 0.5 * i * dell, -0.5 * kPi + 0.5 * j * dtheta, R);
      if (j == 0) zeta = Complex(0.0, zeta.imag());  // on the axis exactly
      add(zeta);
    }
  }
  auto grid = [nj](int i, int j) { return i * nj + j; };

  // The fans: the last ring of cells at each pole collapsed onto the pole (a pie of M
  // quadratic sectors); their middle nodes halfway along the radius, on the circle at the
  // surface.
  auto fan = [&](int ring, Complex pole_zeta, double pole_psi) {
    std::vector<int> mid(nj);
    for (int j = 0; j < nj; ++j) {
      const Complex outer(mesh.r[grid(ring, j)], mesh.z[grid(ring, j)] + R);
      Complex m = 0.5 * (outer + pole_zeta);
      if (j == 0) m = Complex(0.0, m.imag());
      if (j == nj - 1) m = on_circle(0.5 * (circle_angle(outer, R) + pole_psi), R);
      mid[j] = add(m);
    }
    return mid;
  };
  const std::vector<int> top_mid = fan(0, Complex(0.0, 2.0 * R), 0.5 * kPi);
  const int top = add(Complex(0.0, 2.0 * R));
  const std::vector<int> pole_mid = fan(ni - 1, Complex(0.0, 0.0), -0.5 * kPi);
  mesh.pole = add(Complex(0.0, 0.0));

  for (int cj = 0; cj < M; ++cj) {
    std::array<int, 9> e{};
    for (int b = 0; b < 3; ++b) {
      e[b] = top;
      e[3 + b] = top_mid[2 * cj + b];
      e[6 + b] = grid(0, 2 * cj + b);
    }
    mesh.elements.push_back(e);
  }
  for (int ci = 0; ci < L; ++ci) {
    for (int cj = 0; cj < M; ++cj) {
      std::array<int, 9> e{};
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) e[3 * a + b] = grid(2 * ci + a, 2 * cj + b);
      mesh.elements.push_back(e);
    }
  }
  for (int cj = 0; cj < M; ++cj) {
    std::array<int, 9> e{};
    for (int b = 0; b < 3; ++b) {
      e[b] = grid(ni - 1, 2 * cj + b);
      e[3 + b] = pole_mid[2 * cj + b];
      e[6 + b] = mesh.pole;
    }
    mesh.elements.push_back(e);
  }

  // Surface nodes nearest P first: the pole fan's middle node, then the grid's θ = 0 line
  // from ℓ_max down.
  mesh.surface.push_back(pole_mid[nj - 1]);
  for (int i = ni - 1; i >= 0; --i) mesh.surface.push_back(grid(i, nj - 1));
  return mesh;
}

Assembly assemble(const Mesh& mesh, double E, double nu, bool pin_pole, bool with_mass) {
  const int n_nodes = static_cast<int>(mesh.r.size());
  Assembly out;
  out.eq.assign(2 * n_nodes, -1);
  for (int n = 0; n < n_nodes; ++n) {
    if (mesh.r[n] > 0.0) out.eq[2 * n] = out.n_eq++;
    if (!(pin_pole && n == mesh.pole)) out.eq[2 * n + 1] = out.n_eq++;
  }
  const std::vector<int>& eq = out.eq;

  // Axisymmetric small strain (ε_rr, ε_zz, ε_θθ, γ_rz), isotropic D, 3 × 3 Gauss points.
  const double c = E / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Eigen::Matrix4d Dm;
  Dm << 1 - nu, nu, nu, 0, nu, 1 - nu, nu, 0, nu, nu, 1 - nu, 0, 0, 0, 0, 0.5 * (1 - 2 * nu);
  Dm *= c;
  const double g = std::sqrt(0.6);
  const std::array<double, 3> gx{-g, 0.0, g}, gw{5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

  std::vector<Eigen::Triplet<double>> triplets, mass_triplets;
  out.body = Eigen::VectorXd::Zero(out.n_eq);
  std::vector<double> nodal_volume(n_nodes, 0.0);
  for (const auto& e : mesh.elements) {
    Eigen::Matrix<double, 18, 18> Ke = Eigen::Matrix<double, 18, 18>::Zero();
    Eigen::Matrix<double, 9, 9> Me = Eigen::Matrix<double, 9, 9>::Zero();
    std::array<double, 9> ve{};
    for (int p = 0; p < 3; ++p) {
      for (int q = 0; q < 3; ++q) {
        const auto La = lagrange(gx[p]), Lb = lagrange(gx[q]);
        const auto dLa = lagrange_derivative(gx[p]), dLb = lagrange_derivative(gx[q]);
        std::array<double, 9> N{}, Nx{}, Ny{};
        for (int a = 0; a < 3; ++a)
          for (int bb = 0; bb < 3; ++bb) {
            N[3 * a + bb] = La[a] * Lb[bb];
            Nx[3 * a + bb] = dLa[a] * Lb[bb];
            Ny[3 * a + bb] = La[a] * dLb[bb];
          }
        double r = 0, J11 = 0, J12 = 0, J21 = 0, J22 = 0;
        for (int k = 0; k < 9; ++k) {
          r += N[k] * mesh.r[e[k]];
          J11 += Nx[k] * mesh.r[e[k]];
          J12 += Nx[k] * mesh.z[e[k]];
          J21 += Ny[k] * mesh.r[e[k]];
          J22 += Ny[k] * mesh.z[e[k]];
        }
        const double det = J11 * J22 - J12 * J21;
        const double w = gw[p] * gw[q] * std::abs(det) * 2.0 * kPi * r;
        Eigen::Matrix<double, 4, 18> B = Eigen::Matrix<double, 4, 18>::Zero();
        for (int k = 0; k < 9; ++k) {
          const double dr = (J22 * Nx[k] - J12 * Ny[k]) / det;
          const double dz = (-J21 * Nx[k] + J11 * Ny[k]) / det;
          B(0, 2 * k) = dr;
          B(1, 2 * k + 1) = dz;
          B(2, 2 * k) = N[k] / r;
          B(3, 2 * k) = dz;
          B(3, 2 * k + 1) = dr;
          ve[k] += w * N[k];
        }
        Ke.noalias() += w * B.transpose() * Dm * B;
        if (with_mass) {
          // 3 × 3 Gauss integrates N_i N_j r exactly on an affine cell (degree 5 per direction)
          // and to fifth order on the curved ones: the consistent mass, not a lumped one.
          const Eigen::Map<const Eigen::Matrix<double, 9, 1>> Nv(N.data());
          Me.noalias() += w * Nv * Nv.transpose();
        }
        out.volume += w;
      }
    }
    for (int k = 0; k < 9; ++k) nodal_volume[e[k]] += ve[k];
    for (int a = 0; a < 18; ++a) {
      const int ia = eq[2 * e[a / 2] + a % 2];
      if (ia < 0) continue;
      for (int bcol = 0; bcol < 18; ++bcol) {
        const int ib = eq[2 * e[bcol / 2] + bcol % 2];
        if (ib >= 0) triplets.emplace_back(ia, ib, Ke(a, bcol));
        // The same mass for both components, none between them.
        if (with_mass && ib >= 0 && a % 2 == bcol % 2)
          mass_triplets.emplace_back(ia, ib, Me(a / 2, bcol / 2));
      }
    }
  }
  for (int n = 0; n < n_nodes; ++n)
    if (eq[2 * n + 1] >= 0) out.body[eq[2 * n + 1]] += nodal_volume[n];

  out.K.resize(out.n_eq, out.n_eq);
  out.K.setFromTriplets(triplets.begin(), triplets.end());
  if (with_mass) {
    out.mass.resize(out.n_eq, out.n_eq);
    out.mass.setFromTriplets(mass_triplets.begin(), mass_triplets.end());
  }
  return out;
}

std::vector<int> contact_candidates(const Mesh& mesh, double reach, bool with_pole) {
  std::vector<int> cand;
  if (with_pole) cand.push_back(mesh.pole);
  for (int n : mesh.surface) {
    if (mesh.r[n] > reach) break;
    cand.push_back(n);
  }
  return cand;
}

// D is symmetric positive definite, so this is the complementarity problem of a convex QP with a
// unique solution. Solved by a primal–dual active set (Hintermüller, Ito & Kunisch 2002, SIAM J.
// Optim. 13: A = {k : R_k − w_k/D_kk > 0}), which settles in a few solves from the free gaps;
// should it cycle, Murty's least-index principal pivoting (one flip at a time, finite for a
// P-matrix; Murty 1974) ends it.
Complementarity solve_complementarity(const Eigen::MatrixXd& D, const Eigen::VectorXd& q,
                                      std::vector<char>& active) {
  const int nc = static_cast<int>(q.size());
  if (static_cast<int>(active.size()) != nc) {
    active.assign(nc, 0);
    for (int k = 0; k < nc; ++k) active[k] = q[k] < 0.0;
  }
  Eigen::VectorXd R = Eigen::VectorXd::Zero(nc), w = q;
  auto solve_on = [&] {
    std::vector<int> A;
    for (int k = 0; k < nc; ++k)
      if (active[k]) A.push_back(k);
    R.setZero();
    if (!A.empty()) {
      const int na = static_cast<int>(A.size());
      Eigen::MatrixXd DAA(na, na);
      Eigen::VectorXd rhs(na);
      for (int i = 0; i < na; ++i) {
        rhs[i] = -q[A[i]];
        for (int j = 0; j < na; ++j) DAA(i, j) = D(A[i], A[j]);
      }
      const Eigen::VectorXd RA = DAA.llt().solve(rhs);
      for (int i = 0; i < na; ++i) R[A[i]] = RA[i];
    }
    w = q + D * R;
    for (int k = 0; k < nc; ++k)
      if (active[k]) w[k] = 0.0;
  };
  // Violations below this are round-off (m): 1e-13 of the largest free gap.
  const double tol = 1e-13 * q.cwiseAbs().maxCoeff();
  bool settled = false;
  for (int iteration = 0; iteration < 30 && !settled; ++iteration) {
    solve_on();
    settled = true;
    for (int k = 0; k < nc; ++k) {
      const bool next = active[k] ? R[k] >= 0.0 : w[k] < -tol;
      settled = settled && next == static_cast<bool>(active[k]);
      active[k] = next;
    }
  }
  for (int iteration = 0; !settled; ++iteration) {
    if (iteration > 20 * nc)
      throw std::runtime_error("finite_sphere: the contact active set did not settle");
    solve_on();
    settled = true;
    for (int k = 0; k < nc && settled; ++k) {
      if ((active[k] && R[k] < 0.0) || (!active[k] && w[k] < -tol)) {
        active[k] = !active[k];
        settled = false;
      }
    }
  }
  return {R, w};
}

}  // namespace asperity::reference::detail
