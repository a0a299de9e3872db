// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fixed-size symmetric positive-definite solves for the least squares
// problems: 4 states, and up to kMaxStates (position + one clock per
// system) used to a run-time size n (no allocation).
#include <array>
#include <cmath>

#include "core/common/sat_id.hpp"

namespace gnssemu::receiver {

using Mat4 = std::array<std::array<double, 4>, 4>;
using Vec4 = std::array<double, 4>;

/// Inverse of a symmetric positive-definite 4x4 matrix by Cholesky. Returns
/// false when a pivot is not positive or is below rel_tol times its diagonal
/// entry (near-singular normal matrix); inv is then unspecified.
inline bool spd_inverse4(const Mat4& a, Mat4& inv, double rel_tol = 1e-12) noexcept {
  Mat4 l{};
  for (int j = 0; j < 4; ++j) {
    double d = a[j][j];
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > rel_tol * std::fabs(a[j][j])) || !std::isfinite(d)) return false;
    l[j][j] = std::sqrt(d);
    for (int i = j + 1; i < 4; ++i) {
      double s = a[i][j];
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      l[i][j] = s / l[j][j];
    }
  }
  // inv = L^-T L^-1, column by column.
  for (int c = 0; c < 4; ++c) {
    Vec4 y{};
    for (int i = 0; i < 4; ++i) {
      double s = (i == c) ? 1.0 : 0.0;
      for (int k = 0; k < i; ++k) s -= l[i][k] * y[k];
      y[i] = s / l[i][i];
    }
    for (int i = 3; i >= 0; --i) {
      double s = y[i];
      for (int k = i + 1; k < 4; ++k) s -= l[k][i] * inv[k][c];
      inv[i][c] = s / l[i][i];
    }
  }
  return true;
}

/// Position + one receiver clock per system: the largest least squares state.
inline constexpr int kMaxStates = 3 + kNumSystems;
using MatN = std::array<std::array<double, kMaxStates>, kMaxStates>;
using VecN = std::array<double, kMaxStates>;

/// spd_inverse4 on the leading n x n block of a (1 <= n <= kMaxStates), with
/// the same operations in the same order (n = 4 gives spd_inverse4's bits).
inline bool spd_inverse(const MatN& a, MatN& inv, int n, double rel_tol = 1e-12) noexcept {
  MatN l{};
  for (int j = 0; j < n; ++j) {
    double d = a[j][j];
    for (int k = 0; k < j; ++k) d -= l[j][k] * l[j][k];
    if (!(d > rel_tol * std::fabs(a[j][j])) || !std::isfinite(d)) return false;
    l[j][j] = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double s = a[i][j];
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      l[i][j] = s / l[j][j];
    }
  }
  for (int c = 0; c < n; ++c) {
    VecN y{};
    for (int i = 0; i < n; ++i) {
      double s = (i == c) ? 1.0 : 0.0;
      for (int k = 0; k < i; ++k) s -= l[i][k] * y[k];
      y[i] = s / l[i][i];
    }
    for (int i = n - 1; i >= 0; --i) {
      double s = y[i];
      for (int k = i + 1; k < n; ++k) s -= l[k][i] * inv[k][c];
      inv[i][c] = s / l[i][i];
    }
  }
  return true;
}

/// a x on the leading n entries.
inline VecN mul(const MatN& a, const VecN& x, int n) noexcept {
  VecN y{};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) y[i] += a[i][k] * x[k];
  return y;
}

inline Vec4 mul4(const Mat4& a, const Vec4& x) noexcept {
  Vec4 y{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) y[i] += a[i][k] * x[k];
  return y;
}

}  // namespace gnssemu::receiver
