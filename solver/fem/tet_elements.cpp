// Element loop of the deformable bodies: plain arrays, one kernel call per element.
#include "fem/tet_elements.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "core/error.hpp"

namespace asperity::fem {

TetElements make_tet_elements(const Eigen::Matrix3Xd& x, const Eigen::Matrix4Xi& tets, double young,
                              double poisson, double density, double damping,
                              const std::string& what) {
  TetElements e;
  e.tets = tets;
  e.lame = lame_from(young, poisson);
  e.density = density;
  e.damping = damping;
  const int n = static_cast<int>(tets.cols());
  e.dm_inv.resize(9 * static_cast<std::size_t>(n));
  e.volume.resize(n);
  for (int k = 0; k < n; ++k) {
    const TetReference r =
        tet_reference(x.col(tets(0, k)), x.col(tets(1, k)), x.col(tets(2, k)), x.col(tets(3, k)));
    if (!(r.volume > 0)) {
      std::ostringstream s;
      s << what << ": element " << k << " has non-positive volume " << r.volume
        << " m^3 (nodes must be ordered so that ((b-a)x(c-a)).(d-a) > 0)";
      throw InputError(s.str());
    }
    Eigen::Map<Mat3>(&e.dm_inv[9 * static_cast<std::size_t>(k)]) = r.dm_inv;
    e.volume[k] = r.volume;
  }
  return e;
}

void add_lumped_mass(const TetElements& e, std::vector<double>& mass) {
  for (int k = 0; k < e.size(); ++k) {
    for (int a = 0; a < 4; ++a) mass[e.tets(a, k)] += 0.25 * e.density * e.volume[k];
  }
}

namespace {

// Kelvin–Voigt viscous forces of one element (see TetElements::damping); returns their power.
double add_viscous_forces(const double* b, double volume, Lame lame, double beta,
                          const double* x[4], const double* v[4], double* f[4]) {
  Mat3 ds, dv;
  for (int c = 0; c < 3; ++c) {
    for (int r = 0; r < 3; ++r) {
      ds(r, c) = x[c + 1][r] - x[0][r];
      dv(r, c) = v[c + 1][r] - v[0][r];
    }
  }
  const Eigen::Map<const Mat3> bm(b);
  const Mat3 F = ds * bm, Fdot = dv * bm;
  const Mat3 Finv = F.inverse();
  const Mat3 L = Fdot * Finv;
  const Mat3 D = 0.5 * (L + L.transpose());
  const Mat3 sigma = beta * (lame.lambda * D.trace() * Mat3::Identity() + 2 * lame.mu * D);
  const double J = F.determinant();
  // P_v = J σ_v F⁻ᵀ; forces −V₀ P_v ∇N_a.
  const Mat3 H = -volume * J * sigma * Finv.transpose() * bm.transpose();
  double power = 0;
  for (int a = 0; a < 3; ++a) {
    for (int r = 0; r < 3; ++r) {
      f[a + 1][r] += H(r, a);
      f[0][r] -= H(r, a);
      power += H(r, a) * (v[a + 1][r] - v[0][r]);
    }
  }
  return power;
}

template <bool kEnergy>
InternalForceResult loop(const TetElements& e, const Eigen::Matrix3Xd& x, const Eigen::Matrix3Xd& v,
                         Eigen::Matrix3Xd& f) {
  InternalForceResult out;
  const int* t = e.tets.data();
  const double* xs = x.data();
  double* fs = f.data();
  const int n = e.size();
  double energy = 0;
  for (int k = 0; k < n; ++k) {
    const int i0 = 3 * t[4 * k], i1 = 3 * t[4 * k + 1], i2 = 3 * t[4 * k + 2],
              i3 = 3 * t[4 * k + 3];
    const double J = neo_hookean_tet_forces<kEnergy>(
        &e.dm_inv[9 * static_cast<std::size_t>(k)], e.volume[k], e.lame, xs + i0, xs + i1, xs + i2,
        xs + i3, fs + i0, fs + i1, fs + i2, fs + i3, &energy);
    if (!(J > 0) && out.inverted < 0) {
      out.inverted = k;
      out.inverted_j = J;
    }
  }
  out.energy = energy;
  if (e.damping > 0 && out.inverted < 0) {
    const double* vs = v.data();
    for (int k = 0; k < n; ++k) {
      const double* xp[4];
      const double* vp[4];
      double* fp[4];
      for (int a = 0; a < 4; ++a) {
        const int i = 3 * t[4 * k + a];
        xp[a] = xs + i;
        vp[a] = vs + i;
        fp[a] = fs + i;
      }
      out.damping_power += add_viscous_forces(&e.dm_inv[9 * static_cast<std::size_t>(k)],
                                              e.volume[k], e.lame, e.damping, xp, vp, fp);
    }
  }
  return out;
}

}  // namespace

InternalForceResult add_internal_forces(const TetElements& e, const Eigen::Matrix3Xd& x,
                                        const Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& f,
                                        bool with_energy) {
  return with_energy ? loop<true>(e, x, v, f) : loop<false>(e, x, v, f);
}

ElementStep element_critical_step(const TetElements& e) {
  ElementStep out;
  for (int k = 0; k < e.size(); ++k) {
    TetReference r{.dm_inv = Eigen::Map<const Mat3>(&e.dm_inv[9 * static_cast<std::size_t>(k)]),
                   .volume = e.volume[k]};
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> es(tet_stiffness(r, e.lame),
                                                                          Eigen::EigenvaluesOnly);
    const double omega = std::sqrt(es.eigenvalues().maxCoeff() / (0.25 * e.density * r.volume));
    if (omega > out.omega_max) {
      out.omega_max = omega;
      out.element = k;
    }
  }
  if (out.omega_max > 0) {
    const double xi = 0.5 * e.damping * out.omega_max;
    out.dt = 2.0 / out.omega_max * (std::sqrt(1 + xi * xi) - xi);
  }
  return out;
}

}  // namespace asperity::fem
