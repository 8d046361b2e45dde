// finite_sphere_table: the tables of reports/fem/finite_sphere.md and finite_sphere.csv (the
// finite-sphere reference, issue 11). Usage: finite_sphere_table OUT.csv > tables.md
// About a minute of CPU (the M = 32 level is most of it).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "solver/core/richardson.hpp"
#include "validation/reference/finite_sphere.hpp"

using namespace asperity::reference;
using asperity::richardson_rate;
using asperity::RichardsonRate;

namespace {

constexpr double kPi = std::numbers::pi;

// The impacts of reports/fem/hertz_convergence.md: R = 0.1 m, E = 10 MPa, ρ = 1000 kg/m³.
constexpr double kE = 10e6, kRho = 1000.0, kR = 0.1;

// The speed that gives a Hertz approach δ_H = (a/R)² R for this sphere.
double speed_for(double a_over_R, double nu) {
  const double m = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;
  const double Es = kE / (1.0 - nu * nu);
  const double d = a_over_R * a_over_R * kR;
  return std::sqrt(2.0 / m * 8.0 / 15.0 * Es * std::sqrt(kR) * std::pow(d, 2.5));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: finite_sphere_table OUT.csv\n");
    return 2;
  }
  const FiniteSphereMaterial unit{.youngs_modulus = 1.0, .poisson_ratio = 0.3, .radius = 1.0};

  std::printf("### Convergence of the reference (nu = 0.3)\n\n");
  std::printf(
      "| M | elements | nodes | volume error | F/F_H at a/R = 0.01 | oscillation | "
      "F/F_H at a/R = 0.107 | oscillation |\n| ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: |\n");
  std::vector<double> g01, g107;
  for (int M : {4, 8, 16, 32}) {
    const FiniteSphere sphere(unit, {.angular_cells = M});
    const auto r01 = sphere.averaged_force_ratio(0.01);
    const auto r107 = sphere.averaged_force_ratio(0.107);
    g01.push_back(r01.ratio);
    g107.push_back(r107.ratio);
    std::printf("| %d | %d | %d | %.1e | %.7f | %.1e | %.7f | %.1e |\n", M, sphere.elements(),
                sphere.nodes(), sphere.volume() / (4.0 / 3.0 * kPi) - 1.0, r01.ratio,
                r01.oscillation, r107.ratio, r107.oscillation);
  }
  // The last three levels, M doubling (solver/core/richardson.hpp). The "error" printed is the
  // limit minus the finest level, the negative of RichardsonRate::finest_error, as this table
  // has always printed it (reports/fem/finite_sphere.md).
  auto richardson = [](const std::vector<double>& g) {
    const std::size_t n = g.size();
    const RichardsonRate r = richardson_rate(g[n - 3], g[n - 2], g[n - 1], 2.0);
    std::printf("observed order %.2f, finest level's error (Richardson) %.1e; ", r.order,
                -r.finest_error);
  };
  std::printf("\nLast three levels, a/R = 0.01: ");
  richardson(g01);
  std::printf("a/R = 0.107: ");
  richardson(g107);
  std::printf("\n\n");

  std::printf(
      "### The law F/F_H = c0 + c1 s + c2 s ln s + c3 s^2 + c4 s^3, s = sqrt(delta/R) "
      "(M = 16 and 32)\n\n");
  std::printf(
      "| nu | M | c0 | c1 | c2 | c3 | c4 | fit residual | (g-1)/s at 0.01 | at 0.05 | at "
      "0.1 | at 0.15 |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | "
      "---: | ---: | ---: |\n");
  for (double nu : {0.2, 0.3, 0.4}) {
    for (int M : {16, 32}) {
      const FiniteSphereLaw law = fit_finite_sphere_law(nu, {.angular_cells = M});
      const auto& c = law.coefficients;
      std::printf("| %.1f | %d | %.6f | %.4f | %.4f | %.3f | %.3f | %.1e |", nu, M, c[0], c[1],
                  c[2], c[3], c[4], law.fit_residual);
      for (double s : {0.01, 0.05, 0.1, 0.15}) std::printf(" %.4f |", (evaluate(law, s) - 1) / s);
      std::printf("\n");
    }
  }

