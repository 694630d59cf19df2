#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"
#include "formats/deck_writer.hpp"

using namespace ssid::formats;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST_CASE("30 INCLUDE-nested mixed-format files round-trip byte for byte", "[deck][roundtrip]") {
  const fs::path src = fs::path(SSID_TEST_DATA) / "deck" / "nested";
  Deck d = read_deck((src / "main.bdf").string());
  CHECK(d.files.size() == 30);
  CHECK(d.problems.empty());
  CHECK(d.cards.size() == 254);
  BulkModel m = parse_bulk(d);
  resolve(d, m);
  for (const auto& p : m.problems) INFO(p.str());
  CHECK(m.problems.empty());
  // Unknown cards are counted, never dropped.
  CHECK(m.unsupported.at("FORCE") == 53);

  const fs::path out = fs::temp_directory_path() / "ssid_nested_roundtrip";
  fs::remove_all(out);
  auto written = write_deck(d, (out / "main.bdf").string());
  CHECK(written.size() == 30);
  std::size_t compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(src)) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), src);
    INFO(rel.string());
    REQUIRE(fs::exists(out / rel));
    CHECK(slurp(out / rel) == slurp(entry.path()));
    ++compared;
  }
  CHECK(compared == 30);
}

TEST_CASE("the writer refuses to overwrite its input", "[deck][writer]") {
  const fs::path dir = fs::temp_directory_path() / "ssid_overwrite";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "a.bdf") << "GRID    1\n";
  Deck d = read_deck((dir / "a.bdf").string());
  CHECK_THROWS_WITH(write_deck(d, (dir / "a.bdf").string()), Catch::Contains("refusing to overwrite"));
}
