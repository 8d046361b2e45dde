// An independent reference for the FEM/DEM Hertz gate (issue 11): a linear-elastic sphere of
// finite size pressed on a rigid frictionless plane, solved quasi-statically by axisymmetric
// finite elements, and the impact that follows from its force–approach law.
//
// Why: Hertz's F = (4/3) E* √R δ^{3/2} is the law of two half-spaces. A finite sphere whose
// approach δ is the motion of its centroid (what an impact's rigid-body motion measures) is
// stiffer by a relative amount of order a/R. This reference computes that finite-sphere law
// without the 3D solver, so the 3D gate can be held against it (docs/physics.md, "A finite-sphere
// reference").
//
// Model (all of it small-strain, linear, frictionless, quasi-static, no wave energy):
// - the meridian half-disc of the sphere, 9-node quadrilaterals on a bipolar (conformal) grid
//   whose cells shrink geometrically toward the contact pole and the opposite pole;
// - the contact force is balanced by a uniform body force (d'Alembert: the deceleration), the
//   rigid translation fixed by the contact itself; δ is the mass-averaged axial displacement
//   toward the plane;
// - unilateral contact of the surface nodes with the plane (no penetration, no tension), solved
//   as a small linear complementarity problem on the contact candidates by an active set;
// - the impact from m δ'' = −F(δ): peak force from ½ m v² = ∫F dδ, duration from
//   T = 2 ∫ dδ / √(v² − (2/m) ∫F dδ).
#pragma once

#include <vector>

namespace asperity::reference {

// The mesh: the bipolar grid has `angular_cells` cells between the axis and the sphere surface;
// cells are conformal squares, so their size is `π/(2·angular_cells)` times the distance to
// the nearer pole. Level n of a refinement sequence doubles it.
struct FiniteSphereMesh {
  int angular_cells = 16;  // the default: within 2e-4 of its limit in F/F_Hertz (tested)
  double pole_fan = 1e-4;  // radius (/R) of the fan of collapsed cells at the contact pole
  double top_fan = 0.05;   // the same at the opposite pole (nothing happens there)
};

struct FiniteSphereMaterial {
  double youngs_modulus = 1.0;  // E (Pa)
  double poisson_ratio = 0.3;   // ν
  double radius = 1.0;          // R (m)
};

// One quasi-static state: the sphere pressed by `force` against the plane.
struct FiniteSphereState {
  double force = 0;           // F, total contact force (N) = total body force
  double approach = 0;        // δ, mass-averaged axial displacement toward the plane (m)
  double contact_radius = 0;  // a (m), interpolated between the last node in contact and the next
  int contact_nodes = 0;      // surface nodes in contact, the pole included
};

// Hertz's sphere on a rigid plane: F = (4/3) E* √R δ^{3/2}, E* = E/(1 − ν²); a = √(Rδ).
double hertz_force(const FiniteSphereMaterial& material, double approach);

// A finite-element model assembled and factorised once, then pressed at any force or approach
// (each a small complementarity problem on the surface near the pole: microseconds to
// milliseconds). Contacts up to a/R ≈ 0.3 are representable (the contact candidates).
class FiniteSphere {
 public:
  FiniteSphere(const FiniteSphereMaterial& material, const FiniteSphereMesh& mesh);
  ~FiniteSphere();
  FiniteSphere(FiniteSphere&&) noexcept;
  FiniteSphere& operator=(FiniteSphere&&) noexcept;

  FiniteSphereState at_force(double force) const;
  FiniteSphereState at_approach(double approach) const;  // solves F for the given δ
  // A sequence of forces, each started from the previous one's contact set (faster).
  std::vector<FiniteSphereState> at_forces(const std::vector<double>& forces) const;

  // F/F_Hertz at δ = s² R averaged over one period of the nodal oscillation (see below), and
  // that oscillation's peak-to-peak amplitude: 16 states evenly across the period in ln s, a
  // line in ln s fitted through them; the ratio is the line at s, the amplitude the spread about
  // it. With nodal contact on a self-similar mesh the ratio at one δ oscillates with the phase
  // of the contact edge between two surface nodes, period π/(2 M) in ln a.
  struct AveragedRatio {
    double ratio = 0;
    double oscillation = 0;
  };
  AveragedRatio averaged_force_ratio(double s) const;

  double volume() const;  // of the meshed half-disc revolved (m³)
  const FiniteSphereMaterial& material() const;
  int angular_cells() const;
  int nodes() const;
  int elements() const;

 private:
  struct Impl;
  Impl* impl_;
};

// The finite-sphere law as F/F_Hertz = g(s), s = √(δ/R) ≈ a/R, fitted on a grid of states:
// g(s) = c_0 + c_1 s + c_2 s ln s + c_3 s² + c_4 s³. The s ln s term is the finite body's
// (measured: a polynomial in s leaves 10× the residual and c_0 0.06 % off 1); c_0 − 1 is the
// mesh's own error at the Hertz limit.
struct FiniteSphereLaw {
  double poisson_ratio = 0.3;
  std::vector<double> coefficients;  // c_0 .. c_4
  double s_max = 0;                  // the fit's range: 0 < s ≤ s_max
  double fit_residual = 0;           // largest |g_fit − g_FE| over the fitted states
};
FiniteSphereLaw fit_finite_sphere_law(double poisson_ratio, const FiniteSphereMesh& mesh,
                                      double s_max = 0.25);
// The same on a model already built (any E and R: the law is dimensionless).
FiniteSphereLaw fit_finite_sphere_law(const FiniteSphere& sphere, double s_max = 0.25);
double evaluate(const FiniteSphereLaw& law, double s);

struct FiniteSphereImpact {
  double peak_force = 0;        // N
  double duration = 0;          // s
  double max_approach = 0;      // m
  double hertz_peak_force = 0;  // Hertz, same E, ν, R, mass and speed
  double hertz_duration = 0;
  double hertz_max_approach = 0;
};

// A sphere (E, ν, density ρ, radius R) striking a rigid frictionless plane at speed v; mass
// (4/3)πR³ρ. Two equal spheres head-on at relative speed w: each is this at v = w/2 (the plane
// of symmetry is rigid and frictionless). The law is fitted once per ν on the default mesh and
// cached (1–3 s of CPU the first time, 0.1 ms after).
FiniteSphereImpact finite_sphere_impact(double E, double nu, double rho, double R, double v);
// Two equal spheres head-on at relative speed w: the force between them and the contact
// duration are those of one sphere on the plane at w/2 (and so are the Hertz values beside
// them: Hertz's pair, R* = R/2 and m* = m/2 at w, is the same impact); max_approach is each
// sphere's, half the pair's.
FiniteSphereImpact finite_sphere_head_on(double E, double nu, double rho, double R,
                                         double relative_speed);
// The same with the mass given (e.g. that of a meshed, faceted sphere).
FiniteSphereImpact finite_sphere_impact_with_mass(double E, double nu, double mass, double R,
                                                  double v);
// The impact from any law (tests use g ≡ 1 to check the quadrature against Hertz).
FiniteSphereImpact impact_from_law(const FiniteSphereLaw& law, double E, double mass, double R,
                                   double v);

}  // namespace asperity::reference
