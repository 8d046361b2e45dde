// The study's fem path on a sphere (issue 12, "Validation"): a sphere-like particle named by path
// in a small study definition (tests/study/sphere_study.json), run through `run_study` with its
// refinement sequence, its Richardson limit (tables/study_cases.hpp) against Hertz corrected by
// the finite-sphere reference (validation/reference/finite_sphere.hpp) and against plain Hertz.
// Ties the study's reference to the convergence issue's gate (reports/fem/hertz_convergence.md).
//
// Measured (2 December 2026, 2 threads on the loaded shared machine: 242 s of CPU, 13 min wall):
// a/R = 0.049; Hertz peak 5512 N, finite sphere 5635 N (+2.23 %); fem peak coarse 6048 N, h = 0.04
// R 5764 N, 0.02 R 5734 N, limit 5720 N ± 0.15 %: +1.52 % from the finite sphere, +3.79 % from
// Hertz. The grading is the study key `growth` = 0.15 (sphere_study.json). At the default
// study's growth of 0.3 the same sequence (165 s of CPU) gave 5831, 5813 N and a limit of 5804 N
// ± 0.09 %: +3.01 % from the finite sphere, failing the 2 % by 1.0 point. Refining h at the strike
// point leaves the far field at 0.3 × its distance from the contact, too stiff by about a point
// (the material beyond 3a carries about a quarter of the compliance, reports/fem/
// hertz_convergence.md), and the extrapolation's error (0.09 %) cannot see a bias the sequence
// does not refine away.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "solver/geometry/geodesic_sphere.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/refined_sphere.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "study/study_def.hpp"
#include "study/study_run.hpp"
#include "study/tables/study_cases.hpp"
#include "validation/reference/finite_sphere.hpp"

