// A Householder QR with column pivoting for the small least-squares systems of the curvature
// fits (curvature.cpp), written out for their few columns: the same pivots and results as
// Eigen::ColPivHouseholderQR, several times faster on those tiny systems. Internal to mesh/.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace surfcomp::mesh::detail {

/// A Householder QR with column pivoting of a rows by Cols matrix (rows >= Cols), computed in
/// place as Eigen::ColPivHouseholderQR computes it: the same pivot order and the same cut-off
/// for the pivots treated as zero. Written out for the few columns of the curvature fits, whose
/// tiny systems Eigen's general code factorises several times slower. The matrix holds R on and
/// above its diagonal and the reflectors' essential parts below it.
template <int Cols>
struct PivotedQr {
  std::array<double, Cols> tau{};  ///< reflector k is I - tau_k v v^T, v = (1, essential)
  std::array<int, Cols> order{};   ///< column k of the factorisation is column order[k]
  int pivots = Cols;               ///< the leading pivots not treated as zero
  double largest_norm = 0.0;       ///< the largest column norm before factorising
};

template <int Cols, class Matrix>
PivotedQr<Cols> pivoted_qr(Matrix& a) {
  const Eigen::Index rows = a.rows();
  constexpr double epsilon = std::numeric_limits<double>::epsilon();
  PivotedQr<Cols> qr;
  std::array<double, Cols> norm_updated{}, norm_direct{};
  for (int j = 0; j < Cols; ++j) {
    norm_direct[j] = norm_updated[j] = a.col(j).norm();
    qr.largest_norm = std::max(qr.largest_norm, norm_updated[j]);
    qr.order[j] = j;
  }
  const double zero_pivot =
      qr.largest_norm * epsilon * (qr.largest_norm * epsilon) / static_cast<double>(rows);
  const double downdate_limit = std::sqrt(epsilon);
  for (int k = 0; k < Cols; ++k) {
    int biggest = k;
    for (int j = k + 1; j < Cols; ++j) {
      if (norm_updated[j] > norm_updated[biggest]) biggest = j;
    }
    if (qr.pivots == Cols && norm_updated[biggest] * norm_updated[biggest] <
                                 zero_pivot * static_cast<double>(rows - k)) {
      qr.pivots = k;
    }
    if (biggest != k) {
      a.col(k).swap(a.col(biggest));
      std::swap(norm_updated[k], norm_updated[biggest]);
      std::swap(norm_direct[k], norm_direct[biggest]);
      std::swap(qr.order[k], qr.order[biggest]);
    }
    // The reflector that maps column k below row k - 1 to (beta, 0, ...).
    const Eigen::Index below = rows - k - 1;
    auto essential = a.col(k).tail(below);
    const double tail = essential.squaredNorm();
    const double c0 = a(k, k);
    if (tail <= std::numeric_limits<double>::min()) {
      qr.tau[k] = 0.0;
      essential.setZero();
    } else {
      double beta = std::sqrt(c0 * c0 + tail);
      if (c0 >= 0.0) beta = -beta;
      essential /= c0 - beta;
      qr.tau[k] = (beta - c0) / beta;
      a(k, k) = beta;
    }
    for (int j = k + 1; j < Cols; ++j) {
      if (below == 0) {
        a(k, j) *= 1.0 - qr.tau[k];
      } else if (qr.tau[k] != 0.0) {
        const double dot = essential.dot(a.col(j).tail(below)) + a(k, j);
        a(k, j) -= qr.tau[k] * dot;
        a.col(j).tail(below) -= (qr.tau[k] * dot) * essential;
      }
      // The norm of column j below row k, downdated (or recomputed when cancellation looms).
      if (norm_updated[j] != 0.0) {
        double ratio = std::abs(a(k, j)) / norm_updated[j];
        ratio = std::max(0.0, (1.0 + ratio) * (1.0 - ratio));
        const double relative = norm_updated[j] / norm_direct[j];
        if (ratio * relative * relative <= downdate_limit) {
          norm_direct[j] = norm_updated[j] = a.col(j).tail(below).norm();
        } else {
          norm_updated[j] *= std::sqrt(ratio);
        }
      }
    }
  }
  return qr;
}

