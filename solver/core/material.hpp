// Elastic material and the pair combinations the contact laws use.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "solver/core/enum_names.hpp"

namespace asperity {

// The elastic law of a deformable (FEM) body's tetrahedra: compressible neo-Hookean
// (fem/neo_hookean_tet.hpp, frame-indifferent, the default) or small-strain linear
// (fem/linear_elastic_tet.hpp: for validation against linear-elastic solutions only; a rotated
// element carries spurious stress, and a run stops past fem::kLinearMaxRotation).
enum class ElasticLaw { neo_hookean, linear };
inline constexpr NameTable<ElasticLaw, 2> kElasticLawNames{{
    {ElasticLaw::neo_hookean, "neo-hookean"},
    {ElasticLaw::linear, "linear"},
}};
inline std::string elastic_law_name(ElasticLaw law) {
  return name_in(kElasticLawNames, law);
}
inline std::optional<ElasticLaw> elastic_law_from_name(std::string_view name) {
  return value_named(kElasticLawNames, name);
}

struct Material {
  std::string name;
  double density = 0;                        // kg/m³
  double young = 0;                          // Pa
  double poisson = 0;                        // -
  double friction = 0;                       // Coulomb coefficient, -
  double restitution = 1;                    // normal coefficient of restitution, (0, 1]
  ElasticLaw law = ElasticLaw::neo_hookean;  // deformable bodies' tetrahedra only
};

inline double shear_modulus(const Material& m) {
  return m.young / (2.0 * (1.0 + m.poisson));
}

// Hertz effective modulus, 1/E* = (1-ν₁²)/E₁ + (1-ν₂²)/E₂ (Johnson 1985, eq. 4.22).
inline double effective_young(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.poisson * a.poisson) / a.young + (1.0 - b.poisson * b.poisson) / b.young);
}

// Mindlin effective shear modulus, 1/G* = (2-ν₁)/G₁ + (2-ν₂)/G₂ (Mindlin 1949; Di Renzo & Di
// Maio 2004, eq. 7), so that k_t = 8 G* a.
inline double effective_shear(const Material& a, const Material& b) {
  return 1.0 / ((2.0 - a.poisson) / shear_modulus(a) + (2.0 - b.poisson) / shear_modulus(b));
}

// Pair friction and restitution: the smaller of the two (YADE's FrictMat takes the smaller
// friction angle); a scene's contact block may override both.
inline double pair_friction(const Material& a, const Material& b) {
  return std::min(a.friction, b.friction);
}
inline double pair_restitution(const Material& a, const Material& b) {
  return std::min(a.restitution, b.restitution);
}

}  // namespace asperity
