// The constants of a pair of materials in contact: Hertz E*, Mindlin G*, Coulomb μ, restitution e
// and the damping ζ that realises e under the normal law. The one rule: scene::pair_constants
// (scene/resolve.hpp) applies it to a scene's contact block, dem::initialise to a sphere world's
// law, so the worlds and the peer adapters read the same numbers (issue 27).
#pragma once

#include <optional>

#include "solver/contact/restitution_damping.hpp"
#include "solver/core/material.hpp"

namespace asperity::contact {

struct PairConstants {
  double young_eff = 0;    // Hertz E*, Pa (core/material.hpp)
  double shear_eff = 0;    // Mindlin G*, Pa
  double friction = 0;     // Coulomb μ: the override, else the smaller of the two
  double restitution = 1;  // the override, else the smaller of the two
  double zeta = 0;         // the damping that realises it under the normal law
};

// `friction` and `restitution`: a scene's contact-block overrides (unset: the pair's own).
inline PairConstants pair_constants(NormalLaw law, std::optional<double> friction,
                                    std::optional<double> restitution, const Material& a,
                                    const Material& b) {
  PairConstants p;
  p.young_eff = effective_young(a, b);
  p.shear_eff = effective_shear(a, b);
  p.friction = friction.value_or(pair_friction(a, b));
  p.restitution = restitution.value_or(pair_restitution(a, b));
  p.zeta = damping_for_restitution(law, p.restitution);
  return p;
}

}  // namespace asperity::contact
