// SPDX-License-Identifier: Apache-2.0
#pragma once
// Fixed-size symmetric positive-definite solves for the 4-state least
// squares problems (no allocation).
#include <array>
#include <cmath>

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

inline Vec4 mul4(const Mat4& a, const Vec4& x) noexcept {
  Vec4 y{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) y[i] += a[i][k] * x[k];
  return y;
}

}  // namespace gnssemu::receiver
