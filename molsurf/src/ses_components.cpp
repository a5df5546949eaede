#include "ses_components.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <limits>
#include <numeric>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// The root of v's set in the union-find forest `parent`, halving the path on the way.
int find_root(std::vector<int>& parent, int v) {
  while (parent[static_cast<std::size_t>(v)] != v) {
    auto& p = parent[static_cast<std::size_t>(v)];
    p = parent[static_cast<std::size_t>(p)];
    v = p;
  }
  return v;
}

/// The union-find forest of the soup's vertex-connected components; each root is the lowest
/// vertex of its component.
std::vector<int> component_forest(const TriangleSoup& soup) {
  std::vector<int> parent(static_cast<std::size_t>(soup.positions.rows()));
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, soup.faces(f, 0));
      const int b = find_root(parent, soup.faces(f, k));
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
  return parent;
}

/// The faces of `soup` whose component root (in `parent`) is marked in `kept_root`, with the
/// vertices they use; vertex and face order preserved.
TriangleSoup select_components(const TriangleSoup& soup, std::vector<int>& parent,
                               const std::vector<bool>& kept_root) {
  const auto n = static_cast<std::size_t>(soup.positions.rows());
  std::vector<int> new_index(n, -1);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    if (!kept_root[static_cast<std::size_t>(find_root(parent, soup.faces(f, 0)))]) continue;
    kept.push_back(f);
    for (int k = 0; k < 3; ++k) new_index[static_cast<std::size_t>(soup.faces(f, k))] = 0;
  }
  int next = 0;
  for (auto& index : new_index) {
    if (index == 0) index = next++;
  }
  TriangleSoup out;
  out.positions.resize(next, 3);
  for (std::size_t v = 0; v < n; ++v) {
    if (new_index[v] >= 0)
      out.positions.row(new_index[v]) = soup.positions.row(static_cast<Eigen::Index>(v));
  }
  out.faces.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t f = 0; f < kept.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      out.faces(static_cast<Eigen::Index>(f), k) =
          new_index[static_cast<std::size_t>(soup.faces(kept[f], k))];
    }
  }
  return out;
}

}  // namespace

TriangleSoup kept_components(const TriangleSoup& soup, const ComponentVolumes& limits) {
  const auto n = static_cast<std::size_t>(soup.positions.rows());
  std::vector<int> parent = component_forest(soup);
  std::vector<double> volume(n, 0.0);
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    const Vec3 a = soup.positions.row(soup.faces(f, 0));
    const Vec3 b = soup.positions.row(soup.faces(f, 1));
    const Vec3 c = soup.positions.row(soup.faces(f, 2));
    volume[static_cast<std::size_t>(find_root(parent, soup.faces(f, 0)))] +=
        a.dot(b.cross(c)) / 6.0;
  }
  // Roots are the lowest vertex of their component, so a tie goes to the lowest index.
  const auto largest = static_cast<std::size_t>(
      std::distance(volume.begin(), std::max_element(volume.begin(), volume.end())));
  std::vector<bool> kept_root(n, false);
  for (std::size_t root = 0; root < n; ++root) {
    const double v = volume[root];
    kept_root[root] = v > 0.0 ? v >= limits.outward || root == largest
                              : limits.keep_cavities && -v >= limits.cavity;
  }
  return select_components(soup, parent, kept_root);
}

ComponentsBySize split_by_extent(const TriangleSoup& soup, double side) {
  const auto n = static_cast<std::size_t>(soup.positions.rows());
  std::vector<int> parent = component_forest(soup);
  std::vector<Vec3> lo(n, Vec3::Constant(std::numeric_limits<double>::infinity()));
  std::vector<Vec3> hi(n, Vec3::Constant(-std::numeric_limits<double>::infinity()));
  for (std::size_t v = 0; v < n; ++v) {
    const auto root = static_cast<std::size_t>(find_root(parent, static_cast<int>(v)));
    const Vec3 p = soup.positions.row(static_cast<Eigen::Index>(v)).transpose();
    lo[root] = lo[root].cwiseMin(p);
    hi[root] = hi[root].cwiseMax(p);
  }
  std::vector<bool> small(n, false);
  std::vector<bool> large(n, false);
  for (std::size_t root = 0; root < n; ++root) {
    if (find_root(parent, static_cast<int>(root)) != static_cast<int>(root)) continue;
    const bool fits = ((hi[root] - lo[root]).array() < side).all();
    small[root] = fits;
    large[root] = !fits;
  }
  return {select_components(soup, parent, small), select_components(soup, parent, large)};
}

}  // namespace surfcomp::molsurf::detail
