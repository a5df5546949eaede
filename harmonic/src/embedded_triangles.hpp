// The triangles of a patch's embedding in the disk, and where a point of the plane falls among
// them: a grid of their bounding boxes and CGAL's exact orientation tests (shape_image.cpp,
// src/ only).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

namespace surfcomp::harmonic::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Plane triangles listed in the cells of a uniform grid over their common bounding box, each
/// in every cell its own bounding box overlaps: a cell lists every triangle that may contain a
/// point of it, by increasing index.
class TriangleBins {
 public:
  /// `boxes`: per triangle its x min, x max, y min, y max.
  explicit TriangleBins(const std::vector<std::array<double, 4>>& boxes) {
    lo_ = {boxes[0][0], boxes[0][2]};
    hi_ = {boxes[0][1], boxes[0][3]};
    for (const auto& b : boxes) {
      lo_ = {std::min(lo_[0], b[0]), std::min(lo_[1], b[2])};
      hi_ = {std::max(hi_[0], b[1]), std::max(hi_[1], b[3])};
    }
    // About two triangles per cell.
    side_ = std::max(
        1, static_cast<int>(std::ceil(std::sqrt(0.5 * static_cast<double>(boxes.size())))));
    for (int axis = 0; axis < 2; ++axis) {
      inverse_[axis] = hi_[axis] > lo_[axis] ? side_ / (hi_[axis] - lo_[axis]) : 0.0;
    }
    offsets_.assign(static_cast<std::size_t>(side_) * side_ + 1, 0);
    std::vector<std::array<int, 4>> ranges(boxes.size());  // first and last cell along x, y
    for (std::size_t t = 0; t < boxes.size(); ++t) {
      const auto& b = boxes[t];
      ranges[t] = {cell(b[0], 0), cell(b[1], 0), cell(b[2], 1), cell(b[3], 1)};
      for (int i = ranges[t][0]; i <= ranges[t][1]; ++i) {
        for (int j = ranges[t][2]; j <= ranges[t][3]; ++j) ++offsets_[i * side_ + j + 1];
      }
    }
    for (std::size_t c = 1; c < offsets_.size(); ++c) offsets_[c] += offsets_[c - 1];
    listed_.resize(static_cast<std::size_t>(offsets_.back()));
    std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
    for (std::size_t t = 0; t < boxes.size(); ++t) {
      for (int i = ranges[t][0]; i <= ranges[t][1]; ++i) {
        for (int j = ranges[t][2]; j <= ranges[t][3]; ++j) {
          listed_[static_cast<std::size_t>(fill[i * side_ + j]++)] = static_cast<int>(t);
        }
      }
    }
  }

  /// Calls visit(t) for the triangles listed in the cell of q, by increasing index, until visit
  /// returns true; nothing when q lies outside the bounding box.
  template <class Visit>
  void for_each_candidate(double x, double y, Visit&& visit) const {
    if (!(x >= lo_[0] && x <= hi_[0] && y >= lo_[1] && y <= hi_[1])) return;
    const int c = cell(x, 0) * side_ + cell(y, 1);
    for (int k = offsets_[c]; k < offsets_[c + 1]; ++k) {
      if (visit(listed_[static_cast<std::size_t>(k)])) return;
    }
  }

 private:
  /// The cell along `axis` holding coordinate v, clamped to the grid; non-decreasing in v, so
  /// a point inside a box falls between the cells of the box's ends.
  int cell(double v, int axis) const {
    const double c = std::floor((v - lo_[axis]) * inverse_[axis]);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(side_ - 1)));
  }

  std::array<double, 2> lo_{}, hi_{}, inverse_{};
  int side_ = 1;
  std::vector<int> offsets_;  ///< cell c lists listed_[offsets_[c] .. offsets_[c + 1])
  std::vector<int> listed_;
};

/// The triangles of an embedding in the plane that have non-zero area, in face order, and where a
/// point falls among them, by CGAL's exact orientation predicates.
class EmbeddedTriangles {
 public:
  EmbeddedTriangles(const Eigen::Ref<const Eigen::MatrixX2d>& uv,
                    const Eigen::Ref<const Eigen::MatrixX3i>& faces) {
    corners_.reserve(static_cast<std::size_t>(faces.rows()));
    face_.reserve(static_cast<std::size_t>(faces.rows()));
    for (Eigen::Index f = 0; f < faces.rows(); ++f) {
      std::array<Kernel::Point_2, 3> c;
      for (std::size_t k = 0; k < 3; ++k) {
        const Eigen::Index v = faces(f, static_cast<Eigen::Index>(k));
        c[k] = Kernel::Point_2(uv(v, 0), uv(v, 1));
      }
      if (CGAL::collinear(c[0], c[1], c[2])) continue;
      corners_.push_back(c);
      face_.push_back(static_cast<int>(f));
    }
    if (corners_.empty()) return;
    turn_.resize(size());
    box_.resize(size());  // x min, x max, y min, y max
    for (std::size_t t = 0; t < size(); ++t) {
      const auto& c = corners_[t];
      turn_[t] = CGAL::orientation(c[0], c[1], c[2]);
      box_[t] = {std::min({c[0].x(), c[1].x(), c[2].x()}), std::max({c[0].x(), c[1].x(), c[2].x()}),
                 std::min({c[0].y(), c[1].y(), c[2].y()}),
                 std::max({c[0].y(), c[1].y(), c[2].y()})};
    }
    bins_.emplace(box_);
    link_neighbours(faces, uv.rows());
  }

