// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>

#include <cmath>

#include "core/common/error.hpp"
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

TEST(TextFields, ColumnReaderBlankIsZeroErrorsNameFileLineAndColumn) {
  const text::ColumnReader r("brdc.n");
  const text::Line l{"  1.5D+01     42        x  inf", 7};
  EXPECT_DOUBLE_EQ(r.real(l, 0, 10, "a"), 15.0);
  EXPECT_EQ(r.integer(l, 10, 6, "b"), 42);
  EXPECT_DOUBLE_EQ(r.real(l, 16, 6, "blank"), 0.0);
  EXPECT_EQ(r.integer(l, 16, 6, "blank"), 0);
  EXPECT_EQ(r.integer(l, 100, 6, "past the end"), 0);
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([&] { r.real(l, 22, 5, "c"); }), "brdc.n:7: unparsable number 'x' for c at column 23");
  EXPECT_EQ(message([&] { r.integer(l, 0, 10, "d"); }), "brdc.n:7: unparsable integer '1.5D+01' for d at column 1");
  EXPECT_EQ(message([&] { r.real(l, 26, 5, "e"); }), "brdc.n:7: non-finite value for e");
  EXPECT_EQ(message([&] { r.fail(0, "f"); }), "brdc.n: f");
}

TEST(TextFields, RinexVersionLine) {
  const text::ColumnReader r("x.rnx");
  // Columns 1-60 hold the data, 61-80 the label (RINEX 3.05 §5.2).
  const auto first_line = [](std::string data) {
    data.resize(60, ' ');
    return std::vector<text::Line>{{data + "RINEX VERSION / TYPE", 1}};
  };
  const text::RinexVersionLine v3 = text::read_rinex_version(r, first_line("     3.04           N: GNSS NAV DATA    M"));
  EXPECT_DOUBLE_EQ(v3.version, 3.04);
  EXPECT_EQ(v3.major, 3);
  EXPECT_EQ(v3.type, 'N');
  EXPECT_EQ(v3.system, 'M');
  const text::RinexVersionLine v2 = text::read_rinex_version(r, first_line("     2.11           O"));
  EXPECT_EQ(v2.major, 2);
  EXPECT_EQ(v2.type, 'O');
  EXPECT_EQ(v2.system, ' ');
  EXPECT_EQ(text::rinex_label(first_line("")[0].text + "  "), "RINEX VERSION / TYPE");
  EXPECT_THROW(text::read_rinex_version(r, {}), Error);
  EXPECT_THROW(text::read_rinex_version(r, {{"     3.04           N", 1}}), Error);
  EXPECT_THROW(text::read_rinex_version(r, first_line("     4.00           N")), Error);
  EXPECT_THROW(text::read_rinex_version(r, first_line("     3.06           N")), Error);
  EXPECT_THROW(text::read_rinex_version(r, first_line("     1.99           N")), Error);
}
