// Checks and safe repairs of triangle surfaces (issue 3, "Checking and repair"). The topology
// (edges, fans, shells, orientation) is counted here on plain index arrays, so every message
// can give counts; CGAL supplies the exact collinearity predicate, degenerate-face collapse and
// the self-intersection test (box intersection of face bounding boxes, exact predicates).
#include "solver/geometry/repair_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <map>
#include <numeric>
#include <sstream>
#include <utility>

#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include "solver/core/error.hpp"
#include "solver/core/vec.hpp"
#include "solver/geometry/cgal_surface_mesh.hpp"

namespace asperity::geometry {
namespace {
using cgal::from_cgal;
using cgal::to_cgal;
using cgal::to_point;
using CgalMesh = cgal::Mesh;
namespace PMP = CGAL::Polygon_mesh_processing;

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

// One face's use of an undirected edge: `forward` when the face runs from the smaller index to
// the larger.
struct EdgeUse {
  std::uint64_t key;
  int face;
  int corner;  // the edge runs from corner to corner+1 (mod 3) of the face
  bool forward;
};

// Edge–face incidence, fans around vertices, shells and orientation of a triangle list.
struct Topology {
  long border_edges = 0, nonmanifold_edges = 0, nonmanifold_vertices = 0, misoriented_edges = 0;
  long border_loops = 0;
  std::vector<std::array<int, 3>>
      neighbour;  // across edge corner→corner+1; −1 if none or non-manifold
  std::vector<std::array<bool, 3>> same_direction;  // the neighbour runs that edge the same way
  std::vector<int> shell;                           // per face
  long shells = 0;
};

Topology analyse(const Eigen::Matrix3Xi& f, long n_vertices) {
  const int nf = static_cast<int>(f.cols());
  std::vector<EdgeUse> uses;
  uses.reserve(3 * static_cast<std::size_t>(nf));
  for (int i = 0; i < nf; ++i) {
    for (int c = 0; c < 3; ++c) {
      const auto a = static_cast<std::uint64_t>(f(c, i)),
                 b = static_cast<std::uint64_t>(f((c + 1) % 3, i));
      uses.push_back({std::min(a, b) << 32 | std::max(a, b), i, c, a < b});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.face < y.face;
  });
  Topology t;
  t.neighbour.assign(nf, {-1, -1, -1});
  t.same_direction.assign(nf, {false, false, false});
  UnionFind corners(3 * static_cast<std::size_t>(nf));  // fans: corners joined across shared edges
  UnionFind faces(static_cast<std::size_t>(nf));
  UnionFind border_vertices(static_cast<std::size_t>(std::max<long>(n_vertices, 0)));
  std::vector<bool> on_border(static_cast<std::size_t>(std::max<long>(n_vertices, 0)), false);
  auto corner_of = [&](int face, int vertex) {
    for (int c = 0; c < 3; ++c)
      if (f(c, face) == vertex) return 3 * face + c;
    return -1;
  };
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const std::size_t n = j - i;
    const int a = static_cast<int>(uses[i].key >> 32),
              b = static_cast<int>(uses[i].key & 0xffffffffu);
    if (n == 1) {
      ++t.border_edges;
      border_vertices.join(a, b);
      on_border[a] = on_border[b] = true;
    } else if (n > 2) {
      ++t.nonmanifold_edges;
    } else {
      const EdgeUse &u = uses[i], &v = uses[i + 1];
      const bool same = u.forward == v.forward;
      if (same) ++t.misoriented_edges;
      t.neighbour[u.face][u.corner] = v.face;
      t.neighbour[v.face][v.corner] = u.face;
      t.same_direction[u.face][u.corner] = t.same_direction[v.face][v.corner] = same;
      faces.join(u.face, v.face);
      for (int vertex : {a, b}) corners.join(corner_of(u.face, vertex), corner_of(v.face, vertex));
    }
    i = j;
  }
  // Fans per vertex: distinct corner classes around it (2 or more: sheets touching at a point).
  std::vector<std::vector<int>> roots(static_cast<std::size_t>(std::max<long>(n_vertices, 0)));
  for (int i = 0; i < nf; ++i)
    for (int c = 0; c < 3; ++c) roots[f(c, i)].push_back(corners.find(3 * i + c));
  for (auto& r : roots) {
    std::sort(r.begin(), r.end());
    if (std::unique(r.begin(), r.end()) - r.begin() > 1) ++t.nonmanifold_vertices;
  }
  std::vector<bool> loop_root(on_border.size(), false);
  for (std::size_t v = 0; v < on_border.size(); ++v) {
    if (on_border[v] && !loop_root[border_vertices.find(static_cast<int>(v))]) {
      loop_root[border_vertices.find(static_cast<int>(v))] = true;
      ++t.border_loops;
    }
  }
  t.shell.assign(nf, 0);
  std::map<int, int> shell_id;
  for (int i = 0; i < nf; ++i) {
    auto [it, fresh] = shell_id.emplace(faces.find(i), static_cast<int>(shell_id.size()));
    t.shell[i] = it->second;
  }
  t.shells = static_cast<long>(shell_id.size());
  return t;
}

// Signed volume by the divergence theorem, about `origin` for round-off (m³).
double signed_volume(const Eigen::Matrix3Xd& p, const Eigen::Matrix3Xi& f,
                     const std::vector<int>* shell_of, int shell, const Eigen::Vector3d& origin) {
  double six_v = 0;
  for (Eigen::Index i = 0; i < f.cols(); ++i) {
    if (shell_of && (*shell_of)[i] != shell) continue;
    const Eigen::Vector3d a = p.col(f(0, i)) - origin, b = p.col(f(1, i)) - origin,
                          c = p.col(f(2, i)) - origin;
    six_v += a.dot(b.cross(c));
  }
  return six_v / 6.0;
}

bool collinear(const Eigen::Matrix3Xd& p, const Eigen::Matrix3Xi& f, Eigen::Index i) {
  return f(0, i) == f(1, i) || f(1, i) == f(2, i) || f(0, i) == f(2, i) ||
         CGAL::collinear(to_point(p.col(f(0, i))), to_point(p.col(f(1, i))),
                         to_point(p.col(f(2, i))));
}

long count_self_intersections(const SurfaceMesh& m) {
  const CgalMesh cm = to_cgal(m);
  if (!PMP::does_self_intersect(cm)) return 0;
  std::vector<std::pair<CgalMesh::Face_index, CgalMesh::Face_index>> pairs;
  PMP::self_intersections(cm, std::back_inserter(pairs));
  return static_cast<long>(pairs.size());
}

// Keeps the referenced vertices only, renumbered in first-use order.
SurfaceMesh compact(const Eigen::Matrix3Xd& p, const std::vector<std::array<int, 3>>& tris,
                    long* dropped) {
  std::vector<int> index(static_cast<std::size_t>(p.cols()), -1);
  SurfaceMesh out;
  out.faces.resize(3, static_cast<Eigen::Index>(tris.size()));
  int n = 0;
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      int& k = index[tris[i][c]];
      if (k < 0) k = n++;
      out.faces(c, static_cast<Eigen::Index>(i)) = k;
    }
  out.vertices.resize(3, n);
  for (Eigen::Index v = 0; v < p.cols(); ++v)
    if (index[v] >= 0) out.vertices.col(index[v]) = p.col(v);
  if (dropped) *dropped = static_cast<long>(p.cols()) - n;
  return out;
}

