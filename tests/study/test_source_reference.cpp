// The source reference's gate (issue 28): on particles the reference was not tuned on, a
// generated one of another seed and a scanned stone, the refined levels on the contact-local
// surface converge (the successive changes of the peak force fall at an observed order between
// 1 and 4) and doubling the contact patch moves the converged peak force by less than 0.5 %.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "solver/contact/hertz_impact.hpp"
#include "solver/geometry/contact_local_surface.hpp"
#include "solver/geometry/mass_properties.hpp"
#include "solver/geometry/repair_mesh.hpp"
#include "solver/geometry/write_mesh.hpp"
#include "solver/run/run_scene.hpp"
#include "solver/scene/scene.hpp"
#include "study/source_reference.hpp"
#include "study/tables/study_cases.hpp"
#include "tests/study/gate_particle.hpp"

namespace asperity::study {
namespace {

namespace fs = std::filesystem;

// The study's impact (data/study/default.json): granite-like rock at 2 m/s onto a rigid block,
// penalty α = 100 with the refined cases' contact factor 2, graded at 0.15 beyond 2 h; the
// factor met as the study's source levels meet it (StudyDef::source_reference): by contact mass,
// lowered within a budget of 1e-4 of the body's mass.
const Material kRock{.name = "rock", .density = 2650, .young = 50e9, .poisson = 0.25};
constexpr double kSpeed = 2.0, kGap = 1e-4;

// One refined level: the contact-local surface `file`, h at the strike point.
SourceLevel run_level(const fs::path& dir, const std::string& name, const fs::path& file,
                      const SourceReferencePlan& plan, const SurfaceMesh& surface, double h) {
  const double centroid_z = geometry::mass_properties(surface).centroid.z();
  const double contact_time =
      contact::hertz_contact_time(plan.mass, plan.equivalent_radius,
                                  kRock.young / (2 * (1 - kRock.poisson * kRock.poisson)), kSpeed);
  const Vec3& f = plan.strike_point;
  const double half = 2 * plan.equivalent_radius + 0.01;  // the study's block (study_run.cpp)
  std::ostringstream s;
  s.precision(17);
  s << R"({"name": ")" << name << R"(", "gravity": [0, 0, -9.81], "duration": )"
    << kGap / kSpeed + 1.5 * contact_time << R"(, "dt": "auto",
  "materials": {"rock": {"density": 2650, "young": 5e10, "poisson": 0.25, "friction": 0}},
  "bodies": [
    {"name": "particle", "material": "rock", "model": "fem",
     "shape": {"type": "mesh", "file": ")"
    << file.string() << R"(", "element_size": )" << h << R"(, "element_size_focus": [)" << f.x()
    << ", " << f.y() << ", " << f.z() << R"(], "element_size_focus_radius": )" << 2 * h
    << R"(, "element_size_growth": 0.15},
     "position": [0, 0, )"
    << kGap + centroid_z - f.z() << R"(], "velocity": [0, 0, )" << -kSpeed << R"(]},
    {"name": "block", "material": "rock", "shape": {"type": "box", "min": [)"
    << -half << ", " << -half << ", " << -half << R"(], "max": [)" << half << ", " << half
    << R"(, 0]}}],
  "contact": {"law": "potential", "penalty_alpha": 100, "max_contact_factor": 2,
              "contact_factor_by": "mass", "max_added_mass": 1e-4},
  "record": {"force_on": "particle", "every": 1000, "end_after_separation": )"
    << 0.25 * contact_time << "}}";
  const fs::path scene = dir / (name + ".json");
  std::ofstream(scene) << s.str();
  const run::RunResult r = run::run_scene(scene::load_scene(scene), {.keep_rows = false});
  EXPECT_EQ(r.status, "ok") << name << ": " << r.message;
  std::printf(
      "%s: h = %.4g R, peak %.8g N (filtered %.8g N), impulse %.8g N s, duration %.8g s, %.1f s "
      "CPU\n",
      name.c_str(), h / plan.equivalent_radius, r.summary["peak_force"].get<double>(),
      r.summary["peak_force_filtered"].get<double>(), r.summary["impulse"].get<double>(),
      r.summary["contact_duration"].get<double>(), r.summary["cpu_seconds"].get<double>());
  return source_level(r.summary["peak_force_filtered"].get<double>(),
                      r.summary["impulse"].get<double>(),
                      r.summary["contact_duration"].get<double>());
}

// The levels of plan.sizes on the contact-local surface of patch radius `patch` × R.
std::vector<SourceLevel> run_levels(const std::string& name, const SurfaceMesh& source,
                                    const SourceReferencePlan& plan,
                                    const SourceReferenceOptions& options, double patch) {
  const fs::path dir = fs::temp_directory_path() / "asperity_source_reference";
  fs::create_directories(dir);
  const geometry::ContactLocalSurface local =
      geometry::contact_local_surface(source, {.centre = plan.strike_point,
                                               .radius = patch * plan.equivalent_radius,
                                               .far_faces = options.far_faces});
  const fs::path file = dir / (name + ".off");
  geometry::write_surface_mesh(file, local.surface);
  std::vector<SourceLevel> levels;
  for (std::size_t k = 0; k < plan.sizes.size(); ++k) {
    levels.push_back(
        run_level(dir, name + "-L" + std::to_string(k), file, plan, local.surface, plan.sizes[k]));
  }
  return levels;
}

void check_reference(const std::string& name, const SurfaceMesh& source) {
  const SourceReferenceOptions options{};
  const SourceReferencePlan plan = plan_source_reference(source, kRock, kSpeed, options);
  std::printf(
      "%s: %ld source triangles, R = %.4g m, local radius %.4g m, Hertz a %.4g m "
      "(%.3g R), finest h %.4g R\n",
      name.c_str(), static_cast<long>(source.faces.cols()), plan.equivalent_radius,
      plan.local_radius, plan.contact_radius, plan.contact_radius / plan.equivalent_radius,
      plan.sizes.back() / plan.equivalent_radius);
  const std::vector<SourceLevel> near =
      run_levels(name + "-patch", source, plan, options, options.patch);
  const std::vector<SourceLevel> wide =
      run_levels(name + "-patch2", source, plan, options, 2 * options.patch);
  std::vector<double> sizes;
  for (double h : plan.sizes) sizes.push_back(h / plan.equivalent_radius);
  const SourceReference ref = source_reference(sizes, near, wide);
  const tables::Extrapolation& peak = ref.peak_force.limit;
  std::printf("%s: peak limit %.8g N +- %.3g %%, order %.3g (%s), doubled patch %+.3g %%\n",
              name.c_str(), peak.limit, 100 * peak.error, peak.order,
              peak.observed ? "observed" : "assumed", 100 * ref.peak_force.patch_change);
  // The issue's convergence statement: the successive changes fall at an observed order between
  // 1 and 4 (graded refinement of a Hertz contact converges at 1.2-2.7 in peak force on the
  // sphere, reports/fem/hertz_convergence.md; outside 1-4 the levels are not asymptotic).
  EXPECT_TRUE(peak.observed) << name << ": the peak force's changes do not fall monotonically";
  EXPECT_GE(peak.order, 1.0) << name;
  EXPECT_LE(peak.order, 4.0) << name;
  // The patch-size check: the far surface's simplification moves the converged peak by less
  // than 0.5 % (the issue's bound: a share of the 1 % the reference's uncertainty may have).
  EXPECT_LT(std::abs(ref.peak_force.patch_change), 0.005) << name;
}

// A generated particle of a seed outside data/particles/set.json (its seeds are 1000-1049), with
// the set's ballast-like shape numbers and its 20 480 source triangles.
TEST(SourceReference, GeneratedParticleConverges) {
  check_reference("generated-7321", test::gate_particle_7321());
}

// A scanned stone (Settimi et al. 2022, ../shared/data/scans: never committed).
TEST(SourceReference, ScannedStoneConverges) {
  const fs::path scan = fs::path(ASPERITY_SCANS_DIR) / "low_res_E34.ply";
  if (!fs::exists(scan)) GTEST_SKIP() << scan << " is absent (the scans are not committed)";
  geometry::MeshLog log;
  const SurfaceMesh source = geometry::load_surface_mesh(scan, {.scale = 1e-3}, log);
  check_reference("scan-E34", source);
}

}  // namespace
}  // namespace asperity::study
