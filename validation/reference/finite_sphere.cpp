// The finite-sphere reference (finite_sphere.hpp): mesh, assembly, contact and impact.
#include "validation/reference/finite_sphere.hpp"

#include "validation/reference/finite_sphere_fe.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <memory>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace asperity::reference {

using detail::effective_modulus;
using detail::Mesh;
using detail::require;

namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

double hertz_force(const FiniteSphereMaterial& material, double approach) {
  const double Es = effective_modulus(material.youngs_modulus, material.poisson_ratio);
  return 4.0 / 3.0 * Es * std::sqrt(material.radius) * std::pow(std::max(0.0, approach), 1.5);
}

struct FiniteSphere::Impl {
  FiniteSphereMaterial material;
  int angular_cells = 0;
  Mesh mesh;
  double volume = 0;
  // The contact candidates (surface nodes within 0.35 R of the axis, nearest first), their
  // initial gaps g = z + R, and their compliance with P pinned: D(j, k) = u_z at j under a unit
  // upward force at k, b(j) = u_z at j under the unit downward body force (total 1 N), and the
  // mass-averaged axial displacement under each: gamma(k), beta.
  std::vector<double> cand_r, gap;
  Eigen::MatrixXd D;
  Eigen::VectorXd b, gamma;
  double beta = 0;

  void build(const FiniteSphereMesh& spec);
  // `active` is the starting guess (empty: from the free gaps) and returns the contact set; a
  // neighbouring state's set makes the active set settle in one or two solves.
  FiniteSphereState solve(double force, std::vector<char>& active) const;
};

void FiniteSphere::Impl::build(const FiniteSphereMesh& spec) {
  const double R = material.radius;
  mesh = detail::make_mesh(spec, R);
  // u_z = 0 at P (the rigid translation: P is always in contact, so the pinned frame is the
  // plane's).
  const detail::Assembly fe =
      detail::assemble(mesh, material.youngs_modulus, material.poisson_ratio, /*pin_pole=*/true,
                       /*with_mass=*/false);
  volume = fe.volume;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(fe.K);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("finite_sphere: the stiffness is not positive definite");

  const std::vector<int> cand = detail::contact_candidates(mesh, 0.35 * R, /*with_pole=*/false);
  for (int n : cand) {
    cand_r.push_back(mesh.r[n]);
    gap.push_back(mesh.z[n] + R);
  }
  const int nc = static_cast<int>(cand.size());
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(fe.n_eq, nc + 1);
  for (int k = 0; k < nc; ++k) rhs(fe.eq[2 * cand[k] + 1], k) = 1.0;
  rhs.col(nc) = -fe.body / volume;  // a unit downward body force, uniform per volume
  const Eigen::MatrixXd u = llt.solve(rhs);
  D.resize(nc, nc);
  b.resize(nc);
  for (int j = 0; j < nc; ++j) {
    const int row = fe.eq[2 * cand[j] + 1];
    D.row(j) = u.row(row).head(nc);
    b[j] = u(row, nc);
  }
  D = 0.5 * (D + D.transpose()).eval();  // symmetric by reciprocity; remove the round-off
  gamma = (fe.body.transpose() * u.leftCols(nc)).transpose() / volume;
  beta = fe.body.dot(u.col(nc)) / volume;
}

