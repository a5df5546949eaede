#include "surfcomp/molsurf/ses_points.hpp"

#include "ses_nodes.hpp"
#include "ses_points_splat.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/spatial_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::molsurf {
namespace {

using detail::kInside;
using detail::kSolvent;
using detail::node_states;
using detail::NodeGrid;
using detail::NodeStates;

const char* const what = "<ses points>";

std::string number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void validate(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
              const Eigen::Ref<const Eigen::VectorXd>& radii, const SesPointOptions& options) {
  if (centers.rows() == 0)
    throw InputError(std::string(what) + ": no atoms; expected at least one");
  if (centers.rows() != radii.size()) {
    throw InputError(std::string(what) + ": " + std::to_string(centers.rows()) + " centres but " +
                     std::to_string(radii.size()) + " radii; expected one radius per centre");
  }
  for (Eigen::Index i = 0; i < centers.rows(); ++i) {
    if (!centers.row(i).allFinite() || !std::isfinite(radii(i)) || !(radii(i) > 0.0)) {
      throw InputError(std::string(what) + ": atom " + std::to_string(i + 1) +
                       " has a non-finite centre or a radius that is not > 0");
    }
  }
  if (!std::isfinite(options.probe_radius) || options.probe_radius < 0.0) {
    throw OptionError(std::string(what) + ": probe radius " + number(options.probe_radius) +
                      " A; expected a finite value >= 0");
  }
  if (!std::isfinite(options.grid_spacing) || !(options.grid_spacing > 0.0)) {
    throw OptionError(std::string(what) + ": grid spacing " + number(options.grid_spacing) +
                      " A; expected a finite value > 0");
  }
  if (!(options.max_grid_cells >= 1.0)) {
    throw OptionError(std::string(what) + ": " + options::named("max_grid_cells") + " " +
                      number(options.max_grid_cells) + "; expected a limit >= 1");
  }
}

/// The grid over the probe-grown balls with two spare nodes on every side, so that the border
/// is solvent. Throws InputError over the cell limit.
NodeGrid make_grid(const Eigen::Ref<const Eigen::MatrixX3d>& centers, const Eigen::VectorXd& grown,
                   const SesPointOptions& options) {
  const double h = options.grid_spacing;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (Eigen::Index a = 0; a < centers.rows(); ++a) {
    lo = lo.cwiseMin(centers.row(a).transpose() - Eigen::Vector3d::Constant(grown(a)));
    hi = hi.cwiseMax(centers.row(a).transpose() + Eigen::Vector3d::Constant(grown(a)));
  }
  const Eigen::Array3d extent = ((hi - lo) / h).array().ceil() + 5.0;
  const double cells = extent.prod();
  if (!(cells <= options.max_grid_cells)) {
    throw InputError(std::string(what) + ": the grid would have about " + number(cells) +
                     " nodes of " + number(h) + " A; the limit is " +
                     number(options.max_grid_cells) + " (raise it with " +
                     options::named("max_grid_cells") + ")");
  }
  NodeGrid grid;
  grid.spacing = h;
  grid.origin = lo - Eigen::Vector3d::Constant(2.0 * h);
  grid.nx = static_cast<int>(extent.x());
  grid.ny = static_cast<int>(extent.y());
  grid.nz = static_cast<int>(extent.z());
  return grid;
}

/// For each atom, the atoms (itself included) whose grown balls come within `slack` of its own.
std::vector<std::vector<std::int32_t>> atom_neighbours(
    const Eigen::Ref<const Eigen::MatrixX3d>& centers, const Eigen::VectorXd& grown, double slack) {
  const Eigen::Matrix3Xd points = centers.transpose();
  const double largest = grown.maxCoeff();
  const mesh::SpatialGrid grid(points, 2.0 * largest + slack);
  std::vector<std::vector<std::int32_t>> out(static_cast<std::size_t>(centers.rows()));
  for (Eigen::Index a = 0; a < centers.rows(); ++a) {
    grid.for_each_near(points.col(a), 2.0 * largest + slack, [&](int b) {
      if ((points.col(a) - points.col(b)).norm() <= grown(a) + grown(b) + slack)
        out[static_cast<std::size_t>(a)].push_back(b);
    });
  }
  return out;
}

/// Probe centres on the SAS, each with its outward SAS normal and the atom whose sphere it lies on
/// (the nearer of the two on a crease).
struct Probes {
  std::vector<Eigen::Vector3f> centres, outward;
  std::vector<std::int32_t> atoms;
  std::vector<std::int64_t> cells;  ///< the cell each falls in, for keeping one per cell

