// What a world emits after each step about its contacts, body by body (as Box2D's contact
// events): the impact measures above the worlds (run/impact_measures.hpp) derive peak force,
// impulse, contact duration and restitution from it, with the same code for every model and peer.
// The worlds themselves keep no measurement bookkeeping.
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Core>

#include "solver/core/vec.hpp"

namespace asperity {

struct BodyContacts {
  Eigen::Matrix3Xd force;         // total contact force on each body this step, N
  Eigen::Matrix3Xd normal_force;  // its normal part (elastic or potential, plus normal damping), N
  // Largest signed overlap among each body's candidate contacts, m: positive while touching,
  // negative the smallest gap, kNone when it has no candidate contact.
  std::vector<double> overlap;
  static constexpr double kNone = -1e300;

  void reset(int bodies) {
    force.setZero(3, bodies);
    normal_force.setZero(3, bodies);
    overlap.assign(static_cast<std::size_t>(bodies), kNone);
  }
  int size() const { return static_cast<int>(overlap.size()); }
  // A candidate contact between bodies a and b: f (and its normal part fn) acts on a, −f on b.
  void add(int a, int b, const Vec3& f, const Vec3& fn, double s) {
    force.col(a) += f;
    normal_force.col(a) += fn;
    force.col(b) -= f;
    normal_force.col(b) -= fn;
    overlap[a] = std::max(overlap[a], s);
    overlap[b] = std::max(overlap[b], s);
  }
  void gap(int a, int b, double s) {
    overlap[a] = std::max(overlap[a], s);
    overlap[b] = std::max(overlap[b], s);
  }
};

}  // namespace asperity
