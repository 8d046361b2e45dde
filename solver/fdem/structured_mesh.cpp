// Structured tetrahedral meshes: boxes and a cube-mapped ball.
#include "solver/fdem/structured_mesh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <vector>

#include "solver/core/error.hpp"

namespace asperity::fdem {

Eigen::Matrix3Xi boundary_faces(const Eigen::Matrix4Xi& tets) {
  // Outward faces of a positive tetrahedron (the face opposite node m).
  constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> count;
  for (int k = 0; k < tets.cols(); ++k) {
    for (const auto& f : kFace) {
      const std::array<int, 3> face{tets(f[0], k), tets(f[1], k), tets(f[2], k)};
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      auto [it, fresh] = count.try_emplace(key, 0, face);
      ++it->second.first;
    }
  }
  std::vector<std::array<int, 3>> out;
  for (const auto& [key, v] : count) {
    if (v.first == 1) out.push_back(v.second);
  }
  Eigen::Matrix3Xi faces(3, static_cast<Eigen::Index>(out.size()));
  for (std::size_t i = 0; i < out.size(); ++i) {
    faces.col(static_cast<Eigen::Index>(i)) << out[i][0], out[i][1], out[i][2];
  }
  return faces;
}

TetMesh box_mesh(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz) {
  return oriented_box_mesh(Vec3::Zero(), Mat3::Identity(), lo, hi, nx, ny, nz);
}

TetMesh oriented_box_mesh(const Vec3& origin, const Mat3& frame, const Vec3& lo, const Vec3& hi,
                          int nx, int ny, int nz) {
  ASPERITY_CHECK(nx > 0 && ny > 0 && nz > 0);
  TetMesh m;
  const int px = nx + 1, py = ny + 1, pz = nz + 1;
  m.nodes.resize(3, px * py * pz);
  auto id = [&](int i, int j, int k) { return i + px * (j + py * k); };
  for (int k = 0; k < pz; ++k) {
    for (int j = 0; j < py; ++j) {
      for (int i = 0; i < px; ++i) {
        const Vec3 local(lo.x() + (hi.x() - lo.x()) * i / nx, lo.y() + (hi.y() - lo.y()) * j / ny,
                         lo.z() + (hi.z() - lo.z()) * k / nz);
        m.nodes.col(id(i, j, k)) = origin + frame * local;
      }
    }
  }
  // Six tetrahedra per cell along the diagonal corner 0 → corner 7, one per axis order.
  constexpr int kOrder[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  m.tets.resize(4, 6 * nx * ny * nz);
  int t = 0;
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        for (const auto& o : kOrder) {
          int c[3] = {i, j, k};
          int v[4];
          v[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[o[s]];
            v[s + 1] = id(c[0], c[1], c[2]);
          }
          const Vec3 a = m.nodes.col(v[0]);
          if ((m.nodes.col(v[1]) - a).cross(m.nodes.col(v[2]) - a).dot(m.nodes.col(v[3]) - a) < 0) {
            std::swap(v[1], v[2]);
          }
          m.tets.col(t++) << v[0], v[1], v[2], v[3];
        }
      }
    }
  }
  m.surface = boundary_faces(m.tets);
  return m;
}

TetMesh ball_mesh(double r, int n) {
  TetMesh m = box_mesh(Vec3(-1, -1, -1), Vec3(1, 1, 1), n, n, n);
  for (Eigen::Index i = 0; i < m.nodes.cols(); ++i) {
    const double x = m.nodes(0, i), y = m.nodes(1, i), z = m.nodes(2, i);
    const double x2 = x * x, y2 = y * y, z2 = z * z;
    m.nodes.col(i) << x * std::sqrt(1 - y2 / 2 - z2 / 2 + y2 * z2 / 3),
        y * std::sqrt(1 - z2 / 2 - x2 / 2 + z2 * x2 / 3),
        z * std::sqrt(1 - x2 / 2 - y2 / 2 + x2 * y2 / 3);
    m.nodes.col(i) *= r;
  }
  for (Eigen::Index k = 0; k < m.tets.cols(); ++k) {
    const Vec3 a = m.nodes.col(m.tets(0, k));
    const double v = (m.nodes.col(m.tets(1, k)) - a)
                         .cross(m.nodes.col(m.tets(2, k)) - a)
                         .dot(m.nodes.col(m.tets(3, k)) - a);
    ASPERITY_CHECK(v > 0);
  }
  return m;
}

}  // namespace asperity::fdem