std::string plural(long n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

MeshCheck check_mesh(const SurfaceMesh& mesh, bool self_intersections) {
  MeshCheck c;
  c.faces = static_cast<long>(mesh.faces.cols());
  c.vertices = static_cast<long>(mesh.vertices.cols());
  const Topology t = analyse(mesh.faces, c.vertices);
  c.border_edges = t.border_edges;
  c.nonmanifold_edges = t.nonmanifold_edges;
  c.nonmanifold_vertices = t.nonmanifold_vertices;
  c.misoriented_edges = t.misoriented_edges;
  c.shells = t.shells;
  for (Eigen::Index i = 0; i < mesh.faces.cols(); ++i)
    c.degenerate_faces += collinear(mesh.vertices, mesh.faces, i);
  const Eigen::Vector3d origin = mesh.vertices.rowwise().mean();
  c.volume = signed_volume(mesh.vertices, mesh.faces, nullptr, 0, origin);
  if (self_intersections && c.closed() && c.manifold() && c.degenerate_faces == 0) {
    c.self_intersections = count_self_intersections(mesh);
  }
  return c;
}

namespace {

using Triangles = std::vector<std::array<int, 3>>;

[[noreturn]] void refuse(const std::string& name, const std::string& problem) {
  throw InputError(name + ": " + problem);
}

// Step 1. Fan-triangulate polygons (OBJ, OFF and PLY may hold quads).
Triangles fan_triangulate(const std::vector<std::vector<int>>& polygons, MeshLog& log) {
  Triangles tris;
  long split = 0;
  for (const auto& poly : polygons) {
    if (poly.size() > 3) ++split;
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      tris.push_back({poly[0], poly[k], poly[k + 1]});
  }
  if (split > 0) log.repairs.push_back("fan-triangulated " + plural(split, "polygon", "polygons"));
  return tris;
}

// Step 2. Merge vertices with identical coordinates (STL stores each triangle's corners apart).
// Returns how many were merged.
long merge_duplicate_vertices(const Eigen::Matrix3Xd& p, Triangles& tris, MeshLog& log) {
  std::vector<int> order(static_cast<std::size_t>(p.cols()));
  std::iota(order.begin(), order.end(), 0);
  auto less = [&](int a, int b) {
    for (int d = 0; d < 3; ++d)
      if (p(d, a) != p(d, b)) return p(d, a) < p(d, b);
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int> same(order.size());
  long merged = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k > 0 && p.col(order[k]) == p.col(order[k - 1])) {
      same[order[k]] = same[order[k - 1]];
      ++merged;
    } else {
      same[order[k]] = order[k];
    }
  }
  for (auto& t : tris)
    for (int& v : t) v = same[v];
  if (merged > 0)
    log.repairs.push_back("merged " + plural(merged, "duplicate vertex", "duplicate vertices"));
  return merged;
}

// Step 3. Faces with a repeated vertex have no area and no orientation; duplicate faces (same
// three vertices) are doubled copies. Both go.
void drop_repeated_and_duplicate_faces(Triangles& tris, const std::string& name, MeshLog& log) {
  long repeated = 0, duplicates = 0;
  Triangles kept;
  kept.reserve(tris.size());
  for (const auto& t : tris) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++repeated;
      continue;
    }
    kept.push_back(t);
  }
  std::vector<std::pair<std::array<int, 3>, std::size_t>> sorted;
  sorted.reserve(kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    auto s = kept[i];
    std::sort(s.begin(), s.end());
    sorted.emplace_back(s, i);
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<bool> drop(kept.size(), false);
  for (std::size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first) {
      drop[sorted[i].second] = true;
      ++duplicates;
    }
  tris.clear();
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (!drop[i]) tris.push_back(kept[i]);
  if (repeated > 0)
    log.repairs.push_back("removed " + plural(repeated, "degenerate face", "degenerate faces") +
                          " with a repeated vertex");
  if (duplicates > 0)
    log.repairs.push_back("removed " + plural(duplicates, "duplicate face", "duplicate faces"));
  if (tris.empty()) refuse(name, "no faces left after removing degenerate faces");
}

