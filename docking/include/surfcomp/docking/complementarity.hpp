// How well a ligand's surface fits a receptor's (docs/method.md#152-the-complementarity-score):
// contact rewarded, interpenetration penalised, and over the contact the product of the two
// sides' ESP (opposite signs attract) and the agreement of their LP (like faces like). The
// receptor's side is tabulated once on a grid over its site (ReceptorField); a pose is then
// scored from a sample of the ligand's surface points in a few microseconds per point.
#pragma once

#include "surfcomp/core/molecule.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/rigid_fit.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/site.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace surfcomp::docking {

/// The terms and weights of the complementarity score.
struct ComplementarityOptions {
  /// Default 0.5 A. The gap, from a ligand surface point to the receptor's van der Waals
  /// surface, at which contact counts fully: atoms in van der Waals contact leave about this.
  /// With contact_width, chosen so that the score's optimum lies nearest crystal poses
  /// (docs/decisions.md#the-contact-terms-gap-and-width). Finite.
  double contact_gap = 0.5;
  /// Default 0.5 A. The width (standard deviation) of the contact term about contact_gap.
  /// Finite, > 0.
  double contact_width = 0.5;
  /// Default 0.5 A. A ligand surface point may lie this deep inside the receptor's van der
  /// Waals surface before it counts as a clash (hydrogen bonds bring atoms that close).
  /// Finite, >= 0.
  double clash_tolerance = 0.5;
  /// Default 100 per A^2. The weight of the clash term, the mean squared depth beyond
  /// clash_tolerance: a point 0.1 A beyond the tolerance costs as much as one point's full
  /// contact, so that no gain in contact pays for pushing into the receptor. Finite, >= 0.
  double clash_weight = 100.0;
  /// Default 1 A. Metal atoms, the receptor's and the ligand's, count this much smaller than
  /// their van der Waals radius in the distances the contact and clash terms read: a
  /// coordination bond (Fe-N, Fe-S, Zn-O: 2.0-2.4 A) is 1.2-1.6 A shorter than van der Waals
  /// contact, which clash_tolerance covers only in part. Finite, >= 0.
  double metal_allowance = 1.0;
  /// Default 0.2. The weight of the ESP term. Finite, >= 0.
  double esp_weight = 0.2;
  /// Default 0.2. The weight of the LP term. Finite, >= 0.
  double lp_weight = 0.2;
  /// Default 1 per A^2. The weight of the site restraint: the squared distance by which the
  /// centre of the ligand's sample lies outside the site's spheres (a docking box's walls).
  /// Finite, >= 0.
  double site_weight = 1.0;
  /// Default 0.4 A. The spacing of the receptor's grid. Finite, in [0.1, 2].
  double spacing = 0.4;
  /// Default 6 A. The grid reaches this far beyond the site's spheres. Finite, >= 0.
  double margin = 6.0;
  /// Default 1 A. The ligand's surface is sampled at about one point per cell of this size.
  /// Finite, > 0.
  double sample_spacing = 1.0;
};

/// Throws OptionError naming the first option outside its domain.
void validate(const ComplementarityOptions& options);

/// A pose's complementarity and its terms, each a mean over the ligand's surface sample.
struct ComplementarityScore {
  /// contact + esp_weight esp + lp_weight lp - clash_weight clash - site_weight outside^2.
  double score = 0.0;
  double contact = 0.0;  ///< [0, 1]: the fraction of the ligand's surface in contact
  double clash = 0.0;    ///< A^2: mean squared depth beyond the clash tolerance
  double esp = 0.0;      ///< over the contact: minus the product of the sides' ESP z-scores
  double lp = 0.0;       ///< over the contact: the product of the sides' LP z-scores
  double outside = 0.0;  ///< A: how far the sample's centre lies outside the site
  /// A: the largest depth of a ligand surface point (lifted) inside the receptor's van der
  /// Waals surface, its metals counted smaller (0 when none is inside).
  double deepest = 0.0;
};

/// True when `score`'s deepest ligand surface point lies deeper inside the receptor than twice
/// the clash tolerance: such a pose intersects the receptor, and ranks after every one that does
/// not (dock, screen --receptor).
inline bool intersects(const ComplementarityScore& score, const ComplementarityOptions& options) {
  return score.deepest > 2.0 * options.clash_tolerance;
}

/// A ligand's surface as the score reads it: points about ComplementarityOptions::
/// sample_spacing apart, with the z-scores (over the whole surface) of their ESP and LP.
struct LigandSample {
  Eigen::Matrix3Xd points;  ///< A, the ligand's frame
  Eigen::VectorXd esp;      ///< z-scores, clipped to [-3, 3]; 0 without the property
  Eigen::VectorXd lp;       ///< z-scores, clipped to [-3, 3]; 0 without the property
  /// A, one per point or empty (all 0): added to the receptor's signed distance at the point.
  /// A point on a metal atom's sphere lies ComplementarityOptions::metal_allowance beyond the
  /// smaller sphere the metal counts as (lift_metal_points). ReceptorField::score throws
  /// InputError for a lift of another size than the points.
  Eigen::VectorXd lift;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< of the points
};