namespace asperity::study {
namespace {
namespace fs = std::filesystem;

// The particle: a sphere of radius R = 25 mm (a geodesic icosphere of frequency 8, edge 0.14 R),
// bisected near its strike point (the lowest vertex, where the study's "lowest" placement puts
// the contact) with every new vertex put back on the sphere, down to facets of edge 0.0167 R
// within 0.15 R of it. At the study's speed (sphere_study.json: 1.25 m/s, E = 50 GPa, ν = 0.3,
// ρ = 2650 kg/m³, rigid block) Hertz gives a/R = 0.050, so a facet's sagitta e²/(8R) = 3.5e-5 R
// is 1.4 % of the approach a²/R and the contact patch (radius a = 3 facets) is sphere-like; the
// patch of 3 contact radii holds the pressure's footprint. (Facets of a/4 at a/R = 0.04, the
// first try, cost 1.5e-9 s steps at α = 100: over 200 000 steps for the coarse case alone.)
constexpr double kRadius = 0.025, kEdge = 0.0167 * kRadius, kPatch = 0.15 * kRadius;

SurfaceMesh sphere_surface() {
  // The strike point: the icosphere's lowest vertex, where the study's "lowest" placement puts
  // the contact.
  SurfaceMesh ico = geometry::geodesic_sphere(8);
  ico.vertices *= kRadius;
  return geometry::refined_sphere(8, kRadius, kEdge, kPatch, geometry::lowest_vertex(ico));
}

// A fresh folder WORK (temporary) holding `surface` as MESH and tests/study/STUDY side by side
// (the definition names the mesh by path, beside it), and the definition loaded from there.
struct StudyBesideSphere {
  fs::path work;
  StudyDef def;
};
StudyBesideSphere sphere_study(const std::string& work_name, const SurfaceMesh& surface,
                               const std::string& mesh, const std::string& study) {
  const fs::path work = fs::temp_directory_path() / work_name;
  fs::remove_all(work);
  fs::create_directories(work);
  geometry::write_surface_mesh(work / mesh, surface);
  fs::copy_file(fs::path(ASPERITY_SOURCE_DIR) / "tests/study" / study, work / study);
  return {.work = work, .def = load_study(work / study)};
}

TEST(SphereStudy, RefinedFemPeakMatchesTheFiniteSphereAndHertz) {
  const SurfaceMesh surface = sphere_surface();
  const auto [work, def] = sphere_study("asperity_sphere_study", surface,
                                        "sphere_strike_refined.off", "sphere_study.json");
  // The study keeps a mesh of exactly its resolution's triangle count: the definition's
  // resolution is the generated surface's, so the surface is used as it is (no simplification).
  ASSERT_EQ(def.resolutions.size(), 1u);
  ASSERT_EQ(def.resolutions[0], static_cast<long>(surface.faces.cols()))
      << "sphere_study.json's resolution must equal the generated surface's triangle count";
  ASSERT_EQ(def.refinement.sizes.size(), 2u);

  StudyRunOptions run{.jobs = 2, .quiet = true};
  const StudyOutcome outcome = run_study(def, work / "out", run);
  ASSERT_EQ(outcome.failed, 0);
  const tables::StudyCases cases = tables::load_study_cases(def, work / "out");
  const tables::Sequence* seq = cases.sequence("sphere", def.resolutions[0], Placement::lowest);
  ASSERT_NE(seq, nullptr);
  ASSERT_TRUE(seq->extrapolated);
  ASSERT_EQ(seq->levels, 3);  // coarse, and the two refined sizes

  // The references for the meshed volume's mass (the faceted sphere's volume is 0.5 % short of
  // the sphere's; Hertz and the finite sphere are both taken at the mass that actually strikes).
  const double mass = def.material.density * geometry::mass_properties(surface).volume;
  const reference::FiniteSphereImpact ref = reference::finite_sphere_impact_with_mass(
      def.material.young, def.material.poisson, mass, kRadius, def.speed);
  const double a_over_r = std::sqrt(ref.hertz_max_approach / kRadius);
  const double finite_correction = ref.peak_force / ref.hertz_peak_force - 1;
  const double coarse =
      cases
          .cases[cases.index_of(
              *cases.find("sphere", ModelKind::fem, def.resolutions[0], Placement::lowest, 0))]
          .summary["peak_force"]
          .get<double>();
  const double h1 = cases.find("sphere", ModelKind::fem, def.resolutions[0], Placement::lowest, 1)
                        ->summary["peak_force"]
                        .get<double>();
  const double h2 = cases.find("sphere", ModelKind::fem, def.resolutions[0], Placement::lowest, 2)
                        ->summary["peak_force"]
                        .get<double>();
  const double limit = seq->limit.peak;
  const double vs_finite = limit / ref.peak_force - 1, vs_hertz = limit / ref.hertz_peak_force - 1;
  std::cout << "a/R " << a_over_r << ", Hertz peak " << ref.hertz_peak_force << " N, finite sphere "
            << ref.peak_force << " N (+" << 100 * finite_correction << " %); fem peak: coarse "
            << coarse << ", h=" << def.refinement.sizes[0] << "R " << h1
            << ", h=" << def.refinement.sizes[1] << "R " << h2 << ", limit " << limit << " ± "
            << 100 * seq->limit_error.peak << " %; limit vs finite sphere " << 100 * vs_finite
            << " %, vs Hertz " << 100 * vs_hertz << " %; CPU " << outcome.cpu_seconds << " s\n";

  // The definition's speed gives a/R in 0.03–0.05, where the finite-sphere correction is known
  // (reports/fem/finite_sphere.md: +2.26 % at a/R = 0.05) and small against the 2 % band.
  EXPECT_GT(a_over_r, 0.03);
  EXPECT_LT(a_over_r, 0.051);
  // 2 %: the convergence issue's gate tolerance (reports/fem/hertz_convergence.md), held against
  // the finite sphere, the limit of a finite elastic sphere's impact (the 3D gates' limits sit
  // within 2 % of it at every a/R measured).
  EXPECT_LT(std::abs(vs_finite), 0.02);
  // Against plain Hertz (half-spaces): 2 % plus the finite-sphere correction, which is the
  // physics a half-space law leaves out, not a solver error.
  EXPECT_LT(std::abs(vs_hertz), 0.02 + finite_correction);
  fs::remove_all(work);
}

// The source reference end to end (issue 28, "reference": "source"): the same sphere as its own
// source surface, its contact-local surface refined at the strike point in three levels by
// run_study, and the reference the tables take from them (tables::StudyCases::Reference): its
// peak force must converge (changes falling monotonically at an observed order) towards the
// finite-sphere reference, the limit within the convergence gate's 2 % of it.
//
// Measured (5 December 2026, 2 threads on the 2-core machine at a load of 8-15) with the finest
// level at a/1.25 (h = 0.158, 0.079, 0.040 R): peak 6155, 5838, 5789 N, observed order 2.69,
// limit 5780 N ± 0.19 %: +2.58 % from the finite sphere (5635 N), +4.87 % from Hertz; failed the
// 2 %. The study's own refined sphere (the test above) falls from 5764 N at 0.04 R to 5734 N at
// 0.02 R, an order of about 1.2: levels as coarse as 0.16 R are not asymptotic, and their order
// says so only with a finer level. Hence the source reference's a/3 here (301 s of CPU at a/1.25).
// At a/3 (h = 0.0659, 0.0329, 0.0165 R; same machine, load 14): peak 5893, 5745, 5726 N, observed
// order 2.95, limit 5722.9 N ± 0.06 %: +1.57 % from the finite sphere, +3.84 % from Hertz (the
// finite-sphere correction +2.23 %), within 0.05 % of the refined sphere's limit above (5720 N);
// passed; 364 s of CPU (64 + 114 + 187 s), 21.5 min of wall.
TEST(SphereStudy, SourceReferenceConvergesTowardsTheFiniteSphere) {
  const SurfaceMesh surface = sphere_surface();
  const auto [work, def] = sphere_study("asperity_sphere_source_study", surface,
                                        "sphere_source.off", "sphere_source_study.json");
  ASSERT_EQ(def.reference_kind, ReferenceKind::source);

  StudyRunOptions run{.jobs = 2, .quiet = true};
  const StudyOutcome outcome = run_study(def, work / "out", run);
  ASSERT_EQ(outcome.failed, 0);
  const tables::StudyCases cases = tables::load_study_cases(def, work / "out");
  const tables::StudyCases::Reference* r = cases.reference("sphere", Placement::lowest);
  ASSERT_NE(r, nullptr);
  ASSERT_EQ(r->kind, ReferenceKind::source);

  const double mass = def.material.density * geometry::mass_properties(surface).volume;
  const reference::FiniteSphereImpact ref = reference::finite_sphere_impact_with_mass(
      def.material.young, def.material.poisson, mass, kRadius, def.speed);
  const double finite_correction = ref.peak_force / ref.hertz_peak_force - 1;
  std::cout << "source reference levels (h/R, peak N, CPU s):";
  double cpu = 0;
  std::vector<double> peaks;
  for (const tables::CaseData& c : cases.source_cases) {
    std::cout << " " << c.record["element_size_rel"].get<double>() << " "
              << c.summary["peak_force"].get<double>() << " " << c.cpu << ";";
    peaks.push_back(c.summary["peak_force"].get<double>());
    cpu += c.cpu;
  }
  const double limit = r->values.peak;
  std::cout << " limit " << limit << " N ± " << 100 * r->discretization.peak << " %, order "
            << r->peak.order << (r->peak.observed ? " (observed)" : " (assumed)")
            << "; vs finite sphere " << 100 * (limit / ref.peak_force - 1) << " %, vs Hertz "
            << 100 * (limit / ref.hertz_peak_force - 1) << " %; source reference CPU " << cpu
            << " s\n";
  ASSERT_EQ(peaks.size(), 3u);
  // Converging: each level closer to the finite sphere than the one before, at an observed order
  // in [1, 4] (graded refinement of a Hertz contact converges at 1.2-2.7 in peak force,
  // reports/fem/hertz_convergence.md; outside [1, 4] the levels are not asymptotic).
  EXPECT_LT(std::abs(peaks[1] - ref.peak_force), std::abs(peaks[0] - ref.peak_force));
  EXPECT_LT(std::abs(peaks[2] - ref.peak_force), std::abs(peaks[1] - ref.peak_force));
  EXPECT_TRUE(r->peak.observed);
  EXPECT_GE(r->peak.order, 1.0);
  EXPECT_LE(r->peak.order, 4.0);
  // 2 %: the convergence issue's gate tolerance, against the finite sphere (as the test above).
  EXPECT_LT(std::abs(limit / ref.peak_force - 1), 0.02);
  EXPECT_LT(std::abs(limit / ref.hertz_peak_force - 1), 0.02 + finite_correction);
  // The Hertz sphere, the study's one candidate, is measured against that reference.
  const tables::CaseData* sphere = cases.find("sphere", ModelKind::sphere, 0, Placement::lowest);
  ASSERT_NE(sphere, nullptr);
  EXPECT_NEAR(cases.err_fem[cases.index_of(*sphere)].peak,
              sphere->summary["peak_force"].get<double>() / limit - 1, 1e-12);
  fs::remove_all(work);
}

}  // namespace
}  // namespace asperity::study
