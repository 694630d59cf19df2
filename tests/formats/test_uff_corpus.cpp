/// Universal files written by lab software, where a copy is at hand: every file
/// of the folder named by SSID_UFF_CORPUS (e.g. pyuff's data/ folder, see
/// docs/uff.md) is read, written and read back; the values must come back
/// exactly and the second writing must equal the first. Without the variable
/// the test says so and checks nothing (the files are not ours to commit).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>

#include "formats/uff.hpp"

using namespace ssid::formats;
using namespace ssid::formats::uff;

namespace {

/// Exact equality of what the reader keeps of two files, dataset by dataset
/// (each dataset's written text, plus the values of 58 and 55/2414 compared as doubles).
std::string first_difference(const UffFile& a, const UffFile& b) {
  if (a.datasets.size() != b.datasets.size()) return "dataset count differs";
  for (std::size_t k = 0; k < a.datasets.size(); ++k) {
    UffFile one, two;
    one.datasets.push_back(a.datasets[k]);
    two.datasets.push_back(b.datasets[k]);
    if (format_uff(one, Precision::Extended) != format_uff(two, Precision::Extended))
      return "dataset " + std::to_string(k + 1) + " (" + std::to_string(dataset_number(a.datasets[k])) + ") differs";
    if (auto f = std::get_if<Function58>(&a.datasets[k])) {
      const auto& g = std::get<Function58>(b.datasets[k]);
      if (f->x != g.x || f->y != g.y) return "values of dataset " + std::to_string(k + 1) + " (58) differ";
    }
    if (auto m = std::get_if<NodalData55>(&a.datasets[k])) {
      const auto& n = std::get<NodalData55>(b.datasets[k]);
      if (m->values != n.values || m->complex_values != n.complex_values || m->nodes != n.nodes)
        return "values of dataset " + std::to_string(k + 1) + " differ";
    }
  }
  return "";
}

}  // namespace

TEST_CASE("UFF corpus: lab files read, written and read back with the same values", "[uff][corpus]") {
  const char* dir = std::getenv("SSID_UFF_CORPUS");
  if (!dir) {
    WARN("SSID_UFF_CORPUS not set: no lab files checked");
    return;
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".uff" && ext != ".unv") continue;
    const std::string path = entry.path().string();
    INFO(path);
    UffFile f;
    try {
      f = read_uff(path);
    } catch (const InputError& e) {
      WARN("not read: " << e.what());
      continue;
    }
    // Extended precision writes single-precision layouts at 17 digits, so what
    // was read comes back exactly whatever the file's own layout.
    const std::string once = format_uff(f, Precision::Extended);
    UffFile g = parse_uff(once, path + " (written)");
    CHECK(first_difference(f, g) == "");
    CHECK(format_uff(g, Precision::Extended) == once);
    // In the standard layouts (as lab software writes them) as well.
    const std::string standard = format_uff(f);
    UffFile h = parse_uff(standard, path + " (standard)");
    CHECK(format_uff(h) == standard);
    std::ifstream in(path, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::map<int, std::size_t> counts;
    for (const auto& d : f.datasets) ++counts[dataset_number(d)];
    std::string list;
    for (const auto& [n, c] : counts) list += " " + std::to_string(n) + "x" + std::to_string(c);
    WARN(entry.path().filename().string() << ":" << list << "; kept verbatim " << f.skipped().size()
                                          << " kind(s); standard text identical to the file: "
                                          << (standard == original ? "yes" : "no"));
  }
}
