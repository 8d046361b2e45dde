// finite_sphere_dynamic_table: the tables of reports/fem/finite_sphere_dynamic.md and .csv (the
// dynamic finite-sphere reference, issue 11). Usage: finite_sphere_dynamic_table OUT.csv >
// tables.md. About five minutes of CPU (the M = 32 runs are most of it).
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <numbers>
#include <vector>

#include "solver/core/richardson.hpp"
#include "validation/reference/finite_sphere.hpp"
#include "validation/reference/finite_sphere_dynamic.hpp"

using namespace asperity::reference;
using asperity::RichardsonRate;

namespace {

constexpr double kPi = std::numbers::pi;

// The impacts of reports/fem/hertz_convergence.md: R = 0.1 m, E = 10 MPa, ν = 0.3,
// ρ = 1000 kg/m³, the nominal sphere's mass.
constexpr double kE = 10e6, kNu = 0.3, kRho = 1000.0, kR = 0.1;
const double kMass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;
const FiniteSphereMaterial kMaterial{.youngs_modulus = kE, .poisson_ratio = kNu, .radius = kR};

// The speed whose Hertz contact radius is a/R (scenes/hertz_series.hpp, speed_for).
double speed_for(double a_over_R) {
  const double Es = kE / (1.0 - kNu * kNu);
  const double d = a_over_R * a_over_R * kR;
  return std::sqrt(16.0 * Es * std::sqrt(kR) * std::pow(d, 2.5) / (15.0 * kMass));
}

// The quasi-static reference's force history, for its T/20-filtered peak: m δ'' = −F(δ) with
// the fitted law (finite_sphere.hpp), classical Runge–Kutta at T_H/4000 to the rebound, then the
// same centred moving average over a twentieth of the contact's samples.
double quasi_static_filtered_peak(const FiniteSphereLaw& law, double v) {
  const double k = 4.0 / 3.0 * kE / (1.0 - kNu * kNu) * std::sqrt(kR);
  auto force = [&](double d) {
    return d > 0.0 ? k * std::pow(d, 1.5) * evaluate(law, std::sqrt(d / kR)) : 0.0;
  };
  const FiniteSphereImpact im = impact_from_law(law, kE, kMass, kR, v);
  const double h = im.hertz_duration / 4000.0;
  double d = 0.0, w = v;
  std::vector<double> f;
  do {
    const double k1d = w, k1w = -force(d) / kMass;
    const double k2d = w + 0.5 * h * k1w, k2w = -force(d + 0.5 * h * k1d) / kMass;
    const double k3d = w + 0.5 * h * k2w, k3w = -force(d + 0.5 * h * k2d) / kMass;
    const double k4d = w + h * k3w, k4w = -force(d + h * k3d) / kMass;
    d += h / 6.0 * (k1d + 2 * k2d + 2 * k3d + k4d);
    w += h / 6.0 * (k1w + 2 * k2w + 2 * k3w + k4w);
    f.push_back(force(d));
  } while (d > 0.0);
  const std::size_t n = f.size(), window = n / 20;
  double sum = 0, best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += f[i];
    if (i >= window) sum -= f[i - window];
    if (i + 1 >= window) best = std::max(best, sum / static_cast<double>(window));
  }
  return best / im.hertz_peak_force - 1.0;
}

double err(double value, double hertz) {
  return value / hertz - 1.0;
}

struct Run {
  FiniteSphereDynamicImpact r;
  double cpu = 0;
};
Run run(int M, double steps, double v) {
  const std::clock_t c = std::clock();
  Run out;
  out.r = simulate_finite_sphere_impact(
      kMaterial, kMass, v, {.mesh = {.angular_cells = M}, .steps_per_hertz_duration = steps});
  out.cpu = static_cast<double>(std::clock() - c) / CLOCKS_PER_SEC;
  return out;
}

