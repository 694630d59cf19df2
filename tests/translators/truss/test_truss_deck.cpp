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
#include "translators/truss/reference_modes.hpp"
#include "translators/truss/truss_deck.hpp"

using namespace ssid::translators::truss;
namespace fmt_ = ssid::formats;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
double real(const fmt_::Card& c, std::size_t i) {
  const auto f = c.field(i);
  return f.empty() ? 0.0 : *fmt_::parse_real(f);
}
int integer(const fmt_::Card& c, std::size_t i) {
  const auto f = c.field(i);
  return f.empty() ? 0 : static_cast<int>(*fmt_::parse_integer(f));
}

/// Rebuilds the model from the deck's own text (only the card types the generator
/// writes): what the reference assembler then solves is what the deck says.
TrussCards fe_from_deck(const fmt_::Deck& d) {
  TrussCards fe;
  for (const auto& c : d.cards) {
    if (c.name == "GRID") {
      FeGrid g{integer(c, 1), {real(c, 3), real(c, 4), real(c, 5)}, std::string(c.field(7)), ""};
      fe.grids.push_back(g);
    } else if (c.name == "MAT1") {
      fe.mat = {integer(c, 1), real(c, 2), real(c, 4), real(c, 5)};
    } else if (c.name == "PROD") {
      fe.rod_props.push_back({integer(c, 1), real(c, 3), real(c, 4), real(c, 6), ""});
    } else if (c.name == "CROD") {
      fe.rods.push_back({integer(c, 1), integer(c, 2), integer(c, 3), integer(c, 4), 0});
    } else if (c.name == "PBAR") {
      fe.bar_props.push_back({integer(c, 1), real(c, 3), real(c, 4), real(c, 5), real(c, 6), real(c, 7), ""});
    } else if (c.name == "CBAR") {
      fe.bars.push_back({integer(c, 1), integer(c, 2), integer(c, 3), integer(c, 4), {real(c, 5), real(c, 6), real(c, 7)}, 0});
    } else if (c.name == "CONM2") {
      REQUIRE(real(c, 11) == real(c, 9));  // the generator writes spheres and points: I11 = I22 = I33
      fe.masses.push_back({integer(c, 1), integer(c, 2), real(c, 4), real(c, 9), ""});
    } else if (c.name == "RBE2") {
      REQUIRE(integer(c, 3) == 123456);
      FeRigid r{integer(c, 1), integer(c, 2), {}};
      for (std::size_t i = 4; i < c.size(); ++i) r.gm.push_back(integer(c, i));
      fe.rigids.push_back(r);
    } else if (c.name == "PELAS") {
      fe.spring_props.push_back({integer(c, 1), real(c, 2), ""});
    } else if (c.name == "CELAS1") {
      fe.springs.push_back({integer(c, 1), integer(c, 2), integer(c, 3), integer(c, 4), integer(c, 5), integer(c, 6)});
    }
  }
  return fe;
}

}  // namespace

TEST_CASE("the deck text holds the model: modes from the re-read deck equal the generator's", "[truss][deck][modes]") {
  const fs::path dir = fs::temp_directory_path() / ("ssid_truss_modes_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (ModelForm form : {ModelForm::Rod, ModelForm::Beam}) {
    const TrussModel t = build_configured({"surge_springs", "tower_diagonal_1", "strut_mass"});
    const TrussCards fe = build_truss_cards(t, form);
    fmt_::write_deck(to_deck(t, fe, "test"), (dir / "m.bdf").string());
    const TrussCards back = fe_from_deck(fmt_::read_deck((dir / "m.bdf").string()));
    CHECK(back.grids.size() == fe.grids.size());
    CHECK(back.total_mass() == Approx(fe.total_mass()).epsilon(1e-12));
    const ReferenceModes a = reference_modes(fe, 20), b = reference_modes(back, 20);
    REQUIRE(a.frequency_hz.size() == b.frequency_hz.size());
    for (std::size_t j = 6; j < a.frequency_hz.size(); ++j) CHECK(b.frequency_hz[j] == Approx(a.frequency_hz[j]).epsilon(1e-8));
  }
  fs::remove_all(dir);
}

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
    const TrussCards fe = build_truss_cards(t, c.form);
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
  const auto j = summary_json(t, build_truss_cards(t, ModelForm::Beam));
  CHECK(j["balls"] == 80);
  CHECK(j["struts"] == 252);
  CHECK(j["mass_kg"].get<double>() == Approx(t.total_mass()));
  CHECK(j["deck_mass_kg"].get<double>() == Approx(t.total_mass()).epsilon(2e-4));
  CHECK(j["parameters"].size() == 10);
  CHECK(j["elements_by_kind"]["bnut"] == 504);
  CHECK(j["suspension"].size() == 3);
}
