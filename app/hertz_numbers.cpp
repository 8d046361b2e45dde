// hertz_numbers IN.json OUT.json: Hertz's numbers for a sphere striking a rigid flat, from
// solver/contact/hertz_impact.hpp (the one place of the formulas), for the report's picture of a
// deformable sphere (tools/report/impact_pictures.py), which measures the meshed sphere and draws
// these beside it.
//
// IN.json: {"mass": kg, "radius": m, "young": Pa, "poisson": -, "speed": m/s, "force": N}: the
// sphere's mass, radius and material, its approach speed, and the force to draw the contact at.
// Writes OUT.json: "e_star" (the sphere against a rigid flat, Pa), the impact's "max_overlap",
// "peak_force", "contact_duration" and "impulse" (§11.4), and at "force" Hertz's
// "contact_radius" and "peak_pressure" (§4.2). Numbers in the shortest form that reads back to
// the same double. Bad input: one line naming the file and the problem, exit 2.
#include <limits>
#include <string>

#include "solver/contact/hertz_impact.hpp"
#include "solver/core/material.hpp"
#include "solver/io/atomic_file.hpp"
#include "solver/io/csv.hpp"
#include "solver/io/json_file.hpp"

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
                      {"peak_pressure", c.peak_pressure}};
    asperity::io::write_atomically(argv[2], out.dump(1) + "\n");
  });
}
