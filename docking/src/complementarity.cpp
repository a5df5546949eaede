#include "surfcomp/docking/complementarity.hpp"

#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/mesh/surface.hpp"
#include "surfcomp/molsurf/potentials.hpp"

#include "require_option.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <tuple>

namespace surfcomp::docking {
namespace {

constexpr double distance_cap = 4.0;  // A: the signed distance saturates here
constexpr double z_clip = 3.0;
constexpr double unknown_radius = 1.7;  // A: carbon's, for a symbol that is not an element

/// The radius a receptor atom counts with: its own, a metal's less `allowance`.
double counted_radius(const Atom& atom, double allowance) {
  return is_metal(atom.element) ? std::max(0.0, atom.radius - allowance) : atom.radius;
}

/// z-scores of `values` by the mean and standard deviation of those flagged in `use`, clipped
/// to [-z_clip, z_clip]; all 0 when fewer than two are flagged or they are constant.
Eigen::VectorXd z_scores(const Eigen::VectorXd& values, const std::vector<bool>& use) {
  double sum = 0.0, squares = 0.0;
  std::size_t n = 0;
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    if (!use[static_cast<std::size_t>(i)]) continue;
    sum += values(i);
    squares += values(i) * values(i);
    ++n;
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(values.size());
  if (n < 2) return out;
  const double mean = sum / static_cast<double>(n);
  const double variance = std::max(0.0, squares / static_cast<double>(n) - mean * mean);
  const double deviation = std::sqrt(variance);
  if (!(deviation > 1e-12 * (std::abs(mean) + 1.0))) return out;
  for (Eigen::Index i = 0; i < values.size(); ++i)
    out(i) = std::clamp((values(i) - mean) / deviation, -z_clip, z_clip);
  return out;
}

}  // namespace

void validate(const ComplementarityOptions& o) {
  const auto require = detail::require_option;
  require(std::isfinite(o.contact_gap), "contact_gap", o.contact_gap, "finite");
  require(std::isfinite(o.contact_width) && o.contact_width > 0.0, "contact_width", o.contact_width,
          "finite and > 0");
  require(std::isfinite(o.clash_tolerance) && o.clash_tolerance >= 0.0, "clash_tolerance",
          o.clash_tolerance, "finite and >= 0");
  require(std::isfinite(o.clash_weight) && o.clash_weight >= 0.0, "clash_weight", o.clash_weight,
          "finite and >= 0");
  require(std::isfinite(o.metal_allowance) && o.metal_allowance >= 0.0, "metal_allowance",
          o.metal_allowance, "finite and >= 0");
  require(std::isfinite(o.esp_weight) && o.esp_weight >= 0.0, "esp_weight", o.esp_weight,
          "finite and >= 0");
  require(std::isfinite(o.lp_weight) && o.lp_weight >= 0.0, "lp_weight", o.lp_weight,
          "finite and >= 0");
  require(std::isfinite(o.site_weight) && o.site_weight >= 0.0, "site_weight", o.site_weight,
          "finite and >= 0");
  require(std::isfinite(o.spacing) && o.spacing >= 0.1 && o.spacing <= 2.0, "grid_spacing",
          o.spacing, "in [0.1, 2] A");
  require(std::isfinite(o.margin) && o.margin >= 0.0, "grid_margin", o.margin, "finite and >= 0");
  require(std::isfinite(o.sample_spacing) && o.sample_spacing > 0.0, "sample_spacing",
          o.sample_spacing, "finite and > 0");
}

LigandSample sample_ligand(const mesh::Surface& surface, double spacing) {
  const Eigen::MatrixX3d positions = surface.positions();
  if (positions.rows() == 0) throw InputError(surface.source() + ": the surface has no vertex");
  // The vertex nearest each occupied cell's centre, cells visited in the order of their first
  // vertex so that the sample does not depend on hashing.
  std::map<std::tuple<long, long, long>, std::pair<Eigen::Index, double>> cells;
  std::vector<std::tuple<long, long, long>> order;
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d x = positions.row(v).transpose() / spacing;
    const std::tuple<long, long, long> key{std::lround(std::floor(x.x())),
                                           std::lround(std::floor(x.y())),
                                           std::lround(std::floor(x.z()))};
    const Eigen::Vector3d centre(static_cast<double>(std::get<0>(key)) + 0.5,
                                 static_cast<double>(std::get<1>(key)) + 0.5,
                                 static_cast<double>(std::get<2>(key)) + 0.5);
    const double d = (x - centre).squaredNorm();
    auto [it, added] = cells.try_emplace(key, v, d);
    if (added) {
      order.push_back(key);
    } else if (d < it->second.second) {
      it->second = {v, d};
    }
  }
  const std::vector<bool> all(static_cast<std::size_t>(positions.rows()), true);
  const auto scores = [&](const char* name) {
    return surface.has_property(name) ? z_scores(surface.property(name), all)
                                      : Eigen::VectorXd(Eigen::VectorXd::Zero(positions.rows()));
  };
  const Eigen::VectorXd esp = scores(mesh::property::esp);
  const Eigen::VectorXd lp = scores(mesh::property::lp);
  LigandSample sample;
  const auto n = static_cast<Eigen::Index>(order.size());
  sample.points.resize(3, n);
  sample.esp.resize(n);
  sample.lp.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Index v = cells.at(order[static_cast<std::size_t>(k)]).first;
    sample.points.col(k) = positions.row(v).transpose();
    sample.esp(k) = esp(v);
    sample.lp(k) = lp(v);
  }
  sample.centroid = sample.points.rowwise().mean();
  return sample;
}

