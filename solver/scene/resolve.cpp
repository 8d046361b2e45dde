// The scene's derived contact constants (resolve.hpp).
#include "solver/scene/resolve.hpp"

#include <numbers>
#include <variant>

namespace asperity::scene {

contact::NormalLaw normal_law(ContactLaw law) {
  return law == ContactLaw::linear ? contact::NormalLaw::linear : contact::NormalLaw::hertz;
}

double linear_kt(const ContactDef& contact) {
  return contact.kt.value_or(2.0 / 7.0 * *contact.kn);
}

PairConstants pair_constants(const ContactDef& contact, const Material& a, const Material& b) {
  PairConstants p;
  p.young_eff = effective_young(a, b);
  p.shear_eff = effective_shear(a, b);
  p.friction = contact.friction.value_or(pair_friction(a, b));
  p.restitution = contact.restitution.value_or(pair_restitution(a, b));
  p.zeta = contact::damping_for_restitution(normal_law(contact.law), p.restitution);
  return p;
}

double sphere_mass(const SceneDef& scene, int body) {
  const BodyDef& b = scene.bodies[body];
  const double r = std::get<SphereShape>(b.shape).radius;
  return scene.materials[b.material].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

}  // namespace asperity::scene
