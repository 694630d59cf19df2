#pragma once
/// \file card_traits.hpp
/// One entry per card type: how it is parsed and written, the id space its ids
/// live in, the fields that refer to other cards, and what it does to K and M.
/// parse_bulk, write_bulk, resolve (bulk_model.cpp), the assembly's list of
/// ignored cards (translators/assembly/fe_model.cpp) and the diagnosis's deck
/// editor read this table and keep no list of their own: adding a card is one
/// entry in card_traits.cpp plus its struct (docs/cards.md, "Adding a card").
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "formats/deck.hpp"

namespace ssid::formats {

struct BulkModel;
class FieldReader;
namespace detail {
class ResolveContext;
}

/// The id spaces of a deck, scoped as NASTRAN scopes them: a second definition
/// within one space is an error, the same id in two spaces is not. NASTRAN keeps
/// four element families apart (the QRG's "unique with respect to all other
/// element identification numbers" is said of each family, and MSC/NX decks reuse
/// ids across them): structural elements (with springs, dampers and bushings),
/// mass elements, rigid elements, plot elements. The order is the order resolve
/// fills them in; the set spaces after Coordinate are filled when resolve reaches
/// the first card of theirs (their duplicates are reported among the references).
enum class IdSpace {
  None,              ///< the card defines no id (PARAM, SPC, the deck-wide defaults)
  GridPoint,         ///< GRID, SPOINT, EPOINT and implied scalar points
  Element,           ///< structural elements, springs, dampers, bushings
  MassElement,       ///< CONM1/2, CMASSi
  RigidElement,      ///< RBAR, RBE2, RBE3, ...
  PlotElement,       ///< PLOTEL
  Property,          ///< PROD, PBAR, ..., PSHELL
  Material,          ///< MAT1, MAT2, ...
  CoordinateSystem,  ///< CORD1x, CORD2x, CORD3x (0 is the basic system)
  SpcSet,            ///< SID of SPC and SPC1: one set is many cards (repeats allowed)
  SpcaddSet,         ///< SID of SPCADD
  EigenMethod,       ///< SID of EIGRL and EIGR
  Desvar,            ///< DESVAR ID
  Dvprel,            ///< DVPREL1, DVPREL2 ID
  Dvmrel,            ///< DVMREL1, DVMREL2 ID
};
constexpr std::size_t kIdSpaceCount = static_cast<std::size_t>(IdSpace::Dvmrel) + 1;

/// The space's name in messages: "element" in "duplicate element 10 (...)",
/// "grid or scalar point" in "grid or scalar point 3 required by SPC1 1 does not exist".
const char* id_space_noun(IdSpace space);

/// True for the spaces resolve fills before it checks any reference (grids,
/// elements, properties, materials, coordinate systems); false for the set spaces
/// (SPC, SPCADD, methods, design model), filled at the first card of theirs.
bool is_model_space(IdSpace space);

/// What a card does to the stiffness and mass matrices of a real-eigenvalue
/// analysis (SOL 103). Cards kept verbatim with effect IgnoredInSol103 are noted
/// and left out by the assembly ("3 FORCE cards ignored: no effect on K or M");
/// any other card kept verbatim is refused, since it may change K or M.
enum class Effect {
  Stiffness,         ///< its values enter K (springs, bushings)
  Mass,              ///< its values enter M (concentrated and scalar masses)
  StiffnessAndMass,  ///< K and M: elements with mass, their properties and materials, geometry, constraints
  Solution,          ///< steers the solution or the updating without entering K or M (EIGRL, DESVAR, DVPREL1)
  IgnoredInSol103,   ///< no effect on K or M in SOL 103 (loads, output, other solutions' data)
};

/// How a scalar element names its connection points, for the scalar points it
/// implies (NASTRAN's SPOINT remark: "need not appear on an SPOINT entry").
enum class ScalarConnection {
  None,
  GridComponentPairs,  ///< G1 C1 G2 C2 in fields 4-7 (CELAS1/2, CMASS1/2, CDAMP1/2): component 0 or blank = scalar point
  ScalarPoints,        ///< S1 S2 in fields 4-5 (CDAMP3/4 kept verbatim): scalar points only
};

/// A field that refers to an id in another space, as resolve checks it:
/// "GRID 12 required by CROD 10 does not exist",
/// "CROD 10 refers to PID 3, which is a PBAR, expected PROD".
struct Reference {
  const char* field_name = "";  ///< "G1", "PID"; the name in messages
  std::size_t field = 0;        ///< the field index reported (Card::field numbering; 0: the card)
  IdSpace space = IdSpace::None;
  std::vector<std::string> expected;  ///< the card types allowed; empty: any definition in the space
  bool zero_means_none = false;       ///< an id <= 0 (blank) refers to nothing and is not checked
  bool each = false;                  ///< the field is a list (RBE2 GM): every id is checked
};

/// The traits of one card type (several names when they share a struct:
/// CORD2R, CORD2C, CORD2S; CMASS1 and CMASS3). Typed cards have a parser; cards kept verbatim are
/// listed when they define ids, imply scalar points or are ignored in SOL 103.
struct CardTraits {
  std::vector<std::string> names;
  Effect effect = Effect::StiffnessAndMass;
  /// Why a card with effect IgnoredInSol103 does not change K or M (its group:
  /// "loads, enforced motion, temperatures", ...): documentation, not a message.
  const char* ignored_because = "";
  /// Where the card's own id lives (field 2 of a card kept verbatim).
  IdSpace space = IdSpace::None;
  /// The same id on several cards of this kind is one thing, not a duplicate
  /// (SPOINT remark: "duplicate scalar point numbers are allowed"; an SPC set).
  bool repeats_allowed = false;
  /// Property cards: the property types one element chooses among ("bar": PBAR and
  /// PBARL for CBAR); empty: the card's type alone. NASTRAN looks an element's
  /// property up among the types the element accepts, so one id on two property
  /// types of different families is no duplicate (MSC Nastran ran pyNastran's
  /// dbxdra7 with PGAP 1 beside PBEAM 1, rs321h with PSHELL 1 beside PSOLID 1);
  /// within a family the element could not tell them apart: a duplicate.
  /// Materials: "thermal" for MAT4 and MAT5, which may share the id of the
  /// structural material they complete; empty: the structural materials' one family.
  const char* id_family = "";
  ScalarConnection scalar_connection = ScalarConnection::None;
  /// The references resolve checks (the card's own checks come on top: scalar
  /// ends, list fields of nested records, DVPREL1's TYPE, warnings).
  std::vector<Reference> references;

