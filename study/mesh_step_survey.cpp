// Predicted steps of the study's meshes against h/c (study/mesh_step_survey.hpp).
#include "study/mesh_step_survey.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "solver/core/clock.hpp"
#include "solver/fdem/fdem_world.hpp"
#include "solver/fdem/time_step.hpp"
#include "solver/fem/neo_hookean_tet.hpp"
#include "study/study_meshes.hpp"

namespace asperity::study {

namespace {

double shortest_edge(const SurfaceMesh& s) {
  double h = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < s.faces.cols(); ++f) {
    for (int i = 0; i < 3; ++i) {
      const Vec3 a = s.vertices.col(s.faces(i, f)), b = s.vertices.col(s.faces((i + 1) % 3, f));
      h = std::min(h, (b - a).norm());
    }
  }
  return h;
}

double p_wave_speed(const Material& m) {
  const fem::Lame l = fem::lame_from(m.young, m.poisson);
  return std::sqrt((l.lambda + 2 * l.mu) / m.density);
}

}  // namespace

std::vector<MeshStep> mesh_steps(const StudyDef& def, std::size_t index,
                                 const std::vector<long>& faces, bool all_fixes) {
  const SurfaceMesh source = particle_source(def, index);
  std::vector<MeshStep> out;
  for (const long n : faces) {
    MeshStep r{.particle = def.particles[index].name, .faces = n, .c = p_wave_speed(def.material)};
    const double cpu0 = thread_and_children_cpu_seconds();
    try {
      const geometry::PreparedParticle p = particle_mesh(source, r.particle, n);
      r.tets = p.tets.tets.cols();
      r.h = shortest_edge(p.surface);
      StudyDef at_default = def;
      at_default.penalty_alpha.reset();
      fdem::WorldDef w = particle_on_block(p.tets, at_default, fdem::BodyKind::deformable,
                                           p.props.equivalent_radius);
      const fdem::CriticalStep d = fdem::critical_step(fdem::make_world(w));
      // The contact factor 2 met by each of the three (fdem::ContactStepFix): face-penalty is a
      // scene's default (contact.max_contact_factor, run/run_fdem.cpp).
      w.contact.max_contact_factor = 2;
      w.contact.contact_step_fix = fdem::ContactStepFix::face_penalty;
      const fdem::World face = fdem::make_world(w);
      r.dt_face = fdem::critical_step(face).critical;
      r.face_scale_min = 1;
      for (const double x : face.tet_penalty_scale)
        r.face_scale_min = std::min(r.face_scale_min, x);
      // The other two cost about as much again each (a limit is ~9 evaluations of the element
      // bound): only when asked (mesh_step_survey --all-fixes).
      if (all_fixes) {
        w.contact.contact_step_fix = fdem::ContactStepFix::penalty;
        const fdem::World limited = fdem::make_world(w);
        r.dt_limited = fdem::critical_step(limited).critical;
        r.alpha_limited = limited.penalty / def.material.young;
        w.contact.contact_step_fix = fdem::ContactStepFix::mass;
        const fdem::World mass = fdem::make_world(w);
        r.dt_mass = fdem::critical_step(mass).critical;
        double added = 0;
        for (const double x : mass.added_mass) added += x;
        r.mass_added = added / mass.bodies[0].mass;
      }
      r.dt_element = d.element;
      r.dt_contact = d.contact;
      r.dt_critical = d.critical;
      r.limited_by = d.limited_by;
      // 0: not computed (without --all-fixes).
      r.dt_critical_study = !all_fixes ? 0.0
                            : def.penalty_alpha
                                ? fdem::critical_step(fdem::make_world(particle_on_block(
                                                          p.tets, def, fdem::BodyKind::deformable,
                                                          p.props.equivalent_radius)))
                                      .critical
                                : d.critical;
    } catch (const std::exception& e) {
      r.error = e.what();
    }
    r.seconds = thread_and_children_cpu_seconds() - cpu0;
    out.push_back(r);
  }
  return out;
}

}  // namespace asperity::study
