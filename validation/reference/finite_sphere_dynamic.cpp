// The dynamic finite-sphere reference (finite_sphere_dynamic.hpp): Newmark steps with nodal
// unilateral contact condensed onto the candidates.
#include "validation/reference/finite_sphere_dynamic.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "solver/run/impact_measures.hpp"
#include "validation/reference/finite_sphere_fe.hpp"

namespace asperity::reference {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kReach = 0.35;  // contact candidates within 0.35 R of the axis (a/R ≤ 0.3)

struct HertzImpact {
  double peak, duration, approach;
};
// Johnson (1985) §11.4: ½ m v² = (8/15) E* √R δ_m^{5/2}, F = (4/3) E* √R δ_m^{3/2},
// T = 2 (2/5) B(2/5, 1/2) δ_m / v.
HertzImpact hertz_impact(const FiniteSphereMaterial& m, double mass, double v) {
  const double k = 4.0 / 3.0 * detail::effective_modulus(m.youngs_modulus, m.poisson_ratio) *
                   std::sqrt(m.radius);
  const double d = std::pow(0.5 * mass * v * v / (0.4 * k), 0.4);
  return {k * std::pow(d, 1.5), 2.0 * 0.4 * std::beta(0.4, 0.5) * d / v, d};
}

void check(const FiniteSphereMaterial& m, double mass, double v) {
  detail::require(m.youngs_modulus > 0.0, "E", m.youngs_modulus, "> 0");
  detail::require(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5, "nu", m.poisson_ratio,
                  "in (-1, 0.5)");
  detail::require(m.radius > 0.0, "R", m.radius, "> 0");
  detail::require(mass > 0.0, "mass", mass, "> 0");
  detail::require(v > 0.0, "v", v, "> 0");
}

}  // namespace

