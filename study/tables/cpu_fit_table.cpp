// cpu_fit.csv: the CPU cost against the resolution, t = C N^p (docs/study.md, "Tables").
#include <cmath>

#include "solver/core/least_squares.hpp"
#include "solver/core/quantile.hpp"
#include "study/tables/tables.hpp"

namespace asperity::study::tables {

std::vector<CpuFit> fit_cpu(const StudyCases& s) {
  const StudyDef& def = s.def;
  std::vector<CpuFit> fits;
  for (ModelKind m : def.models) {
    if (is_sphere(m)) continue;
    for (Placement pl : def.placements) {
      // log N and log of the median CPU across particles, per resolution with any CPU.
      std::vector<double> lx, ly;
      for (long n : def.resolutions) {
        std::vector<double> cpu;
        for (const ParticleSource& p : def.particles) {
          const CaseData* c = s.find(p.name, m, n, pl);
          if (StudyCases::usable(c) && c->cpu > 0) cpu.push_back(c->cpu);
        }
        if (cpu.empty()) continue;
        lx.push_back(std::log(static_cast<double>(n)));
        ly.push_back(std::log(quantile(cpu, 0.5)));
      }
      if (lx.size() < 2) continue;
      const LineFit line = fit_line(lx, ly);
      fits.push_back({.model = m,
                      .placement = pl,
                      .exponent = line.slope,
                      .coefficient = std::exp(line.intercept),
                      .points = line.points});
    }
  }
  return fits;
}

void write_cpu_fit_table(const std::vector<CpuFit>& fits, const std::filesystem::path& dir) {
  std::vector<std::vector<OJson>> rows;
  for (const CpuFit& f : fits) {
    rows.push_back(
        {model_name(f.model), placement_name(f.placement), f.exponent, f.coefficient, f.points});
  }
  write_csv(dir / "cpu_fit.csv", {"model", "placement", "exponent", "coefficient", "points"}, rows);
}

}  // namespace asperity::study::tables
