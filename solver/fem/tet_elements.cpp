// Deformable bodies' reference data, lumped masses and the element critical time step (the element
// loop is internal_forces.cpp).
#include "solver/fem/tet_elements.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "solver/core/central_difference.hpp"
#include "solver/core/error.hpp"
#include "solver/fem/largest_eigenvalue.hpp"

namespace asperity::fem {

TetElements make_tet_elements(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets, double young,
                              double poisson, double density, double damping,
                              const std::string& what) {
  TetElements e;
  e.tets = tets;
  e.lame = lame_from(young, poisson);
  e.density = density;
  e.damping = damping;
  const int n = static_cast<int>(tets.cols());
  e.dm_inv.resize(9 * static_cast<std::size_t>(n));
  e.volume.resize(n);
  for (int k = 0; k < n; ++k) {
    const TetReference r =
        tet_reference(x.col(tets(0, k)), x.col(tets(1, k)), x.col(tets(2, k)), x.col(tets(3, k)));
    if (!(r.volume > 0)) {
      std::ostringstream s;
      s << what << ": element " << k << " has non-positive volume " << r.volume
        << " m^3 (nodes must be ordered so that ((b-a)x(c-a)).(d-a) > 0)";
      throw InputError(s.str());
    }
    Eigen::Map<Mat3>(&e.dm_inv[9 * static_cast<std::size_t>(k)]) = r.dm_inv;
    e.volume[k] = r.volume;
  }
  return e;
}

void add_lumped_mass(const TetElements& e, std::vector<double>& mass) {
  for (int k = 0; k < e.size(); ++k) {
    for (int a = 0; a < 4; ++a) mass[e.tets(a, k)] += 0.25 * e.density * e.volume[k];
  }
}

namespace {

// λ_max(M⁻¹K) with M = diag(m per node, 3 DOF each); a node with no mass must carry no stiffness
// (K ≥ 0 with a zero diagonal block has zero rows there), so its rows are dropped.
double split_eigenvalue(const Eigen::Matrix<double, 12, 12>& k, const double m[4]) {
  Eigen::Matrix<double, 12, 1> s;
  for (int i = 0; i < 12; ++i) s[i] = m[i / 3] > 0 ? 1.0 / std::sqrt(m[i / 3]) : 0.0;
  const Eigen::Matrix<double, 12, 12> a = s.asDiagonal() * k * s.asDiagonal();
  return largest_eigenvalue(a);
}

// The same λ_max for an element with no extra stiffness, in closed form. With S = M^-½ and
// H = Σ_a s_a u_a g_aᵀ (g_a = ∇N_a), uᵀ S K S u = V [λ tr(H)² + 2μ |sym H|²] and |u|² is the
// norm of H weighted by P⁻¹, P = Σ_a g_a g_aᵀ / m_a (3×3). In P's principal frame (the material
// is isotropic) the shear strains decouple, with eigenvalues V μ (p_i + p_j), and the normal
// strains give V N, N = 2μ diag(p) + λ √p √pᵀ, whose largest eigenvalue is above every shear one
// (the secular equation 1 = λ Σ p_i / (x − 2μ p_i) has its largest root x > 2μ max p_i). N's
// characteristic polynomial, from P's invariants I1 = tr P, I2 (sum of principal 2×2 minors),
// I3 = det P, with a = 2μ:
//   x³ − (a + λ) I1 x² + a (a + 2λ) I2 x − a² (a + 3λ) I3,
// three real roots ≥ 0, convex above the largest: Newton from their sum (an upper bound)
// descends monotonically onto it. The largest root is at least λ max p_i above the next (from the
// secular equation), so for λ ≥ μ/10 it is conditioned to about 10⁴ ε or better; equal to
// split_eigenvalue to round-off (tests/fem/test_element_step.cpp) at a few dozen flops instead of
// a 12×12 eigen-solve. Below λ = μ/10 (ν < 0.045) the caller takes split_eigenvalue.
double split_eigenvalue_isotropic(const double g[12], double volume, Lame lame, const double m[4]) {
  double p00 = 0, p11 = 0, p22 = 0, p01 = 0, p02 = 0, p12 = 0;
  for (int a = 0; a < 4; ++a) {
    if (!(m[a] > 0)) continue;  // a massless node carries no stiffness (split_eigenvalue)
    const double w = 1.0 / m[a], x = g[3 * a], y = g[3 * a + 1], z = g[3 * a + 2];
    p00 += w * x * x, p11 += w * y * y, p22 += w * z * z;
    p01 += w * x * y, p02 += w * x * z, p12 += w * y * z;
  }
  const double i1 = p00 + p11 + p22;
  const double i2 = p00 * p11 - p01 * p01 + p00 * p22 - p02 * p02 + p11 * p22 - p12 * p12;
  const double i3 =
      p00 * (p11 * p22 - p12 * p12) - p01 * (p01 * p22 - p12 * p02) + p02 * (p01 * p12 - p11 * p02);
  const double a = 2 * lame.mu, l = lame.lambda;
  const double c2 = (a + l) * i1, c1 = a * (a + 2 * l) * i2, c0 = a * a * (a + 3 * l) * i3;
  double x = c2;
  for (int it = 0; it < 100; ++it) {
    const double f = ((x - c2) * x + c1) * x - c0, df = (3 * x - 2 * c2) * x + c1;
    if (!(f > 0 && df > 0)) break;  // on the root (or below it by round-off)
    const double next = x - f / df;
    if (!(next < x)) break;  // no longer descending: round-off reached
    x = next;
  }
  return volume * x;
}

// Whether split_eigenvalue_isotropic is conditioned well enough for this material (λ ≥ μ/10).
bool closed_form_applies(Lame lame) {
  return lame.lambda >= 0.1 * lame.mu;
}

}  // namespace

ElementStep element_critical_step(const TetElements& e,
                                  const std::vector<ElementExtraStiffness>& extra,
                                  const std::vector<double>& added_mass) {
  ElementStep out;
  const int n = e.size();
  if (n == 0) return out;
  // Shape-function gradients g_a = ∇N_a (12 per element) for the closed form; an element with
  // extra stiffness keeps its assembled 12×12 matrix (the extra part is not of the form Bᵀ D B).
  std::vector<double> grad(12 * static_cast<std::size_t>(n));
  for (int t = 0; t < n; ++t) {
    const Eigen::Map<const Mat3> b(&e.dm_inv[9 * static_cast<std::size_t>(t)]);
    double* g = &grad[12 * static_cast<std::size_t>(t)];
    for (int r = 0; r < 3; ++r) {
      g[3 + r] = b(0, r), g[6 + r] = b(1, r), g[9 + r] = b(2, r);
      g[r] = -(b(0, r) + b(1, r) + b(2, r));
    }
  }
  std::vector<int> own(static_cast<std::size_t>(n), -1);  // index into k; -1: no extra
  std::vector<Eigen::Matrix<double, 12, 12>> k;
  for (const ElementExtraStiffness& x : extra) {
    int& i = own[static_cast<std::size_t>(x.element)];
    if (i < 0) {
      i = static_cast<int>(k.size());
      k.push_back(tet_stiffness(
          {.dm_inv = Eigen::Map<const Mat3>(&e.dm_inv[9 * static_cast<std::size_t>(x.element)]),
           .volume = e.volume[x.element]},
          e.lame));
    }
    k[static_cast<std::size_t>(i)] += x.k;
  }
  const bool closed_form = closed_form_applies(e.lame);
  const double trace_per_g2 = e.lame.lambda + 4 * e.lame.mu;  // tr K_aa = V (λ + 4μ) |g_a|²
  const auto eigenvalue = [&](int t, const double* m) {
    const int i = own[static_cast<std::size_t>(t)];
    if (i >= 0) return split_eigenvalue(k[static_cast<std::size_t>(i)], m);
    if (closed_form) {
      return split_eigenvalue_isotropic(&grad[12 * static_cast<std::size_t>(t)], e.volume[t],
                                        e.lame, m);
    }
    return split_eigenvalue(
        tet_stiffness({.dm_inv = Eigen::Map<const Mat3>(&e.dm_inv[9 * static_cast<std::size_t>(t)]),
                       .volume = e.volume[t]},
                      e.lame),
        m);
  };
  // Node masses and the diagonal stiffness sums, over the element's own node range.
  const int lo = e.tets.minCoeff(), hi = e.tets.maxCoeff();
  std::vector<double> node_mass(hi - lo + 1, 0.0), node_sum(hi - lo + 1, 0.0);
  std::vector<double> share(4 * static_cast<std::size_t>(n));  // m_ea, kg
  for (int t = 0; t < n; ++t) {
    const int i = own[static_cast<std::size_t>(t)];
    for (int a = 0; a < 4; ++a) {
      const int node = e.tets(a, t) - lo;
      node_mass[node] += 0.25 * e.density * e.volume[t];
      const double* g = &grad[12 * static_cast<std::size_t>(t) + 3 * a];
      share[4 * t + a] =
          i >= 0 ? k[static_cast<std::size_t>(i)].block<3, 3>(3 * a, 3 * a).trace()
                 : e.volume[t] * trace_per_g2 * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
      node_sum[node] += share[4 * t + a];
    }
  }
  if (!added_mass.empty()) {
    for (int i = lo; i <= hi; ++i) node_mass[i - lo] += added_mass[static_cast<std::size_t>(i)];
  }
  for (int t = 0; t < n; ++t) {
    for (int a = 0; a < 4; ++a) {
      const int i = e.tets(a, t) - lo;
      share[4 * t + a] = node_sum[i] > 0 ? node_mass[i] * share[4 * t + a] / node_sum[i] : 0.0;
    }
  }
  // Rebalancing passes (each split is a valid bound; keep the best), until a pass gains less than
  // 1 % in λ (0.5 % in ω) or after eight, which take the bound most of the way to its fixed point
  // on the meshes tested (tests/fem/test_element_step.cpp). Each pass costs one eigen-solve per
  // element (closed form, or a 12×12 solve where extra stiffness is added).
  constexpr int kPasses = 8;
  std::vector<double> lambda(n);
  double best = std::numeric_limits<double>::infinity();
  for (int pass = 0; pass <= kPasses; ++pass) {
    double worst = 0;
    int worst_element = -1;
    for (int t = 0; t < n; ++t) {
      lambda[t] = eigenvalue(t, &share[4 * static_cast<std::size_t>(t)]);
      if (lambda[t] > worst) worst = lambda[t], worst_element = t;
    }
    const bool gained = worst < 0.99 * best;
    if (worst < best) {
      best = worst;
      out.element = worst_element;
    }
    if (pass == kPasses || !gained) break;
    std::fill(node_sum.begin(), node_sum.end(), 0.0);
    for (int t = 0; t < n; ++t) {
      for (int a = 0; a < 4; ++a) {
        share[4 * t + a] *= std::sqrt(lambda[t]);
        node_sum[e.tets(a, t) - lo] += share[4 * t + a];
      }
    }
    for (int t = 0; t < n; ++t) {
      for (int a = 0; a < 4; ++a) {
        const int i = e.tets(a, t) - lo;
        share[4 * t + a] = node_sum[i] > 0 ? node_mass[i] * share[4 * t + a] / node_sum[i] : 0.0;
      }
    }
  }
  out.omega_max = std::sqrt(best);
  if (out.omega_max > 0) {
    out.dt = damped_critical_step(out.omega_max, 0.5 * e.damping * out.omega_max);
  }
  return out;
}

}  // namespace asperity::fem
