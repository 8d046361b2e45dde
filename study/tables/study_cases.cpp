// A study's case folders loaded once for its tables (tables/study_cases.hpp).
#include "study/tables/study_cases.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"
#include "study/source_reference.hpp"

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

FemErrors abs_of(const FemErrors& e) {
  return {std::abs(e.peak), std::abs(e.impulse), std::abs(e.duration), std::abs(e.arrival)};
}

double number(const OJson& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::nan("");
}
Measures measures_of(const CaseData& c) {
  return {number(c.summary, "peak_force"), number(c.summary, "impulse"),
          number(c.summary, "contact_duration"), number(c.summary, "first_contact_time")};
}
double rel(double a, double b) {
  return std::isfinite(a) && std::isfinite(b) && b != 0 ? (a - b) / b : std::nan("");
}
// a against reference values b (compare's measures).
FemErrors compare(const CaseData& a, const Measures& b) {
  const Measures m = measures_of(a);
  FemErrors e{rel(m.peak, b.peak), rel(m.impulse, b.impulse), rel(m.duration, b.duration)};
  if (std::isfinite(m.first_contact) && std::isfinite(b.first_contact) && b.duration > 0) {
    e.arrival = (m.first_contact - b.first_contact) / b.duration;
  }
  return e;
}
FemErrors compare(const Measures& a, const Measures& b) {
  FemErrors e{rel(a.peak, b.peak), rel(a.impulse, b.impulse), rel(a.duration, b.duration)};
  if (std::isfinite(a.first_contact) && std::isfinite(b.first_contact) && b.duration > 0) {
    e.arrival = (a.first_contact - b.first_contact) / b.duration;
  }
  return e;
}

// The sequence's limit: its refined levels (level > 0) extrapolated per metric; the first-contact
// time is not (it is the free flight's, the same at every level within steps): the answer's, with
// its last change as the error.
void extrapolate(Sequence& q, const std::vector<const CaseData*>& seq) {
  const CaseData& answer = *seq.back();
  q.limit = measures_of(answer);
  q.limit_error = q.change;
  std::vector<const CaseData*> refined;
  for (const CaseData* c : seq) {
    if (c->key.level > 0) refined.push_back(c);
  }
  q.refined = static_cast<int>(refined.size());
  if (refined.size() < 2 || refined.back() != &answer) return;
  std::vector<double> sizes;
  for (const CaseData* c : refined) sizes.push_back(c->key.relative_size);
  auto along = [&](double Measures::*field, double* limit, double* error) {
    std::vector<double> v;
    for (const CaseData* c : refined) v.push_back(measures_of(*c).*field);
    const Extrapolation e = richardson(sizes, v);
    *limit = e.limit;
    *error = e.error;
    return e;
  };
  q.peak = along(&Measures::peak, &q.limit.peak, &q.limit_error.peak);
  along(&Measures::impulse, &q.limit.impulse, &q.limit_error.impulse);
  along(&Measures::duration, &q.limit.duration, &q.limit_error.duration);
  q.extrapolated = true;
}

// Per metric quadrature_sum (study_cases.hpp): √(a² + b²), a term that is not finite counting 0.
FemErrors quadrature(const FemErrors& a, const FemErrors& b) {
  return {quadrature_sum(a.peak, b.peak), quadrature_sum(a.impulse, b.impulse),
          quadrature_sum(a.duration, b.duration), quadrature_sum(a.arrival, b.arrival)};
}

