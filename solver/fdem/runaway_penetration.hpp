// Runaway penetration: an instability criterion of the potential contact beside the energy check,
// which cannot see it (energy is conserved while a body tunnels through another).
//
// 1. Depth. The potential of an element rises from 0 on its faces to 1 at its centroid
//    (contact/munjiza_potential.hpp), and the penalty force on a point grows with it only up to
//    there: past the centroid the point is in another sub-tetrahedron and is pushed on, out
//    through the far side. A contact whose deepest point has gone half-way to the contacting
//    element's centroid (World::penetration ≥ 0.5) is tunnelling the penalty: a healthy contact at
//    α = 10 stays below a few per cent (its penetration is about a tenth of the element's elastic
//    shortening), so 0.5 leaves an order of magnitude of margin while still stopping the run
//    before the node reaches the centroid, where the force reverses.
// 2. Path. A body passed through another when its centre, on its way through the last step,
//    entered the other's tetrahedra (taken where they are at the end of the step). Checked every
//    step for bodies whose centre lies in their own material at the start (a hollow or hooked
//    body's centre may legitimately lie in another). It catches a body that sank into a far larger
//    element, where the depth ratio stays small, and one that jumped through a body within a
//    single step, which no contact ever saw.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "solver/fdem/fdem_world.hpp"

namespace asperity::fdem {

inline constexpr double kRunawayPenetration = 0.5;

class RunawayPenetration {
 public:
  // `def`: the definition the world was made from (its bodies' tetrahedra, in world order).
  RunawayPenetration(const World& world, const WorldDef& def);

  // After each step: empty while the contact is healthy, else the message that stops the run.
  std::string check(const World& world);

 private:
  struct BodyTets {
    Eigen::Matrix4Xi tets;  // global node indices
    int node_begin = 0, node_end = 0;
    bool centre_inside_itself = false;
  };
  std::vector<BodyTets> bodies_;
  std::vector<Vec3> centre_before_;
};

// Whether the segment p0 → p1 meets a tetrahedron of the given (global-index) tets of `world`.
bool path_meets_tets(const World& world, const Eigen::Matrix4Xi& tets, int node_begin, int node_end,
                     const Vec3& p0, const Vec3& p1);

}  // namespace asperity::fdem