// Observed order and the finest value's Richardson error from three levels halving h
// (solver/core/richardson.hpp), from the magnitude of the changes' ratio, so that levels whose
// changes alternate in sign (the filtered peak in dt) still show an order, and as the limit minus
// the finest level, the negative of RichardsonRate::finest_error: as this table has always
// printed them (reports/fem/finite_sphere_dynamic.md).
void richardson(const char* what, double coarse, double middle, double fine) {
  const RichardsonRate r = asperity::richardson_from_ratio(
      std::abs((coarse - middle) / (middle - fine)), middle, fine, 2.0);
  std::printf(
      "- %s: %+.4f, %+.4f, %+.4f %%: observed order %.2f, finest level's error %.1e "
      "of Hertz's (Richardson)\n",
      what, 100 * coarse, 100 * middle, 100 * fine, r.order, -r.finest_error);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: finite_sphere_dynamic_table OUT.csv\n");
    return 2;
  }
  std::ofstream csv(argv[1]);
  csv << "table,a_over_R,M,steps_per_hertz_duration,peak_error,step_mean_peak_error,"
         "filtered_peak_error,duration_error,impulse_ratio,energy_ratio,contact_work,"
         "contact_intervals,cpu_s,qs_peak_error,qs_filtered_peak_error,qs_duration_error\n";
  auto row = [&](const char* table, double aR, int M, double steps, const Run& x,
                 const FiniteSphereImpact* qs, double qs_filtered) {
    const auto& r = x.r;
    csv << table << "," << aR << "," << M << "," << steps << ","
        << err(r.peak_force, r.hertz_peak_force) << ","
        << err(r.step_mean_peak_force, r.hertz_peak_force) << ","
        << err(r.filtered_peak_force, r.hertz_peak_force) << ","
        << err(r.duration, r.hertz_duration) << "," << r.impulse_ratio << "," << r.energy_ratio
        << "," << r.contact_work << "," << r.contact_intervals << "," << x.cpu << ",";
    if (qs)
      csv << err(qs->peak_force, qs->hertz_peak_force) << "," << qs_filtered << ","
          << err(qs->duration, qs->hertz_duration);
    else
      csv << ",,";
    csv << "\n";
  };

  std::printf(
      "### The free sphere's lowest axisymmetric mode (R = 0.1 m, E = 10 MPa, nu = 0.3, "
      "rho = 1000 kg/m3)\n\n| M | period (ms) |\n| ---: | ---: |\n");
  for (int M : {8, 16, 32})
    std::printf("| %d | %.4f |\n", M,
                1e3 * lowest_axisymmetric_period(kMaterial, kRho, {.angular_cells = M}));

  const double v107 = speed_for(0.107);
  std::printf("\n### Convergence at a/R = 0.107 (v = %.4f m/s), errors against Hertz\n\n", v107);
  std::printf(
      "| M | steps per T_H | peak | step-mean peak | filtered peak | duration | impulse / "
      "2mv | energy end / start | contact intervals | CPU (s) |\n| ---: | ---: | ---: | "
      "---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  std::vector<std::vector<Run>> grid;
  for (int M : {8, 16, 32}) {
    grid.emplace_back();
    for (double steps : {500.0, 1000.0, 2000.0}) {
      const Run x = run(M, steps, v107);
      const auto& r = x.r;
      std::printf(
          "| %d | %.0f | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | %.6f | %.6f | %d | "
          "%.1f |\n",
          M, steps, 100 * err(r.peak_force, r.hertz_peak_force),
          100 * err(r.step_mean_peak_force, r.hertz_peak_force),
          100 * err(r.filtered_peak_force, r.hertz_peak_force),
          100 * err(r.duration, r.hertz_duration), r.impulse_ratio, r.energy_ratio,
          r.contact_intervals, x.cpu);
      row("convergence", 0.107, M, steps, x, nullptr, 0);
      grid.back().push_back(x);
    }
  }
  auto measure = [](const Run& x, int which) {
    const auto& r = x.r;
    switch (which) {
      case 0:
        return err(r.step_mean_peak_force, r.hertz_peak_force);
      case 1:
        return err(r.filtered_peak_force, r.hertz_peak_force);
      default:
        return err(r.duration, r.hertz_duration);
    }
  };
  const char* names[] = {"step-mean peak", "filtered peak", "duration"};
  for (std::size_t i = 0; i < 3; ++i) {
    std::printf("\nIn dt at M = %d:\n\n", 8 << i);
    for (int w = 0; w < 3; ++w)
      richardson(names[w], measure(grid[i][0], w), measure(grid[i][1], w), measure(grid[i][2], w));
  }
  for (std::size_t j = 0; j < 3; ++j) {
    std::printf("\nIn M at %d steps per T_H:\n\n", 500 << j);
    for (int w = 0; w < 3; ++w)
      richardson(names[w], measure(grid[0][j], w), measure(grid[1][j], w), measure(grid[2][j], w));
  }

  std::printf(
      "\n### Dynamic against quasi-static (M = 16, 1000 steps per T_H; same mass, same v)\n\n");
  std::printf(
      "| a/R | v (m/s) | T_H (ms) | dynamic: step-mean peak | filtered peak | duration | "
      "quasi-static: peak | filtered peak | duration | dynamic − quasi-static: peak | "
      "filtered | duration | impulse / 2mv |\n| ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  const FiniteSphereLaw law = fit_finite_sphere_law(kNu, {});
  for (double aR : {0.01, 0.02, 0.05, 0.08, 0.107, 0.15}) {
    const double v = speed_for(aR);
    const Run x = run(16, 1000, v);
    const auto& r = x.r;
    const FiniteSphereImpact qs = finite_sphere_impact_with_mass(kE, kNu, kMass, kR, v);
    const double qf = quasi_static_filtered_peak(law, v);
    const double dp = err(r.step_mean_peak_force, r.hertz_peak_force),
                 df = err(r.filtered_peak_force, r.hertz_peak_force),
                 dd = err(r.duration, r.hertz_duration);
    const double qp = err(qs.peak_force, qs.hertz_peak_force),
                 qd = err(qs.duration, qs.hertz_duration);
    std::printf(
        "| %.3f | %.4f | %.3f | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | %+.3f %% | "
        "%+.3f %% | %+.3f | %+.3f | %+.3f | %.5f |\n",
        aR, v, 1e3 * r.hertz_duration, 100 * dp, 100 * df, 100 * dd, 100 * qp, 100 * qf, 100 * qd,
        100 * (dp - qp), 100 * (df - qf), 100 * (dd - qd), r.impulse_ratio);
    row("comparison", aR, 16, 1000, x, &qs, qf);
  }
  return 0;
}
