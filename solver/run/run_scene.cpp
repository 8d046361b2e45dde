// Scene → its model's runner; the contract's output files.
#include "solver/run/run_scene.hpp"

#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/run/run_fdem.hpp"
#include "solver/run/run_spheres.hpp"

namespace asperity::run {

RunResult run_scene(const scene::SceneDef& s, const RunOptions& options) {
  return is_fdem_scene(s) ? run_fdem(s, options) : run_spheres(s, options);
}

StepChoice predicted_step(const scene::SceneDef& s, const RunOptions& options) {
  return is_fdem_scene(s) ? fdem_step(s, options) : sphere_step(s, options);
}

using io::write_atomically;

void write_outputs(const RunResult& r, const std::filesystem::path& out) {
  std::filesystem::create_directories(out);
  if (r.status == "unstable") {
    // An unstable history is not a result: drop any earlier run's curves so none is mistaken
    // for this run's.
    std::filesystem::remove(out / "force.csv");
    std::filesystem::remove(out / "energy.csv");
  } else {
    io::CsvWriter f({"t", "fx", "fy", "fz", "f"});
    for (const ForceRow& row : r.force) {
      f.number(row.t).number(row.fx).number(row.fy).number(row.fz).number(row.f).end_row();
    }
    write_atomically(out / "force.csv", f.str());
    io::CsvWriter e({"t", "kinetic", "elastic", "contact", "gravity", "dissipated", "total"});
    for (const EnergyRow& row : r.energy) {
      e.number(row.t).number(row.kinetic).number(row.elastic).number(row.contact);
      e.number(row.gravity).number(row.dissipated).number(row.total).end_row();
    }
    write_atomically(out / "energy.csv", e.str());
  }
  write_atomically(out / "summary.json", r.summary.dump(2) + "\n");
}

}  // namespace asperity::run