// Unilateral contact at a given total force W: reactions R_k ≥ 0 on the candidates, gaps
// w = g + W b + D R ≥ 0, R·w = 0; P takes the rest, W − Σ R_k (detail::solve_complementarity).
FiniteSphereState FiniteSphere::Impl::solve(double force, std::vector<char>& active) const {
  const int nc = static_cast<int>(gap.size());
  const Eigen::Map<const Eigen::VectorXd> g0(gap.data(), nc);
  const Eigen::VectorXd free_gap = g0 + force * b;
  const detail::Complementarity c = detail::solve_complementarity(D, free_gap, active);
  const Eigen::VectorXd& R = c.reaction;
  const Eigen::VectorXd& w = c.gap;

  FiniteSphereState state;
  state.force = force;
  state.approach = -(force * beta + gamma.dot(R));
  // The pole carries the rest, W − Σ R_k; the pinned frame is the plane's only while that is
  // a compression (round-off allowed).
  if (force - R.sum() < -1e-9 * force)
    throw std::runtime_error("finite_sphere: the pole's reaction is tensile");
  int last = -1;
  for (int k = 0; k < nc; ++k)
    if (active[k]) last = k;
  if (last + 2 >= nc)
    throw std::runtime_error("finite_sphere: the contact reaches the last candidate (a/R > 0.3)");
  state.contact_nodes = last + 2;  // the candidates in contact and P
  // a between the last node in contact and the next: outside a Hertz-like contact the gap grows
  // as (r − a)^{3/2}, so w^{2/3} is linear in r; extrapolate it from the next two nodes.
  const double r0 = last >= 0 ? cand_r[last] : 0.0;
  const double r1 = cand_r[last + 1], r2 = cand_r[last + 2];
  const double w1 = std::cbrt(std::max(0.0, w[last + 1]) * std::max(0.0, w[last + 1]));
  const double w2 = std::cbrt(std::max(0.0, w[last + 2]) * std::max(0.0, w[last + 2]));
  double a = r1;
  if (w2 > w1) a = r1 - w1 * (r2 - r1) / (w2 - w1);
  state.contact_radius = std::clamp(a, r0, r1);
  return state;
}

FiniteSphere::FiniteSphere(const FiniteSphereMaterial& material, const FiniteSphereMesh& mesh)
    : impl_(nullptr) {
  require(material.youngs_modulus > 0.0, "youngs_modulus", material.youngs_modulus, "> 0");
  require(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5, "poisson_ratio",
          material.poisson_ratio, "in (-1, 0.5)");
  require(material.radius > 0.0, "radius", material.radius, "> 0");
  require(mesh.angular_cells >= 2 && mesh.angular_cells <= 256, "angular_cells", mesh.angular_cells,
          "in [2, 256]");
  require(mesh.pole_fan > 0.0 && mesh.pole_fan < 1e-2, "pole_fan", mesh.pole_fan,
          "in (0, 0.01) (it must be far inside the smallest contact)");
  require(mesh.top_fan > 0.0 && mesh.top_fan < 0.5, "top_fan", mesh.top_fan, "in (0, 0.5)");
  auto impl = std::make_unique<Impl>();
  impl->material = material;
  impl->angular_cells = mesh.angular_cells;
  impl->build(mesh);
  impl_ = impl.release();
}
FiniteSphere::~FiniteSphere() {
  delete impl_;
}
FiniteSphere::FiniteSphere(FiniteSphere&& other) noexcept : impl_(other.impl_) {
  other.impl_ = nullptr;
}
FiniteSphere& FiniteSphere::operator=(FiniteSphere&& other) noexcept {
  std::swap(impl_, other.impl_);
  return *this;
}

FiniteSphereState FiniteSphere::at_force(double force) const {
  std::vector<char> active;
  return impl_->solve(force, active);
}

std::vector<FiniteSphereState> FiniteSphere::at_forces(const std::vector<double>& forces) const {
  std::vector<char> active;
  std::vector<FiniteSphereState> states;
  for (double f : forces) states.push_back(impl_->solve(f, active));
  return states;
}

FiniteSphereState FiniteSphere::at_approach(double approach) const {
  // δ(F) is close to F^{2/3}, so F ← F (δ/δ(F))^{3/2} contracts by |1 − (3/2) dlnδ/dlnF|, a few
  // per cent: 1e-13 in δ within ten solves from Hertz's force.
  double force = hertz_force(impl_->material, approach);
  std::vector<char> active;
  FiniteSphereState state = impl_->solve(force, active);
  for (int i = 0; i < 40 && std::abs(state.approach / approach - 1.0) > 1e-13; ++i) {
    force *= std::pow(approach / state.approach, 1.5);
    state = impl_->solve(force, active);
  }
  return state;
}

FiniteSphere::AveragedRatio FiniteSphere::averaged_force_ratio(double s) const {
  constexpr int kStates = 16;
  const double period = std::numbers::pi / (2.0 * impl_->angular_cells);
  const double R = impl_->material.radius;
  Eigen::MatrixXd A(kStates, 2);
  Eigen::VectorXd y(kStates);
  for (int k = 0; k < kStates; ++k) {
    const double x = ((k + 0.5) / kStates - 0.5) * period;
    const double sk = s * std::exp(x);
    const FiniteSphereState st = at_approach(sk * sk * R);
    A(k, 0) = 1.0;
    A(k, 1) = x;
    y[k] = st.force / hertz_force(impl_->material, st.approach);
  }
  const Eigen::Vector2d line = A.colPivHouseholderQr().solve(y);
  const Eigen::VectorXd residual = y - A * line;
  return {.ratio = line[0], .oscillation = residual.maxCoeff() - residual.minCoeff()};
}

