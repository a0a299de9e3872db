// SPDX-License-Identifier: Apache-2.0
// JsonWriter: commas, nesting, escaping and numbers as a JSON parser reads them.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "daemon/status/json_writer.hpp"
#include "tests/support/alloc_counter.hpp"

namespace gnssemu::daemon {
namespace {

TEST(JsonWriter, NestedObjectsAndArraysParse) {
  std::string out;
  JsonWriter w(out);
  w.begin_object();
  w.field_int("a", 1);
  w.key("list");
  w.begin_array();
  w.integer(1);
  w.begin_object();
  w.field_bool("x", true);
  w.end_object();
  w.begin_array();
  w.end_array();
  w.null();
  w.end_array();
  w.key("empty");
  w.begin_object();
  w.end_object();
  w.field_string("s", "t");
  w.end_object();
  EXPECT_EQ(out, R"({"a":1,"list":[1,{"x":true},[],null],"empty":{},"s":"t"})");
  EXPECT_TRUE(nlohmann::json::accept(out));
}

TEST(JsonWriter, EscapesQuotesBackslashAndControlCharacters) {
  std::string out;
  JsonWriter w(out);
  const std::string nasty = std::string("a\"b\\c\nd\te") + '\x01' + "</script>";
  w.begin_object();
  w.field_string(nasty, nasty);
  w.end_object();
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_EQ(j.at(nasty).get<std::string>(), nasty);
  EXPECT_NE(out.find("\\u0001"), std::string::npos);
}

TEST(JsonWriter, NumbersFixedDecimalsNonFiniteAsNullNoNegativeZero) {
  std::string out;
  JsonWriter w(out);
  w.begin_array();
  w.number(1.23456, 2);
  w.number(-0.0001, 2);
  w.number(std::numeric_limits<double>::quiet_NaN(), 3);
  w.number(std::numeric_limits<double>::infinity(), 3);
  w.number(-2.5, 0);
  w.number(1e300, 1);
  w.end_array();
  const nlohmann::json j = nlohmann::json::parse(out);
  EXPECT_EQ(out.substr(0, 15), "[1.23,0.00,null");
  EXPECT_TRUE(j[3].is_null());
  EXPECT_DOUBLE_EQ(j[4].get<double>(), -2.0);  // round half to even
  EXPECT_DOUBLE_EQ(j[5].get<double>(), 1e300);
}

TEST(JsonWriter, NoAllocationOnceTheStringHasCapacity) {
  std::string out;
  out.reserve(4096);
  const long before = support::allocation_count();
  for (int k = 0; k < 10; ++k) {
    out.clear();
    JsonWriter w(out);
    w.begin_object();
    w.field("pi", 3.14159, 4);
    w.field_string("name", "a long enough string that small-string optimisation does not apply");
    w.key("v");
    w.begin_array();
    for (int i = 0; i < 50; ++i) w.number(i * 0.5, 1);
    w.end_array();
    w.end_object();
  }
  EXPECT_EQ(support::allocation_count() - before, 0);
}

}  // namespace
}  // namespace gnssemu::daemon
