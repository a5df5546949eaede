#include "surfcomp/mesh/potentials.hpp"

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

namespace surfcomp::mesh {
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
  const SpatialGrid grid(sources.positions.transpose(), cutoff / 2.0);
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
  require_finite_points(points, caller);
  const Sources sources = collect_sources(molecule, &Atom::charge, "charge", caller);
  const double scale = coulomb_constant / options.dielectric;
  const double min_distance = options.min_distance;
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

}  // namespace surfcomp::mesh