// Newmark average acceleration (β = 1/4, γ = 1/2) on M a + K u = Pᵀ R:
//   u_{n+1} = u_n + dt v_n + (dt²/4)(a_n + a_{n+1}),  v_{n+1} = v_n + (dt/2)(a_n + a_{n+1}),
// so (K + c0 M) u_{n+1} = M (c0 u_n + c1 v_n + a_n) + Pᵀ R_{n+1}, c0 = 4/dt², c1 = 4/dt. With
// u* the solution for R = 0 and U = K_eff⁻¹ Pᵀ, the candidates' gaps at the end of the step are
// w = g0 + P u* + D R, D = P U: the complementarity problem of the quasi-static model, with the
// predicted gaps in place of the body force's.
FiniteSphereDynamicImpact simulate_finite_sphere_impact(const FiniteSphereMaterial& material,
                                                        double mass, double v,
                                                        const FiniteSphereDynamicDef& def) {
  check(material, mass, v);
  detail::require(def.steps_per_hertz_duration >= 20, "steps_per_hertz_duration",
                  def.steps_per_hertz_duration, ">= 20");
  const double R = material.radius;
  const detail::Mesh mesh = detail::make_mesh(def.mesh, R);
  const detail::Assembly fe =
      detail::assemble(mesh, material.youngs_modulus, material.poisson_ratio, /*pin_pole=*/false,
                       /*with_mass=*/true);
  const double rho = mass / fe.volume;
  const HertzImpact hz = hertz_impact(material, mass, v);

  FiniteSphereDynamicImpact out;
  out.mass = mass;
  out.hertz_peak_force = hz.peak;
  out.hertz_duration = hz.duration;
  out.hertz_max_approach = hz.approach;
  out.dt = hz.duration / def.steps_per_hertz_duration;
  const double dt = out.dt, c0 = 4.0 / (dt * dt), c1 = 4.0 / dt;

  const Eigen::SparseMatrix<double> M = rho * fe.mass;
  const Eigen::SparseMatrix<double> K_eff = fe.K + c0 * M;
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(K_eff);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("finite_sphere_dynamic: K + 4M/dt² is not positive definite");

  const std::vector<int> cand = detail::contact_candidates(mesh, kReach * R, /*with_pole=*/true);
  const int nc = static_cast<int>(cand.size());
  std::vector<int> row(nc);
  Eigen::VectorXd g0(nc);
  Eigen::MatrixXd unit = Eigen::MatrixXd::Zero(fe.n_eq, nc);
  for (int k = 0; k < nc; ++k) {
    row[k] = fe.eq[2 * cand[k] + 1];
    g0[k] = mesh.z[cand[k]] + R;  // the plane is z = −R; the pole touches it
    unit(row[k], k) = 1.0;
  }
  const Eigen::MatrixXd U = llt.solve(unit);
  Eigen::MatrixXd D(nc, nc);
  for (int j = 0; j < nc; ++j) D.row(j) = U.row(row[j]);
  D = 0.5 * (D + D.transpose()).eval();  // symmetric by reciprocity; remove the round-off

  // The axial translation t (1 on every u_z): M t = ρ × body, tᵀ M t = m. Mass-averaged axial
  // displacement and velocity are body·u_z / V.
  Eigen::VectorXd axial = Eigen::VectorXd::Zero(fe.n_eq);
  const int n_nodes = static_cast<int>(mesh.r.size());
  for (int n = 0; n < n_nodes; ++n) axial[fe.eq[2 * n + 1]] = 1.0;
  const Eigen::VectorXd weight = fe.body / fe.volume;

  Eigen::VectorXd u = Eigen::VectorXd::Zero(fe.n_eq), vel = -v * axial;
  Eigen::VectorXd acc = Eigen::VectorXd::Zero(fe.n_eq);
  const double energy0 = 0.5 * vel.dot(M * vel);
  std::vector<char> active;
  Eigen::VectorXd reaction = Eigen::VectorXd::Zero(nc);  // the previous step's
  std::vector<double> time{0.0}, force{0.0};
  const long max_steps = static_cast<long>(3.0 * def.steps_per_hertz_duration);
  long last_contact = -1;
  bool touching = false;
  for (long n = 1;; ++n) {
    if (n > max_steps)
      throw std::runtime_error("finite_sphere_dynamic: the contact did not end within 3 T_Hertz");
    const Eigen::VectorXd u_pred = llt.solve(M * (c0 * u + c1 * vel + acc));
    Eigen::VectorXd q(nc);
    for (int k = 0; k < nc; ++k) q[k] = g0[k] + u_pred[row[k]];
    const detail::Complementarity c = detail::solve_complementarity(D, q, active);
    if (active.back())
      throw std::runtime_error(
          "finite_sphere_dynamic: the contact reaches the last candidate (a/R > 0.3)");
    Eigen::VectorXd u_next = u_pred;
    for (int k = 0; k < nc; ++k)
      if (c.reaction[k] != 0.0) u_next += c.reaction[k] * U.col(k);
    // The work of the contact forces over the step, trapezoidal as the scheme's energy identity
    // has it: E_{n+1} − E_n = ½ (f_n + f_{n+1})·(u_{n+1} − u_n) exactly for linear M and K.
    Eigen::VectorXd du(nc);
    for (int k = 0; k < nc; ++k) du[k] = u_next[row[k]] - u[row[k]];
    out.contact_work += 0.5 * (reaction.dot(du) + c.reaction.dot(du));
    const Eigen::VectorXd acc_next = c0 * (u_next - u) - c1 * vel - acc;
    vel += 0.5 * dt * (acc + acc_next);
    u = u_next;
    acc = acc_next;

    reaction = c.reaction;
    const double F = c.reaction.sum();
    time.push_back(static_cast<double>(n) * dt);
    force.push_back(F);
    out.max_approach = std::max(out.max_approach, -weight.dot(u));
    const double energy = 0.5 * vel.dot(M * vel) + 0.5 * u.dot(fe.K * u);
    out.energy_excursion = std::max(out.energy_excursion, std::abs(energy / energy0 - 1.0));
    if (F > 0.0) {
      if (!touching) ++out.contact_intervals;
      touching = true;
      last_contact = n;
    } else {
      touching = false;
    }
    if (last_contact > 0 && !touching &&
        static_cast<double>(n - last_contact) * dt >= 0.25 * hz.duration) {
      out.steps = n;
      out.energy_ratio = energy / energy0;
      out.contact_work /= energy0;
      out.rebound_ratio = weight.dot(vel) / v;
      break;
    }
  }
  if (last_contact < 2) throw std::runtime_error("finite_sphere_dynamic: no contact");

  // Contact from t = 0 to the end of the last step with a force, interpolated: near its end
  // Hertz's force falls as (T − t)^{3/2}, so F^{2/3} is linear in t there. A least-squares line
  // through the steps of the last 2 % of T_Hertz with a force (at least 8; 20 at the default
  // step), which averages out the scheme's period-2 oscillation, gives the zero. Measured spread
  // between 1000 and 2000 steps per T_Hertz: 6e-5 of the duration.
  const auto L = static_cast<std::size_t>(last_contact);
  {
    const auto window = std::max<std::size_t>(
        8, static_cast<std::size_t>(std::lround(0.02 * def.steps_per_hertz_duration)));
    const std::size_t first = L > window ? L + 1 - window : 1;
    double st = 0, sf = 0, stt = 0, stf = 0;
    const auto n_fit = static_cast<double>(L + 1 - first);
    for (std::size_t i = first; i <= L; ++i) {
      const double f = std::cbrt(force[i] * force[i]);
      st += time[i];
      sf += f;
      stt += time[i] * time[i];
      stf += time[i] * f;
    }
    const double slope = (n_fit * stf - st * sf) / (n_fit * stt - st * st);
    const double end = slope < 0.0 ? (st * slope - sf) / (n_fit * slope) : time[L] + dt;
    out.duration = std::clamp(end, time[first], time[L] + dt);
  }

  // Peak, impulse and the filtered peak by the code the 3D runs use, over the contact from the
  // first step to the last with a force (chatter inside it counted as contact).
  run::ImpactMeasures measures;
  measures.start(0.0, Vec3::Zero(), 1.0);
  for (std::size_t i = 1; i < force.size(); ++i)
    measures.add(time[i], Vec3(0.0, 0.0, force[i]), i <= L ? 1.0 : -1.0);
  out.peak_force = measures.peak_force;
  for (std::size_t i = 1; i <= L + 1; ++i)
    out.step_mean_peak_force = std::max(out.step_mean_peak_force, 0.5 * (force[i - 1] + force[i]));
  out.filtered_peak_force = measures.filtered_peak();
  out.impulse_ratio = measures.impulse / (2.0 * mass * v);
  if (def.record) {
    out.time = std::move(time);
    out.force = std::move(force);
  }
  return out;
}