// The mesh of the referenced vertices; those dropped beyond the `merged` duplicates are logged.
SurfaceMesh drop_unreferenced_vertices(const Eigen::Matrix3Xd& p, const Triangles& tris,
                                       long merged, MeshLog& log) {
  long unreferenced = 0;
  SurfaceMesh mesh = compact(p, tris, &unreferenced);
  if (unreferenced - merged > 0)
    log.repairs.push_back(
        "removed " + plural(unreferenced - merged, "unreferenced vertex", "unreferenced vertices"));
  return mesh;
}

// Step 4. Topology: refuse what cannot be repaired without guessing the intended surface.
void refuse_unrepairable_topology(const Topology& t, const std::string& name) {
  if (t.nonmanifold_edges > 0) {
    refuse(name, "non-manifold edge: " + plural(t.nonmanifold_edges, "edge is", "edges are") +
                     " shared by more than two faces" +
                     (t.border_edges > 0
                          ? " (and " + plural(t.border_edges, "border edge", "border edges") + ")"
                          : ""));
  }
  if (t.border_edges > 0) {
    refuse(name, "open mesh: " + plural(t.border_edges, "border edge", "border edges") + " in " +
                     plural(t.border_loops, "hole", "holes"));
  }
  if (t.nonmanifold_vertices > 0) {
    refuse(name, "non-manifold vertex: at " + plural(t.nonmanifold_vertices, "vertex", "vertices") +
                     " separate sheets of faces touch");
  }
}

