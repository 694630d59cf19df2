// The generated decks: valid for the reader, byte-for-byte round trip, cards as the model says.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>

#include "formats/bulk_model.hpp"
#include "formats/deck_writer.hpp"
#include "formats/field_reader.hpp"
#include "formats/nastran_number.hpp"
#include <unistd.h>
#include "translators/truss/configurations.hpp"
#include "translators/truss/truss_deck.hpp"

using namespace ssid::translators::truss;
namespace fmt_ = ssid::formats;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
}  // namespace

TEST_CASE("generated truss decks read back with no problems and round-trip byte for byte", "[truss][deck]") {
  const fs::path dir = fs::temp_directory_path() / ("ssid_truss_deck_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  struct Case {
    ModelForm form;
    std::vector<std::string> configs;
  };
  for (const Case& c : {Case{ModelForm::Rod, {"bare"}}, Case{ModelForm::Beam, {"bare"}},
                        Case{ModelForm::Rod, {"surge_springs", "metrology_tip_mass", "tower_diagonal_2"}},
                        Case{ModelForm::Beam, {"long_bnut", "strut_mass", "surge_springs"}},
                        Case{ModelForm::Beam, {"component4"}}}) {
    const TrussModel t = build_configured(c.configs);
    const FeModel fe = build_fe_model(t, c.form);
    const fmt_::Deck d = to_deck(t, fe, "test");
    const fs::path first = dir / "first.bdf", second = dir / "second.bdf";
    fmt_::write_deck(d, first.string());

    fmt_::Deck back = fmt_::read_deck(first.string());
    INFO(fe.title);
    for (const auto& p : back.problems) INFO(p.str());
    CHECK(back.problems.empty());
    CHECK(back.has_bulk_marker);
    fmt_::BulkModel bm = fmt_::parse_bulk(back);
    fmt_::resolve(back, bm);
    for (const auto& p : bm.problems) INFO(p.str());
    CHECK(bm.problems.empty());

    std::map<std::string, std::size_t> n;
    for (const auto& card : back.cards) ++n[card.name];
    CHECK(n["GRID"] == fe.grids.size());
    CHECK(n["CROD"] == fe.rods.size());
    CHECK(n["CBAR"] == fe.bars.size());
    CHECK(n["RBE2"] == fe.rigids.size());
    CHECK(n["CONM2"] == fe.masses.size());
    CHECK(n["CELAS1"] == fe.springs.size());
    CHECK(n["DESVAR"] == fe.desvars.size());
    CHECK(n["DVPREL1"] == fe.dvprels.size());
    CHECK(n["EIGRL"] == 1);
    CHECK(n["MAT1"] == 1);

    // Values survive the text: grid coordinates and the DVPREL1 table read back exactly.
    for (const auto& card : back.cards) {
      if (card.name == "GRID") {
        const int id = static_cast<int>(*fmt_::parse_integer(card.field(1)));
        const FeGrid& g = fe.grid(id);
        CHECK(*fmt_::parse_real(card.field(3)) == g.x.x());
        CHECK(*fmt_::parse_real(card.field(4)) == g.x.y());
        CHECK(*fmt_::parse_real(card.field(5)) == g.x.z());
      }
    }

    fmt_::write_deck(back, second.string());
    CHECK(slurp(first) == slurp(second));
  }
  fs::remove_all(dir);
}

TEST_CASE("truss JSON summary: counts, mass and the parameter table", "[truss][deck]") {
  const TrussModel t = build_configured({"bare"});
  const auto j = summary_json(t, build_fe_model(t, ModelForm::Beam));
  CHECK(j["balls"] == 80);
  CHECK(j["struts"] == 252);
  CHECK(j["mass_kg"].get<double>() == Approx(t.total_mass()));
  CHECK(j["deck_mass_kg"].get<double>() == Approx(t.total_mass()).epsilon(2e-4));
  CHECK(j["parameters"].size() == 10);
  CHECK(j["elements_by_kind"]["bnut"] == 504);
  CHECK(j["suspension"].size() == 3);
}