  void add(const Eigen::Vector3d& centre, const Eigen::Vector3d& normal, std::int32_t atom,
           const NodeGrid& grid, double cell) {
    const Eigen::Vector3d c = ((centre - grid.origin) / cell).array().floor();
    const auto span = static_cast<std::int64_t>(std::ceil(grid.spacing / cell)) + 1;
    cells.push_back(
        (static_cast<std::int64_t>(c.z()) * span * grid.ny + static_cast<std::int64_t>(c.y())) *
            span * grid.nx +
        static_cast<std::int64_t>(c.x()));
    centres.push_back(centre.cast<float>());
    outward.push_back(normal.cast<float>());
    atoms.push_back(atom);
  }

  /// Keeps the first probe of each cell, in order.
  void keep_one_per_cell() {
    std::vector<std::size_t> order(centres.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return cells[a] < cells[b]; });
    std::vector<bool> keep(centres.size(), false);
    for (std::size_t q = 0; q < order.size(); ++q)
      keep[order[q]] = q == 0 || cells[order[q]] != cells[order[q - 1]];
    std::size_t kept = 0;
    for (std::size_t p = 0; p < centres.size(); ++p) {
      if (!keep[p]) continue;
      centres[kept] = centres[p];
      outward[kept] = outward[p];
      atoms[kept] = atoms[p];
      cells[kept] = cells[p];
      ++kept;
    }
    centres.resize(kept);
    outward.resize(kept);
    atoms.resize(kept);
    cells.resize(kept);
  }

  void append(const Probes& other) {
    centres.insert(centres.end(), other.centres.begin(), other.centres.end());
    outward.insert(outward.end(), other.outward.begin(), other.outward.end());
    atoms.insert(atoms.end(), other.atoms.begin(), other.atoms.end());
    cells.insert(cells.end(), other.cells.begin(), other.cells.end());
  }
};

/// The atoms as the probe placement and the field read them: centres as columns, radii, the
/// probe-grown radii and, for each atom, those whose grown balls come within two spacings.
struct GrownAtoms {
  Eigen::Matrix3Xd points;
  Eigen::VectorXd radii, grown;
  std::vector<std::vector<std::int32_t>> neighbours;

  /// The atom whose sphere the SES follows at x when x's nearest probe lies on atom `a`'s grown
  /// sphere: `a`, where the probe rolling over it touches it at x's radial projection (which is
  /// then solvent: inside no other grown sphere); -1 where the surface is re-entrant there.
  std::int32_t contact(const Eigen::Vector3d& x, std::int32_t a) const {
    const Eigen::Vector3d ca = points.col(a);
    const double from_centre = (x - ca).norm();
    if (!(from_centre > 1e-9)) return -1;
    const Eigen::Vector3d touching = ca + grown(a) / from_centre * (x - ca);
    for (const std::int32_t b : neighbours[static_cast<std::size_t>(a)]) {
      if (b != a && (touching - points.col(b)).squaredNorm() < grown(b) * grown(b)) return -1;
    }
    return a;
  }
};

