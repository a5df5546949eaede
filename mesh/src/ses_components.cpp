#include "ses_components.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <numeric>
#include <vector>

namespace surfcomp::mesh::detail {
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

}  // namespace

TriangleSoup kept_components(const TriangleSoup& soup, const ComponentVolumes& limits) {
  const auto n = static_cast<std::size_t>(soup.positions.rows());
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (Eigen::Index f = 0; f < soup.faces.rows(); ++f) {
    for (int k = 1; k < 3; ++k) {
      const int a = find_root(parent, soup.faces(f, 0));
      const int b = find_root(parent, soup.faces(f, k));
      parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    }
  }
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

}  // namespace surfcomp::mesh::detail