void lift_metal_points(LigandSample& sample, const std::vector<harmonic::SurfaceAtom>& atoms,
                       double allowance) {
  sample.lift.resize(0);
  std::vector<double> radii;
  bool metal = false;
  for (const harmonic::SurfaceAtom& atom : atoms) {
    radii.push_back(bondi_radius(atom.element).value_or(unknown_radius));
    metal = metal || is_metal(atom.element);
  }
  if (!metal || allowance == 0.0) return;
  sample.lift = Eigen::VectorXd::Zero(sample.points.cols());
  for (Eigen::Index k = 0; k < sample.points.cols(); ++k) {
    double nearest = std::numeric_limits<double>::infinity();
    std::size_t owner = 0;
    for (std::size_t i = 0; i < atoms.size(); ++i) {
      const double d = (sample.points.col(k) - atoms[i].position).norm() - radii[i];
      if (d < nearest) {
        nearest = d;
        owner = i;
      }
    }
    // The metal's sphere, `allowance` smaller, shrinks at most to its centre (as the receptor's).
    if (is_metal(atoms[owner].element)) sample.lift(k) = std::min(allowance, radii[owner]);
  }
}

LigandSample pooled_sample(const Eigen::Matrix3Xd& points, const Eigen::VectorXd& esp,
                           const Eigen::VectorXd& lp, const std::string& source) {
  if (points.cols() == 0) throw InputError(source + ": the surface sample has no point");
  if (esp.size() != points.cols() || lp.size() != points.cols())
    throw InputError(source + ": the surface sample's ESP or LP values do not match its points");
  const std::vector<bool> all(static_cast<std::size_t>(points.cols()), true);
  LigandSample sample;
  sample.points = points;
  sample.esp = z_scores(esp, all);
  sample.lp = z_scores(lp, all);
  sample.centroid = points.rowwise().mean();
  return sample;
}

