// SPDX-License-Identifier: Apache-2.0
#pragma once
// Integer ambiguity resolution by the LAMBDA method (Teunissen, "The
// least-squares ambiguity decorrelation adjustment", J. Geodesy 70, 1995):
// Q = L^T D L, integer Gauss transformations and permutations that
// decorrelate the float ambiguities (de Jonge & Tiberius, LGR-12, 1996),
// then the integer least-squares search for the two best candidates with a
// shrinking ellipsoid (Chang, Yang & Zhou, "MLAMBDA", J. Geodesy 79, 2005).
// The ratio of the second-best to the best squared norm is the
// discrimination test (RTKLIB manual 2.4.2 §E.7). Fixed-size workspace: no
// allocation, no exceptions.
#include <array>

namespace gnssemu::receiver::rtk {

/// Most ambiguities one search handles.
inline constexpr int kMaxAmbiguities = 48;

using AmbMat = std::array<std::array<double, kMaxAmbiguities>, kMaxAmbiguities>;
using AmbVec = std::array<double, kMaxAmbiguities>;

/// The two best integer vectors and their squared distances (Q^-1 norm).
struct LambdaResult {
  bool ok = false;         ///< false: Q not positive definite or the search did not end
  AmbVec best{};           ///< the integer least-squares solution (as doubles)
  double best_sq = 0.0;    ///< its squared distance to the float vector
  double second_sq = 0.0;  ///< the second best's
  double ratio() const noexcept { return best_sq > 0.0 ? second_sq / best_sq : 1.0e9; }
};

class Lambda {
public:
  /// Resolve n (2..kMaxAmbiguities) float ambiguities a (cycles) with
  /// covariance q (cycles^2; the leading n x n block, symmetric positive definite).
  const LambdaResult& solve(const AmbVec& a, const AmbMat& q, int n) noexcept;

private:
  bool factor(int n) noexcept;
  void gauss(int n, int i, int j) noexcept;
  void permute(int n, int j, double del) noexcept;
  void reduce(int n) noexcept;
  bool search(int n) noexcept;

  AmbMat l_{}, z_{}, zinv_{};
  AmbVec d_{}, zf_{};
  // Search workspace.
  AmbMat s_{};
  AmbVec dist_{}, zb_{}, zc_{}, step_{};
  std::array<AmbVec, 2> cand_{};
  std::array<double, 2> cand_sq_{};
  LambdaResult res_;
};

}  // namespace gnssemu::receiver::rtk
