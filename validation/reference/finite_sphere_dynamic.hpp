// A dynamic finite-sphere reference for the FEM/DEM Hertz gate (issue 11): the linear-elastic
// sphere of finite_sphere.hpp, now with its inertia, striking a rigid frictionless plane.
//
// Why: finite_sphere.hpp presses the sphere quasi-statically (a uniform d'Alembert body force)
// and integrates its force law as one degree of freedom. A contact of 17 ms against a lowest
// axisymmetric mode of about 4 ms makes the quasi-static law an approximation of order
// (T_mode/T_c)², the same order in a/R as the finite-size correction it measures. This model
// keeps the waves, so "dynamic − quasi-static" is a number (docs/physics.md, point 6b).
//
// Model (small-strain, linear, frictionless, rigid plane; only the quasi-static assumption
// dropped): the same bipolar mesh of 9-node axisymmetric quadrilaterals (finite_sphere_fe.hpp),
// a consistent mass matrix, the whole sphere moving at v toward the plane it touches at t = 0;
// implicit Newmark average acceleration (β = 1/4, γ = 1/2: unconditionally stable, second
// order, energy-conserving for the linear part), K_eff = K + 4M/dt² factorised once; each step
// the nodal unilateral frictionless contact of the candidate surface nodes (the pole included,
// within 0.35 R of the axis) is condensed onto them (D = K_eff⁻¹ restricted to the candidates) and
// solved as the same complementarity problem as the quasi-static model's. No rigid-body
// constraint: M makes K_eff definite.
//
// Scheme's known error: contact imposed on the gap at the end of each step (Carpenter, Taylor &
// Katona 1991) makes the contact forces work at the transitions (a node entering contact loses
// ½ R Δu, one leaving gains it) and lets the contact nodes' velocities oscillate step to step;
// both vanish as dt → 0 (measured: reports/fem/finite_sphere_dynamic.md). Laursen & Chawla's
// (1997) persistency condition would remove the energy error; not done here.
#pragma once

#include <vector>

#include "validation/reference/finite_sphere.hpp"

namespace asperity::reference {

struct FiniteSphereDynamicDef {
  FiniteSphereMesh mesh{};  // M = 16 by default (reports/fem/finite_sphere_dynamic.md)
  // dt = T_Hertz / steps_per_hertz_duration (T_Hertz: Hertz's duration at this mass and speed).
  double steps_per_hertz_duration = 1000;
  bool record = false;  // keep the force history (time, force) in the result
};

struct FiniteSphereDynamicImpact {
  double peak_force = 0;            // N, the largest total contact force of any step: it
                                    // carries the scheme's period-2 chatter (grows as dt → 0)
  double step_mean_peak_force = 0;  // N, the largest (F_n + F_{n+1})/2: the force the scheme's
                                    // momentum balance applies over a step (chatter cancels)
  double filtered_peak_force = 0;   // N, after the centred moving average over T/20
                                    // (run/impact_measures.hpp, as the 3D runs report it)
  double duration = 0;              // s, first contact (t = 0) to the last, end interpolated
  double impulse_ratio = 0;         // ∫F dt / (2 m v): 1 for a rebound leaving no vibration
  double rebound_ratio = 0;         // centre-of-mass speed after / before (the restitution)
  double energy_ratio = 0;          // (kinetic + strain) at the end / ½ m v² at the start
  double energy_excursion = 0;      // largest |E(t)/E(0) − 1| over the run
  double contact_work = 0;          // the contact forces' work / ½ m v² (trapezoidal): the
                                    // scheme's energy error, = energy_ratio − 1 to round-off
  double max_approach = 0;          // m, largest mass-averaged displacement toward the plane
  int contact_intervals = 0;        // separate intervals with a force (1 unless it chatters)
  double dt = 0;                    // s
  long steps = 0;
  double mass = 0;  // kg
  double hertz_peak_force = 0, hertz_duration = 0, hertz_max_approach = 0;
  std::vector<double> time, force;  // per step, when FiniteSphereDynamicDef::record
};

// A sphere (E, ν, R of `material`) of mass `mass` (kg; density mass / meshed volume) moving at
// v (m/s) onto the plane, run to 0.25 T_Hertz after the contact ends (a separated sphere's
// energy is constant in the scheme, so the end values are the rebound's). Cost: a few seconds at
// M = 16 and 1000 steps.
FiniteSphereDynamicImpact simulate_finite_sphere_impact(const FiniteSphereMaterial& material,
                                                        double mass, double v,
                                                        const FiniteSphereDynamicDef& def = {});

// The reference the 3D gates use: the default model above, cached per parameter set (the first
// call costs a few seconds, later ones nothing). Mass (4/3)πR³ρ, or given (e.g. that of a
// meshed, faceted sphere).
FiniteSphereDynamicImpact finite_sphere_impact_dynamic(double E, double nu, double rho, double R,
                                                       double v);
FiniteSphereDynamicImpact finite_sphere_impact_dynamic_with_mass(double E, double nu, double mass,
                                                                 double R, double v);

// The period (s) of the free sphere's lowest axisymmetric vibration mode (after the rigid
// translation), by shifted inverse iteration on the same mesh and consistent mass.
double lowest_axisymmetric_period(const FiniteSphereMaterial& material, double density,
                                  const FiniteSphereMesh& mesh = {});

}  // namespace asperity::reference