/// The solvent nodes next to an inside node: beside an inside run in its own row, or in a run of a
/// neighbouring row (y or z), each once, in node order.
std::vector<std::size_t> boundary_nodes(const NodeGrid& grid, const NodeStates& nodes) {
  std::vector<std::size_t> boundary;
  for (int k = 1; k + 1 < grid.nz; ++k) {
    for (int j = 1; j + 1 < grid.ny; ++j) {
      const std::size_t row_start = grid.index(0, j, k);
      const auto add = [&](int i) {
        if (i < 1 || i + 1 >= grid.nx) return;
        const std::size_t at = row_start + static_cast<std::size_t>(i);
        if (nodes.state[at] == kSolvent) boundary.push_back(at);
      };
      const auto [own_begin, own_end] = nodes.inside.row(grid.row(j, k));
      for (const auto* run = own_begin; run != own_end; ++run) {
        add(run->first - 1);
        add(run->second + 1);
      }
      // Beside a neighbour row's inside run, the nodes of this row's gaps (not inside here).
      for (const std::size_t r :
           {grid.row(j - 1, k), grid.row(j + 1, k), grid.row(j, k - 1), grid.row(j, k + 1)}) {
        const auto* own = own_begin;
        const auto [begin, end] = nodes.inside.row(r);
        for (const auto* run = begin; run != end; ++run) {
          int i = run->first;
          while (i <= run->second) {
            while (own != own_end && own->second < i) ++own;
            if (own != own_end && own->first <= i) {
              i = own->second + 1;
              continue;
            }
            const int gap_end =
                own != own_end ? std::min(run->second, own->first - 1) : run->second;
            for (; i <= gap_end; ++i) add(i);
          }
        }
      }
    }
  }
  std::sort(boundary.begin(), boundary.end());
  boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
  return boundary;
}

/// Probe centres: each boundary node moved to its nearest point of the union's boundary (the
/// nearest point of the union to a point outside it lies on the nearest sphere, and inside no other
/// sphere). That sphere is within one spacing of the node, so it is a neighbour of the atom that
/// holds the node's inside neighbour. Probes closer than these cells to an earlier one add little
/// the surface can show: one per cell of two spacings is kept of the probes on one sphere, one per
/// cell of a spacing of those on creases, which come last.
Probes place_probes(const NodeGrid& grid, const NodeStates& nodes,
                    const std::vector<std::size_t>& boundary, const GrownAtoms& atoms) {
  const double h = grid.spacing;
  Probes probes, crease_probes;
  const double probe_cell = 2.0 * h, crease_cell = h;
  for (const std::size_t at : boundary) {
    std::int32_t holder = -1;
    for (int axis = 0; axis < 3; ++axis) {
      const std::size_t s = grid.step(axis);
      for (const std::size_t next : {at - s, at + s}) {
        if (nodes.state[next] == kInside) holder = nodes.atom[next];
      }
    }
    const int i = static_cast<int>(at % static_cast<std::size_t>(grid.nx));
    const int j = static_cast<int>(at / static_cast<std::size_t>(grid.nx) %
                                   static_cast<std::size_t>(grid.ny));
    const int k = static_cast<int>(
        at / (static_cast<std::size_t>(grid.nx) * static_cast<std::size_t>(grid.ny)));
    const Eigen::Vector3d x = grid.position(i, j, k);
    // The nearest sphere, and the second nearest where the node lies near their crease.
    double nearest = std::numeric_limits<double>::infinity(), second = nearest;
    std::int32_t which = -1, other = -1;
    for (const std::int32_t a : atoms.neighbours[static_cast<std::size_t>(holder)]) {
      const double gap = (x - atoms.points.col(a)).norm() - atoms.grown(a);
      if (gap < nearest) {
        second = nearest;
        other = which;
        nearest = gap;
        which = a;
      } else if (gap < second) {
        second = gap;
        other = a;
      }
    }
    const Eigen::Vector3d u = (x - atoms.points.col(which)).normalized();
    const Eigen::Vector3d s = atoms.points.col(which) + atoms.grown(which) * u;
    probes.add(s, u, which, grid, probe_cell);
    // Near a crease, also the nearest point of the circle where the two spheres meet, when no
    // other sphere holds it: the probe positions the re-entrant surface hangs from, which the
    // projections onto one sphere only approach.
    if (other < 0 || second - nearest > h) continue;
    const Eigen::Vector3d ci = atoms.points.col(which), cj = atoms.points.col(other);
    const double d = (cj - ci).norm();
    const double ri = atoms.grown(which), rj = atoms.grown(other);
    if (!(d > std::abs(ri - rj)) || !(d < ri + rj)) continue;
    const Eigen::Vector3d axis = (cj - ci) / d;
    const double along = (d * d + ri * ri - rj * rj) / (2.0 * d);
    const double rho = std::sqrt(std::max(0.0, ri * ri - along * along));
    const Eigen::Vector3d radial = (x - ci) - (x - ci).dot(axis) * axis;
    if (!(radial.norm() > 1e-9)) continue;
    const Eigen::Vector3d crease = ci + along * axis + rho * radial.normalized();
    bool free = true;
    for (const std::int32_t a : atoms.neighbours[static_cast<std::size_t>(holder)]) {
      if (a == which || a == other) continue;
      if ((crease - atoms.points.col(a)).norm() < atoms.grown(a) - 1e-9) {
        free = false;
        break;
      }
    }
    if (!free) continue;
    crease_probes.add(crease,
                      ((crease - ci).normalized() + (crease - cj).normalized()).normalized(), which,
                      grid, crease_cell);
  }
  probes.keep_one_per_cell();
  crease_probes.keep_one_per_cell();
  probes.append(crease_probes);
  return probes;
}