/// Applies the first `count` reflectors of `qr` (factorised in `a`) to column `b`: Q^T b.
template <int Cols, class Matrix, class Vector>
void apply_reflectors(const Matrix& a, const PivotedQr<Cols>& qr, int count, Vector&& b) {
  const Eigen::Index rows = a.rows();
  for (int k = 0; k < count; ++k) {
    const Eigen::Index below = rows - k - 1;
    if (below == 0) {
      b(k) *= 1.0 - qr.tau[k];
    } else if (qr.tau[k] != 0.0) {
      const auto essential = a.col(k).tail(below);
      const double dot = essential.dot(b.tail(below)) + b(k);
      b(k) -= qr.tau[k] * dot;
      b.tail(below) -= (qr.tau[k] * dot) * essential;
    }
  }
}

/// apply_reflectors to every column of `b` (rows by Columns, column-major) at once: one sweep
/// over the rows per reflector for all the dot products, one for all the updates.
template <int Cols, int Columns, class Matrix, class Block>
void apply_reflectors_to_columns(const Matrix& a, const PivotedQr<Cols>& qr, int count, Block&& b) {
  const Eigen::Index rows = a.rows();
  for (int k = 0; k < count; ++k) {
    if (rows - k == 1) {
      b.row(k) *= 1.0 - qr.tau[k];
      continue;
    }
    if (qr.tau[k] == 0.0) continue;
    const double* essential = a.col(k).data();
    std::array<double, Columns> dot{};
    for (Eigen::Index i = k + 1; i < rows; ++i) {
      for (int c = 0; c < Columns; ++c) dot[c] += essential[i] * b(i, c);
    }
    for (int c = 0; c < Columns; ++c) {
      dot[c] = qr.tau[k] * (dot[c] + b(k, c));
      b(k, c) -= dot[c];
    }
    for (Eigen::Index i = k + 1; i < rows; ++i) {
      for (int c = 0; c < Columns; ++c) b(i, c) -= dot[c] * essential[i];
    }
  }
}

/// The solution x of R x = c over the first qr.pivots pivots (zero in the other columns), in
/// the original column order; `c` holds Q^T b in its first qr.pivots entries.
template <int Cols, class Matrix>
Eigen::Matrix<double, Cols, 1> back_substitute(const Matrix& a, const PivotedQr<Cols>& qr,
                                               Eigen::Matrix<double, Cols, 1> c) {
  for (int k = qr.pivots - 1; k >= 0; --k) {
    double sum = c(k);
    for (int j = k + 1; j < qr.pivots; ++j) sum -= a(k, j) * c(j);
    c(k) = sum / a(k, k);
  }
  Eigen::Matrix<double, Cols, 1> x = Eigen::Matrix<double, Cols, 1>::Zero();
  for (int k = 0; k < qr.pivots; ++k) x(qr.order[k]) = c(k);
  return x;
}

/// The least-squares solution of a x = b as Eigen::ColPivHouseholderQR solves it (for a
/// rank-deficient a, the same basic solution). `a` and `b` are overwritten.
template <int Cols, class Matrix, class Vector>
Eigen::Matrix<double, Cols, 1> pivoted_least_squares(Matrix& a, Vector& b) {
  const PivotedQr<Cols> qr = pivoted_qr<Cols>(a);
  apply_reflectors(a, qr, qr.pivots, b);
  return back_substitute<Cols>(a, qr, b.template head<Cols>());
}

/// True when the factorisation has all its pivots and none below 1e-7 of its largest column
/// norm: far from the cut-off of rank-deficient systems, where a solution assembled from the
/// factors of two column blocks equals the pivoted QR's of the whole to rounding.
template <int Cols, class Matrix>
bool well_conditioned(const Matrix& a, const PivotedQr<Cols>& qr) {
  if (qr.pivots < Cols || !(qr.largest_norm > 0.0)) return false;
  for (int k = 0; k < Cols; ++k) {
    if (!(std::abs(a(k, k)) > 1e-7 * qr.largest_norm)) return false;
  }
  return true;
}

}  // namespace surfcomp::mesh::detail
