// The energy balance every world reports and every runner checks, J. gravity is the potential
// measured from the initial positions (−Σ m g·(x − x₀)); dissipated is accumulated (damping,
// friction). Models without a term leave it 0 (rigid spheres store no elastic energy).
#pragma once

namespace asperity {

struct EnergyBalance {
  double kinetic = 0, elastic = 0, contact = 0, gravity = 0, dissipated = 0;
  double total() const { return kinetic + elastic + contact + gravity + dissipated; }
};

}  // namespace asperity
