#include "surfcomp/molsurf/potentials.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::molsurf {
namespace {

std::string name_of(const Molecule& molecule) {
  return molecule.source.empty() ? std::string("<molecule>") : molecule.source;
}

std::string format_number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void require_finite_points(const Eigen::Ref<const Eigen::MatrixX3d>& points, const char* caller) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) {
      throw InputError(std::string(caller) + ": point " + std::to_string(i) +
                       " has a non-finite coordinate");
    }
  }
}

/// Atom positions (#A by 3) and one weight per atom (charge or lipophilicity), after checking
/// that there is at least one atom and everything used is finite.
struct Sources {
  Eigen::MatrixX3d positions;
  Eigen::VectorXd weights;
};

/// The sources whose weight is not zero, in their order.
Sources charged_only(const Sources& sources) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < sources.weights.size(); ++i)
    if (sources.weights(i) != 0.0) kept.push_back(i);
  Sources out;
  out.positions = sources.positions(kept, Eigen::all);
  out.weights = sources.weights(kept);
  return out;
}

Sources collect_sources(const Molecule& molecule, double Atom::*weight, const char* weight_name,
                        const char* caller) {
  if (molecule.atoms.empty()) {
    throw InputError(std::string(caller) + ": " + name_of(molecule) + " has no atoms");
  }
  Sources s;
  const auto n = static_cast<Eigen::Index>(molecule.atoms.size());
  s.positions.resize(n, 3);
  s.weights.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Atom& atom = molecule.atoms[static_cast<std::size_t>(i)];
    if (!atom.position.allFinite()) {
      throw InputError(std::string(caller) + ": " + name_of(molecule) + ": atom " +
                       std::to_string(i + 1) + " (" + atom.name + ") has a non-finite position");
    }
    if (!std::isfinite(atom.*weight)) {
      throw InputError(std::string(caller) + ": " + name_of(molecule) + ": atom " +
                       std::to_string(i + 1) + " (" + atom.name + ") has a non-finite " +
                       weight_name + " " + format_number(atom.*weight));
    }
    s.positions.row(i) = atom.position.transpose();
    s.weights(i) = atom.*weight;
  }
  return s;
}

/// values(p) = sum over atoms in index order of weight_i * kernel(d_i); points in parallel.
/// Calls `progress` (when set) as points are finished, about once per percent, serialised.
class ProgressReporter {
 public:
  ProgressReporter(const PotentialProgress& progress, std::int64_t total)
      : progress_(progress), total_(total), step_(std::max<std::int64_t>(1, total / 100)) {}
  void add(std::int64_t finished) {
    if (!progress_) return;
    const std::int64_t before = done_.fetch_add(finished);
    const std::int64_t after = before + finished;
    if (after / step_ == before / step_ && after != total_) return;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (after <= reported_) return;
    reported_ = after;
    progress_(after, total_);
  }

 private:
  const PotentialProgress& progress_;
  std::int64_t total_;
  std::int64_t step_;
  std::atomic<std::int64_t> done_{0};
  std::mutex mutex_;
  std::int64_t reported_ = 0;
};

template <class Kernel>
Eigen::VectorXd sum_over_atoms(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                               const Sources& sources, Kernel kernel,
                               const PotentialProgress& progress) {
  Eigen::VectorXd values(points.rows());
  const Eigen::Index n_atoms = sources.positions.rows();
  ProgressReporter reporter(progress, points.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, points.rows(), 256),
                    [&](const tbb::blocked_range<Eigen::Index>& range) {
                      for (Eigen::Index p = range.begin(); p != range.end(); ++p) {
                        const Eigen::RowVector3d x = points.row(p);
                        double sum = 0.0;
                        for (Eigen::Index a = 0; a < n_atoms; ++a) {
                          const double d = (x - sources.positions.row(a)).norm();
                          sum += sources.weights(a) * kernel(d);
                        }
                        values(p) = sum;
                      }
                      reporter.add(range.end() - range.begin());
                    });
  return values;
}

/// sum_over_atoms restricted to the atoms within `cutoff` (A, > 0) of each point: the atoms
/// are binned in a SpatialGrid of cells of cutoff / 2, and each point sums over the cells its
/// cutoff cube touches, in the grid's order (fixed, whatever the thread count), skipping atoms
/// farther than `cutoff`.
template <class Kernel>
Eigen::VectorXd sum_over_near_atoms(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                    const Sources& sources, double cutoff, Kernel kernel,
                                    const PotentialProgress& progress) {
  const mesh::SpatialGrid grid(sources.positions.transpose(), cutoff / 2.0);
  const double cutoff2 = cutoff * cutoff;
  Eigen::VectorXd values(points.rows());
  ProgressReporter reporter(progress, points.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, points.rows(), 256),
                    [&](const tbb::blocked_range<Eigen::Index>& range) {
                      for (Eigen::Index p = range.begin(); p != range.end(); ++p) {
                        const Eigen::Vector3d x = points.row(p).transpose();
                        double sum = 0.0;
                        grid.for_each_near(x, cutoff, [&](std::size_t a) {
                          const auto atom = static_cast<Eigen::Index>(a);
                          const double d2 =
                              (x - sources.positions.row(atom).transpose()).squaredNorm();
                          if (d2 <= cutoff2) sum += sources.weights(atom) * kernel(std::sqrt(d2));
                        });
                        values(p) = sum;
                      }
                      reporter.add(range.end() - range.begin());
                    });
  return values;
}