double FiniteSphere::volume() const {
  return impl_->volume;
}
const FiniteSphereMaterial& FiniteSphere::material() const {
  return impl_->material;
}
int FiniteSphere::angular_cells() const {
  return impl_->angular_cells;
}
int FiniteSphere::nodes() const {
  return static_cast<int>(impl_->mesh.r.size());
}
int FiniteSphere::elements() const {
  return static_cast<int>(impl_->mesh.elements.size());
}

FiniteSphereLaw fit_finite_sphere_law(double poisson_ratio, const FiniteSphereMesh& mesh,
                                      double s_max) {
  const FiniteSphereMaterial unit{
      .youngs_modulus = 1.0, .poisson_ratio = poisson_ratio, .radius = 1.0};
  return fit_finite_sphere_law(FiniteSphere(unit, mesh), s_max);
}

FiniteSphereLaw fit_finite_sphere_law(const FiniteSphere& sphere, double s_max) {
  const FiniteSphereMaterial& material = sphere.material();
  const double R = material.radius;
  // Nodal contact on a self-similar mesh: g_FE oscillates about the smooth law with the period
  // of the surface nodes in ln a, π/(2 M) (the bipolar cells), by about ±0.1 % at M = 16. States
  // eight to a period, evenly in ln s from s = 0.02 s_max to s_max (s = √(δ/R)), sample every
  // phase alike, so the least-squares fit averages the oscillation out.
  constexpr int kTerms = 5;
  const double step = std::numbers::pi / (16.0 * sphere.angular_cells());
  const int n_states = static_cast<int>(std::ceil(std::log(50.0) / step)) + 1;
  Eigen::MatrixXd A(n_states, kTerms);
  Eigen::VectorXd y(n_states);
  std::vector<double> forces;
  for (int i = 0; i < n_states; ++i) {
    const double s_target = s_max * std::exp(-std::log(50.0) * i / (n_states - 1.0));
    forces.push_back(hertz_force(material, s_target * s_target * R));
  }
  const std::vector<FiniteSphereState> states = sphere.at_forces(forces);
  for (int i = 0; i < n_states; ++i) {
    const FiniteSphereState& st = states[i];
    const double s = std::sqrt(st.approach / R);
    y[i] = st.force / hertz_force(material, st.approach);
    A.row(i) << 1.0, s, s * std::log(s), s * s, s * s * s;
  }
  const Eigen::VectorXd coef = A.colPivHouseholderQr().solve(y);
  FiniteSphereLaw law;
  law.poisson_ratio = material.poisson_ratio;
  law.coefficients.assign(coef.data(), coef.data() + coef.size());
  law.s_max = s_max;
  law.fit_residual = (A * coef - y).cwiseAbs().maxCoeff();
  return law;
}

double evaluate(const FiniteSphereLaw& law, double s) {
  const auto& c = law.coefficients;
  if (s <= 0.0) return c[0];
  return c[0] + s * (c[1] + c[2] * std::log(s) + s * (c[3] + s * c[4]));
}

namespace {

// Gauss–Legendre nodes and weights on [0, 1] (Golub–Welsch: the Jacobi matrix's eigenvalues).
std::pair<Eigen::VectorXd, Eigen::VectorXd> gauss_legendre(int n) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) J(k, k - 1) = J(k - 1, k) = k / std::sqrt(4.0 * k * k - 1.0);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(J);
  Eigen::VectorXd x = 0.5 * (es.eigenvalues().array() + 1.0);
  Eigen::VectorXd w = es.eigenvectors().row(0).transpose().array().square();
  return {x, w};
}

}  // namespace

