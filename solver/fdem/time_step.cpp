// Predicted critical step of an FEM/DEM world (formulas in time_step.hpp).
#include "fdem/time_step.hpp"

#include <cmath>
#include <limits>
#include <vector>

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
    if (w.mass[i] > 0) omega_c2 = std::max(omega_c2, k_row[i] / w.mass[i]);
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