/// The charges of many atoms as an octree of boxes, each with the multipole expansion of its
/// charges (to the quadrupole) about its centre, for the ESP treecode (EspOptions::
/// treecode_tolerance). Built once; potential() is const and may run from any number of threads.
class ChargeTree {
 public:
  ChargeTree(const Sources& sources, double min_distance)
      : sources_(sources), min_distance_(min_distance) {
    order_.resize(static_cast<std::size_t>(sources.positions.rows()));
    for (std::size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<Eigen::Index>(i);
    build(0, order_.size(), 0);
  }

  /// sum_i q_i / max(d_i, min_distance) at x: a box through its expansion when R - a >=
  /// min_distance and its error bound sum|q| a^3 / (R^3 (R - a)) is at most `tolerance`, the
  /// others opened, down to their atoms; boxes in a fixed order.
  double potential(const Eigen::Vector3d& x, double tolerance) const {
    double sum = 0.0;
    std::vector<std::size_t> stack{0};
    while (!stack.empty()) {
      const Node& node = nodes_[stack.back()];
      stack.pop_back();
      const Eigen::Vector3d r = x - node.center;
      const double distance = r.norm();
      const double gap = distance - node.radius;
      const double a_over_r = node.radius / distance;
      if (gap >= min_distance_ &&
          node.abs_charge * a_over_r * a_over_r * a_over_r <= tolerance * gap) {
        const double inverse = 1.0 / distance;
        const double inverse3 = inverse * inverse * inverse;
        sum += node.charge * inverse + node.dipole.dot(r) * inverse3 +
               0.5 * r.dot(node.quadrupole * r) * inverse3 * inverse * inverse;
      } else if (node.children.empty()) {
        for (std::size_t k = node.first; k < node.last; ++k) {
          const Eigen::Index atom = order_[k];
          const double d = (x - sources_.positions.row(atom).transpose()).norm();
          sum += sources_.weights(atom) / std::max(d, min_distance_);
        }
      } else {
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child)
          stack.push_back(*child);
      }
    }
    return sum;
  }

 private:
  static constexpr std::size_t kLeafAtoms = 16;
  static constexpr int kMaxDepth = 32;

  struct Node {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    double radius = 0.0;
    double charge = 0.0;
    double abs_charge = 0.0;
    Eigen::Vector3d dipole = Eigen::Vector3d::Zero();
    Eigen::Matrix3d quadrupole = Eigen::Matrix3d::Zero();  ///< sum q (3 r r^T - |r|^2 I)
    std::size_t first = 0, last = 0;                       ///< its atoms in order_
    std::vector<std::size_t> children;                     ///< in octant order
  };

  Eigen::Vector3d position(std::size_t k) const {
    return sources_.positions.row(order_[k]).transpose();
  }

  /// Makes the node of order_[first, last) and, unless it is small (or its atoms coincide),
  /// its children, one per non-empty octant of its bounding box. Returns its index.
  std::size_t build(std::size_t first, std::size_t last, int depth) {
    Eigen::Vector3d low = position(first);
    Eigen::Vector3d high = low;
    for (std::size_t k = first; k < last; ++k) {
      low = low.cwiseMin(position(k));
      high = high.cwiseMax(position(k));
    }
    Node node;
    node.first = first;
    node.last = last;
    node.center = (low + high) / 2.0;
    for (std::size_t k = first; k < last; ++k) {
      const Eigen::Vector3d r = position(k) - node.center;
      const double q = sources_.weights(order_[k]);
      node.radius = std::max(node.radius, r.norm());
      node.charge += q;
      node.abs_charge += std::abs(q);
      node.dipole += q * r;
      node.quadrupole +=
          q * (3.0 * r * r.transpose() - r.squaredNorm() * Eigen::Matrix3d::Identity());
    }
    const std::size_t index = nodes_.size();
    nodes_.push_back(node);
    if (last - first <= kLeafAtoms || depth >= kMaxDepth || node.radius == 0.0) return index;
    // Octants: split by x, then each half by y, then each quarter by z.
    std::vector<std::size_t> bounds{first, last};
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<std::size_t> split{first};
      for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
        const auto begin = order_.begin() + static_cast<std::ptrdiff_t>(bounds[b]);
        const auto end = order_.begin() + static_cast<std::ptrdiff_t>(bounds[b + 1]);
        const auto middle = std::stable_partition(begin, end, [&](Eigen::Index atom) {
          return sources_.positions(atom, axis) < node.center(axis);
        });
        split.push_back(static_cast<std::size_t>(middle - order_.begin()));
        split.push_back(bounds[b + 1]);
      }
      bounds = std::move(split);
    }
    std::vector<std::size_t> children;
    for (std::size_t b = 0; b + 1 < bounds.size(); ++b) {
      if (bounds[b + 1] > bounds[b]) children.push_back(build(bounds[b], bounds[b + 1], depth + 1));
    }
    nodes_[index].children = std::move(children);
    return index;
  }

  const Sources& sources_;
  double min_distance_;
  std::vector<Eigen::Index> order_;
  std::vector<Node> nodes_;
};

}  // namespace

