// The geometry pipeline for one particle (issue 3, `asperity mesh`).
#include "solver/geometry/mesh_pipeline.hpp"

#include <chrono>
#include <stdexcept>

#include "solver/core/error.hpp"
#include "solver/geometry/refined_sphere.hpp"
#include "solver/geometry/simplify_edge_collapse.hpp"
#include "solver/geometry/write_mesh.hpp"

namespace asperity::geometry {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json vec(const Vec3& v) {
  return {v(0), v(1), v(2)};
}
nlohmann::json mat(const Mat3& m) {
  return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
}

PreparedParticle finish(PreparedParticle p, const PipelineOptions& options) {
  p.source_props = mass_properties(p.source);
  const long input_faces = static_cast<long>(p.source.faces.cols());
  const long faces = options.faces > 0 ? options.faces : input_faces;
  if (const std::string problem = face_target_problem(faces, input_faces); !problem.empty()) {
    throw InputError(p.source_name + ": " + problem);
  }
  auto t0 = std::chrono::steady_clock::now();
  if (options.contact_patch > 0) {
    p.patch_centre = lowest_vertex(p.source);
    p.patch_radius = options.contact_patch;
    ContactLocalSurface local = contact_local_surface(
        p.source, {.centre = p.patch_centre, .radius = p.patch_radius, .far_faces = faces});
    p.surface = std::move(local.surface);
    p.patch_faces = local.kept_faces;
  } else {
    p.surface = simplify_edge_collapse(p.source, faces);
  }
  p.seconds_simplify = seconds_since(t0);
  p.check = check_mesh(p.surface, true);
  if (!p.check.valid()) {
    throw std::runtime_error(
        p.source_name + ": the surface simplified to " + std::to_string(faces) +
        " triangles is not a valid solid (" + std::to_string(p.check.self_intersections) +
        " self-intersecting face pairs, " + std::to_string(p.check.nonmanifold_vertices) +
        " non-manifold vertices); try another face count");
  }
  p.props = mass_properties(p.surface);
  p.change = shape_change(p.source, p.source_props, p.surface, p.props);
  if (options.tetrahedralize) {
    if (options.tet.element_size.size != 0) {
      const std::string problem = element_size_problem(p.surface, options.tet.element_size);
      if (!problem.empty()) {
        throw InputError((options.element_size_key.empty() ? p.source_name + ": element_size"
                                                           : options.element_size_key) +
                         ": " + problem + " (surface " + p.source_name + ", " +
                         std::to_string(p.surface.faces.cols()) + " triangles)");
      }
    }
    if (options.on_tetrahedralize) {
      options.on_tetrahedralize(options.tet.element_size.set()
                                    ? estimated_tets(p.surface, options.tet.element_size)
                                    : 0.0);
    }
    t0 = std::chrono::steady_clock::now();
    p.element_size = options.tet.element_size;
    try {
      p.tets = tetrahedralize(p.surface, options.tet);
    } catch (const InputError& e) {  // a budget passed: name the input it was passed on
      throw InputError(p.source_name + ": " + e.what());
    }
    p.seconds_tetrahedralize = seconds_since(t0);
    p.quality = tet_quality(p.tets);
  }
  return p;
}

}  // namespace

PreparedParticle prepare_particle(const std::filesystem::path& file,
                                  const PipelineOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  PreparedParticle p;
  p.source_name = file.string();
  p.source = load_surface_mesh(file, options.read, p.log);
  p.seconds_read = seconds_since(t0);
  return finish(std::move(p), options);
}

PreparedParticle prepare_particle(const SurfaceMesh& source, const std::string& name,
                                  const PipelineOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  PreparedParticle p;
  p.source_name = name;
  PolygonSoup soup;
  soup.points = options.read.scale * source.vertices;
  soup.polygons.reserve(static_cast<std::size_t>(source.faces.cols()));
  for (Eigen::Index i = 0; i < source.faces.cols(); ++i)
    soup.polygons.push_back({source.faces(0, i), source.faces(1, i), source.faces(2, i)});
  p.source = repair_mesh(soup, name, p.log);
  p.seconds_read = seconds_since(t0);
  return finish(std::move(p), options);
}

