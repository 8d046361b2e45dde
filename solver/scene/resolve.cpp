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
  return contact::pair_constants(normal_law(contact.law), contact.friction, contact.restitution, a,
                                 b);
}

double sphere_mass(const SceneDef& scene, int body) {
  const BodyDef& b = scene.bodies[body];
  const double r = std::get<SphereShape>(b.shape).radius;
  return scene.materials[b.material].density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

}  // namespace asperity::scene
