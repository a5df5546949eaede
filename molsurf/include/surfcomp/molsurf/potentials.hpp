// Molecular potentials sampled at points (surface vertices): the Coulomb electrostatic
// potential (ESP) and the lipophilic potential (LP) of method §0.
#pragma once

#include "surfcomp/core/molecule.hpp"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

namespace surfcomp::molsurf {

/// Coulomb's constant in kcal*A/(mol*e^2): 332.06 * q1 * q2 / d is an energy in kcal/mol.
inline constexpr double coulomb_constant = 332.06;

/// Reports the progress of a long sum over atoms and points: called with the points done so far
/// and the total, at most about 100 times per call, increasing, the last time with done ==
/// total; never concurrently (calls are serialised), but from any thread. Empty by default.
using PotentialProgress = std::function<void(std::int64_t done, std::int64_t total)>;

/// The ESP treecode's default tolerance per box, kcal/(mol*e), and the atom count above which
/// it replaces the exact sum (a ligand's ESP stays exact). Measured over 4we2's vertices:
/// docs/benchmarks.md#potentials_bench.
inline constexpr double default_treecode_tolerance = 1e-3;
inline constexpr std::size_t treecode_min_atoms = 512;

/// How the ESP screens charges.
struct EspOptions {
  /// Relative permittivity eps (default 1, vacuum); must be > 0.
  double dielectric = 1.0;
  /// Default false. When true, eps = dielectric * d with d in A, i.e. the classic "4d" with
  /// dielectric = 4.
  bool distance_dependent = false;
  /// Default 0.5 A; distances below are clamped to it, guarding a point on an atom centre.
  /// Must be > 0.
  double min_distance = 0.5;
  /// The treecode that sums the Coulomb ESP of molecules of more than treecode_min_atoms
  /// atoms: the atoms are boxed in an octree, and a box of radius a (about its centre) at
  /// distance R from a point counts through the multipole expansion of its charges to the
  /// quadrupole when R - a >= min_distance and the expansion's error bound,
  /// 332.06 / eps * sum|q| a^3 / (R^3 (R - a)), is at most this tolerance (kcal/(mol*e));
  /// other boxes are opened, down to exact sums over their atoms. A point's error is at most
  /// the tolerance times the boxes so counted. 0 = the exact sum always. Must be finite and
  /// >= 0. Not used with distance_dependent (always exact).
  double treecode_tolerance = default_treecode_tolerance;
  /// Default empty; see PotentialProgress. The exact sum costs #points x #atoms distance
  /// evaluations; the treecode about #points x log(#atoms).
  PotentialProgress progress;
};

/// Coulomb ESP 332.06 * sum_i q_i / (eps * d_i) in kcal/(mol*e) at each point.
/// `points` is #P by 3 in A; q_i = Atom::charge (e); d_i = max(|p - x_i|, min_distance).
/// Returns #P values. Each point is computed independently (in parallel), so the result does not
/// depend on the thread count. Throws InputError for an empty molecule or a non-finite point,
/// atom position or charge, OptionError for dielectric or min_distance <= 0 or non-finite, or
/// a negative or non-finite treecode_tolerance.
Eigen::VectorXd electrostatic_potential(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                        const Molecule& molecule, const EspOptions& options = {});

/// The distance kernel g(d) of the lipophilic potential.
enum class LipophilicKernel {
  fauchere,  ///< g(d) = exp(-d), Fauchere et al. 1988
  dubost,    ///< g(d) = 1 / (1 + d), Dubost 1975
};

/// The names of the kernels, indexed by LipophilicKernel (as --lp-kernel spells them).
inline constexpr std::array<const char*, 2> lipophilic_kernel_names = {"fauchere", "dubost"};

/// The cutoff of Fauchere's kernel unless LpOptions says otherwise, A. The atoms beyond it
/// change a point's LP by at most exp(-12) = 6.1e-6 times the sum of their |f_i|; measured over
/// 4we2's vertices, at most 1.1e-4 of the LP's range (docs/benchmarks.md#potentials_bench).
inline constexpr double default_fauchere_cutoff = 12.0;

/// How the LP weighs atoms.
struct LpOptions {
  /// Default fauchere (exp(-d)).
  LipophilicKernel kernel = LipophilicKernel::fauchere;
  /// Atoms farther than this from a point (A) contribute nothing to it; 0 = every atom counts.
  /// Must be >= 0. Unset (default): default_fauchere_cutoff for Fauchere's kernel, none for
  /// Dubost's, whose 1 / (1 + d) decays too slowly for a cutoff to be harmless. The atoms
  /// within the cutoff are found from a grid of cells, so a protein's LP costs #points x the
  /// atoms near each point instead of #points x #atoms.
  std::optional<double> cutoff;
  /// Default empty; see PotentialProgress.
  PotentialProgress progress;
};

/// Lipophilic potential LP = sum_i f_i * g(d_i) (logP units) at each point, f_i =
/// Atom::lipophilicity, d_i = |p - x_i| in A. `points` is #P by 3 in A; returns #P values,
/// each computed independently (in parallel). Throws InputError for an empty molecule or a
/// non-finite point, atom position or lipophilicity, OptionError for a negative or non-finite
/// cutoff.
Eigen::VectorXd lipophilic_potential(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                     const Molecule& molecule, const LpOptions& options = {});

}  // namespace surfcomp::molsurf
