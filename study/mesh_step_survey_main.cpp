// mesh_step_survey STUDY.json --out DIR: every particle of the study meshed at every resolution
// and its predicted critical step set against h/c (study/mesh_step_survey.hpp); writes
// DIR/mesh_step.csv (one row per mesh) and DIR/mesh_step.md (the distribution). Makes
// reports/fem/mesh_step.md from data/study/full.json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "solver/core/error.hpp"
#include "solver/core/quantile.hpp"
#include "solver/io/atomic_file.hpp"
#include "study/mesh_step_survey.hpp"
#include "study/study_def.hpp"

namespace fs = std::filesystem;
using asperity::study::MeshStep;

namespace {

std::string num(double v, const char* f = "%.3g") {
  char b[32];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// min, median (solver/core/quantile.hpp), max of `v`; zeros for none.
struct Spread {
  double min = 0, median = 0, max = 0;
};
Spread spread(const std::vector<double>& v) {
  if (v.empty()) return {};
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return {*lo, asperity::quantile(v, 0.5), *hi};
}

std::string spread_cells(const std::vector<double>& v) {
  const Spread s = spread(v);
  return num(s.min) + " | " + num(s.median) + " | " + num(s.max);
}

std::string table(const std::vector<MeshStep>& rows, const std::vector<long>& resolutions,
                  bool all_fixes) {
  std::ostringstream md;
  md << "| N faces | meshes | failed | dt_element·c/h min | median | max | α = 10: dt·c/h min | "
        "median | max | contact factor min | median | max | face-penalty (default): dt·c/h min | "
        "median | max | contact factor max | least penalty factor min | median |"
     << (all_fixes ? " one penalty: contact factor max | α left min | median | contact mass: "
                     "contact factor max | Δm/m median | max |"
                   : "")
     << "\n";
  for (int k = 0; k < (all_fixes ? 24 : 18); ++k) md << "| ---: ";
  md << "|\n";
  auto line = [&](const std::string& label, long n) {
    std::vector<double> e, c, k, a, fr, ff, fs, lf, mf, ma;
    int failed = 0;
    for (const MeshStep& r : rows) {
      if (n > 0 && r.faces != n) continue;
      if (!r.error.empty()) {
        ++failed;
        continue;
      }
      e.push_back(r.element_ratio());
      c.push_back(r.critical_ratio());
      k.push_back(r.contact_factor());
      a.push_back(r.alpha_limited);
      fr.push_back(r.face_ratio());
      ff.push_back(r.face_factor());
      fs.push_back(r.face_scale_min);
      lf.push_back(r.limited_factor());
      mf.push_back(r.mass_factor());
      ma.push_back(r.mass_added);
    }
    const Spread sfs = spread(fs), sa = spread(a), sma = spread(ma);
    md << "| " << label << " | " << e.size() + static_cast<std::size_t>(failed) << " | " << failed
       << " | " << spread_cells(e) << " | " << spread_cells(c) << " | " << spread_cells(k) << " | "
       << spread_cells(fr) << " | " << num(spread(ff).max) << " | " << num(sfs.min) << " | "
       << num(sfs.median) << " |";
    if (all_fixes) {
      md << " " << num(spread(lf).max) << " | " << num(sa.min) << " | " << num(sa.median) << " | "
         << num(spread(mf).max) << " | " << num(sma.median) << " | " << num(sma.max) << " |";
    }
    md << "\n";
  };
  for (const long n : resolutions) line(std::to_string(n), n);
  line("all", 0);
  return md.str();
}

int run(int argc, char** argv) {
  const std::string usage =
      "usage: mesh_step_survey STUDY.json --out DIR [--all-fixes] [--particles FIRST:COUNT]\n";
  if (argc < 4 || std::string(argv[2]) != "--out") {
    std::cerr << usage;
    return 2;
  }
  bool all_fixes = false;
  std::size_t first = 0, count = static_cast<std::size_t>(-1);
  for (int i = 4; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--all-fixes") {
      all_fixes = true;
    } else if (a == "--particles" && i + 1 < argc) {
      const std::string v = argv[++i];
      const std::size_t colon = v.find(':');
      if (colon == std::string::npos) {
        std::cerr << "mesh_step_survey: --particles: expected FIRST:COUNT, got " << v << "\n";
        return 2;
      }
      first = std::stoul(v.substr(0, colon));
      count = std::stoul(v.substr(colon + 1));
    } else {
      std::cerr << usage;
      return 2;
    }
  }
  const asperity::study::StudyDef def = asperity::study::load_study(argv[1]);
  const fs::path out = argv[3];
  fs::create_directories(out);
  std::vector<MeshStep> rows;
  std::ostringstream csv;
  csv << "particle,faces,tets,h,c,dt_element,dt_contact,dt_critical,limited_by,"
         "dt_limited,alpha_limited,dt_critical_study_alpha,element_ratio,critical_ratio,contact_"
         "factor,"
         "limited_ratio,dt_face,face_factor,face_scale_min,dt_mass,mass_factor,mass_added,"
         "cpu_seconds,error\n";
  for (std::size_t i = first; i < def.particles.size() && i - first < count; ++i) {
    for (const MeshStep& r : asperity::study::mesh_steps(def, i, def.resolutions, all_fixes)) {
      std::cerr << r.particle << " " << r.faces << ": dt c/h " << r.critical_ratio() << " (element "
                << r.element_ratio() << ", contact factor " << r.contact_factor()
                << ", limited: dt c/h " << r.limited_ratio() << " alpha " << r.alpha_limited
                << ", face factor " << r.face_factor() << " scale " << r.face_scale_min
                << ", mass factor " << r.mass_factor() << " added " << r.mass_added << ")"
                << (r.error.empty() ? "" : " FAILED: " + r.error) << "\n";
      csv << r.particle << "," << r.faces << "," << r.tets << "," << num(r.h, "%.6g") << ","
          << num(r.c, "%.6g") << "," << num(r.dt_element, "%.6g") << ","
          << num(r.dt_contact, "%.6g") << "," << num(r.dt_critical, "%.6g") << "," << r.limited_by
          << "," << num(r.dt_limited, "%.6g") << "," << num(r.alpha_limited, "%.4g") << ","
          << num(r.dt_critical_study, "%.6g") << "," << num(r.element_ratio(), "%.4g") << ","
          << num(r.critical_ratio(), "%.4g") << "," << num(r.contact_factor(), "%.4g") << ","
          << num(r.limited_ratio(), "%.4g") << "," << num(r.dt_face, "%.6g") << ","
          << num(r.face_factor(), "%.4g") << "," << num(r.face_scale_min, "%.4g") << ","
          << num(r.dt_mass, "%.6g") << "," << num(r.mass_factor(), "%.4g") << ","
          << num(r.mass_added, "%.4g") << "," << num(r.seconds, "%.3g") << ",\"" << r.error
          << "\"\n";
      rows.push_back(r);
    }
  }
  asperity::io::write_atomically(out / "mesh_step.csv", csv.str());
  asperity::io::write_atomically(out / "mesh_step.md", table(rows, def.resolutions, all_fixes));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const asperity::InputError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mesh_step_survey: " << e.what() << "\n";
    return 1;
  }
}
