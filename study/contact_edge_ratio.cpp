// contact_edge_ratio STUDY.json DIR ROWS.csv SUMMARY.csv: how many surface edges the contact
// spans at peak force, per particle and resolution of the study folder DIR (asperity study
// STUDY.json --out DIR; the definition is STUDY.json's, as `asperity study --collect` reads it):
// why the geometry term of the study does not close in N. Computed here, from the study's own
// tables (study/tables/) and meshes, for tools/report/contact_edge_ratio.py, which only formats
// what this writes.
//
// For each particle, Hertz's contact radius at the converged peak force of the reference (the fem
// sequence's limit at the finest resolution that has one, cases.csv `extrapolated_peak_force` on
// the answer, lowest placement), on the particle's local radius of curvature at its lowest vertex
// (the sphere-local case's `local_radii`, R = √(R1 R2)), against the mean edge h of the surface at
// each resolution (geometry::mean_edge_length):
//
//     a = (3 F R / (4 E*))^(1/3),   1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2   (Johnson 1985, eq. 4.22)
//
// While a/h < 1 the contact at peak lies inside the fan of faces around the lowest vertex: the
// particle meets the block at a faceted corner whose face angles come from the simplification, not
// from the particle's curvature, and the converged answer at N is that corner's. Since h ~ N^-1/2,
// a/h reaches k at N_k = N (k h / a)².
//
// ROWS.csv: one row per particle and mesh resolution; SUMMARY.csv: per resolution the particles,
// the median and largest a/h and the median N_3 (solver/core/quantile.hpp). Numbers in the
// shortest form that reads back to the same double (the study tables' write_csv). Exit 2 with one
// line when DIR is not a study folder of STUDY.json or has no particle with a converged fem answer
// and a sphere-local case.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/core/material.hpp"
#include "solver/core/quantile.hpp"
#include "solver/geometry/local_curvature.hpp"
#include "study/study_def.hpp"
#include "study/study_meshes.hpp"
#include "study/study_run.hpp"
#include "study/tables/study_cases.hpp"

namespace fs = std::filesystem;
using namespace asperity;
using namespace asperity::study;

namespace {

struct Row {
  std::string particle;
  long resolution = 0;
  double mean_edge = 0, local_radius = 0, contact_radius = 0;
  tables::OJson converged_peak_force;  // null where this resolution has no converged answer
  double contact_over_edge() const { return contact_radius / mean_edge; }
  double faces_for_three_edges() const {
    return static_cast<double>(resolution) * std::pow(3 * mean_edge / contact_radius, 2);
  }
};

// The resolutions meshed for particle p (DIR/meshes/p/N/), ascending.
std::vector<long> meshed(const fs::path& dir, const std::string& p) {
  std::vector<long> out;
  for (const fs::directory_entry& e : fs::directory_iterator(dir / "meshes" / p)) {
    const std::string name = e.path().filename().string();
    if (!name.empty() &&
        std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isdigit(c); }))
      out.push_back(std::stol(name));
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Row> rows(const StudyDef& def, const tables::StudyCases& s, const fs::path& dir) {
  const double e_star = effective_young(def.material, def.block_material);
  std::vector<Row> out;
  for (const ParticleSource& p : def.particles) {
    // The sequences' limits on the answer, lowest placement, by resolution.
    std::map<long, double> answers;
    for (long n : def.resolutions) {
      const tables::Sequence* q = s.sequence(p.name, n, Placement::lowest);
      if (q && q->extrapolated && std::isfinite(q->limit.peak)) answers[n] = q->limit.peak;
    }
    const tables::CaseData* local = s.find(p.name, ModelKind::sphere_local, 0, Placement::lowest);
    if (answers.empty() || !local || !local->record.contains("local_radii")) continue;
    const tables::OJson& radii = local->record["local_radii"];
    if (!radii[0].is_number() || !radii[1].is_number()) continue;
    const double r1 = radii[0].get<double>(), r2 = radii[1].get<double>();
    if (!(r1 > 0 && r2 > 0)) continue;
    const double radius = std::sqrt(r1 * r2);
    const double force = answers.rbegin()->second;  // the finest resolution's
    const double contact = std::pow(3 * force * radius / (4 * e_star), 1.0 / 3);
    for (const long n : meshed(dir, p.name)) {
      const SurfaceMesh surface =
          read_surface(dir / "meshes" / p.name / std::to_string(n) / "surface.off");
      const auto answer = answers.find(n);
      out.push_back({.particle = p.name,
                     .resolution = n,
                     .mean_edge = geometry::mean_edge_length(surface),
                     .local_radius = radius,
                     .contact_radius = contact,
                     .converged_peak_force = answer == answers.end()
                                                 ? tables::OJson()
                                                 : tables::OJson(answer->second)});
    }
  }
  return out;
}

void write_rows(const std::vector<Row>& rows, const fs::path& file) {
  std::vector<std::vector<tables::OJson>> table;
  for (const Row& r : rows) {
    table.push_back({r.particle, r.resolution, r.mean_edge, r.local_radius, r.contact_radius,
                     r.contact_over_edge(), r.converged_peak_force, r.faces_for_three_edges()});
  }
  tables::write_csv(file,
                    {"particle", "resolution", "mean_edge", "local_radius", "contact_radius",
                     "contact_over_edge", "converged_peak_force", "faces_for_three_edges"},
                    table);
}

void write_summary(const std::vector<Row>& rows, const fs::path& file) {
  std::map<long, std::vector<const Row*>> by_n;
  for (const Row& r : rows) by_n[r.resolution].push_back(&r);
  std::vector<std::vector<tables::OJson>> table;
  for (const auto& [n, here] : by_n) {
    std::vector<double> ratio, faces;
    for (const Row* r : here) {
      ratio.push_back(r->contact_over_edge());
      faces.push_back(r->faces_for_three_edges());
    }
    table.push_back({n, static_cast<long>(here.size()), quantile(ratio, 0.5),
                     *std::max_element(ratio.begin(), ratio.end()), quantile(faces, 0.5)});
  }
  tables::write_csv(file,
                    {"resolution", "particles", "contact_over_edge_median", "contact_over_edge_max",
                     "faces_for_three_edges_median"},
                    table);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: contact_edge_ratio STUDY.json DIR ROWS.csv SUMMARY.csv\n");
    return 2;
  }
  const fs::path dir = argv[2];
  try {
    const StudyDef def = load_study(argv[1]);
    // DIR/study.json, written by the run, must be this definition's (study_run.hpp).
    if (!fs::exists(dir / "study.json")) throw InputError((dir / "study.json").string() + ": none");
    adopt_folder(def, dir);
    const tables::StudyCases cases = tables::load_study_cases(def, dir);
    const std::vector<Row> found = rows(def, cases, dir);
    if (found.empty()) {
      std::fprintf(stderr,
                   "contact_edge_ratio: %s: no particle with a converged fem answer and a "
                   "sphere-local case\n",
                   dir.string().c_str());
      return 2;
    }
    write_rows(found, argv[3]);
    write_summary(found, argv[4]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "contact_edge_ratio: %s: not a study folder (%s)\n", dir.string().c_str(),
                 e.what());
    return 2;
  }
  return 0;
}
