// Test-only unions of balls: atoms as centres and radii, and the area of their union by
// Shrake-Rupley, the reference the surface tests compare the SES and SAS areas with, and the
// analytic SES area of two atoms; the heavy atoms of a PDB file.
#pragma once

#include "surfcomp/core/elements.hpp"

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
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

/// Heavy atoms of a PDB file (ATOM/HETATM, no water, alternate location ' ' or 'A'), with
/// Bondi radii from the element in columns 77-78.
inline Atoms read_pdb_heavy_atoms(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<Eigen::Vector3d> centers;
  std::vector<double> radii;
  std::string line;
  while (std::getline(in, line)) {
    if (line.size() < 78 || (line.rfind("ATOM", 0) != 0 && line.rfind("HETATM", 0) != 0)) continue;
    if (line.substr(17, 3) == "HOH" || (line[16] != ' ' && line[16] != 'A')) continue;
    const std::string element = normalize_element(line.substr(76, 2));
    if (element == "H") continue;
    centers.emplace_back(std::stod(line.substr(30, 8)), std::stod(line.substr(38, 8)),
                         std::stod(line.substr(46, 8)));
    radii.push_back(bondi_radius(element).value());
  }
  return make_atoms(centers, radii);
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

/// Analytic SES area of two atoms (radii r1, r2, centres d apart) bridged by the probe (p).
/// Put c1 at x = 0 and c2 at x = d on the axis. A probe touching both atoms has its centre P at
/// distance R1 = r1 + p from c1 and R2 = r2 + p from c2; in a plane through the axis
///   x0 = (d^2 + R1^2 - R2^2) / (2 d),  h = sqrt(R1^2 - x0^2)  (P's distance from the axis).
/// It touches atom 1 at polar angle theta1 from the axis (cos theta1 = x0 / R1) and atom 2 at
/// cos theta2 = (d - x0) / R2 measured from the reversed axis. The SES is
///  - the cap of atom 1 beyond its contact circle: 2 pi r1^2 (1 + cos theta1),
///  - the cap of atom 2 beyond its contact circle: 2 pi r2^2 (1 + cos theta2),
///  - the re-entrant patch swept by the probe's arc between the two contact points, the arc
///    that faces the axis: points P + p (cos phi, sin phi) for phi from phi1 = atan2(-h, -x0)
///    (towards c1) to phi2 = atan2(-h, d - x0) (towards c2). A point at distance
///    y = h + p sin phi from the axis sweeps a circle of length 2 pi y, so (Pappus)
///      A_torus = int 2 pi y p dphi = 2 pi p [h (phi2 - phi1) - p (cos phi2 - cos phi1)]
///    with cos phi1 = -x0 / R1 and cos phi2 = (d - x0) / R2.
/// Valid when the torus does not self-intersect (h > p: the probe cannot pass between the
/// atoms through the axis, so y > 0 on the arc) and each contact circle lies outside the other
/// atom; the caller asserts both.
struct TwoAtomSes {
  double area = 0.0;
  double h = 0.0;              ///< probe centre's distance from the axis, A
  double contact1_margin = 0;  ///< distance of atom 1's contact points from atom 2's surface, A
  double contact2_margin = 0;
};

inline TwoAtomSes two_atom_ses(double r1, double r2, double d, double p) {
  const double big1 = r1 + p;
  const double big2 = r2 + p;
  const double x0 = (d * d + big1 * big1 - big2 * big2) / (2.0 * d);
  TwoAtomSes out;
  out.h = std::sqrt(big1 * big1 - x0 * x0);
  const double phi1 = std::atan2(-out.h, -x0);
  const double phi2 = std::atan2(-out.h, d - x0);
  const double cap1 = 2.0 * M_PI * r1 * r1 * (1.0 + x0 / big1);
  const double cap2 = 2.0 * M_PI * r2 * r2 * (1.0 + (d - x0) / big2);
  const double torus = 2.0 * M_PI * p * (out.h * (phi2 - phi1) - p * ((d - x0) / big2 + x0 / big1));
  out.area = cap1 + cap2 + torus;
  const Eigen::Vector2d t1 = r1 / big1 * Eigen::Vector2d(x0, out.h);
  const Eigen::Vector2d t2 = Eigen::Vector2d(d, 0) + r2 / big2 * Eigen::Vector2d(x0 - d, out.h);
  out.contact1_margin = (t1 - Eigen::Vector2d(d, 0)).norm() - r2;
  out.contact2_margin = t2.norm() - r1;
  return out;
}

}  // namespace surfcomp::test
