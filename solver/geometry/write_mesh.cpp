// Mesh writers (issue 3: surface.off, a tetrahedral mesh ParaView opens, `asperity particle`).
#include "solver/geometry/write_mesh.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>

#include <unistd.h>

#include "solver/core/error.hpp"
#include "solver/core/interrupt.hpp"
#include "solver/core/vec.hpp"

namespace asperity::geometry {
namespace {

void write_points(std::ostream& os, const Eigen::Matrix3Xd& p, const char* prefix) {
  for (Eigen::Index i = 0; i < p.cols(); ++i)
    os << prefix << p(0, i) << ' ' << p(1, i) << ' ' << p(2, i) << '\n';
}

void write_binary_stl(std::ostream& os, const SurfaceMesh& m) {
  char header[80] = {};
  std::strncpy(header, "asperity binary STL", sizeof header - 1);
  os.write(header, sizeof header);
  const auto n = static_cast<std::uint32_t>(m.faces.cols());
  os.write(reinterpret_cast<const char*>(&n), 4);
  for (Eigen::Index i = 0; i < m.faces.cols(); ++i) {
    const Eigen::Vector3d a = m.vertices.col(m.faces(0, i)), b = m.vertices.col(m.faces(1, i)),
                          c = m.vertices.col(m.faces(2, i));
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    float record[12];
    for (int d = 0; d < 3; ++d) {
      record[d] = static_cast<float>(normal(d));
      record[3 + d] = static_cast<float>(a(d));
      record[6 + d] = static_cast<float>(b(d));
      record[9 + d] = static_cast<float>(c(d));
    }
    os.write(reinterpret_cast<const char*>(record), sizeof record);
    const std::uint16_t attribute = 0;
    os.write(reinterpret_cast<const char*>(&attribute), 2);
  }
}

}  // namespace

void write_surface_mesh(const std::filesystem::path& file, const SurfaceMesh& m) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const Eigen::Index nv = m.vertices.cols(), nf = m.faces.cols();
  if (ext == ".off") {
    write_atomically(file, [&](std::ostream& os) {
      os << "OFF\n" << nv << ' ' << nf << " 0\n";
      write_points(os, m.vertices, "");
      for (Eigen::Index i = 0; i < nf; ++i)
        os << "3 " << m.faces(0, i) << ' ' << m.faces(1, i) << ' ' << m.faces(2, i) << '\n';
    });
  } else if (ext == ".obj") {
    write_atomically(file, [&](std::ostream& os) {
      os << "# asperity surface mesh, m\n";
      write_points(os, m.vertices, "v ");
      for (Eigen::Index i = 0; i < nf; ++i)
        os << "f " << m.faces(0, i) + 1 << ' ' << m.faces(1, i) + 1 << ' ' << m.faces(2, i) + 1
           << '\n';
    });
  } else if (ext == ".ply") {
    write_atomically(file, [&](std::ostream& os) {
      os << "ply\nformat ascii 1.0\ncomment asperity surface mesh, m\nelement vertex " << nv
         << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << nf
         << "\nproperty list uchar int vertex_indices\nend_header\n";
      write_points(os, m.vertices, "");
      for (Eigen::Index i = 0; i < nf; ++i)
        os << "3 " << m.faces(0, i) << ' ' << m.faces(1, i) << ' ' << m.faces(2, i) << '\n';
    });
  } else if (ext == ".stl") {
    write_atomically(file, [&](std::ostream& os) { write_binary_stl(os, m); });
  } else {
    throw InputError(file.string() + ": unknown mesh format \"" + file.extension().string() +
                     "\" to write (expected .off, .obj, .ply or .stl)");
  }
}

void write_vtk_tets(const std::filesystem::path& file, const TetMesh& m) {
  write_atomically(file, [&](std::ostream& os) {
    const Eigen::Index nt = m.tets.cols();
    os << "# vtk DataFile Version 3.0\nasperity tetrahedral mesh (m)\nASCII\nDATASET "
          "UNSTRUCTURED_GRID\n";
    os << "POINTS " << m.nodes.cols() << " double\n";
    write_points(os, m.nodes, "");
    os << "CELLS " << nt << ' ' << 5 * nt << '\n';
    for (Eigen::Index t = 0; t < nt; ++t)
      os << "4 " << m.tets(0, t) << ' ' << m.tets(1, t) << ' ' << m.tets(2, t) << ' '
         << m.tets(3, t) << '\n';
    os << "CELL_TYPES " << nt << '\n';
    for (Eigen::Index t = 0; t < nt; ++t) os << "10\n";
  });
}

}  // namespace asperity::geometry
