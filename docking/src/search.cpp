#include "surfcomp/docking/search.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include "require_option.hpp"

#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace surfcomp::docking {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// `pose` followed by a translation `step.head(3)` (A) and a rotation `step.tail(3)` (radians,
/// as a rotation vector) about the moved sample's centroid `centre`.
matching::RigidTransform moved_by(const matching::RigidTransform& pose,
                                  const Eigen::Vector3d& centre, const Vector6d& step) {
  const Eigen::Vector3d turn = step.tail<3>();
  const double angle = turn.norm();
  const Eigen::Matrix3d q = angle > 0.0 ? Eigen::AngleAxisd(angle, turn / angle).toRotationMatrix()
                                        : Eigen::Matrix3d(Eigen::Matrix3d::Identity());
  matching::RigidTransform out;
  out.rotation = q * pose.rotation;
  out.translation = q * (pose.translation - centre) + centre + step.head<3>();
  return out;
}

double radius_of_gyration(const LigandSample& sample) {
  if (sample.points.cols() == 0) return 1.0;
  const double r =
      std::sqrt((sample.points.colwise() - sample.centroid).colwise().squaredNorm().mean());
  return std::max(r, 1.0);
}

Eigen::Vector3d random_in_ball(std::mt19937_64& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (;;) {
    Eigen::Vector3d x;
    for (int a = 0; a < 3; ++a) x(a) = unit(random);  // in order: arguments' order is unspecified
    if (x.squaredNorm() <= 1.0) return x;
  }
}

Eigen::Matrix3d random_rotation(std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  Eigen::Vector4d x;
  for (int a = 0; a < 4; ++a) x(a) = normal(random);
  return Eigen::Quaterniond(x(0), x(1), x(2), x(3)).normalized().toRotationMatrix();
}

/// A point of the site: a sphere drawn by volume, a point uniform in it.
Eigen::Vector3d random_site_point(const std::vector<molsurf::SiteSphere>& site,
                                  std::mt19937_64& random) {
  double total = 0.0;
  for (const molsurf::SiteSphere& s : site) total += s.radius * s.radius * s.radius;
  double pick = std::uniform_real_distribution<double>(0.0, total)(random);
  for (const molsurf::SiteSphere& s : site) {
    pick -= s.radius * s.radius * s.radius;
    if (pick <= 0.0) return s.center + s.radius * random_in_ball(random);
  }
  return site.back().center + site.back().radius * random_in_ball(random);
}

}  // namespace

void validate(const SearchOptions& o) {
  const auto require = detail::require_option;
  require(o.chains >= 0, "search_chains", o.chains, ">= 0");
  require(o.steps >= 0, "search_steps", o.steps, ">= 0");
  require(std::isfinite(o.temperature) && o.temperature > 0.0, "search_temperature", o.temperature,
          "finite and > 0");
  require(std::isfinite(o.min_gain) && o.min_gain > 0.0, "search_min_gain", o.min_gain,
          "finite and > 0");
  require(std::isfinite(o.sample_spacing) && o.sample_spacing > 0.0, "search_sample_spacing",
          o.sample_spacing, "finite and > 0");
  // Every optimum visited is kept (about 200 bytes each): a bound on memory.
  const auto optima = static_cast<long long>(o.chains) * (static_cast<long long>(o.steps) + 1);
  if (optima > kMaxSearchOptima) {
    throw OptionError(options::named("search_chains") + " x (" + options::named("search_steps") +
                      " + 1) = " + std::to_string(optima) + " is more than " +
                      std::to_string(kMaxSearchOptima) + " optima to keep");
  }
}

