// The effective mass of a pair of bodies, for the contact laws and their step bounds.
#pragma once

#include <cmath>

namespace asperity {

// m* = m₁ m₂ / (m₁ + m₂), kg; an infinite mass (a fixed body, a plane) leaves the other's own.
inline double effective_mass(double m1, double m2) {
  if (std::isinf(m2)) return m1;
  if (std::isinf(m1)) return m2;
  return m1 * m2 / (m1 + m2);
}

}  // namespace asperity