ReceptorField::ReceptorField(const Molecule& receptor, const std::vector<molsurf::SiteSphere>& site,
                             const ComplementarityOptions& options)
    : options_(options), site_(site) {
  validate(options);
  if (receptor.atoms.empty()) throw InputError(receptor.source + ": the receptor has no atoms");
  if (site.empty()) throw InputError(receptor.source + ": the site has no sphere");
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const molsurf::SiteSphere& s : site) {
    low = low.cwiseMin(s.center - Eigen::Vector3d::Constant(s.radius));
    high = high.cwiseMax(s.center + Eigen::Vector3d::Constant(s.radius));
  }
  low -= Eigen::Vector3d::Constant(options.margin);
  high += Eigen::Vector3d::Constant(options.margin);
  const double h = options.spacing;
  origin_ = low;
  for (int a = 0; a < 3; ++a) size_(a) = static_cast<int>(std::ceil((high(a) - low(a)) / h)) + 1;
  const double count = static_cast<double>(size_.x()) * size_.y() * size_.z();
  if (count > 64e6) {
    throw OptionError("the site is too large for a grid of " + std::to_string(h) +
                      " A: " + std::to_string(static_cast<long long>(count)) +
                      " nodes (at most 64 million); give a smaller site or a coarser " +
                      options::named("grid_spacing"));
  }
  // The atoms that can be within the distance cap of the grid, in cells of the cap's size.
  double largest_radius = 0.0;
  for (const Atom& atom : receptor.atoms) largest_radius = std::max(largest_radius, atom.radius);
  const double reach = distance_cap + largest_radius;
  const double cell = reach;
  const Eigen::Vector3d cell_origin = low - Eigen::Vector3d::Constant(reach);
  Eigen::Vector3i cells;
  for (int a = 0; a < 3; ++a)
    cells(a) = static_cast<int>(std::ceil((high(a) - low(a) + 2 * reach) / cell)) + 1;
  std::vector<std::vector<int>> atoms_in(static_cast<std::size_t>(cells.prod()));
  const auto cell_index = [&](const Eigen::Vector3i& c) {
    return (static_cast<std::size_t>(c.z()) * static_cast<std::size_t>(cells.y()) +
            static_cast<std::size_t>(c.y())) *
               static_cast<std::size_t>(cells.x()) +
           static_cast<std::size_t>(c.x());
  };
  for (std::size_t i = 0; i < receptor.atoms.size(); ++i) {
    const Eigen::Vector3d x = receptor.atoms[i].position;
    if (!x.allFinite()) throw InputError(receptor.source + ": an atom's position is not finite");
    if ((x.array() < (low.array() - reach)).any() || (x.array() > (high.array() + reach)).any())
      continue;
    const Eigen::Vector3i c = ((x - cell_origin) / cell).array().floor().cast<int>();
    atoms_in[cell_index(c.cwiseMax(0).cwiseMin(cells - Eigen::Vector3i::Ones()))].push_back(
        static_cast<int>(i));
  }
  const auto node_count = static_cast<std::size_t>(count);
  nodes_.assign(node_count, Node{static_cast<float>(distance_cap), 0.0f, 0.0f});
  const auto position = [this](std::size_t n) { return node_position(n); };
  tbb::parallel_for(std::size_t{0}, node_count, [&](std::size_t n) {
    const Eigen::Vector3d x = position(n);
    const Eigen::Vector3i c = ((x - cell_origin) / cell).array().floor().cast<int>();
    double best = distance_cap;
    for (int dz = -1; dz <= 1; ++dz) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3i k = c + Eigen::Vector3i(dx, dy, dz);
          if ((k.array() < 0).any() || (k.array() >= cells.array()).any()) continue;
          for (const int i : atoms_in[cell_index(k)]) {
            const Atom& atom = receptor.atoms[static_cast<std::size_t>(i)];
            best = std::min(
                best, (x - atom.position).norm() - counted_radius(atom, options.metal_allowance));
          }
        }
      }
    }
    nodes_[n].distance = static_cast<float>(std::max(best, -distance_cap));
  });
  tabulate_potentials(receptor);
  mark_far_cells();
}

void ReceptorField::tabulate_potentials(const Molecule& receptor) {
  // ESP and LP where a ligand's surface can touch: from just inside the surface to the cap.
  std::vector<std::size_t> shell;
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    if (nodes_[n].distance > -1.5f && nodes_[n].distance < static_cast<float>(distance_cap))
      shell.push_back(n);
  }
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(shell.size()), 3);
  for (std::size_t k = 0; k < shell.size(); ++k)
    points.row(static_cast<Eigen::Index>(k)) = node_position(shell[k]).transpose();
  if (shell.empty()) return;
  const Eigen::VectorXd esp = molsurf::electrostatic_potential(points, receptor);
  const Eigen::VectorXd lp = molsurf::lipophilic_potential(points, receptor);
  std::vector<bool> near_surface(shell.size());
  for (std::size_t k = 0; k < shell.size(); ++k) {
    const float d = nodes_[shell[k]].distance;
    near_surface[k] = d >= 0.0f && d <= 2.0f;
  }
  const Eigen::VectorXd esp_z = z_scores(esp, near_surface);
  const Eigen::VectorXd lp_z = z_scores(lp, near_surface);
  for (std::size_t k = 0; k < shell.size(); ++k) {
    nodes_[shell[k]].esp = static_cast<float>(esp_z(static_cast<Eigen::Index>(k)));
    nodes_[shell[k]].lp = static_cast<float>(lp_z(static_cast<Eigen::Index>(k)));
  }
}

void ReceptorField::mark_far_cells() {
  const auto nx = static_cast<std::size_t>(size_.x());
  const auto nxy = nx * static_cast<std::size_t>(size_.y());
  const auto at_cap = [this](std::size_t n) {
    const Node& node = nodes_[n];
    return node.distance == static_cast<float>(distance_cap) && node.esp == 0.0f && node.lp == 0.0f;
  };
  far_cells_.assign(nodes_.size(), 0);
  // The last node of each axis starts no cell: sample never reads its flag.
  for (std::size_t n = 0; n + nxy + nx + 1 < nodes_.size(); ++n) {
    far_cells_[n] = at_cap(n) && at_cap(n + 1) && at_cap(n + nx) && at_cap(n + nx + 1) &&
                    at_cap(n + nxy) && at_cap(n + nxy + 1) && at_cap(n + nxy + nx) &&
                    at_cap(n + nxy + nx + 1);
  }
}

