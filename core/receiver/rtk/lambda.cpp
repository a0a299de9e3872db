// SPDX-License-Identifier: Apache-2.0
#include "core/receiver/rtk/lambda.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace gnssemu::receiver::rtk {
namespace {

constexpr int kMaxSearchSteps = 100000;  // bounds the search time on a badly conditioned Q

double sign_step(double y) noexcept { return y <= 0.0 ? -1.0 : 1.0; }

}  // namespace

// Q = L^T D L (L unit lower triangular), from the last row up.
bool Lambda::factor(int n) noexcept {
  for (int i = n - 1; i >= 0; --i) {
    const double di = l_[i][i];
    if (!(di > 0.0) || !std::isfinite(di)) return false;
    d_[i] = di;
    const double r = std::sqrt(di);
    for (int j = 0; j <= i; ++j) l_[i][j] /= r;
    for (int j = 0; j < i; ++j)
      for (int k = 0; k <= j; ++k) l_[j][k] -= l_[i][k] * l_[i][j];
    for (int j = 0; j <= i; ++j) l_[i][j] /= l_[i][i];
  }
  return true;
}

// Integer Gauss transformation of column j by column i (i > j).
void Lambda::gauss(int n, int i, int j) noexcept {
  const double mu = std::round(l_[i][j]);
  if (mu == 0.0) return;
  for (int k = i; k < n; ++k) l_[k][j] -= mu * l_[k][i];
  for (int k = 0; k < n; ++k) z_[k][j] -= mu * z_[k][i];
  for (int k = 0; k < n; ++k) zinv_[i][k] += mu * zinv_[j][k];
}

// Swap ambiguities j and j+1 with the factors updated.
void Lambda::permute(int n, int j, double del) noexcept {
  const double eta = d_[j] / del;
  const double lam = d_[j + 1] * l_[j + 1][j] / del;
  d_[j] = eta * d_[j + 1];
  d_[j + 1] = del;
  for (int k = 0; k < j; ++k) {
    const double a0 = l_[j][k], a1 = l_[j + 1][k];
    l_[j][k] = -l_[j + 1][j] * a0 + a1;
    l_[j + 1][k] = eta * a0 + lam * a1;
  }
  l_[j + 1][j] = lam;
  for (int k = j + 2; k < n; ++k) std::swap(l_[k][j], l_[k][j + 1]);
  for (int k = 0; k < n; ++k) std::swap(z_[k][j], z_[k][j + 1]);
  std::swap(zinv_[j], zinv_[j + 1]);
}

void Lambda::reduce(int n) noexcept {
  int j = n - 2, k = n - 2;
  while (j >= 0) {
    if (j <= k)
      for (int i = j + 1; i < n; ++i) gauss(n, i, j);
    const double del = d_[j] + l_[j + 1][j] * l_[j + 1][j] * d_[j + 1];
    if (del + 1.0e-6 < d_[j + 1]) {
      permute(n, j, del);
      k = j;
      j = n - 2;
    } else {
      --j;
    }
  }
}

// Depth-first enumeration from the last (best determined) ambiguity down,
// keeping the two best leaves and shrinking the radius to the worse of them.
bool Lambda::search(int n) noexcept {
  double max_sq = std::numeric_limits<double>::infinity();
  int found = 0, worst = 0;
  int k = n - 1;
  dist_[k] = 0.0;
  zb_[k] = zf_[k];
  zc_[k] = std::round(zb_[k]);
  double y = zb_[k] - zc_[k];
  step_[k] = sign_step(y);
  for (int it = 0; it < kMaxSearchSteps; ++it) {
    const double nd = dist_[k] + y * y / d_[k];
    if (nd < max_sq) {
      if (k != 0) {
        --k;
        dist_[k] = nd;
        for (int i = 0; i <= k; ++i) s_[k][i] = s_[k + 1][i] + (zc_[k + 1] - zb_[k + 1]) * l_[k + 1][i];
        zb_[k] = zf_[k] + s_[k][k];
        zc_[k] = std::round(zb_[k]);
        y = zb_[k] - zc_[k];
        step_[k] = sign_step(y);
      } else {
        if (found < 2) {
          cand_[found] = zc_;
          cand_sq_[found] = nd;
          if (found == 0 || nd > cand_sq_[worst]) worst = found;
          ++found;
          if (found == 2) max_sq = cand_sq_[worst];
        } else if (nd < cand_sq_[worst]) {
          cand_[worst] = zc_;
          cand_sq_[worst] = nd;
          worst = cand_sq_[0] > cand_sq_[1] ? 0 : 1;
          max_sq = cand_sq_[worst];
        }
        zc_[0] += step_[0];
        y = zb_[0] - zc_[0];
        step_[0] = -step_[0] - sign_step(step_[0]);
      }
    } else {
      if (k == n - 1) return found == 2;
      ++k;
      zc_[k] += step_[k];
      y = zb_[k] - zc_[k];
      step_[k] = -step_[k] - sign_step(step_[k]);
    }
  }
  return false;
}

const LambdaResult& Lambda::solve(const AmbVec& a, const AmbMat& q, int n) noexcept {
  res_ = LambdaResult{};
  if (n < 2 || n > kMaxAmbiguities) return res_;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      l_[i][j] = q[i][j];
      z_[i][j] = zinv_[i][j] = (i == j) ? 1.0 : 0.0;
    }
  }
  if (!factor(n)) return res_;
  reduce(n);
  // z = Z^T a: the decorrelated float ambiguities.
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int k = 0; k < n; ++k) s += z_[k][i] * a[k];
    zf_[i] = s;
  }
  for (int i = 0; i < n; ++i) s_[n - 1][i] = 0.0;
  if (!search(n)) return res_;
  const int best = cand_sq_[0] <= cand_sq_[1] ? 0 : 1;
  // a = Z^-T z.
  for (int i = 0; i < n; ++i) {
    double s = 0.0;
    for (int k = 0; k < n; ++k) s += zinv_[k][i] * cand_[best][k];
    res_.best[i] = std::round(s);
  }
  res_.best_sq = cand_sq_[best];
  res_.second_sq = cand_sq_[1 - best];
  res_.ok = true;
  return res_;
}

}  // namespace gnssemu::receiver::rtk
