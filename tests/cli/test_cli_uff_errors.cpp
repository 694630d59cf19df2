// ssid uff list on files that are not (usable) universal files: each is bad
// input (exit 2) with a message that names the cause and echoes no raw byte.
#include <catch2/catch.hpp>

#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch_file(const std::string& name, const std::string& content) {
  const fs::path p = cli_scratch("uff_errors") / name;
  std::ofstream(p, std::ios::binary) << content;
  return p;
}

}  // namespace

TEST_CASE("ssid uff list: a binary file is said to be one, without its bytes", "[cli][uff][errors]") {
  std::string zip("PK\x03\x04\x14\x00\x00\x00\x08\x00", 10);
  for (int i = 0; i < 300; ++i) zip += static_cast<char>((i * 37) & 0xff);
  const fs::path p = scratch_file("x.unv", zip);
  const auto r = run_ssid("uff list " + p.string());
  CHECK(r.code == 2);
  CHECK(r.out.empty());
  CHECK(r.err == "ssid: error: " + p.string() + ": not a universal file: byte 0x03 at line 1, column 3 is not text\n");
}

TEST_CASE("ssid uff list: an empty file and a file without a dataset are errors", "[cli][uff][errors]") {
  const std::string why = ": a universal file holds datasets, each opened by a line \"    -1\" and its dataset number "
                          "and closed by a line \"    -1\"\n";
  const fs::path empty = scratch_file("empty.unv", "");
  const auto e = run_ssid("uff list " + empty.string());
  CHECK(e.code == 2);
  CHECK(e.out.empty());
  CHECK(e.err == "ssid: error: " + empty.string() + ": empty file" + why);
  const fs::path none = scratch_file("none.unv", "    -1\n    -1\n\n");
  const auto n = run_ssid("uff list " + none.string());
  CHECK(n.code == 2);
  CHECK(n.out.empty());
  CHECK(n.err == "ssid: error: " + none.string() + ": no dataset in the file" + why);
}

TEST_CASE("ssid uff list: a line missing a value is blamed on that line", "[cli][uff][errors]") {
  const fs::path p = scratch_file("short.unv",
                                  "    -1\n    55\nA\nB\nC\nD\nE\n"
                                  "         1         2         2         8         2         3\n"
                                  "         2         4         1         1\n"
                                  "  7.75000E+00  1.00000E+00  1.20000E-02  0.00000E+00\n"
                                  "         1\n  1.00000E+00 -5.00000E-01\n"
                                  "         2\n  1.00000E+00  2.00000E+00  3.00000E+00\n    -1\n");
  const auto r = run_ssid("uff list " + p.string());
  CHECK(r.code == 2);
  CHECK(r.out.empty());
  CHECK(r.err == "ssid: error: " + p.string() +
                     ":12: dataset 55 record 10 field 3 (data at node): expected real (E13, columns 27-39), value 3 "
                     "of 3, got \"\"\n");
}
