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
#include <cmath>

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

/// The values pyuff's own tests (tests/test_2414.py, test_1858.py, test_58.py)
/// expect of its data files, where the file is one of them.
void check_pyuff_expectations(const std::string& name, const UffFile& f, const std::string& dir) {
  if (name == "NX simulation output.uff") {
    // pyuff read_sets(7): last node's data_at_node (complex, re/im pairs).
    const auto& m = std::get<NodalData55>(f.datasets.at(7));
    const auto last = static_cast<Eigen::Index>(m.nodes.size()) - 1;
    CHECK(m.nodes.back() == 9761);
    CHECK(m.complex_values(last, 0) == std::complex<double>(5.34055E-02, -0.0));
    CHECK(m.complex_values(last, 1) == std::complex<double>(-1.58675E+00, 0.0));
    CHECK(m.complex_values(last, 2) == std::complex<double>(-8.87909E-18, 0.0));
  }
  if (name == "simcenter_exported_result.uff") {
    const auto& m = std::get<NodalData55>(f.datasets.at(3));
    CHECK(m.nodes.front() == 1);
    CHECK(m.nodes[9] == 10);
    CHECK(m.nodes.back() == 11619);
    CHECK(m.values(2, 0) == -4.29674E-05);
    CHECK(m.values(2, 1) == -9.05452E-06);
    CHECK(m.values(2, 2) == -9.67413E-04);
  }
  if (name == "1858.uff") {
    const auto& a = std::get<Qualifiers1858>(f.datasets.at(0));
    const auto& b = std::get<Qualifiers1858>(f.datasets.at(1));
    CHECK(a.r1[2] == 1);  // measurement run
    CHECK(a.window() == 4);
    CHECK(a.exponential_damping() == Approx(0.052706007).epsilon(1e-12));
    CHECK(a.directions == "X+    X+");
    CHECK(b.r1[2] == 1);
    CHECK(b.r1[1] == 3);  // octave format
    CHECK(b.directions == "NONE  NONE");
  }
  if (name == "Sample_UFF58b_bin.uff") {
    // pyuff: the binary file holds the ASCII file's function (x equal, data to 6 decimals).
    const UffFile ascii = read_uff(dir + "/Sample_UFF58_ascii.uff");
    const auto& b = *f.functions().at(0);
    const auto& a = *ascii.functions().at(0);
    CHECK(a.id_lines[0] == b.id_lines[0]);
    CHECK(a.response_direction == b.response_direction);
    REQUIRE(a.y.size() == b.y.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.y.size(); ++i) {
      CHECK(a.x[i] == b.x[i]);
      worst = std::max(worst, std::abs(a.y[i] - b.y[i]));
    }
    CHECK(worst < 1.5e-6);  // assert_array_almost_equal: 6 decimals
  }
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
    check_pyuff_expectations(entry.path().filename().string(), f, dir);
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