Eigen::VectorXd electrostatic_potential(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                        const Molecule& molecule, const EspOptions& options) {
  constexpr const char* caller = "electrostatic_potential";
  if (!(options.dielectric > 0.0) || !std::isfinite(options.dielectric)) {
    throw OptionError(std::string(caller) + ": dielectric is " + format_number(options.dielectric) +
                      "; expected a finite value > 0");
  }
  if (!(options.min_distance > 0.0) || !std::isfinite(options.min_distance)) {
    throw OptionError(std::string(caller) + ": min_distance is " +
                      format_number(options.min_distance) + " A; expected a finite value > 0");
  }
  if (!(options.treecode_tolerance >= 0.0) || !std::isfinite(options.treecode_tolerance)) {
    throw OptionError(std::string(caller) + ": treecode_tolerance is " +
                      format_number(options.treecode_tolerance) +
                      "; expected a finite value >= 0 (0 = the exact sum)");
  }
  require_finite_points(points, caller);
  const Sources sources = collect_sources(molecule, &Atom::charge, "charge", caller);
  const double scale = coulomb_constant / options.dielectric;
  const double min_distance = options.min_distance;
  if (!options.distance_dependent && options.treecode_tolerance > 0.0 &&
      molecule.atoms.size() > treecode_min_atoms) {
    // An uncharged atom adds nothing: the tree holds the charged ones only (a protein read from
    // PDB carries formal charges on a few atoms of its ionisable groups).
    const Sources charged = charged_only(sources);
    if (charged.weights.size() == 0) return Eigen::VectorXd::Zero(points.rows());
    const ChargeTree tree(charged, min_distance);
    Eigen::VectorXd values(points.rows());
    ProgressReporter reporter(options.progress, points.rows());
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, points.rows(), 256),
                      [&](const tbb::blocked_range<Eigen::Index>& range) {
                        for (Eigen::Index p = range.begin(); p != range.end(); ++p) {
                          values(p) = scale * tree.potential(points.row(p).transpose(),
                                                             options.treecode_tolerance / scale);
                        }
                        reporter.add(range.end() - range.begin());
                      });
    return values;
  }
  if (options.distance_dependent) {
    return sum_over_atoms(
        points, sources,
        [=](double d) {
          const double r = std::max(d, min_distance);
          return scale / (r * r);
        },
        options.progress);
  }
  return sum_over_atoms(
      points, sources, [=](double d) { return scale / std::max(d, min_distance); },
      options.progress);
}

Eigen::VectorXd lipophilic_potential(const Eigen::Ref<const Eigen::MatrixX3d>& points,
                                     const Molecule& molecule, const LpOptions& options) {
  constexpr const char* caller = "lipophilic_potential";
  const bool is_dubost = options.kernel == LipophilicKernel::dubost;
  const double cutoff = options.cutoff.value_or(is_dubost ? 0.0 : default_fauchere_cutoff);
  if (!(cutoff >= 0.0) || !std::isfinite(cutoff)) {
    throw OptionError(std::string(caller) + ": cutoff is " + format_number(cutoff) +
                      " A; expected a finite value >= 0 (0 = no cutoff)");
  }
  require_finite_points(points, caller);
  const Sources sources = collect_sources(molecule, &Atom::lipophilicity, "lipophilicity", caller);
  const auto dubost = [](double d) { return 1.0 / (1.0 + d); };
  const auto fauchere = [](double d) { return std::exp(-d); };
  if (cutoff > 0.0) {
    return is_dubost ? sum_over_near_atoms(points, sources, cutoff, dubost, options.progress)
                     : sum_over_near_atoms(points, sources, cutoff, fauchere, options.progress);
  }
  return is_dubost ? sum_over_atoms(points, sources, dubost, options.progress)
                   : sum_over_atoms(points, sources, fauchere, options.progress);
}

}  // namespace surfcomp::molsurf
