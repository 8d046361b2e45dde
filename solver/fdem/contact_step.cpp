// The contact step's remedies (contact_step.hpp): limit_penalty, limit_face_penalty and
// scale_contact_mass, each meeting a contact factor on the predicted step's bound (time_step.hpp).
#include "solver/fdem/contact_step.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/fdem/world_phases.hpp"

namespace asperity::fdem {

using detail::face_springs;

namespace {

// Deformable body `b` with its face springs scaled by s: the damped step of elements and
// contact together, the smaller of the mass-split bound and Weyl's sum (critical_step).
struct BodySteps {
  fem::ElementStep element;
  double gershgorin = 0;  // max over nodes of Σ (k_f/3) / m
  std::vector<fem::ElementExtraStiffness> springs;
};
BodySteps body_steps(const World& w, int b, const std::vector<double>& k_row) {
  const Body& body = w.bodies[static_cast<std::size_t>(b)];
  const fem::TetElements& e = w.elements[body.elements];
  BodySteps out{.element = fem::element_critical_step(e, {}, w.added_mass),
                .springs = face_springs(w, b)};
  for (int i = body.node_begin; i < body.node_end; ++i) {
    if (w.mass[i] > 0) out.gershgorin = std::max(out.gershgorin, k_row[i] / w.mass[i]);
  }
  return out;
}
double combined_omega(const World& w, int b, const BodySteps& s, double scale) {
  const fem::TetElements& e = w.elements[w.bodies[static_cast<std::size_t>(b)].elements];
  std::vector<fem::ElementExtraStiffness> springs = s.springs;
  for (fem::ElementExtraStiffness& x : springs) x.k *= scale;
  const double weyl2 = s.element.omega_max * s.element.omega_max + scale * s.gershgorin;
  const fem::ElementStep both = fem::element_critical_step(e, springs, w.added_mass);
  return std::sqrt(std::min(weyl2, both.omega_max * both.omega_max));
}
std::vector<double> face_rows(const World& w) {
  std::vector<double> k_row(w.node_count(), 0.0);
  for (Eigen::Index f = 0; f < w.face_nodes.cols(); ++f) {
    for (int i = 0; i < 3; ++i) k_row[w.face_nodes(i, f)] += w.face_stiffness[f] / 3.0;
  }
  return k_row;
}

// How close to the factor the searches below stop, as a fraction of it: the contact factor met
// lies in [(1 − kMeetTolerance) factor, factor] unless their six steps run out first (1.92–1.96
// of 2 on 4 of the 161 lowered meshes of the bench_fem set). Each evaluation is one element step
// bound (up to nine λ_max per element: a closed form, or a 12×12 eigen-solve where a face spring
// sits), and the last few of the six mostly moved
// the factor in its third digit: stopping at 2 % took the set-up (make_world + critical_step) of
// the bench_fem collision at 1000 triangles from 0.91, 0.84, 0.59 to 0.62, 0.60, 0.35 s of CPU on
// the three of five particles whose faces it lowers (BM_CollisionSetup; reports/fem/mesh_step.md).
constexpr double kMeetTolerance = 0.02;

// Illinois regula falsi for the largest x in [lo, hi] with g(x) ≤ 0, given g(lo) ≤ 0 < g(hi):
// at most six evaluations, fewer once the kept x is within `tolerance` of meeting it exactly
// (g(lo) ≥ −tolerance); the last x that met it.
template <class G>
double largest_meeting(G g, double lo, double hi, double g_lo, double g_hi, double tolerance) {
  int side = 0;  // Illinois: halve the kept end's value when the same end is kept twice
  for (int it = 0; it < 6 && g_lo < -tolerance; ++it) {
    const double x = lo - g_lo * (hi - lo) / (g_hi - g_lo);
    const double gx = g(x);
    if (gx <= 0) {
      lo = x, g_lo = gx;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      hi = x, g_hi = gx;
      if (side == 1) g_lo *= 0.5;
      side = 1;
    }
  }
  return lo;
}

}  // namespace

double limit_penalty(World& w, double factor) {
  const std::vector<double> k_row = face_rows(w);
  double scale = 1;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    if (w.bodies[b].kind != BodyKind::deformable) continue;
    const int bi = static_cast<int>(b);
    const BodySteps s = body_steps(w, bi, k_row);
    // Undamped: ω(x)/ω_element − factor, so that a body's damping_ratio does not move its penalty.
    auto excess = [&](double x) {
      return combined_omega(w, bi, s, x) / s.element.omega_max - factor;
    };
    const double f_hi = excess(1);
    if (f_hi <= 0) continue;
    scale =
        std::min(scale, largest_meeting(excess, 0, 1, 1 - factor, f_hi, kMeetTolerance * factor));
  }
  if (scale < 1) {
    w.penalty *= scale;
    for (double& k : w.face_stiffness) k *= scale;
  }
  return scale;
}

