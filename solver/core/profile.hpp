// Where a step's time goes, phase by phase (Box2D's b2Profile, Chrono's timers), in ticks of
// core/ticks.hpp: cheap enough to read every phase of every step; a runner turns them into
// seconds once, from the run's wall time (seconds_per_tick). Phases a model lacks stay 0.
#pragma once

#include <cstdint>

namespace asperity {

struct Profile {
  std::uint64_t broad_phase = 0;  // neighbour or candidate-pair lists
  std::uint64_t contact = 0;      // narrow phase and contact forces
  std::uint64_t internal = 0;     // element (internal) forces of deformable bodies
  std::uint64_t integrate = 0;    // kicks and drifts
  std::uint64_t total() const { return broad_phase + contact + internal + integrate; }
};

}  // namespace asperity
