// The rebound of the recorded sphere from its first impact: the oblique-impact measures of
// Chung & Ooi (2011, Granular Matter 13:643) tests 4–8 — tangential restitution, contact-point
// recoil angle, spin — computed the same way for asperity's and YADE's final states.
#pragma once

#include <optional>

#include <nlohmann/json.hpp>

#include "solver/core/vec.hpp"
#include "solver/scene/scene.hpp"

namespace asperity::run {

// Where the recorded sphere first touches another body, found from the scene's initial state by
// straight-line motion (so only for scenes without gravity).
struct FirstImpact {
  int partner = -1;             // scene body index
  Vec3 normal = Vec3::UnitZ();  // unit, from the partner into the recorded sphere
  double time = 0;              // s
};

// Empty when the scene has gravity, the recorded body is not a free sphere, or nothing is hit
// within the scene's duration.
std::optional<FirstImpact> first_impact(const scene::SceneDef& s);

struct BodyMotion {
  Vec3 v = Vec3::Zero();  // m/s
  Vec3 w = Vec3::Zero();  // rad/s
};

// Adds the rebound keys to `summary` (docs/contract.md extension; docs/crosscheck.md):
//   impact_partner; normal_velocity_in/out (m/s, relative, along the impact normal, both > 0 for
//   an impact and a rebound); tangential_velocity_in/out (centre, along t̂); slip_velocity_in/out
//   (contact point, along t̂); spin_in/out (rad/s about n × t̂, positive for forward roll);
//   tangential_restitution = tangential_velocity_out/in; slip_ratio = slip_velocity_out/in
//   (Chung & Ooi's β = −slip_ratio); incident_angle_deg (centre) and rebound_angle_deg (contact
//   point, Maw et al. 1976 recoil angle); angular_velocity_change |ω_out − ω_in|;
//   tangential_speed_out (centre, any direction).
// t̂ is the direction of the incoming contact-point slip, or of the incoming centre tangential
// velocity when there is no slip; quantities along t̂ are omitted when neither exists.
// `separated`: the first contact has ended (otherwise the "out" keys are omitted).
void add_rebound_measures(const scene::SceneDef& s, const FirstImpact& impact,
                          const BodyMotion& record_end, const BodyMotion& partner_end,
                          bool separated, nlohmann::ordered_json& summary);

}  // namespace asperity::run
