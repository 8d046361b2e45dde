// PRIVATE to solver/geometry/*.cpp: conversion between the plain SurfaceMesh and CGAL's
// Surface_mesh. Never include this from a public header: CGAL stays inside geometry's .cpp files.
#pragma once

#include <array>
#include <vector>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include "solver/core/mesh.hpp"

namespace asperity::geometry::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

inline Point to_point(const Eigen::Vector3d& x) {
  return {x.x(), x.y(), x.z()};
}

inline Mesh to_cgal(const SurfaceMesh& m) {
  std::vector<Point> pts;
  pts.reserve(static_cast<std::size_t>(m.vertices.cols()));
  for (Eigen::Index i = 0; i < m.vertices.cols(); ++i) pts.push_back(to_point(m.vertices.col(i)));
  std::vector<std::array<std::size_t, 3>> tris;
  tris.reserve(static_cast<std::size_t>(m.faces.cols()));
  for (Eigen::Index i = 0; i < m.faces.cols(); ++i)
    tris.push_back({static_cast<std::size_t>(m.faces(0, i)),
                    static_cast<std::size_t>(m.faces(1, i)),
                    static_cast<std::size_t>(m.faces(2, i))});
  Mesh out;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, tris, out);
  return out;
}

// Live vertices renumbered 0..n−1 in index order; faces in index order.
inline SurfaceMesh from_cgal(const Mesh& m) {
  SurfaceMesh out;
  std::vector<int> index(m.num_vertices(), -1);
  out.vertices.resize(3, static_cast<Eigen::Index>(m.number_of_vertices()));
  int n = 0;
  for (auto v : m.vertices()) {
    const Point& q = m.point(v);
    out.vertices.col(n) = Eigen::Vector3d(q.x(), q.y(), q.z());
    index[v.idx()] = n++;
  }
  out.faces.resize(3, static_cast<Eigen::Index>(m.number_of_faces()));
  int k = 0;
  for (auto face : m.faces()) {
    int c = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(face), m))
      out.faces(c++, k) = index[v.idx()];
    ++k;
  }
  return out;
}

}  // namespace asperity::geometry::cgal