namespace {

// What limit_face_penalty and scale_contact_mass share for one deformable body: its element
// bound ω_e (unscaled), its nodes' face rows c_i, and the γ where the factor is met: γ_lo =
// factor² − 1 (Weyl) and γ_hi, where nothing is scaled (the largest c_i / (m_i ω_e²)).
struct LocalLimit {
  double omega_e2 = 0, gamma_lo = 0, gamma_hi = 0;
};
LocalLimit local_limit(const World& w, const Body& body, const std::vector<double>& k_row,
                       double omega_e, double factor) {
  LocalLimit out{.omega_e2 = omega_e * omega_e, .gamma_lo = factor * factor - 1};
  for (int i = body.node_begin; i < body.node_end; ++i) {
    if (w.mass[i] > 0) out.gamma_hi = std::max(out.gamma_hi, k_row[i] / (w.mass[i] * out.omega_e2));
  }
  return out;
}

}  // namespace

double limit_face_penalty(World& w, double factor) {
  const std::vector<double> k_row = face_rows(w);
  std::vector<double> node_scale(static_cast<std::size_t>(w.node_count()), 1.0);
  const auto n_faces = static_cast<std::size_t>(w.face_nodes.cols());
  std::vector<double> face_scale(n_faces, 1.0);
  // Node and face scales of body b at γ (faces of other bodies keep theirs).
  auto set_scales = [&](const Body& body, const LocalLimit& l, double gamma) {
    for (int i = body.node_begin; i < body.node_end; ++i) {
      node_scale[i] = k_row[i] > 0 ? std::min(1.0, gamma * l.omega_e2 * w.mass[i] / k_row[i]) : 1.0;
    }
    for (std::size_t f = 0; f < n_faces; ++f) {
      const auto fi = static_cast<Eigen::Index>(f);
      if (w.node_body[w.face_nodes(0, fi)] != &body - w.bodies.data()) continue;
      face_scale[f] = std::min({node_scale[w.face_nodes(0, fi)], node_scale[w.face_nodes(1, fi)],
                                node_scale[w.face_nodes(2, fi)]});
    }
  };
  bool changed = false;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const Body& body = w.bodies[b];
    if (body.kind != BodyKind::deformable) continue;
    const fem::TetElements& e = w.elements[body.elements];
    const double omega_e = fem::element_critical_step(e, {}, w.added_mass).omega_max;
    const LocalLimit l = local_limit(w, body, k_row, omega_e, factor);
    // Undamped ω(γ)/ω_e − factor, the smaller of the mass-split and Weyl bounds as critical_step.
    auto excess = [&](double gamma) {
      set_scales(body, l, gamma);
      std::vector<double> row(k_row.size(), 0.0);
      for (std::size_t f = 0; f < n_faces; ++f) {
        for (int i = 0; i < 3; ++i) {
          row[w.face_nodes(i, static_cast<Eigen::Index>(f))] +=
              face_scale[f] * w.face_stiffness[f] / 3.0;
        }
      }
      double gershgorin = 0;
      for (int i = body.node_begin; i < body.node_end; ++i) {
        if (w.mass[i] > 0) gershgorin = std::max(gershgorin, row[i] / w.mass[i]);
      }
      const fem::ElementStep both = fem::element_critical_step(
          e, face_springs(w, static_cast<int>(b), &face_scale), w.added_mass);
      const double omega2 = std::min(l.omega_e2 + gershgorin, both.omega_max * both.omega_max);
      return std::sqrt(omega2 / l.omega_e2) - factor;
    };
    const double g_hi = excess(l.gamma_hi);
    if (g_hi <= 0 || !(l.gamma_hi > l.gamma_lo)) {
      set_scales(body, l, std::max(l.gamma_hi, l.gamma_lo));
      continue;
    }
    const double g_lo = excess(l.gamma_lo);
    set_scales(body, l,
               largest_meeting(excess, l.gamma_lo, l.gamma_hi, std::min(g_lo, 0.0), g_hi,
                               kMeetTolerance * factor));
    changed = true;
  }
  if (!changed) return 1;
  w.tet_penalty_scale.assign(static_cast<std::size_t>(w.surface_tets.cols()), 1.0);
  for (Eigen::Index t = 0; t < w.surface_tets.cols(); ++t) {
    double s = 1;
    for (int i = 0; i < 4; ++i) s = std::min(s, node_scale[w.surface_tets(i, t)]);
    w.tet_penalty_scale[static_cast<std::size_t>(t)] = s;
  }
  double least = 1;
  for (std::size_t f = 0; f < n_faces; ++f) {
    w.face_stiffness[f] *= face_scale[f];
    least = std::min(least, face_scale[f]);
  }
  return least;
}

