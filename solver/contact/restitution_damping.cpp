// Numerical inverse of the restitution of a clipped, damped normal contact (see header).
#include "solver/contact/restitution_damping.hpp"

#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace asperity::contact {
namespace {

double exponent(NormalLaw law) {
  return law == NormalLaw::linear ? 1.0 : 1.5;
}

// x'' = −max(0, x^n + ζ x^{(n-1)/2} x') for x > 0 (n is 1 or 3/2: square roots, no pow).
double accel(double x, double v, double n, double zeta) {
  if (x <= 0) return 0;
  double f;
  if (n == 1.0) {
    f = x + zeta * v;
  } else {
    const double r = std::sqrt(x);
    f = x * r + zeta * std::sqrt(r) * v;
  }
  return -std::max(0.0, f);
}

}  // namespace

double restitution_for_damping(NormalLaw law, double zeta) {
  const double n = exponent(law);
  // Dimensionless contact lasts about π (linear) or 3.2 (Hertz); heavy damping lengthens the
  // clipped tail, so integrate until separation with a step far below the contact time.
  const double h = 2e-4;
  double x = 0, v = 1;
  for (int i = 0; i < 50'000'000; ++i) {
    const double k1x = v, k1v = accel(x, v, n, zeta);
    const double k2x = v + 0.5 * h * k1v, k2v = accel(x + 0.5 * h * k1x, k2x, n, zeta);
    const double k3x = v + 0.5 * h * k2v, k3v = accel(x + 0.5 * h * k2x, k3x, n, zeta);
    const double k4x = v + h * k3v, k4v = accel(x + h * k3x, k4x, n, zeta);
    const double xn = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    const double vn = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    if (xn <= 0) return -vn;  // separated; the clipped force is zero, so the speed is final
    x = xn;
    v = vn;
  }
  throw std::runtime_error("restitution_for_damping: no separation");
}

double damping_for_restitution(NormalLaw law, double e) {
  if (!(e > 0 && e <= 1)) throw std::invalid_argument("restitution must lie in (0, 1]");
  if (e == 1) return 0;
  static std::mutex mutex;
  static std::map<std::pair<int, double>, double> cache;
  const std::lock_guard lock(mutex);
  const auto key = std::make_pair(static_cast<int>(law), e);
  if (auto it = cache.find(key); it != cache.end()) return it->second;
  double lo = 0, hi = 1;
  while (restitution_for_damping(law, hi) > e) hi *= 2;
  for (int i = 0; i < 60 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (restitution_for_damping(law, mid) > e ? lo : hi) = mid;
  }
  const double zeta = 0.5 * (lo + hi);
  cache.emplace(key, zeta);
  return zeta;
}

double linear_unclipped_restitution(double zeta) {
  const double xi = 0.5 * zeta;
  return std::exp(-std::numbers::pi * xi / std::sqrt(1 - xi * xi));
}

}  // namespace asperity::contact
