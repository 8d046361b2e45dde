// What asperity derives from a scene's contact block and materials, in one place: the linear
// law's default k_t, each material pair's E*, G*, friction, restitution and damping ζ, and a
// sphere's mass (a pair's effective mass: core/effective_mass.hpp). The sphere world and every
// peer adapter read them here, so that a default or a pair rule changes once (issue 27, item 3).
#pragma once

#include "solver/contact/pair_constants.hpp"
#include "solver/contact/restitution_damping.hpp"
#include "solver/core/effective_mass.hpp"
#include "solver/core/material.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::scene {

// The normal law a sphere contact law damps with: the linear spring–dashpot for "linear", Hertz
// with Tsuji-form damping for every other (contact/restitution_damping.hpp).
contact::NormalLaw normal_law(ContactLaw law);

// The linear law's tangential stiffness, N/m: contact.kt, else k_t = 2/7 k_n, which gives a solid
// sphere equal normal and tangential periods (Schäfer, Dippel & Wolf 1996). Needs contact.kn.
double linear_kt(const ContactDef& contact);

// The constants of the pair of materials a and b under the scene's contact block (friction and
// restitution overrides, damping for normal_law(contact.law)): contact/pair_constants.hpp's rule.
using PairConstants = contact::PairConstants;
PairConstants pair_constants(const ContactDef& contact, const Material& a, const Material& b);

// The mass of sphere body `body` (density × 4/3 π r³), kg.
double sphere_mass(const SceneDef& scene, int body);

}  // namespace asperity::scene
