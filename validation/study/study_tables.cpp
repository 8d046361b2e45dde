// Tables, classification, cost fit and guidelines from a study's case folders.
#include "study/study_tables.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/csv.hpp"
#include "io/json_file.hpp"

namespace asperity::study {
namespace fs = std::filesystem;
using OJson = nlohmann::ordered_json;

CurveShape curve_shape(const std::vector<double>& t, const std::vector<double>& f) {
  // Trapezoidal moments of t under the weight f.
  double m0 = 0, m1 = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1];
    m0 += 0.5 * h * (f[i] + f[i - 1]);
    m1 += 0.5 * h * (t[i] * f[i] + t[i - 1] * f[i - 1]);
  }
  CurveShape s;
  if (!(m0 > 0)) return s;
  s.mean_time = m1 / m0;
  double m2 = 0, m3 = 0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1], a = t[i] - s.mean_time, b = t[i - 1] - s.mean_time;
    m2 += 0.5 * h * (a * a * f[i] + b * b * f[i - 1]);
    m3 += 0.5 * h * (a * a * a * f[i] + b * b * b * f[i - 1]);
  }
  s.spread = std::sqrt(m2 / m0);
  s.skewness = s.spread > 0 ? m3 / m0 / (s.spread * s.spread * s.spread) : 0;
  return s;
}

namespace {

std::vector<double> resample(const std::vector<double>& t, const std::vector<double>& f,
                             double t_end, int n) {
  std::vector<double> out(n, 0.0);
  std::size_t j = 0;
  for (int i = 0; i < n; ++i) {
    const double x = t_end * i / (n - 1);
    while (j + 1 < t.size() && t[j + 1] < x) ++j;
    if (t.empty() || x < t.front() || x > t.back()) continue;
    if (j + 1 >= t.size()) {
      out[i] = f.back();
    } else {
      const double h = t[j + 1] - t[j];
      const double w = h > 0 ? (x - t[j]) / h : 0;
      out[i] = (1 - w) * f[j] + w * f[j + 1];
    }
  }
  return out;
}

}  // namespace

double cross_correlation_lag(const std::vector<double>& t_ref, const std::vector<double>& ref,
                             const std::vector<double>& t, const std::vector<double>& f,
                             double t_end, int points) {
  const std::vector<double> a = resample(t_ref, ref, t_end, points),
                            b = resample(t, f, t_end, points);
  const int max_lag = points / 2;
  std::vector<double> c(2 * max_lag + 1, 0.0);
  for (int k = -max_lag; k <= max_lag; ++k) {
    double s = 0;
    for (int i = std::max(0, -k); i < points && i + k < points; ++i) s += a[i] * b[i + k];
    c[k + max_lag] = s;
  }
  const int best = static_cast<int>(std::max_element(c.begin(), c.end()) - c.begin());
  double shift = best - max_lag;
  if (best > 0 && best + 1 < static_cast<int>(c.size())) {
    // Vertex of the parabola through the peak and its neighbours: sub-sample lag.
    const double l = c[best - 1], m = c[best], r = c[best + 1], den = l - 2 * m + r;
    if (den < 0) shift += 0.5 * (l - r) / den;
  }
  return shift * t_end / (points - 1);
}

std::string classify(double lag_rel, double duration_ratio, double skew_diff,
                     const ClassifyCriteria& c) {
  std::string out;
  auto add = [&](const char* s) { out += (out.empty() ? "" : "+") + std::string(s); };
  if (std::abs(lag_rel) > c.shift) add("shifted");
  if (duration_ratio > c.tail) add("tail");
  if (std::abs(skew_diff) > c.asymmetry) add("asymmetric");
  return out.empty() ? "overlapping" : out;
}

