// The rows of reports/peers/calculix/ (levels.csv: the Hertz sphere's CalculiX levels;
// particles.csv: both codes' particle levels), computed from one level's run folder: the folders
// the CalculiX gates write (tests/peers/test_calculix.cpp: LEVEL/calculix/, and for a particle
// LEVEL/asperity/summary.json) or `asperity crosscheck --peer calculix --out LEVEL` writes (the
// same two). The gates read their measures through the same functions, so a committed row is the
// number the gate compared, computed once (the `calculix_rows` program writes them into the CSV
// files; docs/crosscheck.md, "CalculiX").
//
// What a level folder holds: calculix/summary.json (run_peer's: the measures, ccx's CPU and mesh)
// and calculix/input.json (the adapter's: the scene's material, speed, radius and element sizes);
// for a particle, asperity/summary.json too (or alone, with the scene.json the gate writes).
#pragma once

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "scenes/hertz_spheres.hpp"
#include "solver/core/error.hpp"
#include "solver/io/json_file.hpp"

namespace asperity::peers::calculix_rows {

// The element-size keys of both gates' levels put the cap at 12.5s mm (scenes/hertz_series.hpp's
// level_mesh and the particle gate's scene): the level's s is read back from it.
inline constexpr double kFarPerLevel = 0.0125;  // m per unit of s

// One printf-formatted field.
template <class... Args>
std::string format(const char* f, Args... args) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, args...);
  return buf;
}

// The level's refinement s and the element size at the strike point (m), from the adapter's deck.
struct Keys {
  double s = 0, h = 0;
};
inline Keys keys(const io::Json& input) {
  return {.s = input.at("far").get<double>() / kFarPerLevel, .h = input.at("size").get<double>()};
}

// A sphere level's CalculiX measures, relative to Hertz at the level's own meshed mass (the
// gate's comparison: Johnson 1985, §11.4, scenes/hertz_spheres.hpp's hertz_impact).
struct SphereLevel {
  double a_over_r = 0;  // Hertz's contact radius over R at the nominal mass
  double s = 0, h = 0;  // refinement, element size at the pole (m)
  double increments_per_hertz_time = 0;
  long nodes = 0, tets = 0;                                 // the quarter model's
  double cpu = 0;                                           // s, ccx's process
  double err_peak = 0, err_filtered = 0, err_duration = 0;  // relative to Hertz
  double impulse_ratio = 0;                                 // ∫F dt / (2 m v)
};

inline SphereLevel sphere_level(const std::filesystem::path& calculix_dir) {
  const io::Json j = io::read_json_file(calculix_dir / "summary.json");
  const io::Json in = io::read_json_file(calculix_dir / "input.json");
  const double young = in.at("young").get<double>(), poisson = in.at("poisson").get<double>(),
               radius = in.at("radius").get<double>(), speed = in.at("speed").get<double>();
  const double e_star = young / (1 - poisson * poisson);
  const double mass = j.at("calculix_meshed_mass").get<double>();
  const fdem::scenes::Hertz h = fdem::hertz::hertz_impact(mass, radius, e_star, speed);
  // a/R from the speed: Hertz's approach at the nominal mass, a² = R δ (fdem::hertz::speed_for's
  // inverse).
  const double nominal =
      in.at("density").get<double>() * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
  const double overlap = fdem::hertz::hertz_impact(nominal, radius, e_star, speed).overlap;
  const Keys k = keys(in);
  return {.a_over_r = std::sqrt(overlap / radius),
          .s = k.s,
          .h = k.h,
          .increments_per_hertz_time = j.at("calculix_increments_per_hertz_time").get<double>(),
          .nodes = j.at("calculix_nodes").get<long>(),
          .tets = j.at("calculix_tets").get<long>(),
          .cpu = j.at("cpu_seconds").get<double>(),
          .err_peak = j.at("peak_force").get<double>() / h.force - 1,
          .err_filtered = j.at("peak_force_filtered").get<double>() / h.force - 1,
          .err_duration = j.at("contact_duration").get<double>() / h.duration - 1,
          .impulse_ratio = j.at("impulse").get<double>() / (2 * mass * speed)};
}

inline const std::vector<std::string> kSphereHeader = {"a_over_r",
                                                       "s",
                                                       "increments_per_hertz_time",
                                                       "h_contact_mm",
                                                       "nodes_quarter",
                                                       "tets_quarter",
                                                       "ccx_cpu_s",
                                                       "raw_peak_pct",
                                                       "filtered_peak_pct",
                                                       "duration_pct",
                                                       "impulse_over_2mv"};
// The key columns: a row of the same a/R, s and step replaces the earlier one.
inline constexpr std::size_t kSphereKey = 3;

