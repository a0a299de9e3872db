// SPDX-License-Identifier: Apache-2.0
#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/common/error.hpp"
#include "core/common/line_source.hpp"

using namespace gnssemu;
using namespace gnssemu::text;

namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("gnssemu-ls-" + std::to_string(::getpid()) + "-" + name)).string();
}

std::vector<std::string> all_lines(LineSource& src) {
  std::vector<std::string> out;
  Line l;
  int expect = 0;
  while (src.next(l)) {
    EXPECT_EQ(l.number, ++expect);
    out.push_back(l.text);
  }
  return out;
}

}  // namespace

TEST(LineSource, LinesEndsAndNumbers) {
  std::istringstream in("a\r\nbb\n\nlast-without-lf");
  LineSource src(in, "mem", LineLimits{});
  EXPECT_EQ(all_lines(src), (std::vector<std::string>{"a", "bb", "", "last-without-lf"}));
  EXPECT_EQ(src.line_number(), 4);
  std::istringstream empty("");
  LineSource none(empty, "empty", LineLimits{});
  Line l;
  EXPECT_FALSE(none.next(l));
}

TEST(LineSource, LinesAcrossReadChunks) {
  std::string text;
  for (int i = 0; i < 20000; ++i) text += std::string(static_cast<std::size_t>(i % 97), 'x') + "\n";
  std::istringstream in(text);
  LineSource src(in, "mem", LineLimits{100, 1u << 30});
  const std::vector<std::string> lines = all_lines(src);
  ASSERT_EQ(lines.size(), 20000u);
  for (std::size_t i = 0; i < lines.size(); ++i) ASSERT_EQ(lines[i].size(), i % 97) << i;
}

TEST(LineSource, LimitsNameFileAndLine) {
  std::istringstream long_line("ok\n" + std::string(5000, 'y') + "\n");
  LineSource a(long_line, "f.txt", LineLimits{4096, 1u << 20});
  Line l;
  EXPECT_TRUE(a.next(l));
  try {
    a.next(l);
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "f.txt:2: line longer than 4096 bytes: not a file of this kind");
  }
  // A line without end is refused once it passes the limit, not at the end of the file.
  std::istringstream endless(std::string(1u << 20, 'z'));
  LineSource b(endless, "g", LineLimits{1024, 1u << 30});
  EXPECT_THROW(b.next(l), Error);
  std::istringstream many(std::string(3u << 20, '\n'));
  LineSource c(many, "h", LineLimits{1024, 1u << 20});
  EXPECT_THROW(all_lines(c), Error);
}

TEST(LineSource, GzipAndPlainFilesReadAlike) {
  const std::string plain = temp_path("plain.txt"), packed = temp_path("packed.txt.gz");
  const std::string text = "RINEX\r\nsecond line\nthird";
  std::ofstream(plain, std::ios::binary) << text;
  gzFile f = gzopen(packed.c_str(), "wb");
  ASSERT_NE(f, nullptr);
  gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  gzclose(f);
  LineSource p(plain, LineLimits{}), g(packed, LineLimits{});
  EXPECT_EQ(all_lines(p), all_lines(g));
  EXPECT_EQ(g.name(), packed);
  std::filesystem::remove(plain);
  std::filesystem::remove(packed);
  try {
    LineSource missing("/nonexistent/x.rnx", LineLimits{});
    ADD_FAILURE() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/x.rnx: cannot open"), std::string::npos) << e.what();
  }
}
