// The map from a target coefficient of restitution e to the damping ζ of a normal law.
#pragma once

namespace asperity::contact {

// Normal laws of the form F = K δ^n + ζ √(m* K) δ^{(n-1)/2} δ̇, clipped at F ≥ 0.
// n = 1: linear spring–dashpot; n = 3/2: Hertz with Tsuji-form damping. In units where m* = K = 1
// and the impact speed is 1, the contact obeys x'' = −max(0, x^n + ζ x^{(n-1)/2} x'), so the
// realised restitution e(ζ) depends on ζ alone (Tsuji, Tanaka & Ishida 1992). We invert e(ζ)
// exactly, by bisection on a fine RK4 solution of that equation, rather than using a closed-form
// guess: the log(e) map (β = −ln e / √(ln²e + π²)) is exact only for the unclipped linear law and
// realises a different e for Hertz (see Thornton et al. 2013, Powder Technol. 233:30–46).
enum class NormalLaw { linear, hertz };

// Realised restitution of the clipped dimensionless contact for damping ζ ≥ 0.
double restitution_for_damping(NormalLaw law, double zeta);

// Damping ζ that realises restitution e ∈ (0, 1]; e = 1 gives 0. Accurate to 1e-9 in e.
double damping_for_restitution(NormalLaw law, double e);

// The common closed-form map for a linear spring–dashpot without clipping:
// e = exp(−π ξ/√(1−ξ²)) with ξ = ζ/2 the damping ratio. Used to check the numerical map.
double linear_unclipped_restitution(double zeta);

}  // namespace asperity::contact