// The source reference of a particle and placement (StudyCases::Reference, "source"): every level
// on the patch usable (the fourth too where plan_source_cases planned one), else none; the doubled
// patch's levels when they all are. With four levels the limit is the last three's.
std::optional<StudyCases::Reference> source_reference_of(const StudyCases& s,
                                                         const std::string& particle,
                                                         Placement pl) {
  std::vector<SourceLevel> near, wide;  // the levels on the patch, on the doubled patch
  std::vector<double> sizes;
  std::vector<const CaseData*> patch;
  bool wide_complete = true;
  double cpu = 0;  // every level's, on both patches
  for (const CaseData& c : s.source_cases) {
    if (c.key.particle != particle || c.key.placement != pl) continue;
    if (std::isfinite(c.cpu)) cpu += c.cpu;
    if (!StudyCases::usable(&c)) {
      if (c.key.source_patch == 1) return std::nullopt;
      wide_complete = false;
      continue;
    }
    const Measures m = measures_of(c);
    const SourceLevel l =
        source_level(number(c.summary, "peak_force_filtered"), m.impulse, m.duration);
    if (c.key.source_patch == 1) {
      near.push_back(l);
      patch.push_back(&c);
      sizes.push_back(c.record.value("element_size_rel", std::nan("")));
    } else {
      wide.push_back(l);
    }
  }
  const int levels = static_cast<int>(patch.size());
  if (levels < SourceReferenceOptions{}.levels) return std::nullopt;
  const bool doubled = wide_complete && wide.size() == patch.size();
  const SourceReference ref =
      source_reference(sizes, near, doubled ? wide : std::vector<SourceLevel>{});
  StudyCases::Reference r;
  r.kind = ReferenceKind::source;
  r.index = s.index_of_source(*patch.back());
  r.levels = levels;
  r.limit_from = levels - 2;
  r.finest_size = sizes.back();
  r.cpu = cpu;
  r.peak = ref.peak_force.limit;
  r.source_limit[0] = ref.peak_force.limit;
  r.source_limit[1] = ref.impulse.limit;
  r.source_limit[2] = ref.contact_duration.limit;
  r.patch_checked = doubled;
  const Measures finest = measures_of(*patch.back()),
                 before = measures_of(*patch[patch.size() - 2]);
  r.values = {ref.peak_force.limit.limit, ref.impulse.limit.limit, ref.contact_duration.limit.limit,
              finest.first_contact};
  r.discretization = {ref.peak_force.discretization, ref.impulse.discretization,
                      ref.contact_duration.discretization,
                      std::abs(finest.first_contact - before.first_contact) / r.values.duration};
  r.patch = {ref.peak_force.patch_change, ref.impulse.patch_change,
             ref.contact_duration.patch_change};
  // The source metrics' own uncertainty (source_reference.hpp); the first contact's, its last
  // change.
  r.uncertainty = {ref.peak_force.uncertainty, ref.impulse.uncertainty,
                   ref.contact_duration.uncertainty, quadrature_sum(r.discretization.arrival, 0)};
  return r;
}

// The refinement sequences (fem), the references, and each case's errors against them.
void settle(StudyCases& s) {
  const StudyDef& def = s.def;
  s.err_fem.assign(s.cases.size(), {});
  s.discretization_error.assign(s.cases.size(), std::nan(""));
  if (!s.has_reference()) return;
  const int levels = static_cast<int>(def.refinement.sizes.size());
  for (const ParticleSource& p : def.particles) {
    for (Placement pl : def.placements) {
      if (def.reference_kind == ReferenceKind::source) {
        if (const std::optional<StudyCases::Reference> r = source_reference_of(s, p.name, pl))
          s.references[std::string(p.name) + "|" + placement_name(pl)] = *r;
      }
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
          q.change = abs_of(compare(*seq[seq.size() - 2], measures_of(*seq.back())));
          q.converged = seq.size() >= 2 && seq.back()->key.level > 0 &&
                        q.change.peak < def.refinement.tolerance;
        }
        extrapolate(q, seq);
        // The discretization error of every level: its peak against the sequence's limit.
        for (const CaseData* c : seq) {
          s.discretization_error[s.index_of(*c)] = rel(measures_of(*c).peak, q.limit.peak);
        }
        s.sequences[seq_key(p.name, n, pl)] = q;
      }
      // The reference: the limit at the finest resolution; the geometry's share of its
      // uncertainty from the next coarser resolution that has a sequence of the same kind.
      const Sequence* ref = s.sequence(p.name, def.reference, pl);
      if (!ref || def.reference_kind != ReferenceKind::finest) continue;
      StudyCases::Reference r;
      r.index = ref->answer;
      r.resolution = def.reference;
      r.levels = ref->levels;
      r.peak = ref->peak;
      r.values = ref->limit;
      r.discretization = ref->limit_error;
      for (auto it = def.resolutions.rbegin() + 1; it < def.resolutions.rend(); ++it) {
        const Sequence* prev = s.sequence(p.name, *it, pl);
        if (prev && (prev->levels > 1) == (ref->levels > 1)) {
          r.geometry = abs_of(compare(prev->limit, ref->limit));
          r.geometry_resolution = *it;
          break;
        }
      }
      r.uncertainty = quadrature(r.discretization, r.geometry);
      s.references[std::string(p.name) + "|" + placement_name(pl)] = r;
    }
  }
  for (std::size_t i = 0; i < s.cases.size(); ++i) {
    const CaseData& c = s.cases[i];
    const StudyCases::Reference* r = s.reference(c.key.particle, c.key.placement);
    if (r && StudyCases::usable(&c)) s.err_fem[i] = compare(c, r->values);
  }
}

}  // namespace