namespace {

// scale_contact_mass with an optional budget (max_added > 0: scale_contact_mass_within). Returns
// the largest Δm/m over the bodies and the factor met (the least over the bodies where the budget
// lowered it, else `factor`).
struct MassScaling {
  double largest = 0, factor = 0;
};
MassScaling scale_contact_mass_impl(World& w, double factor, double max_added) {
  const std::vector<double> k_row = face_rows(w);
  const auto n = static_cast<std::size_t>(w.node_count());
  std::vector<double> added(n, 0.0);
  MassScaling out{.factor = factor};
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const Body& body = w.bodies[b];
    if (body.kind != BodyKind::deformable) continue;
    const fem::TetElements& e = w.elements[body.elements];
    const std::vector<fem::ElementExtraStiffness> springs = face_springs(w, static_cast<int>(b));
    const double omega_e = fem::element_critical_step(e).omega_max;
    const LocalLimit l = local_limit(w, body, k_row, omega_e, factor);
    auto set_added = [&](double gamma) {
      for (int i = body.node_begin; i < body.node_end; ++i) {
        added[i] = std::max(0.0, k_row[i] / (gamma * l.omega_e2) - w.mass[i]);
      }
    };
    auto body_added = [&] {
      double dm = 0;
      for (int i = body.node_begin; i < body.node_end; ++i) dm += added[i];
      return dm;
    };
    // ω(γ)/ω_e on the combined bound, the smaller of the mass-split and Weyl bounds as
    // critical_step.
    auto ratio = [&](double gamma) {
      set_added(gamma);
      double gershgorin = 0;
      for (int i = body.node_begin; i < body.node_end; ++i) {
        if (w.mass[i] > 0) gershgorin = std::max(gershgorin, k_row[i] / (w.mass[i] + added[i]));
      }
      const fem::ElementStep both = fem::element_critical_step(e, springs, added);
      const double omega2 = std::min(l.omega_e2 + gershgorin, both.omega_max * both.omega_max);
      return std::sqrt(omega2 / l.omega_e2);
    };
    auto excess = [&](double gamma) { return ratio(gamma) - factor; };
    const double g_hi = excess(l.gamma_hi);
    double gamma = std::max(l.gamma_hi, l.gamma_lo);
    if (g_hi > 0 && l.gamma_hi > l.gamma_lo) {
      const double g_lo = excess(l.gamma_lo);
      gamma = largest_meeting(excess, l.gamma_lo, l.gamma_hi, std::min(g_lo, 0.0), g_hi,
                              kMeetTolerance * factor);
    }
    set_added(gamma);
    // The budget: the mass added grows as γ falls (each node's c_i/(γ ω_e²) − m_i, where
    // positive), so the least γ within it is found by bisection in log γ on the nodes alone (no
    // step bound per try); then one bound for the factor it meets. γ never falls below the γ of
    // kLeastContactFactor by Weyl's sum (factor² − 1), nor rises above the factor asked's.
    if (max_added > 0 && body_added() <= max_added * body.mass) {
      double lo = kLeastContactFactor * kLeastContactFactor - 1, hi = gamma;
      set_added(lo);
      if (body_added() <= max_added * body.mass) {
        hi = lo;
      } else {
        for (int k = 0; k < 60 && hi > lo * (1 + 1e-12); ++k) {
          const double mid = std::sqrt(lo * hi);
          set_added(mid);
          (body_added() <= max_added * body.mass ? hi : lo) = mid;
        }
      }
      // The factor met never below kLeastContactFactor: below 1 the mass would lengthen the
      // elements' own step too (mass scaling of the refined zone, not of the contact springs):
      // on the finest levels (h/8) of ballast_01-o1 and rock_04-o1 the budget alone reached
      // 0.73 and 0.81. Then the least γ above it that meets kLeastContactFactor, by bisection on
      // the bound (each try one step bound; 6 halvings of [γ, γ asked]).
      double met = ratio(hi);
      if (met < kLeastContactFactor) {
        double below = hi, above = gamma;
        for (int k = 0; k < 6; ++k) {
          const double mid = std::sqrt(below * above);
          (ratio(mid) < kLeastContactFactor ? below : above) = mid;
        }
        hi = above;
        met = ratio(hi);
      }
      out.factor = std::min(out.factor, met);  // the added mass is set at hi
    }
    out.largest = std::max(out.largest, body_added() / body.mass);
  }
  if (out.largest == 0) return out;
  w.added_mass = added;
  for (std::size_t i = 0; i < n; ++i) {
    if (added[i] > 0) {
      w.mass[i] += added[i];
      w.inv_mass[i] = 1.0 / w.mass[i];
    }
  }
  return out;
}

}  // namespace

double scale_contact_mass(World& w, double factor) {
  return scale_contact_mass_impl(w, factor, 0).largest;
}

double scale_contact_mass_within(World& w, double factor, double max_added) {
  return scale_contact_mass_impl(w, factor, max_added).factor;
}

}  // namespace asperity::fdem
