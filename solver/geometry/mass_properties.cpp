// Exact polyhedral mass properties (issue 3, "Mass properties"); formulas in the header.
#include "solver/geometry/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "solver/core/error.hpp"

namespace asperity::geometry {

MassProperties mass_properties(const SurfaceMesh& mesh) {
  ASPERITY_CHECK(mesh.vertices.cols() > 0 && mesh.faces.cols() > 0);
  const Vec3 o = mesh.vertices.rowwise().mean();
  double volume = 0;
  Vec3 first = Vec3::Zero();   // ∫ (x − o) dV
  Mat3 second = Mat3::Zero();  // ∫ (x − o)(x − o)ᵀ dV
  for (Eigen::Index i = 0; i < mesh.faces.cols(); ++i) {
    const Vec3 a = mesh.vertices.col(mesh.faces(0, i)) - o;
    const Vec3 b = mesh.vertices.col(mesh.faces(1, i)) - o;
    const Vec3 c = mesh.vertices.col(mesh.faces(2, i)) - o;
    const double v = a.dot(b.cross(c)) / 6.0;  // signed volume of (o, a, b, c)
    const Vec3 s = a + b + c;                  // the fourth vertex o is the zero vector
    volume += v;
    first += v / 4.0 * s;
    second +=
        v / 20.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  MassProperties m;
  m.volume = volume;
  ASPERITY_CHECK(volume > 0);
  const Vec3 d = first / volume;  // centroid − o
  m.centroid = o + d;
  m.covariance = second - volume * d * d.transpose();  // parallel-axis shift to the centroid
  m.covariance = 0.5 * (m.covariance + m.covariance.transpose());
  m.inertia = m.covariance.trace() * Mat3::Identity() - m.covariance;

  // The covariance and inertia share eigenvectors; the largest covariance eigenvalue (the long
  // axis) is the smallest moment. Solving the covariance avoids the cancellation in tr(C) − λ.
  Eigen::SelfAdjointEigenSolver<Mat3> eig(m.covariance);
  const Vec3 lambda = eig.eigenvalues();  // ascending
  Mat3 axes;
  Vec3 l;
  for (int k = 0; k < 3; ++k) {
    axes.col(k) = eig.eigenvectors().col(2 - k);
    l(k) = std::max(lambda(2 - k), 0.0);  // descending
  }
  if (axes.determinant() < 0) axes.col(2) = -axes.col(2);
  m.principal_axes = axes;
  const double trace = l.sum();
  for (int k = 0; k < 3; ++k) m.principal_moments(k) = trace - l(k);
  for (int k = 0; k < 3; ++k) m.ellipsoid_semi_axes(k) = std::sqrt(5.0 * l(k) / volume);

  const Eigen::Matrix3Xd q = axes.transpose() * (mesh.vertices.colwise() - m.centroid);
  m.extents = q.rowwise().maxCoeff() - q.rowwise().minCoeff();
  m.equivalent_radius = std::cbrt(3.0 * volume / (4.0 * std::numbers::pi));
  const Vec3& e = m.ellipsoid_semi_axes;
  m.elongation = e(0) > 0 ? e(1) / e(0) : 0.0;
  m.flatness = e(1) > 0 ? e(2) / e(1) : 0.0;
  return m;
}

double surface_area(const SurfaceMesh& mesh) {
  double a = 0;
  for (Eigen::Index f = 0; f < mesh.faces.cols(); ++f) {
    const Vec3 p = mesh.vertices.col(mesh.faces(0, f)), q = mesh.vertices.col(mesh.faces(1, f)),
               r = mesh.vertices.col(mesh.faces(2, f));
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

}  // namespace asperity::geometry