// Step 5. Orient every shell consistently: a breadth-first walk flips a face whose neighbour
// runs the shared edge the same way. A conflict means a non-orientable surface.
void orient_shells(SurfaceMesh& mesh, const Topology& t, const std::string& name, MeshLog& log) {
  const int nf = static_cast<int>(mesh.faces.cols());
  std::vector<int> flip(nf, -1);
  for (int seed = 0; seed < nf; ++seed) {
    if (flip[seed] >= 0) continue;
    std::vector<int> members;
    std::deque<int> queue{seed};
    flip[seed] = 0;
    while (!queue.empty()) {
      const int a = queue.front();
      queue.pop_front();
      members.push_back(a);
      for (int c = 0; c < 3; ++c) {
        const int b = t.neighbour[a][c];
        if (b < 0) continue;
        const int want = flip[a] ^ static_cast<int>(t.same_direction[a][c]);
        if (flip[b] < 0) {
          flip[b] = want;
          queue.push_back(b);
        } else if (flip[b] != want) {
          refuse(name,
                 "non-orientable surface: a one-sided shell (like a Moebius strip) cannot be "
                 "oriented");
        }
      }
    }
    // Flip the minority, so a mostly consistent shell changes least.
    long ones = 0;
    for (int m : members) ones += flip[m];
    if (2 * ones > static_cast<long>(members.size()))
      for (int m : members) flip[m] ^= 1;
  }
  long flipped = 0;
  for (int i = 0; i < nf; ++i)
    if (flip[i] == 1) {
      std::swap(mesh.faces(1, i), mesh.faces(2, i));
      ++flipped;
    }
  if (flipped > 0)
    log.repairs.push_back("reoriented " + plural(flipped, "face", "faces") +
                          " to match their neighbours");
}

// Step 6. One shell: drop tiny ones (debris, inner bubbles), refuse a second particle.
void keep_main_shell(SurfaceMesh& mesh, const Topology& t, const std::string& name, MeshLog& log) {
  const int nf = static_cast<int>(mesh.faces.cols());
  const Eigen::Vector3d origin = mesh.vertices.rowwise().mean();
  std::vector<double> shell_volume(static_cast<std::size_t>(t.shells));
  std::vector<long> shell_faces(static_cast<std::size_t>(t.shells), 0);
  for (int s = 0; s < t.shells; ++s)
    shell_volume[s] = signed_volume(mesh.vertices, mesh.faces, &t.shell, s, origin);
  for (int i = 0; i < nf; ++i) ++shell_faces[t.shell[i]];
  const int main_shell = static_cast<int>(
      std::max_element(shell_volume.begin(), shell_volume.end(),
                       [](double a, double b) { return std::abs(a) < std::abs(b); }) -
      shell_volume.begin());
  const double main_volume = std::abs(shell_volume[main_shell]);
  long large = 0;
  for (int s = 0; s < t.shells; ++s)
    if (s != main_shell && std::abs(shell_volume[s]) >= kTinyShellFraction * main_volume) ++large;
  if (large > 0) {
    std::ostringstream m;
    m << "several shells: " << t.shells << " separate closed surfaces, " << large
      << " of them larger than " << 100 * kTinyShellFraction
      << "% of the largest; split the file into one particle per file";
    refuse(name, m.str());
  }
  Triangles kept;
  for (int i = 0; i < nf; ++i)
    if (t.shell[i] == main_shell)
      kept.push_back({mesh.faces(0, i), mesh.faces(1, i), mesh.faces(2, i)});
  for (int s = 0; s < t.shells; ++s) {
    if (s == main_shell) continue;
    std::ostringstream m;
    m << "dropped a tiny shell of " << shell_faces[s] << " faces (volume "
      << 100 * std::abs(shell_volume[s]) / main_volume << "% of the main shell)";
    log.repairs.push_back(m.str());
    log.warnings.push_back(m.str());
  }
  mesh = compact(mesh.vertices, kept, nullptr);
}