inline std::vector<std::string> sphere_fields(const SphereLevel& l) {
  return {format("%.3f", l.a_over_r),
          format("%.4f", l.s),
          format("%.0f", l.increments_per_hertz_time),
          format("%.3f", 1e3 * l.h),
          std::to_string(l.nodes),
          std::to_string(l.tets),
          format("%.1f", l.cpu),
          format("%+.3f", 100 * l.err_peak),
          format("%+.3f", 100 * l.err_filtered),
          format("%+.3f", 100 * l.err_duration),
          format("%.5f", l.impulse_ratio)};
}

// A particle level of one code, in the CSV's units (N, ms, N s).
struct ParticleLevel {
  std::string code;     // asperity | calculix
  double s = 0, h = 0;  // refinement, element size at the strike point (m)
  long nodes = 0, tets = 0;
  double cpu = 0;  // s: asperity's time loop, ccx's process
  long increments_or_steps = 0;
  double raw_peak = 0, filtered_peak = 0, duration = 0, impulse = 0;
  std::optional<double> restitution, first_contact;
};

// The keys of the scene LEVEL ran: CalculiX's deck (LEVEL/calculix/input.json), else the scene
// the gate wrote beside the runs (LEVEL/scene.json, its first fem body: asperity's level alone).
inline Keys level_keys(const std::filesystem::path& level) {
  if (std::filesystem::exists(level / "calculix" / "input.json"))
    return keys(io::read_json_file(level / "calculix" / "input.json"));
  const io::Json scene = io::read_json_file(level / "scene.json");
  for (const io::Json& b : scene.at("bodies")) {
    if (b.value("model", "") != "fem") continue;
    const io::Json& shape = b.at("shape");
    return {.s = shape.at("element_size_far").get<double>() / kFarPerLevel,
            .h = shape.at("element_size").get<double>()};
  }
  throw InputError((level / "scene.json").string() + ": no fem body");
}

// `code`'s level in LEVEL (LEVEL/asperity/ or LEVEL/calculix/ summary.json).
inline ParticleLevel particle_level(const std::filesystem::path& level, const std::string& code) {
  const io::Json j = io::read_json_file(level / code / "summary.json");
  const Keys k = level_keys(level);
  const auto optional = [&](const char* key) {
    return j.contains(key) && j.at(key).is_number() ? std::optional<double>(j.at(key).get<double>())
                                                    : std::nullopt;
  };
  ParticleLevel l{.code = code,
                  .s = k.s,
                  .h = k.h,
                  .cpu = j.at("cpu_seconds").get<double>(),
                  .increments_or_steps = j.at("steps").get<long>(),
                  .raw_peak = j.at("peak_force").get<double>(),
                  .filtered_peak = j.at("peak_force_filtered").get<double>(),
                  .duration = 1e3 * j.at("contact_duration").get<double>(),
                  .impulse = j.at("impulse").get<double>(),
                  .restitution = optional("restitution"),
                  .first_contact = optional("first_contact_time")};
  if (l.first_contact) *l.first_contact *= 1e3;
  if (code == "calculix") {
    l.nodes = j.at("calculix_nodes").get<long>();
    l.tets = j.at("calculix_tets").get<long>();
  } else {
    const std::string body = j.at("recorded_body").get<std::string>();
    for (const io::Json& b : j.at("bodies")) {
      if (b.at("name") != body) continue;
      l.nodes = b.at("nodes").get<long>();
      l.tets = b.value("tets", 0L);
    }
  }
  return l;
}

inline const std::vector<std::string> kParticleHeader = {"particle",    "code",
                                                         "s",           "h_contact_mm",
                                                         "nodes",       "tets",
                                                         "cpu_s",       "increments_or_steps",
                                                         "raw_peak_n",  "filtered_peak_n",
                                                         "duration_ms", "impulse_ns",
                                                         "restitution", "first_contact_ms"};

inline std::vector<std::string> particle_fields(const std::string& particle,
                                                const ParticleLevel& l) {
  const auto optional = [](const std::optional<double>& v) {
    return v ? format("%.4f", *v) : std::string();
  };
  return {particle,
          l.code,
          format("%.4f", l.s),
          format("%.2f", 1e3 * l.h),
          std::to_string(l.nodes),
          std::to_string(l.tets),
          format("%.1f", l.cpu),
          std::to_string(l.increments_or_steps),
          format("%.2f", l.raw_peak),
          format("%.2f", l.filtered_peak),
          format("%.3f", l.duration),
          format("%.4f", l.impulse),
          optional(l.restitution),
          optional(l.first_contact)};
}

}  // namespace asperity::peers::calculix_rows
