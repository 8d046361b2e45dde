// The contact-local surface (issue 28): the source's triangles kept around the strike point, the
// rest simplified by constrained edge collapse; the choice of policies is in the header.
#include "solver/geometry/contact_local_surface.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "solver/core/error.hpp"
#include "solver/geometry/cgal_surface_mesh.hpp"

namespace asperity::geometry {
namespace {

// The thin-face filter of contact_local_surface (the header): refuses a placement that leaves a
// face of the collapse's star thinner than kContactLocalThinFace and thinner than it was. The
// two faces on the collapsed edge vanish and are not checked (as Bounded_normal_change_filter).
struct ThinFaceFilter {
  template <typename Profile>
  boost::optional<typename Profile::Point> operator()(
      const Profile& profile, boost::optional<typename Profile::Point> op) const {
    if (!op) return op;
    const auto& vpm = profile.vertex_point_map();
    const auto vec = [](const auto& p) {
      return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    };
    const auto& triangles = profile.triangles();
    auto it = triangles.begin();
    if (profile.left_face_exists()) ++it;
    if (profile.right_face_exists()) ++it;
    for (; it != triangles.end(); ++it) {
      // v1 is the vertex the collapse places (CGAL's Edge_profile::triangles()).
      const Vec3 p = vec(get(vpm, it->v0)), q = vec(get(vpm, it->v1)), r = vec(get(vpm, it->v2));
      const double after = face_thickness(p, vec(*op), r);
      if (after < kContactLocalThinFace && after < face_thickness(p, q, r)) return boost::none;
    }
    return op;
  }
};

}  // namespace

double face_thickness(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return longest2 > 0 ? (b - a).cross(c - a).norm() / longest2 : 0.0;
}

ContactLocalSurface contact_local_surface(const SurfaceMesh& source, const ContactPatch& patch) {
  namespace SMS = CGAL::Surface_mesh_simplification;
  ContactLocalSurface out;
  out.source_faces = static_cast<long>(source.faces.cols());
  const double r2 = patch.radius * patch.radius;
  const auto inside = [&](int v) {
    return (source.vertices.col(v) - patch.centre).squaredNorm() <= r2;
  };
  for (Eigen::Index f = 0; f < source.faces.cols(); ++f) {
    if (inside(source.faces(0, f)) && inside(source.faces(1, f)) && inside(source.faces(2, f)))
      ++out.kept_faces;
  }
  // The far part at the density of a far_faces-triangle particle, rounded down to even.
  const long far = patch.far_faces * (out.source_faces - out.kept_faces) / out.source_faces;
  const long target = out.kept_faces + far - (out.kept_faces + far) % 2;
  if (target >= out.source_faces || out.kept_faces == out.source_faces) {
    out.surface = source;
    return out;
  }
  cgal::Mesh cm = cgal::to_cgal(source);
  ASPERITY_CHECK(static_cast<long>(cm.number_of_faces()) == out.source_faces &&
                 CGAL::is_closed(cm));
  // to_cgal keeps the vertex order, so a CGAL vertex's index is the source's.
  auto constrained =
      cm.add_property_map<cgal::Mesh::Edge_index, bool>("e:contact_patch", false).first;
  for (const auto e : cm.edges()) {
    const auto h = cm.halfedge(e);
    constrained[e] = inside(static_cast<int>(cm.source(h).idx())) ||
                     inside(static_cast<int>(cm.target(h).idx()));
  }
  const SMS::Count_stop_predicate<cgal::Mesh> stop(static_cast<std::size_t>(3 * target / 2 + 1));
  const SMS::Bounded_normal_change_filter<ThinFaceFilter> filter;
  SMS::edge_collapse(cm, stop,
                     CGAL::parameters::get_cost(SMS::LindstromTurk_cost<cgal::Mesh>())
                         .get_placement(SMS::LindstromTurk_placement<cgal::Mesh>())
                         .filter(filter)
                         .edge_is_constrained_map(constrained));
  cm.collect_garbage();
  const long got = static_cast<long>(cm.number_of_faces());
  if (got != target) {
    throw std::runtime_error("contact-local simplification stopped at " + std::to_string(got) +
                             " triangles, not the " + std::to_string(target) +
                             " asked for: the remaining collapses would fold faces over or "
                             "touch the patch");
  }
  out.surface = cgal::from_cgal(cm);
  return out;
}

}  // namespace asperity::geometry
