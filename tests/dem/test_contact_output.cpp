// The worlds' per-body contact output and the measures derived above them (run/time_loop.hpp,
// run/impact_measures.hpp): one definition whichever body is recorded.
#include <gtest/gtest.h>

#include "scenes/dem_scenes.hpp"
#include "solver/contact/hertz_impact.hpp"
#include "solver/core/material.hpp"
#include "solver/dem/sphere_world.hpp"
#include "solver/io/csv.hpp"
#include "solver/run/run_scene.hpp"

namespace asperity {
namespace {

// A damped impact (e = 0.8 target) on the plane, recorded on the ball and then on the plane:
// force equal and opposite at every row (Newton's third law, to round-off), and the same peak,
// impulse, duration and restitution (one definition, whichever body is recorded).
TEST(ContactOutput, RecordingEitherBodyGivesTheSameImpact) {
  scene::SceneDef s = test::sphere_on_plane(0.5, 2e-4, scene::ContactLaw::hertz);
  s.materials = {test::glass(0, 0.8)};
  const run::RunResult on_ball = run::run_scene(s);
  s.record.body = 1;
  const run::RunResult on_plane = run::run_scene(s);
  ASSERT_EQ(on_ball.status, "ok");
  ASSERT_EQ(on_plane.status, "ok");
  ASSERT_EQ(on_ball.force.size(), on_plane.force.size());
  for (std::size_t k = 0; k < on_ball.force.size(); ++k) {
    EXPECT_EQ(on_ball.force[k].fz, -on_plane.force[k].fz) << "row " << k;
  }
  for (const char* key : {"peak_force", "impulse", "contact_duration", "restitution"}) {
    // Same arithmetic on negated vectors: equal to the last bit.
    EXPECT_EQ(on_ball.summary[key].get<double>(), on_plane.summary[key].get<double>()) << key;
  }
  // The realised restitution is the target to the gates' tolerance (1 %: the damping is found
  // by bisection on the dimensionless contact equation, restitution_damping.hpp).
  EXPECT_NEAR(on_ball.summary["restitution"].get<double>(), 0.8, 0.008);
}

// Elastic Hertz impact: restitution 1 and the Hertz peak force, both to the analytic gates' 1e-4
// (energy error and peak error at the default 200+ steps per contact).
TEST(ContactOutput, ElasticImpactHasRestitutionOneAndTheHertzPeak) {
  const scene::SceneDef s = test::sphere_on_plane(0.5, 2e-4, scene::ContactLaw::hertz);
  const run::RunResult r = run::run_scene(s);
  ASSERT_EQ(r.status, "ok");
  EXPECT_NEAR(r.summary["restitution"].get<double>(), 1.0, 1e-4);
  const double m = 2500 * 4.0 / 3.0 * 3.141592653589793 * 1e-6;
  const Material g = test::glass();
  const contact::HertzImpact h = contact::hertz_impact(m, 0.01, effective_young(g, g), 0.5);
  EXPECT_NEAR(r.summary["peak_force"].get<double>() / h.peak_force, 1.0, 1e-4);
}

// RFC 4180: a field with a comma, a quote or a line break is quoted, quotes doubled.
TEST(Csv, FieldsAreQuotedOnlyWhenNeeded) {
  EXPECT_EQ(io::csv_field("plain"), "plain");
  EXPECT_EQ(io::csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(io::csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(io::csv_field("two\nlines"), "\"two\nlines\"");
  io::CsvWriter w({"t", "message"}, 3);
  w.number(0.123456).field("failed, at 1 s").end_row();
  EXPECT_EQ(w.str(), "t,message\n0.123,\"failed, at 1 s\"\n");
}

}  // namespace
}  // namespace asperity