FiniteSphereDynamicImpact finite_sphere_impact_dynamic_with_mass(double E, double nu, double mass,
                                                                 double R, double v) {
  const FiniteSphereMaterial material{.youngs_modulus = E, .poisson_ratio = nu, .radius = R};
  check(material, mass, v);
  static std::mutex guard;
  static std::map<std::tuple<double, double, double, double, double>, FiniteSphereDynamicImpact>
      cache;
  const auto key = std::make_tuple(E, nu, mass, R, v);
  {
    const std::lock_guard lock(guard);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  const FiniteSphereDynamicImpact result = simulate_finite_sphere_impact(material, mass, v);
  const std::lock_guard lock(guard);
  return cache.emplace(key, result).first->second;
}

FiniteSphereDynamicImpact finite_sphere_impact_dynamic(double E, double nu, double rho, double R,
                                                       double v) {
  detail::require(rho > 0.0, "rho", rho, "> 0");
  return finite_sphere_impact_dynamic_with_mass(E, nu, 4.0 / 3.0 * kPi * R * R * R * rho, R, v);
}

// Shifted inverse iteration: x ← (K + σM)⁻¹ M x, kept M-orthogonal to the rigid translation t
// (the free sphere's zero mode), converges to the lowest elastic mode at the rate
// (ω₁² + σ)/(ω₂² + σ); ω₁² is its Rayleigh quotient. σ = (c/R)²/100, c = √(E/ρ), well below ω₁².
double lowest_axisymmetric_period(const FiniteSphereMaterial& material, double density,
                                  const FiniteSphereMesh& spec) {
  detail::require(density > 0.0, "density", density, "> 0");
  const detail::Mesh mesh = detail::make_mesh(spec, material.radius);
  const detail::Assembly fe =
      detail::assemble(mesh, material.youngs_modulus, material.poisson_ratio, false, true);
  const Eigen::SparseMatrix<double> M = density * fe.mass;
  const double sigma =
      material.youngs_modulus / density / (material.radius * material.radius) / 100;
  const Eigen::SparseMatrix<double> shifted = fe.K + sigma * M;
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(shifted);
  if (llt.info() != Eigen::Success)
    throw std::runtime_error("finite_sphere_dynamic: K + σM is not positive definite");
  Eigen::VectorXd t = Eigen::VectorXd::Zero(fe.n_eq);
  for (std::size_t n = 0; n < mesh.r.size(); ++n) t[fe.eq[2 * n + 1]] = 1.0;
  const Eigen::VectorXd Mt = M * t;
  const double tMt = t.dot(Mt);
  // A start with every axisymmetric shape in it: r and z components of varying sign.
  Eigen::VectorXd x(fe.n_eq);
  for (int i = 0; i < fe.n_eq; ++i) x[i] = std::sin(0.37 * i + 0.1);
  double omega2 = 0, previous = -1;
  for (int it = 0; it < 500; ++it) {
    x -= (Mt.dot(x) / tMt) * t;
    x /= std::sqrt(x.dot(M * x));
    omega2 = x.dot(fe.K * x);
    if (std::abs(omega2 - previous) < 1e-12 * omega2) break;
    previous = omega2;
    x = llt.solve(M * x);
  }
  return 2.0 * kPi / std::sqrt(omega2);
}

}  // namespace asperity::reference
