#pragma once
/// \file deck.hpp
/// A NASTRAN input file as read: every file (the main one and each INCLUDE),
/// split into verbatim text, bulk data cards and INCLUDE statements, in order.
///
/// The deck model is lossless: writing a deck whose cards were not modified
/// reproduces every file byte for byte. Executive and case control are kept
/// as text (with the statements listed for callers that need SPC=, METHOD=).
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include <memory>

#include "formats/arena.hpp"
#include "formats/card.hpp"
#include "formats/parse_error.hpp"

namespace ssid::formats {

/// Where a line sits. PartBulk: the bulk data of a part superelement or another
/// partition (after `BEGIN SUPER = n`, `BEGIN BULK SUPER = n`, `BEGIN AUXMODEL = n`
/// inside the bulk data), kept verbatim and not read as cards; the BEGIN line is
/// a statement with section Bulk.
enum class Section : std::uint8_t { Executive, CaseControl, Bulk, AfterEnddata, PartBulk };

/// A piece of a file, in order: text copied as is, a card, an INCLUDE, or a
/// continuation line of an earlier card that NASTRAN matched by its marker
/// (Detached: `index` is that card; written as is, or not at all once the card
/// changed, since the card is then written whole at its own place).
struct Chunk {
  enum class Kind : std::uint8_t { Verbatim, Card, Include, Detached };
  Kind kind = Kind::Verbatim;
  std::uint32_t begin = 0, end = 0;  ///< byte span in the file's text
  std::uint32_t index = 0;           ///< card index (Card) or file index (Include)
};

struct SourceFile {
  std::string path;          ///< as opened (relative to the working directory, or absolute)
  std::string include_name;  ///< as written in the INCLUDE statement; empty for the main file
  std::int32_t parent = -1;  ///< index of the including file, -1 for the main file
  std::uint32_t parent_line = 0;
  std::string text;          ///< the whole file
  std::vector<Chunk> chunks;
  std::string newline = "\n";  ///< line ending used when a card is rewritten
};

/// An executive or case control statement (continuation lines joined).
struct Statement {
  Section section = Section::Executive;
  std::string text;  ///< upper-cased, comment stripped, trimmed
  std::uint32_t file = 0, line = 0;
};

struct Deck {
  /// Storage of field texts; a Deck is move-only so the cards' views stay valid.
  std::unique_ptr<Arena> arena = std::make_unique<Arena>();
  /// files[0] is the main file; a deque so references stay valid while INCLUDEs are read.
  std::deque<SourceFile> files;
  std::vector<Card> cards;        ///< bulk data cards in reading order
  std::vector<Statement> statements;
  bool has_bulk_marker = false;   ///< BEGIN BULK seen (false: a bulk-data-only deck)
  std::vector<Problem> problems;  ///< structural problems found while reading

  /// Location of field `field` of card `card` (its own line), with the include chain.
  SourceLocation location(const Card& card, std::size_t field = 0) const;
  SourceLocation location(std::uint32_t file, std::uint32_t line) const;

  /// Replaces the values of a card; the writer will format it anew in its field
  /// format, keeping the original text of fields whose value did not change.
  void set_values(std::size_t card_index, std::vector<FieldValue> values);

  /// Appends a generated card to `file` (values[0] is the name); returns its index.
  std::size_t append_card(std::size_t file, const std::string& name, std::vector<FieldValue> values,
                          FieldFormat format = FieldFormat::Small);
  /// Appends verbatim text (comments, control statements) to `file`.
  void append_text(std::size_t file, const std::string& text);
};

/// An empty deck with one (unwritten) main file, for generated decks.
Deck new_deck(const std::string& path);

/// Options for reading. Limits protect against garbage input.
struct ReadOptions {
  std::size_t max_line_length = 4096;  ///< longer lines are an error (bulk data lines are 80 columns)
  int max_include_depth = 64;
};

/// Reads a deck and every file it includes. Throws ParseError on input that
/// cannot be a deck (missing file, empty file, binary data, overlong line,
/// unterminated INCLUDE quote, INCLUDE cycle); collects the deck's integrity
/// problems in Deck::problems, each an error at its file:line (docs/deck.md,
/// "Deck integrity"): a continuation line with no card before it, a continuation
/// announced in field 10 that never comes, and, in a deck with BEGIN BULK, a
/// missing ENDDATA and a card cut by the end of the file.
Deck read_deck(const std::string& path, const ReadOptions& options = {});

/// Reads a deck from text in memory; `name` is used in messages and as the base
/// for relative INCLUDE paths.
Deck read_deck_text(std::string text, const std::string& name, const ReadOptions& options = {});

}  // namespace ssid::formats
