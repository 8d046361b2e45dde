// Small meshes with known answers and files written into a temporary folder, for the geometry
// tests.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "solver/core/error.hpp"
#include "solver/core/mesh.hpp"
#include "solver/geometry/repair_mesh.hpp"

namespace asperity::geometry::test {

// Axis-aligned box [lo, hi], 12 outward triangles.
inline SurfaceMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  SurfaceMesh m;
  m.vertices.resize(3, 8);
  for (int i = 0; i < 8; ++i)
    m.vertices.col(i) =
        Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  m.faces.resize(3, 12);
  m.faces << 0, 0, 4, 4, 0, 0, 2, 2, 0, 0, 1, 1,  //
      2, 3, 5, 7, 1, 5, 6, 7, 4, 6, 3, 7,         //
      3, 1, 7, 6, 5, 4, 7, 3, 6, 2, 7, 5;
  return m;
}

inline SurfaceMesh unit_cube() {
  return box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
}

inline SurfaceMesh flipped(SurfaceMesh m) {
  m.faces.row(1).swap(m.faces.row(2));
  return m;
}

inline SurfaceMesh translated(SurfaceMesh m, const Eigen::Vector3d& t) {
  m.vertices.colwise() += t;
  return m;
}

// Two meshes in one (separate shells).
inline SurfaceMesh merged(const SurfaceMesh& a, const SurfaceMesh& b) {
  SurfaceMesh m;
  m.vertices.resize(3, a.vertices.cols() + b.vertices.cols());
  m.vertices << a.vertices, b.vertices;
  m.faces.resize(3, a.faces.cols() + b.faces.cols());
  m.faces << a.faces, (b.faces.array() + static_cast<int>(a.vertices.cols())).matrix();
  return m;
}

// A fresh folder per test, removed at the end.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& name)
      : path(std::filesystem::temp_directory_path() /
             ("asperity-geometry-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TempDir() { std::filesystem::remove_all(path); }
  std::filesystem::path operator/(const std::string& f) const { return path / f; }
};

// Loads FILE and returns the InputError message, or "" when it loads.
inline std::string load_error(const std::filesystem::path& file, MeshLog* log = nullptr,
                              double scale = 1.0) {
  MeshLog local;
  try {
    load_surface_mesh(file, {.scale = scale}, log ? *log : local);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

inline std::string off_text(const SurfaceMesh& m) {
  std::string s =
      "OFF\n" + std::to_string(m.vertices.cols()) + " " + std::to_string(m.faces.cols()) + " 0\n";
  char buf[128];
  for (Eigen::Index i = 0; i < m.vertices.cols(); ++i) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", m.vertices(0, i), m.vertices(1, i),
                  m.vertices(2, i));
    s += buf;
  }
  for (Eigen::Index i = 0; i < m.faces.cols(); ++i)
    s += "3 " + std::to_string(m.faces(0, i)) + " " + std::to_string(m.faces(1, i)) + " " +
         std::to_string(m.faces(2, i)) + "\n";
  return s;
}

// Binary STL bytes; `keep` triangles of the body are written (fewer than the header declares
// gives a truncated file).
inline std::string binary_stl(const SurfaceMesh& m, long keep = -1) {
  std::string s(80, ' ');
  const auto n = static_cast<std::uint32_t>(m.faces.cols());
  s.append(reinterpret_cast<const char*>(&n), 4);
  const long count = keep < 0 ? static_cast<long>(n) : keep;
  for (long i = 0; i < count; ++i) {
    float rec[12] = {};
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d)
        rec[3 + 3 * c + d] = static_cast<float>(m.vertices(d, m.faces(c, i)));
    s.append(reinterpret_cast<const char*>(rec), sizeof rec);
    s.append(2, '\0');
  }
  return s;
}

}  // namespace asperity::geometry::test
