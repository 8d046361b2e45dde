// Running a particle-geometry study: particles × resolutions × models × placements, each case a
// scene run to its end, in a pool of worker threads, resumable and failure-tolerant.
//
// Layout of the study folder DIR (docs/study.md):
//   DIR/study.json                      the resolved study definition, written by the first run;
//                                        a run of another definition is refused (adopt_folder)
//   DIR/particles/P.off                 each particle's source surface (scaled and rotated)
//   DIR/meshes/P/N/surface.off          P simplified to exactly N triangles; mesh.json beside it
//                                        (geometry::mesh_report plus the study's placement data)
//   DIR/cases/P/MODEL-N-PLACEMENT/      one case: scene.json (its input, written first), the
//                                        run's summary.json, force.csv, energy.csv, and case.json
//                                        (written last: the done marker); a failed case has
//                                        failed.json instead and is retried on the next run
//   (sphere cases are named sphere-PLACEMENT; a refined fem case fem-N-hSIZE-PLACEMENT, SIZE the
//   element size at the strike point over the equivalent radius)
#pragma once

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cluster/world.hpp"
#include "solver/core/interrupt.hpp"
#include "study/study_def.hpp"

namespace asperity::study {

// Shard K of N (`--shard K/N`, 1 <= K <= N): the particles whose place in the study is K−1
// modulo N, their meshes and their cases. Shards share no file, so a job array may run them side
// by side into one folder; count 0: the whole study.
struct Shard {
  int index = 0, count = 0;
};
// "K/N" → Shard; InputError "--shard: problem (got ...)" otherwise.
Shard parse_shard(const std::string& text);
// Indices (into def.particles) of the shard's particles.
std::vector<std::size_t> shard_particles(const StudyDef& def, const Shard& shard);

struct StudyRunOptions {
  int jobs = 0;        // worker threads per rank; 0: the study's "jobs", else every core
  bool quiet = false;  // no progress line
  Shard shard;
  cluster::World* world = nullptr;  // the ranks to run on; nullptr: joins the launch itself
  // A wall-clock deadline (`advise --budget`, `study --stop-after`): no mesh or case starts after
  // it, and a case running at it stops within 256 steps (run::RunOptions::stop_at). What it cut
  // is postponed, not failed: nothing of it is written as done, so the next run does it.
  std::optional<std::chrono::steady_clock::time_point> stop_at;
};

// StudyRunOptions::stop_at `minutes` of wall from now (`advise --budget`, `study --stop-after`);
// none for minutes ≤ 0.
std::optional<std::chrono::steady_clock::time_point> deadline_after(double minutes);

struct StudyOutcome {
  int cases = 0, ran = 0, skipped = 0, failed = 0;
  int postponed = 0;  // meshes and cases left for the next run by StudyRunOptions::stop_at
  double wall_seconds = 0;
  double cpu_seconds = 0;  // summed thread CPU of the cases run now (meshing included)
  // The cases phase on rank 0 (cluster::PoolStats): ranks, workers over all ranks, the share of
  // worker time left idle, and how long the end ran with idle workers.
  int ranks = 1, workers = 0;
  double idle_fraction = 0, drain_seconds = 0;
};

// One study at a time per folder (flock on DIR/study.lock, held while it lives): a whole run
// excludes any other; shards of a study may run side by side (InputError when taken).
class FolderLock {
 public:
  FolderLock(const std::filesystem::path& out, const Shard& shard);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  std::vector<int> fds_;
  std::vector<std::filesystem::path> files_;
  std::vector<std::unique_ptr<RemoveOnInterrupt>> on_interrupt_;
};

// Makes DIR the folder of this study definition: writes DIR/study.json on first use; InputError
// naming the first key that differs when DIR holds another definition's cases.
void adopt_folder(const StudyDef& def, const std::filesystem::path& out);

// One case of the study, as the runner plans it.
struct CaseKey {
  std::string particle;
  ModelKind model = ModelKind::fem;
  long resolution = 0;  // 0 for the sphere
  Placement placement = Placement::centroid;
  // fem only: 0 the coarse default (the surface triangles are the elements' faces), k ≥ 1 the
  // k-th size of the study's refinement sequence.
  int level = 0;
  double relative_size = 0;  // that size over the equivalent radius (0 at level 0)
  // The source reference's cases ("reference": "source"; model fem, resolution 0): 1 its levels
  // on the contact patch, 2 on the doubled patch (the patch check); `level` 1 to
  // SourceReferenceOptions::levels, coarsest first, or the fourth that the first three may ask
  // for (plan_source_cases with OUT). 0: a case of the study's own models.
  int source_patch = 0;
  // MODEL-N-PLACEMENT, fem-N-hSIZE-PLACEMENT, sphere-PLACEMENT, or source-LK-PLACEMENT
  // (source-patch2-LK-PLACEMENT on the doubled patch)
  std::string dir_name() const;
};

// Every case of the study's models, in a fixed order (particle, model, resolution, placement,
// level).
std::vector<CaseKey> plan_cases(const StudyDef& def);

// The source reference's cases (none unless "reference" is "source"): per particle and
// placement, its levels on the patch, then on the doubled patch when "reference_patch_check".
// Their meshes are DIR/meshes/P/source/ (and source-patch2/): the contact-local surface
// (surface.off) and the plan (mesh.json: strike point, Hertz contact radius, element sizes).
// These are the first round's levels (SourceReferenceOptions::levels).
std::vector<CaseKey> plan_source_cases(const StudyDef& def);
// Every level the source reference of OUT asks for: plan_source_cases(def) and, for each particle
// and placement whose levels on the patch all finished ("ok") with a peak force that shows no
// steady order (wants_finer_level), one more at half the finest size (source-L4-PLACEMENT, and
// source-patch2-L4-PLACEMENT with the patch check), up to "reference_max_levels". Read from the
// levels' summary.json and case.json alone, so a rerun of a folder plans the same, and the tables
// (tables::load_study_cases) load what the runner ran.
std::vector<CaseKey> plan_source_cases(const StudyDef& def, const std::filesystem::path& out);

// The folder of a case's files: OUT/cases/PARTICLE/CASE.
std::filesystem::path case_dir(const std::filesystem::path& out, const CaseKey& key);

// The cases of OUT (plan_cases and plan_source_cases with OUT) that neither finished (case.json)
// nor failed (failed.json): those of a shard that has not run, was cancelled or ran out of time.
int unfinished_cases(const StudyDef& def, const std::filesystem::path& out);

// Runs every case of the shard not already done, on every rank of `options.world` with
// `jobs` threads each, the most expensive first, handed out one at a time (docs/cluster.md).
// Throws InputError for a particle that cannot be read, a folder of another study or a folder in
// use; a mesh or case that fails is recorded and the rest go on. The phases: sources (every
// rank), folder adopted and sources written (rank 0), meshes, plans (every rank), cases, and a
// second round of cases for the source reference's fourth levels that the first round's levels
// ask for (rank 0 plans it from the folder and tells the others).
StudyOutcome run_study(const StudyDef& def, const std::filesystem::path& out,
                       const StudyRunOptions& options);

}  // namespace asperity::study
