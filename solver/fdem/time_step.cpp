// Predicted critical step of an FEM/DEM world (formulas in time_step.hpp).
#include "fdem/time_step.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Eigenvalues>

namespace asperity::fdem {

CriticalStep critical_step(const World& w) {
  CriticalStep out;
  double omega_e = 0, xi = 0;
  for (const fem::TetElements& e : w.elements) {
    const fem::ElementStep s = fem::element_critical_step(e);
    if (s.omega_max > omega_e) {
      omega_e = s.omega_max;
      xi = 0.5 * e.damping * s.omega_max;
      out.element_body = w.bodies[w.node_body[e.tets(0, s.element)]].name;
    }
  }
  std::vector<double> k_row(w.node_count(), 0.0);
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    for (int i = 0; i < 3; ++i) k_row[w.face_nodes(i, f)] += w.face_stiffness[f] / 3.0;
  }
  double omega_c2 = 0;
  for (int i = 0; i < w.node_count(); ++i) {
    if (w.mass[i] > 0 && w.bodies[w.node_body[i]].kind != BodyKind::rigid) {
      omega_c2 = std::max(omega_c2, k_row[i] / w.mass[i]);
    }
  }
  // Rigid bodies: the same node springs seen through the body's 6 DOF, u_i = t + θ × r_i, so
  // K_r = Σ_i κ_i G_iᵀ G_i with G_i = [I, −[r_i]×] and κ_i the node's row sum above (the
  // consistent face matrix is ≤ (k_f/3) I on each node); M_r = diag(m I, I_c). The largest root
  // of det(K_r − ω² M_r) = 0 bounds the rigid body's contact frequency (rigid motion is a
  // subspace of the nodes' motion, so the nodal bound holds too but is far more conservative).
  for (const RigidBody& rb : w.rigid) {
    const Body& b = w.bodies[rb.body];
    Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero(),
                                m = Eigen::Matrix<double, 6, 6>::Zero();
    for (int i = b.node_begin; i < b.node_end; ++i) {
      Eigen::Matrix<double, 3, 6> g;
      const Vec3 r = w.x.col(i) - rb.centre;
      Mat3 rx;
      rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
      g << Mat3::Identity(), -rx;
      k += k_row[i] * g.transpose() * g;
    }
    const Mat3 rot = rb.orientation.toRotationMatrix();
    m.topLeftCorner<3, 3>() = rb.mass * Mat3::Identity();
    m.bottomRightCorner<3, 3>() = rot * rb.inertia_body * rot.transpose();
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> es(
        k, m, Eigen::EigenvaluesOnly);
    omega_c2 = std::max(omega_c2, es.eigenvalues().maxCoeff());
  }
  const double omega_c = std::sqrt(omega_c2);
  const double inf = std::numeric_limits<double>::infinity();
  out.element = omega_e > 0 ? 2.0 / omega_e * (std::sqrt(1 + xi * xi) - xi) : inf;
  out.contact = omega_c > 0 ? 2.0 / omega_c : inf;
  const double omega = std::sqrt(omega_e * omega_e + omega_c2);
  // ξ scales with ω for stiffness-proportional damping; taken at the combined ω.
  const double xi_all = omega_e > 0 ? xi * omega / omega_e : 0;
  out.critical = omega > 0 ? 2.0 / omega * (std::sqrt(1 + xi_all * xi_all) - xi_all) : inf;
  out.limited_by = out.element <= out.contact ? "element" : "contact";
  return out;
}

}  // namespace asperity::fdem
