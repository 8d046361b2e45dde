// YADE polyhedra input: the bodies as the vertices asperity collides with (peers/
// yade_polyhedra_input.hpp).
#include "peers/yade_polyhedra_input.hpp"

#include <algorithm>
#include <set>
#include <sstream>

#include "solver/core/error.hpp"
#include "solver/run/run_fdem.hpp"

namespace asperity::peers {
namespace {

using Json = nlohmann::ordered_json;

Json vec(const Vec3& v) {
  return Json::array({v.x(), v.y(), v.z()});
}

// A body's defect above which it is not convex: 1e-9 of its size is round-off of the mesh
// pipeline's coordinates; anything above changes the body YADE builds.
constexpr double kConvexTolerance = 1e-9;

}  // namespace

double convexity_defect(const Eigen::Matrix3Xd& nodes, const Eigen::Matrix3Xi& surface) {
  std::set<int> used(surface.data(), surface.data() + surface.size());
  Vec3 centre = Vec3::Zero();
  for (const int i : used) centre += nodes.col(i);
  centre /= static_cast<double>(used.size());
  double size = 0;
  for (const int i : used) size = std::max(size, (nodes.col(i) - centre).norm());
  double worst = 0;
  for (Eigen::Index f = 0; f < surface.cols(); ++f) {
    const Vec3 a = nodes.col(surface(0, f)), b = nodes.col(surface(1, f)),
               c = nodes.col(surface(2, f));
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.norm() > 0)) continue;
    const Vec3 u = n.normalized();
    for (const int i : used) worst = std::max(worst, u.dot(nodes.col(i) - a));
  }
  return size > 0 ? worst / size : 0;
}

Json yade_polyhedra_input(const scene::SceneDef& s, double dt, long steps) {
  const std::string where = s.file.string() + ": ";
  if (s.contact.law != scene::ContactLaw::volume_linear) {
    throw InputError(where +
                     "contact.law: yade: rigid polyhedra cross-check under \"volume-linear\" "
                     "only (YADE's volumetric law, with a kv); \"" +
                     std::string(scene::contact_law_name(s.contact.law)) +
                     "\" has no YADE counterpart");
  }
  const std::vector<TetMesh> meshes = run::collision_meshes(s);
  Json j;
  j["scene"] = s.name;
  j["law"] = "volume-linear";
  j["kv"] = *s.contact.kv;
  // Coulomb friction (the volume laws' tangential spring kt and μ, run/run_fdem.cpp): the pair's μ
  // is the scene's, else the smallest of the bodies' materials'.
  double mu = s.contact.friction.value_or(1e300);
  if (!s.contact.friction) {
    for (const scene::BodyDef& b : s.bodies) mu = std::min(mu, s.materials[b.material].friction);
  }
  if (mu > 0 && mu < 1e300) {
    j["friction"] = mu;
    j["kt"] = s.contact.kt.value_or(0.0);
  }
  j["materials"] = Json::object();
  for (const Material& m : s.materials) {
    j["materials"][m.name] = {{"density", m.density}, {"young", m.young}, {"poisson", m.poisson}};
  }
  j["bodies"] = Json::array();
  for (std::size_t k = 0; k < s.bodies.size(); ++k) {
    const scene::BodyDef& b = s.bodies[k];
    const std::string key = where + "bodies[" + std::to_string(k) + "] \"" + b.name + "\": ";
    if (b.model != scene::Model::rigid && !b.fixed) {
      throw InputError(key + "model: YADE's polyhedra are rigid; use model \"rigid\"");
    }
    const TetMesh& m = meshes[k];
    if (const double defect = convexity_defect(m.nodes, m.surface); defect > kConvexTolerance) {
      std::ostringstream msg;
      msg << key << "shape: not convex (a vertex lies " << defect
          << " of the body's size outside a face's plane, tolerance " << kConvexTolerance
          << "); YADE's Polyhedra is the convex hull of its vertices, so the cross-check would "
             "compare another particle";
      throw InputError(msg.str());
    }
    std::set<int> used(m.surface.data(), m.surface.data() + m.surface.size());
    Json verts = Json::array();
    for (const int i : used) verts.push_back(vec(m.nodes.col(i)));
    j["bodies"].push_back({{"name", b.name},
                           {"material", s.materials[b.material].name},
                           {"fixed", b.fixed},
                           {"vertices", verts},
                           {"velocity", vec(b.fixed ? Vec3::Zero() : b.velocity)},
                           {"angular_velocity", vec(b.fixed ? Vec3::Zero() : b.angular_velocity)}});
  }
  j["gravity"] = vec(s.gravity);
  j["dt"] = dt;
  j["steps"] = steps;
  j["record_body"] = s.bodies[s.record.body].name;
  return j;
}

}  // namespace asperity::peers
