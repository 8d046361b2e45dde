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

std::string key_of(const std::string& p, ModelKind m, long n, Placement pl, int level = 0) {
  return p + "|" + model_name(m) + "|" + std::to_string(n) + "|" + placement_name(pl) + "|" +
         std::to_string(level);
}
std::string seq_key(const std::string& p, long n, Placement pl) {
  return p + "|" + std::to_string(n) + "|" + placement_name(pl);
}

// a against b, per metric (FemErrors): relative errors, and the first-contact shift over b's
// contact duration.
FemErrors compare(const CaseData& a, const CaseData& b) {
  FemErrors e;
  e.peak = rel_err(a.summary["peak_force"], b.summary["peak_force"]);
  e.impulse = rel_err(a.summary["impulse"], b.summary["impulse"]);
  e.duration = rel_err(a.summary["contact_duration"], b.summary["contact_duration"]);
  const OJson &ta = a.summary["first_contact_time"], &tb = b.summary["first_contact_time"],
              &d = b.summary["contact_duration"];
  if (ta.is_number() && tb.is_number() && d.is_number() && d.get<double>() > 0) {
    e.arrival = (ta.get<double>() - tb.get<double>()) / d.get<double>();
  }
  return e;
}

FemErrors abs_of(const FemErrors& e) {
  return {std::abs(e.peak), std::abs(e.impulse), std::abs(e.duration), std::abs(e.arrival)};
}

// The refinement sequences (fem), the references, and each case's errors against them.
void settle(StudyCases& s) {
  const StudyDef& def = s.def;
  s.err_fem.assign(s.cases.size(), {});
  s.discretization_error.assign(s.cases.size(), std::nan(""));
  if (!s.has_fem_reference()) return;
  const int levels = static_cast<int>(def.refinement.sizes.size());
  for (const ParticleSource& p : def.particles) {
    for (Placement pl : def.placements) {
      for (long n : def.resolutions) {
        // The usable levels, coarse first; the answer is the finest.
        std::vector<const CaseData*> seq;
        const int top = def.refinement.applies(n, pl) ? levels : 0;
        for (int l = 0; l <= top; ++l) {
          const CaseData* c = s.find(p.name, ModelKind::fem, n, pl, l);
          if (StudyCases::usable(c)) seq.push_back(c);
        }
        if (seq.empty()) continue;
        Sequence q;
        q.answer = s.index_of(*seq.back());
        q.levels = static_cast<int>(seq.size());
        if (seq.size() >= 2) {
          q.change = abs_of(compare(*seq[seq.size() - 2], *seq.back()));
          q.converged = seq.size() >= 2 && seq.back()->key.level > 0 &&
                        q.change.peak < def.refinement.tolerance;
        }
        const CaseData& answer = s.cases[q.answer];
        for (int l = 0; l <= top; ++l) {
          const CaseData* c = s.find(p.name, ModelKind::fem, n, pl, l);
          if (StudyCases::usable(c)) {
            s.discretization_error[s.index_of(*c)] =
                rel_err(c->summary["peak_force"], answer.summary["peak_force"]);
          }
        }
        s.sequences[seq_key(p.name, n, pl)] = q;
      }
      // The reference: the answer at the finest resolution; the geometry's share of its
      // uncertainty from the next coarser resolution that has a sequence.
      const Sequence* ref = s.sequence(p.name, def.reference, pl);
      if (!ref) continue;
      StudyCases::Reference r;
      r.index = ref->answer;
      r.discretization = ref->change;
      for (auto it = def.resolutions.rbegin() + 1; it < def.resolutions.rend(); ++it) {
        const Sequence* prev = s.sequence(p.name, *it, pl);
        if (prev && (prev->levels > 1) == (ref->levels > 1)) {
          r.geometry = abs_of(compare(s.cases[prev->answer], s.cases[ref->answer]));
          break;
        }
      }
      const auto hyp = [](double a, double b) {
        return std::hypot(std::isfinite(a) ? a : 0.0, std::isfinite(b) ? b : 0.0);
      };
      r.uncertainty = {hyp(r.discretization.peak, r.geometry.peak),
                       hyp(r.discretization.impulse, r.geometry.impulse),
                       hyp(r.discretization.duration, r.geometry.duration),
                       hyp(r.discretization.arrival, r.geometry.arrival)};
      s.references[std::string(p.name) + "|" + placement_name(pl)] = r;
    }
  }
  for (std::size_t i = 0; i < s.cases.size(); ++i) {
    const CaseData& c = s.cases[i];
    const StudyCases::Reference* r = s.reference(c.key.particle, c.key.placement);
    if (r && StudyCases::usable(&c)) s.err_fem[i] = compare(c, s.cases[r->index]);
  }
}

}  // namespace

const CaseData* StudyCases::find(const std::string& particle, ModelKind m, long resolution,
                                 Placement pl, int level) const {
  const auto it = index.find(key_of(particle, m, resolution, pl, level));
  return it == index.end() ? nullptr : &cases[it->second];
}

const Sequence* StudyCases::sequence(const std::string& particle, long resolution,
                                     Placement pl) const {
  const auto it = sequences.find(seq_key(particle, resolution, pl));
  return it == sequences.end() ? nullptr : &it->second;
}

const StudyCases::Reference* StudyCases::reference(const std::string& particle,
                                                   Placement pl) const {
  const auto it = references.find(particle + "|" + placement_name(pl));
  return it == references.end() ? nullptr : &it->second;
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
    s.index[key_of(k.particle, k.model, k.resolution, k.placement, k.level)] = s.cases.size();
    s.cases.push_back(std::move(c));
  }
  settle(s);
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