/// The nodes within `reach` of a probe: each one's squared distance to the nearest probe centre and
/// that probe (solvent nodes too: they are outside the SES whatever their distance), and each row's
/// first and last node reached.
struct ProbeReach {
  double reach = 0.0;
  std::vector<float> distance2;
  std::vector<std::int32_t> owner;  ///< -1 where no probe reaches
  std::vector<int> first,
      last;  ///< per row; first nx and last -1 where none is reached

  ProbeReach(const NodeGrid& grid, const Probes& probes, double reach_)
      : reach(reach_),
        distance2(grid.size() + detail::row_padding, std::numeric_limits<float>::infinity()),
        owner(grid.size() + detail::row_padding, -1),
        first(grid.rows(), grid.nx),
        last(grid.rows(), -1) {
    detail::SplatGrid splat;
    for (int c = 0; c < 3; ++c) splat.origin[c] = grid.origin(c);
    splat.spacing = grid.spacing;
    splat.nx = grid.nx;
    splat.ny = grid.ny;
    splat.nz = grid.nz;
    std::vector<float> centres;
    centres.reserve(3 * probes.centres.size());
    for (const Eigen::Vector3f& c : probes.centres)
      centres.insert(centres.end(), {c.x(), c.y(), c.z()});
    detail::splat_probes(splat, centres, reach, distance2.data(), owner.data(), first.data(),
                         last.data());
  }
};

// f > 0 inside the SES: the distance to the solvent's probe centres less the probe radius, which
// is at least the distance to the solvent itself (the probes are some of its boundary points),
// by up to the sagitta between probes. Where the SES follows an atom's sphere, the distance to
// the solvent is exact, R_a - |x - c_a|: there the field is r_a - |x - c_a| instead, so that
// contact surfaces cross the grid where they are, not where the probes' spheres bulge.
std::vector<float> ses_field(const NodeGrid& grid, const NodeStates& nodes, const Probes& probes,
                             const ProbeReach& reached_by, const GrownAtoms& atoms, double probe) {
  std::vector<float> field(grid.size());
  const double bulge = grid.spacing, reach = reached_by.reach;
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      const std::size_t row = grid.row(j, k);
      for (int i = 0; i < grid.nx; ++i) {
        const std::size_t at = grid.index(i, j, k);
        const bool reached = i + 1 >= reached_by.first[row] && i <= reached_by.last[row] + 1;
        if (nodes.state[at] == kSolvent) {
          field[at] = static_cast<float>(-probe);
          continue;
        }
        double f =
            (reached ? std::min(std::sqrt(static_cast<double>(reached_by.distance2[at])), reach)
                     : reach) -
            probe;
        const std::int32_t owner = reached_by.owner[at];
        if (reached && f > 0.0 && f <= bulge && owner >= 0) {
          const Eigen::Vector3d x = grid.position(i, j, k);
          const std::int32_t a = atoms.contact(x, probes.atoms[static_cast<std::size_t>(owner)]);
          if (a >= 0) f = atoms.radii(a) - (x - atoms.points.col(a)).norm();
        }
        field[at] = static_cast<float>(f);
      }
    }
  }
  return field;
}

