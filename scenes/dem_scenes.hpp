// Small scenes built from definition structs, shared by the DEM tests.
#pragma once

#include "solver/scene/scene.hpp"

namespace asperity::test {

inline Material glass(double friction = 0, double restitution = 1) {
  return {.name = "glass",
          .density = 2500,
          .young = 6.3e10,
          .poisson = 0.23,
          .friction = friction,
          .restitution = restitution};
}

// A sphere of radius r touching the plane z = 0 at t = 0 (zero gap), moving down at v.
inline scene::SceneDef sphere_on_plane(double v, double duration, scene::ContactLaw law) {
  scene::SceneDef s;
  s.name = "sphere-on-plane";
  s.duration = duration;
  s.materials = {glass()};
  s.bodies = {
      {.name = "ball",
       .material = 0,
       .shape = scene::SphereShape{.radius = 0.01},
       .position = Vec3(0, 0, 0.01),
       .velocity = Vec3(0, 0, -v)},
      {.name = "floor",
       .material = 0,
       .shape = scene::PlaneShape{.point = Vec3::Zero(), .normal = Vec3::UnitZ()},
       .fixed = true},
  };
  s.contact.law = law;
  s.record = {.body = 0, .every = 1};
  return s;
}

}  // namespace asperity::test
