// A study's case folders loaded once for its tables (tables/study_cases.hpp).
#include "study/tables/study_cases.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/json_file.hpp"

namespace asperity::study::tables {
namespace fs = std::filesystem;
namespace {

std::string key_of(const std::string& p, ModelKind m, long n, Placement pl) {
  return p + "|" + model_name(m) + "|" + std::to_string(n) + "|" + placement_name(pl);
}

// Each case's error against the fem reference (same particle and placement).
std::vector<FemErrors> errors_against_fem(const StudyCases& s) {
  std::vector<FemErrors> err(s.cases.size());
  for (std::size_t i = 0; i < s.cases.size(); ++i) {
    const CaseData& c = s.cases[i];
    const CaseData* fem = s.find(c.key.particle, ModelKind::fem, s.def.reference, c.key.placement);
    if (StudyCases::usable(&c) && StudyCases::usable(fem)) {
      err[i].peak = rel_err(c.summary["peak_force"], fem->summary["peak_force"]);
      err[i].impulse = rel_err(c.summary["impulse"], fem->summary["impulse"]);
    }
  }
  return err;
}

}  // namespace

const CaseData* StudyCases::find(const std::string& particle, ModelKind m, long resolution,
                                 Placement pl) const {
  const auto it = index.find(key_of(particle, m, resolution, pl));
  return it == index.end() ? nullptr : &cases[it->second];
}

bool StudyCases::has_fem_reference() const {
  return std::find(def.models.begin(), def.models.end(), ModelKind::fem) != def.models.end();
}

StudyCases load_study_cases(const StudyDef& def, const fs::path& dir) {
  StudyCases s{.def = def};
  for (const CaseKey& k : plan_cases(def)) {
    CaseData c;
    c.key = k;
    c.dir = dir / "cases" / k.particle / k.dir_name();
    if (fs::exists(c.dir / "case.json")) {
      const io::Json rec = io::read_json_file(c.dir / "case.json");
      c.summary = OJson::parse(io::read_json_file(c.dir / "summary.json").dump());
      c.status = c.summary.value("status", "missing");
      c.cpu = c.summary.value("cpu_seconds_thread", std::nan(""));
      c.start_gap = rec.value("start_gap", std::nan(""));
      ++s.done;
    } else if (fs::exists(c.dir / "failed.json")) {
      c.status = "failed";
      c.message = io::read_json_file(c.dir / "failed.json").value("message", "");
      ++s.failed;
    } else {
      c.status = "missing";
    }
    const long faces = k.model == ModelKind::sphere ? def.reference : k.resolution;
    const fs::path mj = dir / "meshes" / k.particle / std::to_string(faces) / "mesh.json";
    if (fs::exists(mj)) c.mesh = OJson::parse(io::read_json_file(mj).dump());
    s.index[key_of(k.particle, k.model, k.resolution, k.placement)] = s.cases.size();
    s.cases.push_back(std::move(c));
  }
  s.err_fem = errors_against_fem(s);
  return s;
}

Curve read_force(const fs::path& file) {
  Curve c;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);  // t,fx,fy,fz,f
  while (std::getline(in, line)) {
    double v[5];
    char comma;
    std::istringstream s(line);
    s >> v[0] >> comma >> v[1] >> comma >> v[2] >> comma >> v[3] >> comma >> v[4];
    if (!s) continue;
    c.t.push_back(v[0]);
    c.f.push_back(v[4]);
  }
  return c;
}

OJson num_or_null(const OJson& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key] : OJson();
}

double rel_err(const OJson& v, const OJson& ref) {
  if (!v.is_number() || !ref.is_number() || ref.get<double>() == 0) return std::nan("");
  return (v.get<double>() - ref.get<double>()) / ref.get<double>();
}

OJson finite_or_null(double x) {
  return std::isfinite(x) ? OJson(x) : OJson();
}

OJson resolution_or_null(ModelKind m, long resolution) {
  return m == ModelKind::sphere ? OJson() : OJson(resolution);
}

void write_csv(const fs::path& file, const std::vector<std::string>& header,
               const std::vector<std::vector<OJson>>& rows) {
  io::CsvWriter w(header);
  for (const auto& row : rows) {
    for (const OJson& v : row) {
      w.field(v.is_null() ? std::string() : v.is_string() ? v.get<std::string>() : v.dump());
    }
    w.end_row();
  }
  io::write_atomically(file, w.str());
}

}  // namespace asperity::study::tables