  // Behaviour of a typed card; empty for a card kept verbatim.
  /// Reads deck card `card` into its vector of the model; throws ParseError.
  std::function<void(const FieldReader&, std::size_t card, BulkModel&)> parse;
  /// Renders every parsed card of this type by card index (a card holding
  /// several entries, PELAS, gets them appended in order).
  std::function<void(const BulkModel&, std::map<std::size_t, std::vector<FieldValue>>&)> write;
  /// Calls `f(id, card)` for every id the parsed cards define in `space`.
  std::function<void(const BulkModel&, const std::function<void(std::int64_t, std::size_t)>&)> each_id;
  /// Calls `f(g, c, card)` for every connection point of a typed scalar element
  /// (its scalar-point forms, CELAS3/4 and CMASS3/4, with c = 0).
  std::function<void(const BulkModel&, const std::function<void(std::int64_t, std::int64_t, std::size_t)>&)>
      each_scalar_end;
  /// Checks the references to coordinate systems (`coordinates`) or all the
  /// others with the card's own checks, card by card; resolve calls it twice.
  std::function<void(const BulkModel&, detail::ResolveContext&, bool coordinates)> resolve;

  bool typed() const { return static_cast<bool>(parse); }
};

/// Every card type ssid knows, in the order resolve checks them (card_traits.cpp).
const std::vector<CardTraits>& card_traits();

/// The entry that lists `name`, or nullptr.
const CardTraits* find_card_traits(const std::string& name);

/// The key under which card type `name` defines ids in `space`: two definitions of
/// one id clash only under one key. CardTraits::id_family where set; otherwise the
/// type itself in the property space and "" (one key) in every other space.
std::string id_family(IdSpace space, const std::string& name);

}  // namespace ssid::formats