Eigen::Vector3d ReceptorField::node_position(std::size_t n) const {
  const auto nx = static_cast<std::size_t>(size_.x());
  const auto ny = static_cast<std::size_t>(size_.y());
  const double h = options_.spacing;
  const std::size_t x = n % nx, y = (n / nx) % ny, z = n / (nx * ny);  // the node's indices
  return {origin_.x() + h * static_cast<double>(x), origin_.y() + h * static_cast<double>(y),
          origin_.z() + h * static_cast<double>(z)};
}

double ReceptorField::free_volume(const std::vector<molsurf::SiteSphere>& site) const {
  std::size_t free = 0;
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    if (nodes_[n].distance >= 0.0f && molsurf::in_site(node_position(n), site)) ++free;
  }
  const double h = options_.spacing;
  return static_cast<double>(free) * h * h * h;
}

bool ReceptorField::site_opens(const std::vector<molsurf::SiteSphere>& site) const {
  constexpr float clearance = 0.5f;
  const auto nx = static_cast<std::size_t>(size_.x());
  const auto ny = static_cast<std::size_t>(size_.y());
  const auto nz = static_cast<std::size_t>(size_.z());
  std::vector<bool> seen(nodes_.size(), false);
  std::vector<std::size_t> front;
  for (std::size_t n = 0; n < nodes_.size(); ++n) {
    if (nodes_[n].distance >= clearance && molsurf::in_site(node_position(n), site)) {
      seen[n] = true;
      front.push_back(n);
    }
  }
  while (!front.empty()) {
    const std::size_t n = front.back();
    front.pop_back();
    const std::size_t x = n % nx, y = (n / nx) % ny, z = n / (nx * ny);
    if (x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz) return true;
    for (const std::size_t m : {n - 1, n + 1, n - nx, n + nx, n - nx * ny, n + nx * ny}) {
      if (!seen[m] && nodes_[m].distance >= clearance) {
        seen[m] = true;
        front.push_back(m);
      }
    }
  }
  return false;
}

Eigen::Vector3d ReceptorField::upper() const {
  return origin_ + options_.spacing * (size_ - Eigen::Vector3i::Ones()).cast<double>();
}

ReceptorField::Where ReceptorField::sample(const Eigen::Vector3d& x, Eigen::Vector3d& out,
                                           Eigen::Matrix3d* gradient) const {
  const Eigen::Vector3d g = (x - origin_) / options_.spacing;
  const Eigen::Vector3d top = (size_ - Eigen::Vector3i::Ones()).cast<double>();
  if (!((g.array() >= 0.0).all() && (g.array() < top.array()).all())) return Where::outside;
  const Eigen::Vector3i i = g.array().floor().cast<int>();
  const auto nx = static_cast<std::size_t>(size_.x());
  const auto nxy = nx * static_cast<std::size_t>(size_.y());
  const std::size_t base = static_cast<std::size_t>(i.z()) * nxy +
                           static_cast<std::size_t>(i.y()) * nx + static_cast<std::size_t>(i.x());
  if (far_cells_[base] != 0) return Where::far;
  const double fx = g.x() - i.x(), fy = g.y() - i.y(), fz = g.z() - i.z();
  // The corners' (distance, esp, lp), vYZ running along x: v00 is (y, z) = (0, 0).
  const auto at = [this](std::size_t n) {
    const Node& node = nodes_[n];
    return Eigen::Array3d(node.distance, node.esp, node.lp);
  };
  const Eigen::Array3d v000 = at(base), v100 = at(base + 1);
  const Eigen::Array3d v010 = at(base + nx), v110 = at(base + nx + 1);
  const Eigen::Array3d v001 = at(base + nxy), v101 = at(base + nxy + 1);
  const Eigen::Array3d v011 = at(base + nxy + nx), v111 = at(base + nxy + nx + 1);
  const Eigen::Array3d c00 = v000 + fx * (v100 - v000), c10 = v010 + fx * (v110 - v010);
  const Eigen::Array3d c01 = v001 + fx * (v101 - v001), c11 = v011 + fx * (v111 - v011);
  const Eigen::Array3d c0 = c00 + fy * (c10 - c00), c1 = c01 + fy * (c11 - c01);
  out = (c0 + fz * (c1 - c0)).matrix();
  if (gradient != nullptr) {
    const Eigen::Array3d dx0 = (v100 - v000) + fy * ((v110 - v010) - (v100 - v000));
    const Eigen::Array3d dx1 = (v101 - v001) + fy * ((v111 - v011) - (v101 - v001));
    const double inverse = 1.0 / options_.spacing;
    gradient->row(0) = inverse * (dx0 + fz * (dx1 - dx0)).matrix().transpose();
    gradient->row(1) =
        inverse * ((c10 - c00) + fz * ((c11 - c01) - (c10 - c00))).matrix().transpose();
    gradient->row(2) = inverse * (c1 - c0).matrix().transpose();
  }
  return Where::near;
}

