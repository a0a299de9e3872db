#include <gtest/gtest.h>

#include <cmath>

#include "core/common/text_fields.hpp"

using namespace gnssemu;

TEST(TextFields, TrimAndColumns) {
  EXPECT_EQ(text::trim("  G01 \t\r"), "G01");
  EXPECT_EQ(text::trim(" \t "), "");
  const std::string line = "     2.11           N: GPS NAV DATA";
  EXPECT_EQ(text::columns(line, 5, 4), "2.11");
  EXPECT_EQ(text::columns(line, 31, 100), "DATA");  // clipped at the end
  EXPECT_EQ(text::columns(line, 200, 5), "");
}

TEST(TextFields, FortranReals) {
  EXPECT_DOUBLE_EQ(*text::parse_real(" 0.188095495105D-03"), 0.188095495105e-3);
  EXPECT_DOUBLE_EQ(*text::parse_real("-2.842170943040d-12"), -2.842170943040e-12);
  EXPECT_DOUBLE_EQ(*text::parse_real("+6.700000000000E+01"), 67.0);
  EXPECT_DOUBLE_EQ(*text::parse_real("3"), 3.0);
  EXPECT_FALSE(text::parse_real("").has_value());
  EXPECT_FALSE(text::parse_real("  ").has_value());
  EXPECT_FALSE(text::parse_real("1.0D+0x").has_value());
  EXPECT_FALSE(text::parse_real("1.0 2.0").has_value());
  EXPECT_FALSE(text::parse_real(std::string(80, '1')).has_value());
  EXPECT_TRUE(std::isinf(*text::parse_real("inf")));  // the reader decides what is allowed
}

TEST(TextFields, Integers) {
  EXPECT_EQ(*text::parse_int("  42 "), 42);
  EXPECT_EQ(*text::parse_int("+7"), 7);
  EXPECT_EQ(*text::parse_int("-3"), -3);
  EXPECT_FALSE(text::parse_int("4.5").has_value());
  EXPECT_FALSE(text::parse_int("").has_value());
  EXPECT_FALSE(text::parse_int("99999999999").has_value());
}