matching::RigidTransform refine_pose(const ReceptorField& field, const LigandSample& sample,
                                     const matching::RigidTransform& start, double min_gain,
                                     int max_iterations) {
  // Rotations are scaled by the radius of gyration so that a unit step moves the sample's
  // points about as far as a unit translation: the Hessian estimate starts near isotropic.
  const double lever = radius_of_gyration(sample);
  Vector6d scale;
  scale << 1.0, 1.0, 1.0, 1.0 / lever, 1.0 / lever, 1.0 / lever;
  constexpr double max_step = 1.0;  // A, or A at the radius of gyration
  matching::RigidTransform pose = start;
  Vector6d gradient;
  double value = field.score(sample, pose, &gradient).score;
  gradient = gradient.cwiseProduct(scale);
  Matrix6d inverse_hessian = Matrix6d::Identity();
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    Vector6d direction = inverse_hessian * gradient;  // ascent
    if (direction.dot(gradient) <= 0.0) {
      inverse_hessian.setIdentity();
      direction = gradient;
    }
    const double length = direction.norm();
    if (!(length > 1e-12)) break;
    if (length > max_step) direction *= max_step / length;
    const Eigen::Vector3d centre = pose.rotation * sample.centroid + pose.translation;
    double alpha = 1.0;
    matching::RigidTransform trial;
    Vector6d trial_gradient;
    double trial_value = value;
    bool accepted = false;
    for (int halving = 0; halving < 12; ++halving, alpha *= 0.5) {
      trial = moved_by(pose, centre, alpha * direction.cwiseProduct(scale));
      trial_value = field.score(sample, trial, &trial_gradient).score;
      if (trial_value >= value + 1e-4 * alpha * direction.dot(gradient)) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    trial_gradient = trial_gradient.cwiseProduct(scale);
    const double gain = trial_value - value;
    // BFGS on -score: s the step, y the change of -gradient.
    const Vector6d s = alpha * direction;
    const Vector6d y = gradient - trial_gradient;
    const double sy = s.dot(y);
    if (sy > 1e-12) {
      const Vector6d hy = inverse_hessian * y;
      const double yhy = y.dot(hy);
      inverse_hessian += ((sy + yhy) / (sy * sy)) * (s * s.transpose()) -
                         (hy * s.transpose() + s * hy.transpose()) / sy;
    }
    pose = trial;
    value = trial_value;
    gradient = trial_gradient;
    if (gain < min_gain) break;
  }
  return pose;
}

std::vector<SearchedPose> search_site(const ReceptorField& field, const LigandSample& sample,
                                      const std::vector<molsurf::SiteSphere>& site,
                                      const SearchOptions& options) {
  validate(options);
  if (site.empty() || options.chains == 0) return {};
  constexpr double pi = 3.14159265358979323846;
  constexpr double max_shift = 2.0;               // A
  constexpr double max_turn = 60.0 * pi / 180.0;  // radians
  const auto chains = static_cast<std::size_t>(options.chains);
  const auto per_chain = static_cast<std::size_t>(options.steps) + 1;
  std::vector<SearchedPose> found(chains * per_chain);
  tbb::parallel_for(std::size_t{0}, chains, [&](std::size_t chain) {
    std::mt19937_64 random(options.seed * 0x9E3779B97F4A7C15ULL + chain);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    matching::RigidTransform start;
    start.rotation = random_rotation(random);
    start.translation = random_site_point(site, random) - start.rotation * sample.centroid;
    SearchedPose current;
    current.pose = refine_pose(field, sample, start, options.min_gain);
    current.score = field.score(sample, current.pose);
    found[chain * per_chain] = current;
    for (std::size_t step = 1; step < per_chain; ++step) {
      const Eigen::Vector3d centre =
          current.pose.rotation * sample.centroid + current.pose.translation;
      Vector6d move = Vector6d::Zero();
      if (unit(random) < 0.5) {
        move.head<3>() = max_shift * random_in_ball(random);
      } else {
        move.tail<3>() = max_turn * random_in_ball(random);
      }
      SearchedPose next;
      next.pose =
          refine_pose(field, sample, moved_by(current.pose, centre, move), options.min_gain);
      next.score = field.score(sample, next.pose);
      found[chain * per_chain + step] = next;
      const double drop = current.score.score - next.score.score;
      if (drop <= 0.0 || unit(random) < std::exp(-drop / options.temperature)) current = next;
    }
  });
  return found;
}

}  // namespace surfcomp::docking