double ReceptorField::signed_distance(const Eigen::Vector3d& x) const {
  Eigen::Vector3d value;
  return sample(x, value) == Where::near ? value(0) : distance_cap;
}

ComplementarityScore ReceptorField::score(const LigandSample& ligand,
                                          const matching::RigidTransform& pose,
                                          Eigen::Matrix<double, 6, 1>* gradient) const {
  const ComplementarityOptions& o = options_;
  const double inverse_width = 1.0 / (2.0 * o.contact_width * o.contact_width);
  ComplementarityScore s;
  const Eigen::Index n = ligand.points.cols();
  const Eigen::Vector3d centre = pose.rotation * ligand.centroid + pose.translation;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  Eigen::Matrix3d slope;
  // A point in a far cell adds the capped distance's contact, and nothing else: no ESP or LP
  // there, no clash, and no gradient.
  const double far_gap = distance_cap - o.contact_gap;
  const double far_contact = std::exp(-far_gap * far_gap * inverse_width);
  if (ligand.lift.size() != 0 && ligand.lift.size() != n) {
    throw InputError("a ligand sample of " + std::to_string(n) + " points has " +
                     std::to_string(ligand.lift.size()) + " lifts");
  }
  std::size_t far = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d x = pose.rotation * ligand.points.col(k) + pose.translation;
    Eigen::Vector3d node;  // distance, esp, lp
    const Where where = sample(x, node, gradient != nullptr ? &slope : nullptr);
    if (where == Where::outside) continue;
    if (where == Where::far) {
      ++far;
      continue;
    }
    const double d = node(0) + (ligand.lift.size() != 0 ? ligand.lift(k) : 0.0);
    const double gap = d - o.contact_gap;
    const double contact = std::exp(-gap * gap * inverse_width);
    const double depth = std::max(0.0, -d - o.clash_tolerance);
    const double esp = -ligand.esp(k) * node(1), lp = ligand.lp(k) * node(2);
    s.contact += contact;
    s.clash += depth * depth;
    s.esp += contact * esp;
    s.lp += contact * lp;
    s.deepest = std::max(s.deepest, -d);
    if (gradient != nullptr) {
      // d(score term)/d(distance, esp, lp) at this point, then through the grid's gradients.
      const double dcontact = -contact * gap * 2.0 * inverse_width;
      const Eigen::Vector3d by_value(
          dcontact * (1.0 + o.esp_weight * esp + o.lp_weight * lp) + 2.0 * o.clash_weight * depth,
          -o.esp_weight * contact * ligand.esp(k), o.lp_weight * contact * ligand.lp(k));
      const Eigen::Vector3d g = slope * by_value;
      force += g;
      torque += (x - centre).cross(g);
    }
  }
  s.contact += static_cast<double>(far) * far_contact;
  if (n > 0) {
    const double inverse = 1.0 / static_cast<double>(n);
    s.contact *= inverse;
    s.clash *= inverse;
    s.esp *= inverse;
    s.lp *= inverse;
    force *= inverse;
    torque *= inverse;
  }
  double outside = std::numeric_limits<double>::infinity();
  Eigen::Vector3d away = Eigen::Vector3d::Zero();
  for (const molsurf::SiteSphere& sphere : site_) {
    const double beyond = (centre - sphere.center).norm() - sphere.radius;
    if (beyond < outside) {
      outside = beyond;
      away = (centre - sphere.center).normalized();
    }
  }
  s.outside = std::max(0.0, outside);
  s.score = s.contact + o.esp_weight * s.esp + o.lp_weight * s.lp - o.clash_weight * s.clash -
            o.site_weight * s.outside * s.outside;
  if (gradient != nullptr) {
    force -= 2.0 * o.site_weight * s.outside * away;
    *gradient << force, torque;
  }
  return s;
}

}  // namespace surfcomp::docking