// Step 7. Outward: the divergence theorem gives a negative volume for an inward-wound surface.
void orient_outward(SurfaceMesh& mesh, const std::string& name, MeshLog& log) {
  const double extent =
      (mesh.vertices.rowwise().maxCoeff() - mesh.vertices.rowwise().minCoeff()).maxCoeff();
  const double volume =
      signed_volume(mesh.vertices, mesh.faces, nullptr, 0, mesh.vertices.rowwise().mean());
  // Zero volume to round-off: |V| within 1e-12 of the bounding cube (a flat or collapsed shell).
  if (!(std::abs(volume) > 1e-12 * extent * extent * extent)) {
    std::ostringstream m;
    m << "zero volume (" << volume << " m^3 inside a " << extent
      << " m bounding box): a flat or collapsed surface";
    refuse(name, m.str());
  }
  if (volume < 0) {
    mesh.faces.row(1).swap(mesh.faces.row(2));
    std::ostringstream m;
    m << "flipped the inward-wound mesh (signed volume was " << volume << " m^3)";
    log.repairs.push_back(m.str());
  }
}

// Step 8. Zero-area faces with three distinct, collinear vertices (needles and caps): CGAL
// collapses or flips them away, which keeps the surface closed; the result is checked again.
void collapse_degenerate_faces(SurfaceMesh& mesh, const std::string& name, MeshLog& log) {
  long degenerate = 0;
  for (Eigen::Index i = 0; i < mesh.faces.cols(); ++i)
    degenerate += collinear(mesh.vertices, mesh.faces, i);
  if (degenerate == 0) return;
  CgalMesh cm = to_cgal(mesh);
  const bool done = PMP::remove_degenerate_faces(cm);
  cm.collect_garbage();
  SurfaceMesh fixed = from_cgal(cm);
  const MeshCheck after = check_mesh(fixed, false);
  if (!done || !after.closed() || !after.manifold() || after.shells != 1 ||
      after.misoriented_edges != 0 || after.degenerate_faces != 0 || after.volume <= 0) {
    refuse(name, "degenerate faces: " + plural(degenerate, "face has", "faces have") +
                     " zero area (collinear vertices) and could not be collapsed safely");
  }
  log.repairs.push_back("removed " + plural(degenerate, "zero-area face", "zero-area faces") +
                        " (collinear vertices) by edge collapse and flip");
  mesh = std::move(fixed);
}

// Step 9. No self-intersections: the tetrahedralization and the contact detection need a solid.
void refuse_self_intersections(const SurfaceMesh& mesh, const std::string& name) {
  if (const long pairs = count_self_intersections(mesh); pairs > 0) {
    refuse(name,
           "self-intersecting surface: " + plural(pairs, "pair", "pairs") + " of faces intersect");
  }
}

}  // namespace

// The repairs are safe ones (nothing guessed); what needs a guess is refused with its counts.
SurfaceMesh repair_mesh(const PolygonSoup& soup, const std::string& name, MeshLog& log) {
  Triangles tris = fan_triangulate(soup.polygons, log);
  const long merged = merge_duplicate_vertices(soup.points, tris, log);
  drop_repeated_and_duplicate_faces(tris, name, log);
  SurfaceMesh mesh = drop_unreferenced_vertices(soup.points, tris, merged, log);
  const Topology t = analyse(mesh.faces, mesh.vertices.cols());
  refuse_unrepairable_topology(t, name);
  orient_shells(mesh, t, name, log);
  keep_main_shell(mesh, t, name, log);
  orient_outward(mesh, name, log);
  collapse_degenerate_faces(mesh, name, log);
  refuse_self_intersections(mesh, name);
  return mesh;
}

SurfaceMesh load_surface_mesh(const std::filesystem::path& file, const ReadOptions& options,
                              MeshLog& log) {
  return repair_mesh(read_mesh_file(file, options), file.string(), log);
}

}  // namespace asperity::geometry