Extrapolation richardson(const std::vector<double>& sizes, const std::vector<double>& values) {
  Extrapolation e;
  const std::size_t n = values.size();
  if (n < 2 || sizes.size() != n) return e;
  for (double v : values) {
    if (!std::isfinite(v)) return e;
  }
  const double v3 = values[n - 1], v2 = values[n - 2];
  if (n >= 3) {
    // Observed order of the last three: (v1 − v2)/(v2 − v3) = (s1^p − s2^p)/(s2^p − s3^p), which
    // grows with p; bisection (the sizes need not halve).
    const double v1 = values[n - 3], s1 = sizes[n - 3], s2 = sizes[n - 2], s3 = sizes[n - 1];
    const double d1 = v2 - v1, d2 = v3 - v2;
    if (d1 * d2 > 0 && std::abs(d2) < std::abs(d1)) {
      const double target = d1 / d2;
      const auto ratio = [&](double p) {
        return (std::pow(s1, p) - std::pow(s2, p)) / (std::pow(s2, p) - std::pow(s3, p));
      };
      double lo = 1e-3, hi = 20;  // the sizes are at most 1 (of R): no overflow
      for (int it = 0; it < 100; ++it) {
        const double mid = 0.5 * (lo + hi);
        (ratio(mid) < target ? lo : hi) = mid;
      }
      const double p = 0.5 * (lo + hi);
      e.changes_order = p;
      if (p >= kObservedOrderMin && p <= kObservedOrderMax) {
        e.weight = 1 / (std::pow(s2 / s3, p) - 1);
        const double correction = e.weight * d2;
        e.limit = v3 + correction;
        e.error = kSafetyObserved * std::abs(correction) / std::abs(e.limit);
        e.order = p;
        e.observed = true;
        return e;
      }
    }
  }
  // The two finest levels at both ends of the assumed bracket.
  const double r = sizes[n - 2] / sizes[n - 1], d = v3 - v2;
  const double lo = v3 + d / (std::pow(r, kAssumedOrderLow) - 1),
               hi = v3 + d / (std::pow(r, kAssumedOrderHigh) - 1);
  e.limit = 0.5 * (lo + hi);
  e.error = e.limit != 0 ? 0.5 * std::abs(lo - hi) / std::abs(e.limit) : std::nan("");
  e.order = 0.5 * (kAssumedOrderLow + kAssumedOrderHigh);
  e.weight =
      0.5 * (1 / (std::pow(r, kAssumedOrderLow) - 1) + 1 / (std::pow(r, kAssumedOrderHigh) - 1));
  return e;
}

double extrapolate_like(const std::vector<double>& values, const Extrapolation& like) {
  const std::size_t n = values.size();
  if (n < 2 || !std::isfinite(like.weight)) return std::nan("");
  const double v3 = values[n - 1], v2 = values[n - 2];
  if (!std::isfinite(v3) || !std::isfinite(v2)) return std::nan("");
  return v3 + like.weight * (v3 - v2);
}

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

bool StudyCases::has_reference() const {
  return has_fem_reference() || def.reference_kind == ReferenceKind::source;
}

namespace {

// One case folder: its status, summary.json and case.json, or failed.json.
CaseData load_case(const CaseKey& k, const fs::path& dir, StudyCases& s) {
  CaseData c;
  c.key = k;
  c.dir = case_dir(dir, k);
  if (fs::exists(c.dir / "case.json")) {
    c.summary = OJson::parse(io::read_json_file(c.dir / "summary.json").dump());
    c.status = c.summary.value("status", "missing");
    c.record = OJson::parse(io::read_json_file(c.dir / "case.json").dump());
    c.cpu = c.record.value("cpu_seconds", std::nan(""));
    c.start_gap = c.record.value("start_gap", std::nan(""));
    ++s.done;
  } else if (fs::exists(c.dir / "failed.json")) {
    c.status = "failed";
    c.message = io::read_json_file(c.dir / "failed.json").value("message", "");
    ++s.failed;
  } else {
    c.status = "missing";
  }
  return c;
}

}  // namespace

StudyCases load_study_cases(const StudyDef& def, const fs::path& dir) {
  StudyCases s{.def = def};
  for (const CaseKey& k : plan_source_cases(def, dir))
    s.source_cases.push_back(load_case(k, dir, s));
  for (const CaseKey& k : plan_cases(def)) {
    CaseData c = load_case(k, dir, s);
    const long faces = is_sphere(k.model) ? def.reference : k.resolution;
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
  return is_sphere(m) ? OJson() : OJson(resolution);
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
