// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include "core/common/constants.hpp"
#include "core/geo/local_frame.hpp"

using namespace gnssemu;

TEST(LocalFrame, RoundTrip) {
  const geo::LocalFrame f({48.8738 * kDegToRad, 2.2950 * kDegToRad, 60.0});
  const Enu p(123.4, -56.7, 8.9);
  const Enu q = f.to_enu(f.to_ecef(p));
  EXPECT_NEAR(q.x, p.x, 1e-8);
  EXPECT_NEAR(q.y, p.y, 1e-8);
  EXPECT_NEAR(q.z, p.z, 1e-8);
  const Enu o = f.from_lla(f.origin());
  EXPECT_NEAR(o.norm(), 0.0, 1e-8);
  const Vec3 v = f.vector_to_ecef(Enu(1.0, 2.0, 3.0));
  const Enu w = f.vector_to_enu(v);
  EXPECT_NEAR(w.y, 2.0, 1e-12);
}