// With F(δ) = k δ^{3/2} g(√(δ/R)), k = (4/3) E* √R: the stored energy U(δ) = ∫_0^δ F is taken
// with δ' = δ t² (an integrand smooth in t); the deepest approach solves U(δ_m) = ½ m v² (Newton
// from Hertz's); the duration T = 2 ∫_0^{δ_m} dδ / √((2/m)(U(δ_m) − U(δ))) is taken with
// δ = δ_m (1 − τ²), which removes the square-root singularity at δ_m. Gauss–Legendre, 48 and 96
// points: g ≡ 1 gives Hertz's 2 (2/5) B(2/5, 1/2) δ_m/v = 2.9432 δ_m/v to 1e-8 (tested).
FiniteSphereImpact impact_from_law(const FiniteSphereLaw& law, double E, double mass, double R,
                                   double v) {
  require(E > 0.0, "E", E, "> 0");
  require(mass > 0.0, "mass", mass, "> 0");
  require(R > 0.0, "R", R, "> 0");
  require(v > 0.0, "v", v, "> 0");
  require(law.coefficients.size() == 5, "the law's coefficients",
          static_cast<double>(law.coefficients.size()), "5 of them");
  const double k = 4.0 / 3.0 * effective_modulus(E, law.poisson_ratio) * std::sqrt(R);
  auto force = [&](double d) { return k * std::pow(d, 1.5) * evaluate(law, std::sqrt(d / R)); };
  static const auto rule48 = gauss_legendre(48);
  static const auto rule96 = gauss_legendre(96);
  auto energy = [&](double d) {
    const auto& [x, w] = rule48;
    double U = 0;
    for (int i = 0; i < x.size(); ++i) U += w[i] * 2.0 * d * x[i] * force(d * x[i] * x[i]);
    return U;
  };
  const double kinetic = 0.5 * mass * v * v;

  FiniteSphereImpact out;
  out.hertz_max_approach = std::pow(kinetic / (0.4 * k), 0.4);
  out.hertz_peak_force = k * std::pow(out.hertz_max_approach, 1.5);
  out.hertz_duration = 2.0 * 0.4 * std::beta(0.4, 0.5) * out.hertz_max_approach / v;

  double d = out.hertz_max_approach;
  for (int i = 0; i < 60; ++i) {
    const double step = (energy(d) - kinetic) / force(d);
    d -= step;
    if (std::abs(step) < 1e-14 * d) break;
  }
  if (!(d > 0.0) || std::sqrt(d / R) > law.s_max)
    throw std::invalid_argument("finite_sphere_impact: the deepest approach sqrt(delta/R) = " +
                                std::to_string(std::sqrt(std::abs(d) / R)) +
                                " is beyond the fitted law's range " + std::to_string(law.s_max));
  out.max_approach = d;
  out.peak_force = force(d);

  const auto& [x, w] = rule96;
  const double Um = energy(d);
  double T = 0;
  for (int i = 0; i < x.size(); ++i) {
    const double tau = x[i];
    T += w[i] * 2.0 * d * tau / std::sqrt(2.0 / mass * (Um - energy(d * (1.0 - tau * tau))));
  }
  out.duration = 2.0 * T;
  return out;
}

FiniteSphereImpact finite_sphere_impact_with_mass(double E, double nu, double mass, double R,
                                                  double v) {
  // Checked before the law is fitted (a second of CPU for nothing otherwise).
  require(E > 0.0, "E", E, "> 0");
  require(nu > -1.0 && nu < 0.5, "nu", nu, "in (-1, 0.5)");
  require(mass > 0.0, "mass", mass, "> 0");
  require(R > 0.0, "R", R, "> 0");
  require(v > 0.0, "v", v, "> 0");
  static std::mutex guard;
  static std::map<double, FiniteSphereLaw> laws;
  FiniteSphereLaw law;
  {
    const std::lock_guard lock(guard);
    auto it = laws.find(nu);
    if (it == laws.end()) it = laws.emplace(nu, fit_finite_sphere_law(nu, {})).first;
    law = it->second;
  }
  return impact_from_law(law, E, mass, R, v);
}

FiniteSphereImpact finite_sphere_impact(double E, double nu, double rho, double R, double v) {
  require(rho > 0.0, "rho", rho, "> 0");
  return finite_sphere_impact_with_mass(E, nu, 4.0 / 3.0 * kPi * R * R * R * rho, R, v);
}

FiniteSphereImpact finite_sphere_head_on(double E, double nu, double rho, double R,
                                         double relative_speed) {
  return finite_sphere_impact(E, nu, rho, R, 0.5 * relative_speed);
}

}  // namespace asperity::reference