  std::printf(
      "\n### Contact radius (nu = 0.3, M = 32)\n\n| a/R | a/sqrt(R delta) | a/a_H(F) |\n"
      "| ---: | ---: | ---: |\n");
  {
    const FiniteSphere sphere(unit, {.angular_cells = 32});
    for (double s : {0.005, 0.01, 0.02, 0.05, 0.107, 0.15}) {
      const FiniteSphereState st = sphere.at_approach(s * s);
      const double a_hertz = std::cbrt(3.0 * st.force * (1.0 - 0.09) / 4.0);
      std::printf("| %.3f | %.4f | %.4f |\n", s, st.contact_radius / s,
                  st.contact_radius / a_hertz);
    }
  }

  std::printf(
      "\n### Impact (nu = 0.3; R = 0.1 m, E = 10 MPa, rho = 1000 kg/m3, sphere on a rigid "
      "plane)\n\n");
  std::printf(
      "| a/R (Hertz) | v (m/s) | peak / Hertz | duration / Hertz | delta_max / Hertz | "
      "peak, M = 8 | peak, M = 32 | duration, M = 32 |\n| ---: | ---: | ---: | ---: | "
      "---: | ---: | ---: | ---: |\n");
  std::ofstream csv(argv[1]);
  csv << "a_over_R_hertz,v_m_per_s,peak_error,duration_error,max_approach_ratio,"
         "peak_error_M8,peak_error_M32,duration_error_M32\n";
  const FiniteSphereLaw law8 = fit_finite_sphere_law(0.3, {.angular_cells = 8});
  const FiniteSphereLaw law32 = fit_finite_sphere_law(0.3, {.angular_cells = 32});
  const double mass = 4.0 / 3.0 * kPi * kR * kR * kR * kRho;
  for (double aR : {0.05, 0.08, 0.107, 0.15, 0.2}) {
    const double v = speed_for(aR, 0.3);
    const FiniteSphereImpact im = finite_sphere_impact(kE, 0.3, kRho, kR, v);
    const FiniteSphereImpact im8 = impact_from_law(law8, kE, mass, kR, v);
    const FiniteSphereImpact im32 = impact_from_law(law32, kE, mass, kR, v);
    const double pe = im.peak_force / im.hertz_peak_force - 1.0;
    const double de = im.duration / im.hertz_duration - 1.0;
    std::printf("| %.3f | %.4f | %+.3f %% | %+.3f %% | %.4f | %+.3f %% | %+.3f %% | %+.3f %% |\n",
                aR, v, 100 * pe, 100 * de, im.max_approach / im.hertz_max_approach,
                100 * (im8.peak_force / im8.hertz_peak_force - 1.0),
                100 * (im32.peak_force / im32.hertz_peak_force - 1.0),
                100 * (im32.duration / im32.hertz_duration - 1.0));
    csv << aR << "," << v << "," << pe << "," << de << ","
        << im.max_approach / im.hertz_max_approach << ","
        << im8.peak_force / im8.hertz_peak_force - 1.0 << ","
        << im32.peak_force / im32.hertz_peak_force - 1.0 << ","
        << im32.duration / im32.hertz_duration - 1.0 << "\n";
  }
  std::printf("\nThe 3D scenes' speeds: ");
  for (double v : {0.2, 0.465}) {
    const FiniteSphereImpact im = finite_sphere_impact(kE, 0.3, kRho, kR, v);
    std::printf("v = %.3f m/s: a/R = %.4f (Hertz), peak %+.3f %%, duration %+.3f %%; ", v,
                std::sqrt(im.hertz_max_approach / kR),
                100 * (im.peak_force / im.hertz_peak_force - 1.0),
                100 * (im.duration / im.hertz_duration - 1.0));
  }
  std::printf("\n");
  return 0;
}
