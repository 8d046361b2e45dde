// Running a particle-geometry study: particles × resolutions × models × placements, each case a
// scene run to its end, in a pool of worker threads, resumable and failure-tolerant.
//
// Layout of the study folder DIR (docs/study.md):
//   DIR/study.json                      the resolved study definition
//   DIR/particles/P.off                 each particle's source surface (scaled and rotated)
//   DIR/meshes/P/N/surface.off          P simplified to exactly N triangles; mesh.json beside it
//                                        (geometry::mesh_report plus the study's placement data)
//   DIR/cases/P/MODEL-N-PLACEMENT/      one case: scene.json (its input, written first), the
//                                        run's summary.json, force.csv, energy.csv, and case.json
//                                        (written last: the done marker); a failed case has
//                                        failed.json instead and is retried on the next run
//   (sphere cases are named sphere-PLACEMENT)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "study/study_def.hpp"

namespace asperity::study {

struct StudyRunOptions {
  int jobs = 0;        // worker threads; 0: the study's "jobs", else every core
  bool quiet = false;  // no progress line
};

struct StudyOutcome {
  int cases = 0, ran = 0, skipped = 0, failed = 0;
  double wall_seconds = 0;
  double cpu_seconds = 0;  // summed thread CPU of the cases run now (meshing included)
};

// One case of the study, as the runner plans it.
struct CaseKey {
  std::string particle;
  ModelKind model = ModelKind::fem;
  long resolution = 0;  // 0 for the sphere
  Placement placement = Placement::centroid;
  std::string dir_name() const;  // MODEL-N-PLACEMENT or sphere-PLACEMENT
};

// Every case of the study, in a fixed order (particle, model, resolution, placement).
std::vector<CaseKey> plan_cases(const StudyDef& def);

// Runs every case not already done. Throws InputError for a particle that cannot be read or
// meshed at every resolution (nothing is run then); a case that fails is recorded and the rest
// go on.
StudyOutcome run_study(const StudyDef& def, const std::filesystem::path& out,
                       const StudyRunOptions& options);

// Hertz contact time of a sphere (radius R, mass m) striking a rigid-backed elastic half-space at
// speed v: t_c = 2.868 (m² / (R E*² v))^{1/5} (Johnson 1985, §11.4), s. Used to size "auto"
// durations.
double hertz_contact_time(double radius, double mass, double effective_young, double speed);

}  // namespace asperity::study