double quantile(std::vector<double> v, double p) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const double h = p * static_cast<double>(v.size() - 1);
  const std::size_t lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (h - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

namespace {

// A CSV cell: numbers in the shortest form that reads back to the same double (as summary.json
// writes them), so a table and the case's summary.json hold the same value.
std::string cell(const OJson& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return io::csv_field(v.get<std::string>());
  return v.dump();
}

std::string csv(const std::vector<std::string>& header,
                const std::vector<std::vector<OJson>>& rows) {
  std::ostringstream s;
  for (std::size_t i = 0; i < header.size(); ++i) s << (i ? "," : "") << io::csv_field(header[i]);
  s << "\n";
  for (const auto& r : rows) {
    for (std::size_t i = 0; i < r.size(); ++i) s << (i ? "," : "") << cell(r[i]);
    s << "\n";
  }
  return s.str();
}

struct Curve {
  std::vector<double> t, f;
};

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

struct CaseData {
  CaseKey key;
  std::string status;  // "ok", "unstable", "no_contact", "failed", "missing"
  std::string message;
  OJson summary, mesh;
  double cpu = std::nan("");
  double start_gap = std::nan("");
  fs::path dir;
};

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

}  // namespace

StudyTables write_tables(const StudyDef& def, const fs::path& dir, const StudyOutcome& run) {
  const std::vector<CaseKey> keys = plan_cases(def);
  std::vector<CaseData> cases;
  std::map<std::string, std::size_t> index;  // particle|model|resolution|placement → case
  auto key_of = [](const std::string& p, ModelKind m, long n, Placement pl) {
    return p + "|" + model_name(m) + "|" + std::to_string(n) + "|" + placement_name(pl);
  };
  StudyTables out;
  for (const CaseKey& k : keys) {
    CaseData c;
    c.key = k;
    c.dir = dir / "cases" / k.particle / k.dir_name();
    if (fs::exists(c.dir / "case.json")) {
      const io::Json rec = io::read_json_file(c.dir / "case.json");
      c.summary = OJson::parse(io::read_json_file(c.dir / "summary.json").dump());
      c.status = c.summary.value("status", "missing");
      c.cpu = c.summary.value("cpu_seconds_thread", std::nan(""));
      c.start_gap = rec.value("start_gap", std::nan(""));
      ++out.done;
    } else if (fs::exists(c.dir / "failed.json")) {
      c.status = "failed";
      c.message = io::read_json_file(c.dir / "failed.json").value("message", "");
      ++out.failed;
    } else {
      c.status = "missing";
    }
    const long faces = k.model == ModelKind::sphere ? def.reference : k.resolution;
    const fs::path mj = dir / "meshes" / k.particle / std::to_string(faces) / "mesh.json";
    if (fs::exists(mj)) c.mesh = OJson::parse(io::read_json_file(mj).dump());
    index[key_of(k.particle, k.model, k.resolution, k.placement)] = cases.size();
    cases.push_back(std::move(c));
  }
  out.cases = static_cast<int>(cases.size());
  auto find = [&](const std::string& p, ModelKind m, long n, Placement pl) -> const CaseData* {
    const auto it = index.find(key_of(p, m, n, pl));
    return it == index.end() ? nullptr : &cases[it->second];
  };
  auto usable = [](const CaseData* c) { return c && c->status == "ok"; };

  // cases.csv: one row per case, errors against the same model's reference resolution and
  // against the fem reference (same placement).
  const std::vector<std::string> case_header = {"particle",
                                                "model",
                                                "resolution",
                                                "placement",
                                                "status",
                                                "peak_force",
                                                "impulse",
                                                "contact_duration",
                                                "first_contact_time",
                                                "cpu_seconds",
                                                "steps",
                                                "dt",
                                                "start_gap",
                                                "volume_change_rel",
                                                "centroid_shift_rel",
                                                "max_asperity_rel",
                                                "max_asperity_change_rel",
                                                "peak_force_err",
                                                "impulse_err",
                                                "contact_duration_err",
                                                "first_contact_shift",
                                                "peak_force_err_fem",
                                                "impulse_err_fem",
                                                "open_at_end",
                                                "message"};
  std::vector<std::vector<OJson>> case_rows;
  struct ErrRow {
    double peak = std::nan(""), impulse = std::nan("");
  };
  std::vector<ErrRow> err_fem(cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const CaseData& c = cases[i];
    const CaseKey& k = c.key;
    const CaseData* same = k.model == ModelKind::sphere
                               ? nullptr
                               : find(k.particle, k.model, def.reference, k.placement);
    const CaseData* fem = find(k.particle, ModelKind::fem, def.reference, k.placement);
    const bool ok = usable(&c);
    double pe = std::nan(""), ie = std::nan(""), de = std::nan(""), fs_ = std::nan("");
    if (ok && usable(same)) {
      pe = rel_err(c.summary["peak_force"], same->summary["peak_force"]);
      ie = rel_err(c.summary["impulse"], same->summary["impulse"]);
      de = rel_err(c.summary["contact_duration"], same->summary["contact_duration"]);
      fs_ = c.summary["first_contact_time"].get<double>() -
            same->summary["first_contact_time"].get<double>();
    }
    if (ok && usable(fem)) {
      err_fem[i].peak = rel_err(c.summary["peak_force"], fem->summary["peak_force"]);
      err_fem[i].impulse = rel_err(c.summary["impulse"], fem->summary["impulse"]);
    }
    const bool has_mesh = k.model != ModelKind::sphere && c.mesh.is_object();
    // A contact still open at the end of the window: its duration and impulse are cut short
    // (the "auto" duration should prevent it; a given duration may not).
    OJson open_at_end;
    if (ok) {
      const Curve curve = read_force(c.dir / "force.csv");
      open_at_end = !curve.f.empty() && curve.f.back() > 0;
    }
    case_rows.push_back({k.particle,
                         model_name(k.model),
                         k.model == ModelKind::sphere ? OJson() : OJson(k.resolution),
                         placement_name(k.placement),
                         c.status,
                         num_or_null(c.summary, "peak_force"),
                         num_or_null(c.summary, "impulse"),
                         num_or_null(c.summary, "contact_duration"),
                         num_or_null(c.summary, "first_contact_time"),
                         num_or_null(c.summary, "cpu_seconds_thread"),
                         num_or_null(c.summary, "steps"),
                         num_or_null(c.summary, "dt"),
                         finite_or_null(c.start_gap),
                         has_mesh ? num_or_null(c.mesh, "volume_change_rel") : OJson(),
                         has_mesh ? num_or_null(c.mesh, "centroid_shift_rel") : OJson(),
                         has_mesh ? num_or_null(c.mesh, "max_asperity_rel") : OJson(),
                         has_mesh ? num_or_null(c.mesh, "max_asperity_change_rel") : OJson(),
                         finite_or_null(pe),
                         finite_or_null(ie),
                         finite_or_null(de),
                         finite_or_null(fs_),
                         finite_or_null(err_fem[i].peak),
                         finite_or_null(err_fem[i].impulse),
                         open_at_end,
                         c.message.empty() ? OJson() : OJson(c.message)});
  }
  io::write_atomically(dir / "cases.csv", csv(case_header, case_rows));

  // classification.csv: each resolution's force curve against its model's reference curve.
  const ClassifyCriteria criteria;
  std::vector<std::vector<OJson>> class_rows, particle_rows;
  for (const ParticleSource& p : def.particles) {
    for (ModelKind m : def.models) {
      if (m == ModelKind::sphere) continue;
      for (Placement pl : def.placements) {
        const CaseData* ref = find(p.name, m, def.reference, pl);
        if (!usable(ref)) continue;
        const Curve rc = read_force(ref->dir / "force.csv");
        const double d_ref = ref->summary["contact_duration"].get<double>();
        const CurveShape rs = curve_shape(rc.t, rc.f);
        std::string all, coarsest;
        for (long n : def.resolutions) {
          if (n == def.reference) continue;
          const CaseData* c = find(p.name, m, n, pl);
          if (!usable(c)) continue;
          const Curve cc = read_force(c->dir / "force.csv");
          const double t_end =
              std::max(rc.t.empty() ? 0.0 : rc.t.back(), cc.t.empty() ? 0.0 : cc.t.back());
          const double lag = cross_correlation_lag(rc.t, rc.f, cc.t, cc.f, t_end);
          const double ratio =
              d_ref > 0 ? c->summary["contact_duration"].get<double>() / d_ref : std::nan("");
          const CurveShape cs = curve_shape(cc.t, cc.f);
          const std::string cls =
              classify(d_ref > 0 ? lag / d_ref : 0, ratio, cs.skewness - rs.skewness, criteria);
          class_rows.push_back({p.name, model_name(m), placement_name(pl), n, lag,
                                finite_or_null(d_ref > 0 ? lag / d_ref : std::nan("")),
                                finite_or_null(ratio), cs.skewness, rs.skewness,
                                cs.skewness - rs.skewness, cls});
          if (coarsest.empty()) coarsest = cls;
          if (cls != "overlapping") {
            std::istringstream parts(cls);
            for (std::string part; std::getline(parts, part, '+');) {
              if (("+" + all + "+").find("+" + part + "+") == std::string::npos)
                all += (all.empty() ? "" : "+") + part;
            }
          }
        }
        if (!coarsest.empty()) {
          particle_rows.push_back({p.name, model_name(m), placement_name(pl),
                                   all.empty() ? "overlapping" : all, coarsest});
        }
      }
    }
  }
  io::write_atomically(
      dir / "classification.csv",
      csv({"particle", "model", "placement", "resolution", "lag", "lag_rel", "duration_ratio",
           "skewness", "skewness_reference", "skewness_diff", "class"},
          class_rows));
  io::write_atomically(
      dir / "particle_classes.csv",
      csv({"particle", "model", "placement", "classes", "coarsest_class"}, particle_rows));

  // cpu_fit.csv: median CPU per resolution across particles, and t = C N^p by least squares on
  // log–log axes.
  std::vector<std::vector<OJson>> fit_rows;
  OJson fits = OJson::array();
  for (ModelKind m : def.models) {
    if (m == ModelKind::sphere) continue;
    for (Placement pl : def.placements) {
      std::vector<double> lx, ly;
      for (long n : def.resolutions) {
        std::vector<double> cpu;
        for (const ParticleSource& p : def.particles) {
          const CaseData* c = find(p.name, m, n, pl);
          if (usable(c) && c->cpu > 0) cpu.push_back(c->cpu);
        }
        if (cpu.empty()) continue;
        lx.push_back(std::log(static_cast<double>(n)));
        ly.push_back(std::log(quantile(cpu, 0.5)));
      }
      if (lx.size() < 2) continue;
      double mx = 0, my = 0;
      const double np_ = static_cast<double>(lx.size());
      for (std::size_t i = 0; i < lx.size(); ++i) mx += lx[i] / np_, my += ly[i] / np_;
      double sxy = 0, sxx = 0;
      for (std::size_t i = 0; i < lx.size(); ++i)
        sxy += (lx[i] - mx) * (ly[i] - my), sxx += (lx[i] - mx) * (lx[i] - mx);
      const double p = sxy / sxx, c0 = std::exp(my - p * mx);
      fit_rows.push_back({model_name(m), placement_name(pl), p, c0, static_cast<long>(lx.size())});
      fits.push_back({{"model", model_name(m)},
                      {"placement", placement_name(pl)},
                      {"exponent", p},
                      {"coefficient", c0}});
    }
  }
  io::write_atomically(dir / "cpu_fit.csv",
                       csv({"model", "placement", "exponent", "coefficient", "points"}, fit_rows));

  // Guidelines: for each tolerance, metric and statistic (median, 90th percentile over the
  // particles), the cheapest (median CPU) model and resolution whose |error| against the fem
  // reference meets it. The fem reference meets every tolerance by definition (error 0).
  struct Candidate {
    ModelKind model;
    long resolution;
  };
  std::vector<Candidate> candidates;
  for (ModelKind m : def.models) {
    if (m == ModelKind::sphere) {
      candidates.push_back({m, 0});
    } else {
      for (long n : def.resolutions) candidates.push_back({m, n});
    }
  }
  const std::vector<double> tolerances = {0.02, 0.05, 0.10};
  const std::vector<std::string> metrics = {"peak_force", "impulse", "peak_force+impulse"};
  std::vector<std::vector<OJson>> guide_rows, cand_rows;
  OJson guide = OJson::array();
  const bool has_fem_ref =
      std::find(def.models.begin(), def.models.end(), ModelKind::fem) != def.models.end();
  for (Placement pl : def.placements) {
    if (!has_fem_ref) break;
    struct Stats {
      Candidate c;
      std::map<std::string, std::pair<double, double>> err;  // metric → (median, p90)
      double cpu = std::nan("");
      int particles = 0;
    };
    std::vector<Stats> stats;
    for (const Candidate& cand : candidates) {
      Stats s{cand, {}, std::nan(""), 0};
      std::vector<double> ep, ei, eb, cpu;
      for (const ParticleSource& p : def.particles) {
        const CaseData* c = find(p.name, cand.model, cand.resolution, pl);
        if (!c) continue;
        const std::size_t i = static_cast<std::size_t>(c - cases.data());
        if (!std::isfinite(err_fem[i].peak) || !std::isfinite(err_fem[i].impulse)) continue;
        ep.push_back(std::abs(err_fem[i].peak));
        ei.push_back(std::abs(err_fem[i].impulse));
        eb.push_back(std::max(ep.back(), ei.back()));
        cpu.push_back(c->cpu);
      }
      if (ep.empty()) continue;
      s.particles = static_cast<int>(ep.size());
      s.err["peak_force"] = {quantile(ep, 0.5), quantile(ep, 0.9)};
      s.err["impulse"] = {quantile(ei, 0.5), quantile(ei, 0.9)};
      s.err["peak_force+impulse"] = {quantile(eb, 0.5), quantile(eb, 0.9)};
      s.cpu = quantile(cpu, 0.5);
      stats.push_back(s);
      cand_rows.push_back({placement_name(pl), model_name(cand.model),
                           cand.model == ModelKind::sphere ? OJson() : OJson(cand.resolution),
                           s.particles, s.err["peak_force"].first, s.err["peak_force"].second,
                           s.err["impulse"].first, s.err["impulse"].second, s.cpu});
    }
    for (double tol : tolerances) {
      for (const std::string& metric : metrics) {
        for (int q = 0; q < 2; ++q) {
          const Stats* best = nullptr;
          for (const Stats& s : stats) {
            const double e = q == 0 ? s.err.at(metric).first : s.err.at(metric).second;
            if (e <= tol && (!best || s.cpu < best->cpu)) best = &s;
          }
          if (!best) continue;
          const double e = q == 0 ? best->err.at(metric).first : best->err.at(metric).second;
          const bool is_ref =
              best->c.model == ModelKind::fem && best->c.resolution == def.reference;
          const OJson res =
              best->c.model == ModelKind::sphere ? OJson() : OJson(best->c.resolution);
          guide_rows.push_back({placement_name(pl), metric, tol, q == 0 ? "median" : "p90",
                                model_name(best->c.model), res, e, best->cpu, is_ref});
          guide.push_back({{"placement", placement_name(pl)},
                           {"metric", metric},
                           {"tolerance", tol},
                           {"statistic", q == 0 ? "median" : "p90"},
                           {"model", model_name(best->c.model)},
                           {"resolution", res},
                           {"error", e},
                           {"cpu_seconds_median", best->cpu},
                           {"is_reference", is_ref}});
        }
      }
    }
  }
  io::write_atomically(dir / "guidelines.csv",
                       csv({"placement", "metric", "tolerance", "statistic", "model", "resolution",
                            "error", "cpu_seconds_median", "is_reference"},
                           guide_rows));
  io::write_atomically(
      dir / "candidates.csv",
      csv({"placement", "model", "resolution", "particles", "peak_force_err_median",
           "peak_force_err_p90", "impulse_err_median", "impulse_err_p90", "cpu_seconds_median"},
          cand_rows));

  // The range of particles and impacts the guidelines were measured on (recommend warns outside).
  double d_min = 1e300, d_max = 0;
  for (const ParticleSource& p : def.particles) {
    const CaseData* c =
        find(p.name, has_fem_ref ? ModelKind::fem : def.models.front(),
             def.models.front() == ModelKind::sphere && !has_fem_ref ? 0 : def.reference,
             def.placements.front());
    if (c && c->mesh.is_object() && c->mesh.contains("equivalent_radius")) {
      const double d = 2 * c->mesh["equivalent_radius"].get<double>();
      d_min = std::min(d_min, d);
      d_max = std::max(d_max, d);
    }
  }
  out.guidelines = {{"study", def.name},
                    {"reference", {{"model", "fem"}, {"resolution", def.reference}}},
                    {"speed", def.speed},
                    {"particle_diameter_range", d_max > 0 ? OJson{d_min, d_max} : OJson()},
                    {"particles", def.particles.size()},
                    {"resolutions", def.resolutions},
                    {"penalty_alpha", def.penalty_alpha ? OJson(*def.penalty_alpha) : OJson()},
                    {"material",
                     {{"density", def.material.density},
                      {"young", def.material.young},
                      {"poisson", def.material.poisson}}},
                    {"rows", guide}};
  io::write_atomically(dir / "guidelines.json", out.guidelines.dump(1) + "\n");

  // study_summary.json: counts, total CPU (every done case, whenever it ran) beside the
  // published study's (Zhang & Zsaki 2019).
  double cpu_total = 0;
  std::map<std::string, double> cpu_by_model;
  for (const CaseData& c : cases) {
    if (std::isfinite(c.cpu)) {
      cpu_total += c.cpu;
      cpu_by_model[model_name(c.key.model)] += c.cpu;
    }
    if (c.mesh.is_object() && c.key.model != ModelKind::sphere &&
        c.key.placement == def.placements.front() && c.key.model == def.models.front()) {
      cpu_total += c.mesh.value("mesh_cpu_seconds", 0.0);
      cpu_by_model["meshing"] += c.mesh.value("mesh_cpu_seconds", 0.0);
    }
  }
  auto median_cpu = [&](ModelKind m, long n) {
    std::vector<double> v;
    for (Placement pl : def.placements) {
      for (const ParticleSource& p : def.particles) {
        const CaseData* c = find(p.name, m, n, pl);
        if (usable(c)) v.push_back(c->cpu);
      }
    }
    return quantile(v, 0.5);
  };
  const bool has_100_1000 = has_fem_ref &&
                            std::count(def.resolutions.begin(), def.resolutions.end(), 100) &&
                            std::count(def.resolutions.begin(), def.resolutions.end(), 1000);
  const long lo = def.resolutions.front(), hi = def.resolutions.back();
  // Wall time of every run that computed cases in this folder (a resumed study adds up; a rerun
  // that only kept cases adds nothing), so the report states what the cases took, not the
  // last, possibly empty, rerun.
  double wall_computing = run.ran > 0 ? run.wall_seconds : 0.0;
  int runs_computing = run.ran > 0 ? 1 : 0;
  if (const fs::path prev = dir / "study_summary.json"; fs::exists(prev)) {
    try {
      const io::Json j = io::read_json_file(prev);
      wall_computing += j.value("wall_seconds_computing", 0.0);
      runs_computing += j.value("runs_computing", 0);
    } catch (const std::exception&) {
      // an unreadable earlier summary only loses the earlier runs' wall time
    }
  }
  out.summary = {
      {"study", def.name},
      {"particles", def.particles.size()},
      {"resolutions", def.resolutions},
      {"models", OJson::array()},
      {"placements", OJson::array()},
      {"cases", out.cases},
      {"done", out.done},
      {"failed", out.failed},
      {"cpu_seconds_total", cpu_total},
      {"cpu_seconds_by_model", cpu_by_model},
      {"wall_seconds_computing", wall_computing},
      {"runs_computing", runs_computing},
      {"last_run",
       {{"wall_seconds", run.wall_seconds},
        {"cpu_seconds", run.cpu_seconds},
        {"ran", run.ran},
        {"kept", run.skipped},
        {"failed", run.failed}}},
      {"fem_cpu_growth", has_fem_ref ? OJson{{"from", lo},
                                             {"to", hi},
                                             {"ratio", median_cpu(ModelKind::fem, hi) /
                                                           median_cpu(ModelKind::fem, lo)}}
                                     : OJson()},
      {"fem_cpu_growth_100_1000",
       has_100_1000 ? OJson(median_cpu(ModelKind::fem, 1000) / median_cpu(ModelKind::fem, 100))
                    : OJson()},
      {"cpu_fit", fits},
      {"published",
       {{"source", "Zhang & Zsaki 2019, FEM/DEM, 50 scanned particles x 4 resolutions"},
        {"simulations", 200},
        {"cpu_seconds_100", 4},
        {"cpu_seconds_1000", 572},
        {"cpu_growth_100_1000", 572.0 / 4.0},
        {"peak_force_variation_max", 0.05},
        {"impulse_variation_max", 0.06}}}};
  for (ModelKind m : def.models) out.summary["models"].push_back(model_name(m));
  for (Placement p : def.placements) out.summary["placements"].push_back(placement_name(p));
  io::write_atomically(dir / "study_summary.json", out.summary.dump(1) + "\n");
  return out;
}

}  // namespace asperity::study