nlohmann::json mesh_report(const PreparedParticle& p) {
  const MassProperties& m = p.props;
  nlohmann::json j;
  j["faces"] = p.surface.faces.cols();
  j["vertices"] = p.surface.vertices.cols();
  j["closed"] = p.check.closed();
  j["manifold"] = p.check.manifold();
  j["shells"] = p.check.shells;
  j["outward"] = p.check.volume > 0 && p.check.misoriented_edges == 0;
  j["self_intersections"] = p.check.self_intersections;
  j["volume"] = m.volume;
  j["centroid"] = vec(m.centroid);
  j["inertia"] = mat(m.inertia);  // m^5 per unit density (× density = kg m²), about the centroid
  j["principal_moments"] = vec(m.principal_moments);
  j["principal_axes"] = mat(m.principal_axes);  // columns
  j["equivalent_radius"] = m.equivalent_radius;
  j["ellipsoid_semi_axes"] = vec(m.ellipsoid_semi_axes);
  j["extents"] = vec(m.extents);
  j["elongation"] = m.elongation;
  j["flatness"] = m.flatness;
  j["volume_change_rel"] = p.change.volume_change_rel;
  j["centroid_shift_rel"] = p.change.centroid_shift_rel;
  j["max_asperity_rel"] = p.change.max_asperity_rel;
  j["max_asperity_rel_source"] = p.change.max_asperity_rel_source;
  j["max_asperity_change_rel"] = p.change.max_asperity_change_rel;
  j["elongation_change"] = p.change.elongation_change;
  j["flatness_change"] = p.change.flatness_change;
  if (p.tets.tets.cols() > 0) {
    j["tets"] = p.quality.tets;
    j["tet_nodes"] = p.quality.nodes;
    j["tet_interior_nodes"] = p.quality.interior_nodes;
    j["tet_volume"] = p.quality.volume_sum;
    j["tet_volume_rel_error"] = (p.quality.volume_sum - m.volume) / m.volume;
    j["min_tet_volume"] = p.quality.min_volume;
    j["min_dihedral_deg"] = p.quality.min_dihedral_deg;
    j["max_dihedral_deg"] = p.quality.max_dihedral_deg;
    j["smallest_edge"] = p.quality.smallest_edge;
    j["longest_edge"] = p.quality.longest_edge;
    j["max_radius_edge_ratio"] = p.quality.max_radius_edge_ratio;
    j["tet_surface_faces"] = p.tets.surface.cols();
    j["element_size"] =
        p.element_size.set() ? nlohmann::json(p.element_size.size) : nlohmann::json();
  }
  if (p.patch_radius > 0) {
    j["contact_patch"] = {
        {"centre", vec(p.patch_centre)}, {"radius", p.patch_radius}, {"kept_faces", p.patch_faces}};
  }
  j["repairs"] = p.log.repairs;
  j["warnings"] = p.log.warnings;
  j["source"] = {{"name", p.source_name},
                 {"faces", p.source.faces.cols()},
                 {"vertices", p.source.vertices.cols()},
                 {"volume", p.source_props.volume},
                 {"centroid", vec(p.source_props.centroid)},
                 {"equivalent_radius", p.source_props.equivalent_radius},
                 {"elongation", p.source_props.elongation},
                 {"flatness", p.source_props.flatness},
                 {"max_asperity_rel", p.change.max_asperity_rel_source}};
  j["method"] = {
      {"simplification",
       "CGAL edge collapse, Lindstrom-Turk cost and placement, bounded normal change filter"},
      {"tetrahedralization",
       "TetGen 1.5 constrained Delaunay, switches pYzQ (+q, +m with an element size, S budget), "
       "surface triangles kept (bisected in their planes to the element size when one is set); "
       "flat surface tetrahedra (height < 0.3 x longest edge) lifted onto an interior apex "
       "(docs/geometry.md)"},
      {"asperity",
       "max over vertices of the radial height above the inertia-equivalent ellipsoid, over the "
       "equivalent-sphere radius (docs/geometry.md)"},
      {"elongation_flatness", "b/a and c/b of the inertia-equivalent ellipsoid"}};
  j["seconds"] = {{"read_and_check", p.seconds_read},
                  {"simplify", p.seconds_simplify},
                  {"tetrahedralize", p.seconds_tetrahedralize}};
  return j;
}

void write_prepared_particle(const PreparedParticle& p, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  write_surface_mesh(dir / "surface.off", p.surface);
  if (p.tets.tets.cols() > 0) write_vtk_tets(dir / "tets.vtk", p.tets);
  const nlohmann::json report = mesh_report(p);
  write_atomically(dir / "mesh.json", [&](std::ostream& os) { os << report.dump(2) << '\n'; });
}

}  // namespace asperity::geometry
