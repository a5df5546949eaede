// Test-only unions of balls: atoms as centres and radii, and the area of their union by
// Shrake-Rupley, the reference the surface tests compare the SES and SAS areas with.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <vector>

namespace surfcomp::test {

struct Atoms {
  Eigen::MatrixX3d centers;  ///< one row per atom, A
  Eigen::VectorXd radii;     ///< A
};

inline Atoms make_atoms(const std::vector<Eigen::Vector3d>& centers,
                        const std::vector<double>& radii) {
  Atoms atoms;
  atoms.centers.resize(static_cast<Eigen::Index>(centers.size()), 3);
  atoms.radii.resize(static_cast<Eigen::Index>(radii.size()));
  for (std::size_t i = 0; i < centers.size(); ++i) {
    atoms.centers.row(static_cast<Eigen::Index>(i)) = centers[i].transpose();
    atoms.radii(static_cast<Eigen::Index>(i)) = radii[i];
  }
  return atoms;
}

/// Area of the union of the balls of radii R_i + `grow` by Shrake-Rupley with `points`
/// Fibonacci points per sphere: 4 pi (R_i + grow)^2 times the fraction of sphere i's points
/// outside every other ball. Converges like points^-3/4.
inline double union_area(const Atoms& atoms, double grow, int points) {
  double area = 0.0;
  const Eigen::Index n = atoms.centers.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    const double big = atoms.radii(i) + grow;
    int exposed = 0;
    for (int k = 0; k < points; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / points;
      const double phi = M_PI * (3.0 - std::sqrt(5.0)) * k;
      const double s = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d p = atoms.centers.row(i).transpose() +
                                big * Eigen::Vector3d(s * std::cos(phi), s * std::sin(phi), z);
      bool buried = false;
      for (Eigen::Index j = 0; j < n && !buried; ++j) {
        const double other = atoms.radii(j) + grow;
        buried = j != i && (p - atoms.centers.row(j).transpose()).squaredNorm() < other * other;
      }
      if (!buried) ++exposed;
    }
    area += 4.0 * M_PI * big * big * exposed / points;
  }
  return area;
}

}  // namespace surfcomp::test