/// The sample of `surface` (a ligand's, with "esp" and "lp" when it has them): the vertex
/// nearest the centre of each occupied cell of a grid of `spacing`, in vertex order. Throws
/// InputError for an empty surface.
LigandSample sample_ligand(const mesh::Surface& surface, double spacing);

/// Sets `sample.lift` from the ligand's heavy atoms `atoms` (in the sample's frame): at each
/// point whose nearest atom, by the distance to its van der Waals sphere, is a metal,
/// `allowance` (at most the metal's radius); 0 elsewhere. Leaves `sample` without lift when no atom
/// is a metal.
void lift_metal_points(LigandSample& sample, const std::vector<harmonic::SurfaceAtom>& atoms,
                       double allowance);

/// A sample of points already pooled (a screening library's stored surface sample): `points`
/// with the z-scores over them of `esp` and `lp` (one value per point). Throws InputError naming
/// `source` for no point or values of another count.
LigandSample pooled_sample(const Eigen::Matrix3Xd& points, const Eigen::VectorXd& esp,
                           const Eigen::VectorXd& lp, const std::string& source);

/// The receptor's side of the score on a grid over its site: at each node the signed distance
/// to the receptor's van der Waals surface (negative inside; capped at +-4 A), and the z-scores
/// of the receptor's ESP and LP (molsurf::electrostatic_potential, lipophilic_potential; the
/// z-scores over the nodes within 2 A outside the surface). A metal atom's sphere is its radius
/// less ComplementarityOptions::metal_allowance. Outside the grid a point is in free
/// space: no contact, no clash.
class ReceptorField {
 public:
  /// Tabulates `receptor` (its atoms' positions, radii, charges and lipophilicities) around
  /// `site` (at least one sphere). Throws InputError for an empty receptor or site, OptionError
  /// for options outside their domain (validate) and for a grid of more than 64 million nodes.
  ReceptorField(const Molecule& receptor, const std::vector<molsurf::SiteSphere>& site,
                const ComplementarityOptions& options = {});

  /// The score of the ligand `sample` moved by `pose` (ligand frame -> receptor frame). With
  /// `gradient`, also the score's gradient for a motion of the moved sample: entries 0-2 per A
  /// of translation, 3-5 per radian of rotation about the moved sample's centroid (the
  /// derivative of the trilinear interpolant, so exact within grid cells).
  ComplementarityScore score(const LigandSample& sample, const matching::RigidTransform& pose,
                             Eigen::Matrix<double, 6, 1>* gradient = nullptr) const;

  /// The signed distance to the receptor's van der Waals surface, its metals counted smaller
  /// (ComplementarityOptions::metal_allowance), at `x` (A, trilinear; +4 outside the grid).
  double signed_distance(const Eigen::Vector3d& x) const;

  /// A^3: the volume of the grid nodes inside `site`'s spheres that lie outside the receptor's
  /// van der Waals surface, the room a ligand has there.
  double free_volume(const std::vector<molsurf::SiteSphere>& site) const;

  /// Whether free space (nodes at least 0.5 A outside the receptor's atoms) joins a node inside
  /// `site`'s spheres to the grid's border: false for a site buried with no opening.
  bool site_opens(const std::vector<molsurf::SiteSphere>& site) const;

  const ComplementarityOptions& options() const { return options_; }
  Eigen::Vector3d lower() const { return origin_; }  ///< the grid's lowest corner, A
  Eigen::Vector3d upper() const;                     ///< the grid's highest corner, A

 private:
  struct Node {
    float distance, esp, lp;
  };
  /// Where a point falls: outside the grid, in a cell whose eight nodes all hold the capped
  /// distance and no ESP or LP (the values there are constant), or in another cell.
  enum class Where { outside, far, near };
  /// The node values at `x` (trilinear) as (distance, esp, lp). With `gradient`, their
  /// gradients too, as its columns. `out` and `gradient` are set only for Where::near.
  Where sample(const Eigen::Vector3d& x, Eigen::Vector3d& out,
               Eigen::Matrix3d* gradient = nullptr) const;
  Eigen::Vector3d node_position(std::size_t n) const;
  /// Sets the ESP and LP z-scores of the nodes near the receptor's surface.
  void tabulate_potentials(const Molecule& receptor);
  void mark_far_cells();  ///< sets far_cells_ from nodes_

  ComplementarityOptions options_;
  std::vector<molsurf::SiteSphere> site_;
  Eigen::Vector3d origin_;
  Eigen::Vector3i size_;
  std::vector<Node> nodes_;
  /// Per node, 1 when the cell it is the lowest corner of is far (Where::far).
  std::vector<std::uint8_t> far_cells_;
};

}  // namespace surfcomp::docking
