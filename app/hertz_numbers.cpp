// hertz_numbers IN.json OUT.json: Hertz's numbers for a sphere striking a rigid flat, from
// solver/contact/hertz_impact.hpp (the one place of the formulas), for the report's picture of a
// deformable sphere (tools/report/impact_pictures.py), which measures the meshed sphere and draws
// these beside it.
//
// IN.json: {"mass": kg, "radius": m, "young": Pa, "poisson": -, "speed": m/s, "force": N}: the
// sphere's mass, radius and material, its approach speed, and the force to draw the contact at.
// Writes OUT.json: "e_star" (the sphere against a rigid flat, Pa), the impact's "max_overlap",
// "peak_force", "contact_duration" and "impulse" (§11.4), and at "force" Hertz's
// "contact_radius", "peak_pressure", "max_shear_depth" and the "pressure_profile" p(r) (§4.2):
// {"radius": [...], "pressure": [...]} at kProfilePoints radii evenly from 0 to a (the ends
// included). Numbers in the shortest form that reads back to the same double. Bad input: one line
// naming the file and the problem, exit 2.
#include <limits>
#include <string>
#include <vector>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/material.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"

namespace {

// The profile's radii: enough for a smooth curve at the picture's size.
constexpr int kProfilePoints = 200;

// Hertz's pressure at kProfilePoints radii from 0 to a: r_k = k (a / (n − 1)), the last a itself.
asperity::io::Json pressure_profile(const asperity::contact::HertzContact& c) {
  std::vector<double> r, p;
  const double step = c.radius / (kProfilePoints - 1);
  for (int k = 0; k < kProfilePoints; ++k) {
    r.push_back(k == kProfilePoints - 1 ? c.radius : k * step);
    p.push_back(asperity::contact::hertz_pressure(c, r.back()));
  }
  return {{"radius", r}, {"pressure", p}};
}

}  // namespace

int main(int argc, char** argv) {
  return asperity::io::table_program(argc, argv, 2, "hertz_numbers IN.json OUT.json", [&] {
    using asperity::io::Json;
    const Json in = asperity::io::read_json_file(argv[1]);
    const auto get = [&](const char* key) { return in.at(key).get<double>(); };
    const asperity::Material sphere{.young = get("young"), .poisson = get("poisson")};
    // The flat is rigid: it adds nothing to 1/E*.
    const asperity::Material rigid{.young = std::numeric_limits<double>::infinity()};
    const double e_star = asperity::effective_young(sphere, rigid);
    const double mass = get("mass"), radius = get("radius");
    const asperity::contact::HertzImpact h =
        asperity::contact::hertz_impact(mass, radius, e_star, get("speed"));
    const asperity::contact::HertzContact c =
        asperity::contact::hertz_contact(get("force"), radius, e_star);
    const Json out = {{"e_star", e_star},
                      {"max_overlap", h.max_overlap},
                      {"peak_force", h.peak_force},
                      {"contact_duration", h.contact_duration},
                      {"impulse", h.impulse},
                      {"contact_radius", c.radius},
                      {"peak_pressure", c.peak_pressure},
                      {"max_shear_depth", c.max_shear_depth},
                      {"pressure_profile", pressure_profile(c)}};
    asperity::io::write_atomically(argv[2], out.dump(1) + "\n");
  });
}