/// The points where the field changes sign along the grid's edges, moved onto the surface they
/// sample: an atom's sphere where the SES follows one (exact point and normal), else the nearest
/// probe's sphere (re-entrant), each with the area of the grid face it stands for.
SurfacePoints field_crossings(const NodeGrid& grid, const std::vector<float>& field,
                              const Probes& probes, const ProbeReach& reached_by,
                              const GrownAtoms& atoms, double probe) {
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<double> areas;
  const double h = grid.spacing;
  const double face = h * h;
  for (int k = 0; k + 1 < grid.nz; ++k) {
    for (int j = 0; j + 1 < grid.ny; ++j) {
      const std::size_t row = grid.row(j, k);
      const int last = std::min(reached_by.last[row], grid.nx - 2);
      for (int i = std::max(reached_by.first[row] - 1, 0); i <= last; ++i) {
        const std::size_t at = grid.index(i, j, k);
        const double fa = field[at];
        for (int axis = 0; axis < 3; ++axis) {
          const std::size_t next = at + grid.step(axis);
          const double fb = field[next];
          if ((fa > 0.0) == (fb > 0.0)) continue;
          const bool a_in = fa > 0.0;
          const double f_in = a_in ? fa : fb;
          const double f_out = a_in ? fb : fa;
          const double t = f_in / (f_in - f_out);
          Eigen::Vector3d x = grid.position(i, j, k);
          x(axis) += (a_in ? t : 1.0 - t) * h;
          // The nearer probe of the two ends': the surface there is that probe's sphere.
          std::int32_t s = reached_by.owner[at];
          const std::int32_t other = reached_by.owner[next];
          if (other >= 0 &&
              (s < 0 ||
               (x - probes.centres[static_cast<std::size_t>(other)].cast<double>()).squaredNorm() <
                   (x - probes.centres[static_cast<std::size_t>(s)].cast<double>()).squaredNorm()))
            s = other;
          if (s < 0) continue;
          // On an atom's sphere the point and normal are exact; elsewhere (re-entrant) they are
          // the nearest probe's.
          const std::int32_t a = atoms.contact(x, probes.atoms[static_cast<std::size_t>(s)]);
          const Eigen::Vector3d centre = probes.centres[static_cast<std::size_t>(s)].cast<double>();
          const Eigen::Vector3d away = x - centre;
          Eigen::Vector3d n;
          if (a >= 0) {
            n = (x - atoms.points.col(a)).normalized();
            x = atoms.points.col(a) + atoms.radii(a) * n;
          } else if (probe > 0.0 && away.norm() > 1e-9) {
            n = -away.normalized();
            x = centre - probe * n;
          } else {
            n = probes.outward[static_cast<std::size_t>(s)].cast<double>();
            x = centre;
          }
          points.push_back(x);
          normals.push_back(n);
          areas.push_back(face * std::abs(n(axis)));
        }
      }
    }
  }
  SurfacePoints out;
  const auto m = static_cast<Eigen::Index>(points.size());
  out.points.resize(3, m);
  out.normals.resize(3, m);
  out.areas.resize(m);
  for (Eigen::Index c = 0; c < m; ++c) {
    out.points.col(c) = points[static_cast<std::size_t>(c)];
    out.normals.col(c) = normals[static_cast<std::size_t>(c)];
    out.areas(c) = areas[static_cast<std::size_t>(c)];
  }
  return out;
}

}  // namespace

SurfacePoints ses_points(const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                         const Eigen::Ref<const Eigen::VectorXd>& radii,
                         const SesPointOptions& options) {
  validate(centers, radii, options);
  const double probe = options.probe_radius;
  const double h = options.grid_spacing;
  GrownAtoms atoms;
  atoms.points = centers.transpose();
  atoms.radii = radii;
  atoms.grown = radii.array() + probe;
  const NodeGrid grid = make_grid(centers, atoms.grown, options);
  const NodeStates nodes = node_states(grid, centers, atoms.grown);
  atoms.neighbours = atom_neighbours(centers, atoms.grown, 2.0 * h);
  const Probes probes = place_probes(grid, nodes, boundary_nodes(grid, nodes), atoms);
  // Every edge the SES crosses has both ends within reach (|f| changes by at most a spacing along
  // an edge), so the crossings are looked for only between each row's first and last node reached.
  const ProbeReach reached_by(grid, probes, std::max(probe + 1.001 * h, 3.0 * h));
  const std::vector<float> field = ses_field(grid, nodes, probes, reached_by, atoms, probe);
  return field_crossings(grid, field, probes, reached_by, atoms, probe);
}

}  // namespace surfcomp::molsurf
