#pragma once
/// \file bulk_model.hpp
/// The typed view of a deck's bulk data: one vector per supported card type,
/// the count of cards kept verbatim, and every problem found, all at once.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "formats/cards/bar.hpp"
#include "formats/cards/beam.hpp"
#include "formats/cards/bush.hpp"
#include "formats/cards/coord.hpp"
#include "formats/cards/crod.hpp"
#include "formats/cards/design.hpp"
#include "formats/cards/eigen.hpp"
#include "formats/cards/grid.hpp"
#include "formats/cards/mat1.hpp"
#include "formats/cards/param.hpp"
#include "formats/cards/rigid.hpp"
#include "formats/cards/rod.hpp"
#include "formats/cards/scalar.hpp"
#include "formats/cards/section.hpp"
#include "formats/cards/spc.hpp"
#include "formats/deck.hpp"

namespace ssid::formats {

struct BulkModel {
  std::vector<Grid> grids;
  std::vector<Spoint> spoints;
  /// Scalar points defined by their appearance on a scalar element's connection
  /// (CELASi, CMASSi, CDAMPi) and on no SPOINT or GRID: NASTRAN's SPOINT remark
  /// says they "need not appear on an SPOINT entry". Filled by resolve, ascending.
  std::vector<std::int64_t> implied_spoints;
  std::vector<Grdset> grdsets;  ///< at most one; applied to grids
  std::vector<Cord2> cord2s;    ///< CORD2R, CORD2C, CORD2S
  // Elements and their properties.
  std::vector<Crod> crods;
  std::vector<Conrod> conrods;
  std::vector<Prod> prods;
  std::vector<Cbar> cbars;
  std::vector<Baror> barors;  ///< at most one (more is a problem); its defaults are applied to cbars
  std::vector<Pbar> pbars;
  std::vector<Pbarl> pbarls;
  std::vector<Cbeam> cbeams;
  std::vector<Beamor> beamors;  ///< at most one; applied to cbeams
  std::vector<Pbeam> pbeams;
  std::vector<Pbeaml> pbeamls;
  // Masses, springs, bushes.
  std::vector<Conm2> conm2s;
  std::vector<Cmass1> cmass1s;
  std::vector<Cmass2> cmass2s;
  std::vector<Pmass> pmasses;  ///< one per property (a PMASS card holds up to four)
  std::vector<Celas1> celas1s;
  std::vector<Celas2> celas2s;
  std::vector<Pelas> pelases;  ///< one per property (a PELAS card holds up to two)
  std::vector<Cbush> cbushes;
  std::vector<Pbush> pbushes;
  // Materials.
  std::vector<Mat1> mat1s;
  // Rigid elements and constraints.
  std::vector<Rbar> rbars;
  std::vector<Rbe2> rbe2s;
  std::vector<Rbe3> rbe3s;
  std::vector<Spc> spcs;
  std::vector<Spc1> spc1s;
  std::vector<Spcadd> spcadds;
  std::vector<Mpc> mpcs;
  // Solution requests and parameters.
  std::vector<Eigrl> eigrls;
  std::vector<Eigr> eigrs;
  std::vector<Param> params;
  // Design model (the updating parameters).
  std::vector<Desvar> desvars;
  std::vector<Dvprel1> dvprel1s;
  std::vector<Dvmrel1> dvmrel1s;

  /// Cards with no typed parser, by name: kept verbatim in the deck, written back unchanged.
  std::map<std::string, std::size_t> unsupported;
  /// Typed cards, by name.
  std::map<std::string, std::size_t> supported;
  /// Field errors and deck-wide defaults problems (parse_bulk, in deck order), then
  /// the cross-reference problems resolve appends (grouped by kind).
  std::vector<Problem> problems;
};

/// Parses every card with a typed parser; field errors are collected, not thrown.
/// A card with no typed parser is kept verbatim when its name is a NASTRAN bulk
/// data entry (bulk_catalogue.hpp); any other name is an error, as in NASTRAN
/// (USER FATAL MESSAGE 307), with the nearest real name as a suggestion:
/// "unknown card name CRDO — did you mean CROD?".
/// Then applies the deck-wide defaults (GRDSET to GRID, BAROR to CBAR, BEAMOR to CBEAM).
BulkModel parse_bulk(const Deck& deck);

/// Checks the model as a whole — duplicate ids, dangling references ("GRID 12
/// required by CROD 10"), properties of the wrong type — and appends every
/// problem found to model.problems.
void resolve(const Deck& deck, BulkModel& model);

/// The values of every typed card as its write_xxx renders them, by card index
/// (cards holding several entries, such as PELAS, get their entries in order).
/// Deck::set_values with these leaves every value of the deck unchanged; the
/// deck updater changes some of them first.
std::map<std::size_t, std::vector<FieldValue>> write_bulk(const BulkModel& model);

/// True when a card of this name has a typed parser.
bool is_supported_card(const std::string& name);

/// The names of the cards with a typed parser, sorted.
std::vector<std::string> supported_card_names();

/// parse_bulk and resolve, refusing a deck with errors: the one check every path
/// from a deck to a model goes through (modes, assemble, correlate, estimate,
/// diagnose, update-deck). Throws InputError when reading the deck (Deck::problems:
/// a missing ENDDATA, a cut card, an orphan continuation) or its cards found any:
/// "<who>: N error(s) in the deck; nothing assembled:" and the first twenty, one a
/// line, each with its file:line ("<who>: " left out when who is empty). Warnings
/// pass, appended to `warnings` when given (as Problem::str()).
BulkModel resolved_bulk(const Deck& deck, const std::string& who = "", std::vector<std::string>* warnings = nullptr);

}  // namespace ssid::formats
