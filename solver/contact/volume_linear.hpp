// Volume-linear: the normal force proportional to the overlap volume, F_n = k_v V (k_v in N/m³),
// along the overlap's cross-section normal and applied at the overlap's centroid, without damping:
// the law of YADE's Law2_PolyhedraGeom_PolyhedraPhys_Volumetric (Eliáš 2014, "Simulation of
// railway ballast using crushable polyhedral particles", Powder Technology 264, §2.2), so that
// the two codes can be compared term for term (docs/crosscheck.md).
//
// Unlike volume-hertz this force is not the gradient of a function of V (that would need
// F = W'(V) |S|, and k_v V / |S| is not a function of V alone); along one fixed direction, as in a
// straight drop, it is conservative all the same (F depends on the approach δ only). Its energy is
// therefore accumulated as ∫ s dV with s = k_v V/|S| (fdem/volume_contact.cpp), exact for
// translations; the torque is the force's at the overlap's centroid, as YADE applies it, which
// makes a spinning contact not exactly conservative. Exponents of F(δ): vertex 3, edge 2, face 1.
#pragma once

#include "solver/core/vec.hpp"

namespace asperity::contact {

// Force on body A, N: k_v V against A's area vector S_A (which points from A into B).
inline Vec3 volume_linear(double volume, const Vec3& area_a, double kv) {
  const double s = area_a.norm();
  if (!(volume > 0) || !(s > 0)) return Vec3::Zero();
  return -(kv * volume / s) * area_a;
}

}  // namespace asperity::contact