  std::size_t size() const { return corners_.size(); }
  /// The face of triangle t.
  int face(std::size_t t) const { return face_[t]; }

  /// Triangle t, or the first of its edge neighbours, that holds q strictly inside (not on its
  /// edges), where no other triangle of an embedding can hold it; size() when none does.
  std::size_t strictly_inside_or_beside(std::size_t t, const Kernel::Point_2& q) const {
    if (strictly_inside(t, q)) return t;
    for (const int n : neighbour_[t]) {
      if (n >= 0 && strictly_inside(static_cast<std::size_t>(n), q))
        return static_cast<std::size_t>(n);
    }
    return size();
  }

  /// The lowest triangle containing q, or size() when none does: the bins' candidates by increasing
  /// index, screened by their bounding boxes before the exact tests.
  std::size_t locate(const Kernel::Point_2& q) const {
    std::size_t found = size();
    bins_->for_each_candidate(q.x(), q.y(), [&](int index) {
      const auto t = static_cast<std::size_t>(index);
      const auto& b = box_[t];
      if (q.x() >= b[0] && q.x() <= b[1] && q.y() >= b[2] && q.y() <= b[3] && contains(t, q)) {
        found = t;
        return true;
      }
      return false;
    });
    return found;
  }

 private:
  /// The orientations of q against triangle t's three edges.
  std::array<CGAL::Orientation, 3> sides(std::size_t t, const Kernel::Point_2& q) const {
    const auto& c = corners_[t];
    return {CGAL::orientation(c[0], c[1], q), CGAL::orientation(c[1], c[2], q),
            CGAL::orientation(c[2], c[0], q)};
  }
  // True when q lies strictly inside triangle t (not on its edges).
  bool strictly_inside(std::size_t t, const Kernel::Point_2& q) const {
    const auto s = sides(t, q);
    return s[0] == turn_[t] && s[1] == turn_[t] && s[2] == turn_[t];
  }
  // True when q lies in the closed triangle t: no edge has q on the other side.
  bool contains(std::size_t t, const Kernel::Point_2& q) const {
    const auto s = sides(t, q);
    const CGAL::Orientation other = CGAL::opposite(turn_[t]);
    return s[0] != other && s[1] != other && s[2] != other;
  }

  // Triangles sharing an edge (as vertex pairs): up to three neighbours per triangle, -1 where
  // none. An edge's first triangle (in triangle and side order) is linked with each later one.
  void link_neighbours(const Eigen::Ref<const Eigen::MatrixX3i>& faces, Eigen::Index vertex_count) {
    neighbour_.assign(size(), {-1, -1, -1});
    // The triangle sides grouped by their lower vertex, in triangle and side order.
    std::vector<int> first(static_cast<std::size_t>(vertex_count) + 1, 0);
    for (std::size_t t = 0; t < size(); ++t) {
      for (int side = 0; side < 3; ++side) {
        const Eigen::Index f = face_[t];
        ++first[static_cast<std::size_t>(std::min(faces(f, side), faces(f, (side + 1) % 3))) + 1];
      }
    }
    for (std::size_t v = 1; v < first.size(); ++v) first[v] += first[v - 1];
    struct Side {
      int high, triangle, side;
    };
    std::vector<Side> sides_of(static_cast<std::size_t>(first.back()));
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < size(); ++t) {
      const Eigen::Index f = face_[t];
      for (int side = 0; side < 3; ++side) {
        const int a = faces(f, side), b = faces(f, (side + 1) % 3);
        const int low = std::min(a, b), high = std::max(a, b);
        const int begin = first[static_cast<std::size_t>(low)];
        int& end = fill[static_cast<std::size_t>(low)];
        for (int k = begin; k < end; ++k) {
          const Side& owner = sides_of[static_cast<std::size_t>(k)];
          if (owner.high != high) continue;
          neighbour_[t][static_cast<std::size_t>(side)] = owner.triangle;
          neighbour_[static_cast<std::size_t>(owner.triangle)]
                    [static_cast<std::size_t>(owner.side)] = static_cast<int>(t);
          break;
        }
        sides_of[static_cast<std::size_t>(end++)] = Side{high, static_cast<int>(t), side};
      }
    }
  }

  std::vector<std::array<Kernel::Point_2, 3>> corners_;
  std::vector<int> face_;  ///< the face of each triangle
  std::vector<CGAL::Orientation> turn_;
  std::vector<std::array<double, 4>> box_;
  std::optional<TriangleBins> bins_;
  std::vector<std::array<int, 3>> neighbour_;
};

}  // namespace surfcomp::harmonic::detail
