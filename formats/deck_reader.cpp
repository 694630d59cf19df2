/// \file deck_reader.cpp
/// Splits NASTRAN input into sections, cards, comments and INCLUDEs.
///
/// Field layout (NASTRAN Quick Reference Guide, "Format of Bulk Data Entries"):
///   small field: field 1 = columns 1-8, fields 2-9 = 8 columns each (9-72),
///                field 10 = columns 73-80 (continuation marker); columns 81+ ignored.
///   large field: name ends in '*'; field 1 = columns 1-8, four fields of 16 columns
///                (9-72), field 10 = columns 73-80; continuation lines start with '*'.
///   free field:  a comma within the first 10 columns; fields separated by commas;
///                "NAME*," makes it large (four fields per line); commas after field 10
///                with nothing between them end the line (a trailing comma). A line
///                ended by a comma with no marker, followed by a line of bare values
///                (its first field a number), is continued by it: fields 2-9 of a new row.
/// A line whose field 1 starts with '+' or '*', or is blank, continues the card
/// above it. Tabs advance to the next multiple of 8 columns; '$' starts a comment.
/// A line whose field 1 is "=", "=n" or "=(n)" replicates the card above it
/// (replicate_fields).
/// A continuation line whose field 1 is a marker of its own (two characters or more,
/// "+R10201") that is not the field 10 of the card above it but of an earlier card
/// continues that earlier card, as NASTRAN matches continuations by their markers
/// (pyNastran's cqra00366, which MSC Nastran ran, has RBE1's "+R10201" after two GRIDs).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "formats/deck.hpp"
#include "formats/nastran_number.hpp"
#include "formats/text_util.hpp"

namespace ssid::formats {

namespace fs = std::filesystem;
using detail::expand_tabs;
using detail::iequals_prefix;
using detail::trim;
using detail::upper;

SourceLocation Deck::location(std::uint32_t file, std::uint32_t line) const {
  SourceLocation loc;
  if (file < files.size()) {
    loc.file = files[file].path;
    std::int32_t p = files[file].parent;
    std::uint32_t pl = files[file].parent_line;
    while (p >= 0) {
      loc.included_from.push_back(files[p].path + ":" + std::to_string(pl));
      pl = files[p].parent_line;
      p = files[p].parent;
    }
  }
  loc.line = line;
  return loc;
}

SourceLocation Deck::location(const Card& card, std::size_t field) const {
  return location(card.file, card.line_of(field));
}

namespace {

struct Line {
  std::uint32_t begin, end;  ///< content span (without the line ending)
  std::uint32_t next;        ///< start of the next line
  std::uint32_t number;      ///< 1-based
};

/// Iterates the lines of a text, keeping byte offsets.
class LineCursor {
public:
  explicit LineCursor(const std::string& t) : m_text(t) {}
  bool next(Line& l) {
    if (m_pos >= m_text.size()) return false;
    std::size_t nl = m_text.find('\n', m_pos);
    std::size_t stop = nl == std::string::npos ? m_text.size() : nl;
    std::size_t content_end = stop;
    if (content_end > m_pos && m_text[content_end - 1] == '\r') --content_end;
    l.begin = static_cast<std::uint32_t>(m_pos);
    l.end = static_cast<std::uint32_t>(content_end);
    l.next = static_cast<std::uint32_t>(nl == std::string::npos ? m_text.size() : nl + 1);
    l.number = ++m_line;
    m_pos = l.next;
    return true;
  }

private:
  const std::string& m_text;
  std::size_t m_pos = 0;
  std::uint32_t m_line = 0;
};

/// Data part of a line: comment removed. Returns the view (not trimmed).
std::string_view strip_comment(std::string_view s) {
  std::size_t d = s.find('$');
  return d == std::string_view::npos ? s : s.substr(0, d);
}

bool is_blank(std::string_view s) { return trim(s).empty(); }

/// ENDDATA in field 1 of a trimmed data part; NASTRAN reads nothing after it, so later
/// fields (pyNastran writes a checksum there: "ENDDATA 58e050da") do not matter.
bool is_enddata(std::string_view t) {
  return iequals_prefix(t, "ENDDATA") && (t.size() == 7 || t[7] == ' ' || t[7] == ',' || t[7] == '\t');
}

/// The fields of one physical line: the first field (name or continuation
/// marker) and the data fields that follow (texts in the deck's arena).
struct LineFields {
  std::string_view first;              ///< field 1, trimmed, upper case
  std::vector<std::string_view> data;  ///< data fields (8 small, 4 large; free: as given)
  bool large = false;
  bool free = false;
  std::string_view marker;             ///< field 10 (continuation marker), trimmed
};

/// Splits a line's data part (comment removed) into fields; `scratch` holds the
/// tab-expanded text when the line has tabs.
void split_line(std::string_view data, Arena& arena, LineFields& lf, std::string& scratch) {
  lf.data.clear();
  lf.marker = {};
  if (data.find('\t') != std::string_view::npos) {
    scratch = expand_tabs(data);
    data = scratch;
  }
  std::size_t comma = data.find(',');
  if (comma != std::string_view::npos && comma < 10) {
    lf.free = true;
    std::size_t start = 0, k = 0;
    std::size_t per_row = 8;
    while (true) {
      std::size_t c = data.find(',', start);
      std::string_view part = arena.copy_upper(
          trim(data.substr(start, c == std::string_view::npos ? std::string_view::npos : c - start)));
      if (k == 0) {
        lf.first = part;
        lf.large = !part.empty() && (part.back() == '*' || part[0] == '*');
        per_row = lf.large ? 4 : 8;
      } else if (k == per_row + 1) {
        lf.marker = part;  // field 10
      } else if (k > per_row + 1 && part.empty() && data.find_first_not_of(", \t", start) == std::string_view::npos) {
        // Nothing but commas after field 10: a line ended with a comma, as in decks MSC
        // Nastran ran (pyNastran's conedg01e: "CORD2R, 5, , 0.0, …, 1.0, +C1,"). Not a field.
        break;
      } else {
        lf.data.push_back(part);
      }
      ++k;
      if (c == std::string_view::npos) break;
      start = c + 1;
    }
    return;
  }
  lf.free = false;
  auto col = [&](std::size_t b, std::size_t w) -> std::string_view {
    if (b >= data.size()) return {};
    return trim(data.substr(b, std::min(w, data.size() - b)));
  };
  lf.first = arena.copy_upper(col(0, 8));
  lf.large = !lf.first.empty() && (lf.first.back() == '*' || lf.first[0] == '*');
  if (lf.large) {
    for (int k = 0; k < 4; ++k) lf.data.push_back(arena.copy_upper(col(8 + 16 * k, 16)));
  } else {
    for (int k = 0; k < 8; ++k) lf.data.push_back(arena.copy_upper(col(8 + 8 * k, 8)));
  }
  lf.marker = arena.copy_upper(col(72, 8));  // matched against field 1 of continuations, upper-cased
}

/// The data part of a line (comment removed) ends with a comma.
bool ends_with_comma(std::string_view data) {
  const std::string_view t = trim(data);
  return !t.empty() && t.back() == ',';
}

/// A free-field line of bare values (its first field a number, never a card name or a
/// continuation marker) after a free-field line ended by a comma: the values are fields
/// 2-9 of a new row, a ninth value its field 10 (marker), and any after that stay data,
/// as after field 10 of any free-field line (the card's reader then finds a field too
/// many). Rewrites `lf` so.
bool implicit_free_continuation(LineFields& lf) {
  if (!lf.free || lf.first.empty()) return false;
  const char c = lf.first[0];
  if (!((c >= '0' && c <= '9') || c == '-' || c == '.')) return false;
  // As split: first = value 1, data = values 2-9 then 11 on, marker = value 10.
  lf.data.insert(lf.data.begin(), lf.first);
  lf.first = {};
  if (lf.data.size() > 8) {
    std::vector<std::string_view> beyond(lf.data.begin() + 9, lf.data.end());
    if (!lf.marker.empty() || !beyond.empty()) beyond.insert(beyond.begin(), lf.marker);
    lf.marker = lf.data[8];
    lf.data.resize(8);
    lf.data.insert(lf.data.end(), beyond.begin(), beyond.end());
  }
  return true;
}

/// Free-field replication (MSC Nastran Quick Reference Guide, "Format of Bulk Data
/// Entries", free field format). A line whose field 1 is "=" is a new entry built from
/// the entry before it, field by field:
///   "="          the field of the entry before;
///   "=="         that field and every field after it;
///   "*x", "*(x)" that field plus x: an integer increment for an integer field, a real
///                one for a real field (the Guide: "x should be a real number for real
///                fields or an integer for integer fields"); a blank field counts as zero
///                (a deck MSC Nastran ran, pyNastran's dbxdra7.bdf, increments a blank
///                GRID CD so; the Guide is silent);
///   blank        a blank field; any other text is the field's value.
/// Fields the line does not reach are blank. A line "=n" or "=(n)" alone makes n more
/// entries, each from the one before by the last "=" line's fields. Only one-line
/// entries are replicated: NASTRAN's continuation replication (incremented markers)
/// is not read, and a replication line that would need it is an error.
constexpr std::size_t kMaxReplicas = 100000;  ///< per "=(n)" line: garbage input must not exhaust memory
/// In all: forty "=(100000)" lines of 10 bytes would be 4 million cards.
constexpr std::size_t kMaxReplicasPerDeck = 200000;
/// Continuation lines matched by marker to one earlier card: each copies the card's
/// fields, so garbage input repeating one marker must not grow without bound.
constexpr std::size_t kMaxDetachedRows = 256;

/// The count of an "=n" or "=(n)" field; 0 when the text is not one.
std::size_t replication_count(std::string_view first) {
  std::string_view n = first.substr(1);
  if (n.size() >= 2 && n.front() == '(' && n.back() == ')') n = trim(n.substr(1, n.size() - 2));
  const auto v = parse_integer(n);
  return v && *v > 0 && static_cast<std::uint64_t>(*v) <= kMaxReplicas ? static_cast<std::size_t>(*v) : 0;
}

/// The text of field `old` incremented by `spec` ("*x" or "*(x)"), or nullopt with `why`.
std::optional<std::string> incremented(std::string_view old, std::string_view spec, std::string& why) {
  std::string_view x = spec.substr(1);
  if (x.size() >= 2 && x.front() == '(' && x.back() == ')') x = trim(x.substr(1, x.size() - 2));
  const FieldKind xk = classify_field(x);
  const FieldKind ok = classify_field(old);
  if (xk != FieldKind::Integer && xk != FieldKind::Real) {
    why = "'" + std::string(spec) + "' is not an increment (expected *x or *(x), x a number)";
    return std::nullopt;
  }
  if (ok != FieldKind::Blank && ok != xk) {
    why = std::string(xk == FieldKind::Integer ? "an integer" : "a real") + " increment '" + std::string(spec) +
          "' on the field '" + std::string(old) + "' of the entry before, " +
          (ok == FieldKind::Integer ? "an integer" : ok == FieldKind::Real ? "a real" : "text") +
          " (NASTRAN: a real increment for a real field, an integer for an integer field)";
    return std::nullopt;
  }
  if (xk == FieldKind::Integer) {
    std::int64_t sum = 0;
    if (__builtin_add_overflow(ok == FieldKind::Blank ? 0 : *parse_integer(old), *parse_integer(x), &sum)) {
      why = "'" + std::string(old) + "' + " + std::string(x) + " overflows an integer";
      return std::nullopt;
    }
    return std::to_string(sum);
  }
  // The sum as a decimal sum would give it: fifteen significant digits, so that
  // -78.87 + 12.5 reads -66.37 and not the double's last-bit noise.
  const double sum = (ok == FieldKind::Blank ? 0.0 : *parse_real(old)) + *parse_real(x);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", sum);
  const double rounded = std::strtod(buf, nullptr);
  const auto text = std::isfinite(sum) && std::isfinite(rounded) ? format_real_exact(rounded, 24) : std::nullopt;
  if (!text) {
    why = "'" + std::string(old) + "' + " + std::string(x) + " is not a finite real";
    return std::nullopt;
  }
  return text;
}

/// The fields of an entry replicated from `prev` (fields 0-8, the name first) by a
/// replication line's fields 2-9 (`specs`); false with `why` when one cannot be made.
bool replicate_fields(const Card& prev, const std::vector<std::string_view>& specs, Arena& arena,
                      std::vector<std::string_view>& out, std::string& why) {
  out.assign(9, std::string_view());
  out[0] = prev.field(0);
  for (std::size_t i = 1; i <= 8; ++i) {
    const std::string_view spec = i - 1 < specs.size() ? specs[i - 1] : std::string_view();
    const std::string_view old = prev.field(i);
    if (spec == "==") {
      for (std::size_t j = i; j <= 8; ++j) out[j] = prev.field(j);
      return true;
    }
    if (spec == "=") {
      out[i] = old;
    } else if (!spec.empty() && spec[0] == '*') {
      auto t = incremented(old, spec, why);
      if (!t) {
        why = "field " + std::to_string(i + 1) + ": " + why;
        return false;
      }
      out[i] = arena.copy(*t);
    } else if (!spec.empty() && spec[0] == '=') {
      why = "field " + std::to_string(i + 1) + ": '" + std::string(spec) +
            "' is not a replication field (expected =, == or *x)";
      return false;
    } else {
      out[i] = spec;
    }
  }
  return true;
}

/// A BEGIN line (upper case) that starts a partition of the bulk data: BEGIN [BULK]
/// SUPER|AUXMODEL|AFPM|TRMC|ARBMODEL|MODULE [=] n (MSC Nastran's partitioned bulk data).
bool is_partition(const std::string& u) {
  std::istringstream in(u);
  std::string word;
  in >> word;  // BEGIN
  if (!(in >> word)) return false;
  if (word == "BULK" && !(in >> word)) return false;
  const std::size_t eq = word.find('=');
  const std::string key = eq == std::string::npos ? word : word.substr(0, eq);
  for (const char* k : {"SUPER", "AUXMODEL", "AFPM", "TRMC", "ARBMODEL", "MODULE"})
    if (key == k) return true;
  return false;
}

bool is_continuation(const LineFields& lf, std::string_view data) {
  if (!lf.first.empty()) return lf.first[0] == '+' || lf.first[0] == '*';
  return !is_blank(data);  // blank field 1 with data after it
}

struct Reader {
  Reader(Deck& d, const ReadOptions& o) : deck(d), opt(o) {}
  Deck& deck;
  const ReadOptions& opt;
  Section section = Section::Bulk;
  std::vector<std::string> chain;  ///< canonical paths of files being read (cycle check)

  // The card being read; continuations may follow it.
  bool pending = false;
  Card card;
  std::string pending_marker;
  std::uint32_t pending_file = 0;
  std::vector<std::string_view> fields;                   ///< fields of the pending card
  std::vector<std::pair<std::uint32_t, std::uint32_t>> rows;  ///< its physical lines
  /// The pending card's last line is the first half of a large-field row (fields
  /// 2-5): a large-field card cut after it has lost its continuation.
  bool pending_half = false;
  /// The pending card's last line was free field, ended by a comma, with no marker: a
  /// line of bare values may continue it (implicit_free_continuation).
  bool pending_free_comma = false;
  std::uint32_t begin_bulk_line = 0;  ///< line of BEGIN BULK in the main file (0: none)
  /// The last "=" line's fields 2-9, which an "=(n)" line repeats; valid while only
  /// replication lines follow it.
  std::vector<std::string_view> repl_specs;
  bool repl_valid = false;
  /// A replication line failed: the lines that replicate from it cannot be read either.
  bool repl_failed = false;
  /// Cards whose last line's field 10 holds a marker no line has answered yet, by
  /// file and marker: where a continuation with that marker goes.
  std::map<std::pair<std::uint32_t, std::string>, std::size_t> open_markers;
  /// Continuation lines attached to earlier cards so far, per card: each copies the
  /// card's fields, so their number is bounded (kMaxDetachedRows).
  std::unordered_map<std::size_t, std::size_t> detached_rows;
  /// The pending card has a large-field line (half rows of four fields).
  bool pending_large = false;
  /// Cards with large-field lines: no continuation is matched to them by marker.
  std::unordered_set<std::size_t> large_cards;
  /// Entries replication has made in this deck (kMaxReplicasPerDeck).
  std::size_t replicas_made = 0;
  LineFields lf;                                          ///< reused per line
  std::string scratch;

  std::string slurp(const std::string& path, std::uint32_t fi) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail(fi, 0, "cannot open file for reading");
    std::string t(static_cast<std::size_t>(in.tellg()), '\0');
    in.seekg(0);
    in.read(t.data(), static_cast<std::streamsize>(t.size()));
    if (!in) fail(fi, 0, "error reading file");
    return t;
  }

  [[noreturn]] void fail(std::uint32_t file, std::uint32_t line, const std::string& msg) {
    throw ParseError(deck.location(file, line), msg);
  }

  static void check_text(Reader& r, std::uint32_t fi, const std::string& text, std::size_t max_line) {
    if (text.empty()) r.fail(fi, 0, "empty file: expected NASTRAN bulk data");
    std::uint32_t line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
      unsigned char c = static_cast<unsigned char>(text[i]);
      if (c == '\n') {
        if (i - line_start > max_line + 1)
          r.fail(fi, line, "line is " + std::to_string(i - line_start) +
                               " characters long (limit " + std::to_string(max_line) +
                               "): not a NASTRAN deck line");
        ++line;
        line_start = i + 1;
      } else if (c < 0x20 && c != '\t' && c != '\r' && c != '\f') {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", c);
        r.fail(fi, line, std::string("binary data (byte ") + hex + " at column " +
                             std::to_string(i - line_start + 1) + "): expected a NASTRAN text deck");
      }
    }
    if (text.size() - line_start > max_line)
      r.fail(fi, line, "line is " + std::to_string(text.size() - line_start) +
                           " characters long (limit " + std::to_string(max_line) +
                           "): not a NASTRAN deck line");
  }

  void add_rows(const LineFields& lf, std::uint32_t line_number) {
    // Rows of the folded card are 8 fields wide; a large line fills half a row.
    if (!lf.large && (fields.size() - 1) % 8 != 0) fields.resize(fields.size() + (8 - (fields.size() - 1) % 8));
    pending_half = lf.large && (fields.size() - 1) % 8 == 0;
    pending_large = pending_large || lf.large;
    rows.emplace_back(line_number, static_cast<std::uint32_t>(fields.size()));
    const std::size_t width = lf.large ? 4 : 8;
    fields.insert(fields.end(), lf.data.begin(), lf.data.end());
    if (lf.data.size() < width) fields.resize(fields.size() + (width - lf.data.size()));
  }

  /// What the pending card's last line `lf` (data part `data`) leaves open: the marker
  /// its next line must answer, or, for a free-field line ended by a comma with no
  /// marker, a line of bare values (implicit_free_continuation).
  void note_line_end(const LineFields& lf, std::string_view data) {
    pending_marker = std::string(lf.marker);
    pending_free_comma = lf.free && ends_with_comma(data) && lf.marker.empty();
  }

  void finish_card(std::uint32_t fi, std::uint32_t& emitted, bool at_end) {
    if (!pending) return;
    pending = false;
    if (!pending_marker.empty() && at_end) {
      deck.problems.push_back({Problem::Severity::Error, deck.location(card.file, rows.back().first),
                               card.name + " " + std::string(fields.size() > 1 ? fields[1] : "") +
                                   ": unterminated continuation: field 10 holds '" + pending_marker +
                                   "' but no continuation line follows"});
    }
    while (fields.size() > 1 && fields.back().empty()) fields.pop_back();
    Arena& a = *deck.arena;
    auto* f = a.make_array<std::string_view>(fields.size());
    std::copy(fields.begin(), fields.end(), f);
    card.m_fields = f;
    card.m_nfields = static_cast<std::uint32_t>(fields.size());
    auto* r = a.make_array<std::pair<std::uint32_t, std::uint32_t>>(rows.size());
    std::copy(rows.begin(), rows.end(), r);
    card.m_rows = r;
    card.m_nrows = static_cast<std::uint32_t>(rows.size());
    fields.clear();
    rows.clear();
    if (!pending_marker.empty()) open_markers[{card.file, pending_marker}] = deck.cards.size();
    if (pending_large) large_cards.insert(deck.cards.size());
    pending_large = false;
    SourceFile& sf = deck.files[card.file];
    if (card.begin > emitted) sf.chunks.push_back({Chunk::Kind::Verbatim, emitted, card.begin, 0});
    sf.chunks.push_back({Chunk::Kind::Card, card.begin, card.end, static_cast<std::uint32_t>(deck.cards.size())});
    emitted = card.end;
    deck.cards.push_back(std::move(card));
    card = Card{};
  }

  std::uint32_t read_file(const std::string& path, const std::string& include_name, std::int32_t parent,
                          std::uint32_t parent_line, std::string* text_in) {
    std::uint32_t fi = static_cast<std::uint32_t>(deck.files.size());
    deck.files.emplace_back();
    deck.files[fi].path = path;
    deck.files[fi].include_name = include_name;
    deck.files[fi].parent = parent;
    deck.files[fi].parent_line = parent_line;
    if (text_in) {
      deck.files[fi].text = std::move(*text_in);
    } else {
      std::error_code ec;
      if (!fs::exists(path, ec)) {
        if (parent >= 0) fail(static_cast<std::uint32_t>(parent), parent_line,
                              "INCLUDE '" + include_name + "': file not found (looked for " + path + ")");
        throw ParseError(SourceLocation{path, 0, {}}, "file not found");
      }
      if (fs::is_directory(path, ec)) fail(fi, 0, "is a directory, expected a NASTRAN deck");
      deck.files[fi].text = slurp(path, fi);
    }
    check_text(*this, fi, deck.files[fi].text, opt.max_line_length);
    if (deck.files[fi].text.find("\r\n") != std::string::npos) deck.files[fi].newline = "\r\n";

    std::error_code ec;
    std::string canon = fs::weakly_canonical(path, ec).string();
    for (const auto& c : chain)
      if (c == canon) fail(static_cast<std::uint32_t>(parent), parent_line, "INCLUDE cycle: " + path + " includes itself");
    if (static_cast<int>(chain.size()) >= opt.max_include_depth)
      fail(static_cast<std::uint32_t>(parent), parent_line, "INCLUDE nested deeper than " + std::to_string(opt.max_include_depth) + " levels");
    chain.push_back(canon);

    const std::string& text = deck.files[fi].text;  // deque: stable while INCLUDEs append files
    LineCursor cursor(text);
    Line l;
    std::uint32_t emitted = 0;
    while (cursor.next(l)) {
      std::string_view content(text.data() + l.begin, l.end - l.begin);
      std::string_view data = strip_comment(content);
      std::string_view tdata = trim(data);

      if (section != Section::AfterEnddata && iequals_prefix(tdata, "INCLUDE") &&
          (tdata.size() == 7 || tdata[7] == ' ' || tdata[7] == '\'' || tdata[7] == '"' || tdata[7] == '\t')) {
        if (section == Section::Bulk) finish_card(fi, emitted, false);
        handle_include(fi, l, cursor, emitted, text);
        continue;
      }
      if (section == Section::Executive || section == Section::CaseControl) {
        std::string u = upper(tdata);
        if (!u.empty()) deck.statements.push_back({section, u, fi, l.number});
        if (section == Section::Executive && u == "CEND") section = Section::CaseControl;
        else if (u.rfind("BEGIN", 0) == 0 && u.find("BULK") != std::string::npos) {
          section = Section::Bulk;
          if (parent < 0) begin_bulk_line = l.number;
        }
        continue;
      }
      if (section == Section::AfterEnddata) continue;

      if (tdata.empty()) continue;  // comment or blank line: verbatim, may sit inside a card
      // Partitioned bulk data (MSC Nastran: BEGIN SUPER = n, BEGIN BULK SUPER = n, BEGIN
      // AUXMODEL = n, ... after the residual's bulk data): a part superelement's cards
      // are a model of their own, with ids of their own, which ssid does not assemble.
      // They are kept verbatim, to the ENDDATA, and the BEGIN line is a statement that
      // `ssid modes` refuses by name.
      if (iequals_prefix(tdata, "BEGIN") && tdata.size() > 5 && (tdata[5] == ' ' || tdata[5] == '\t')) {
        if (section == Section::Bulk) finish_card(fi, emitted, false);
        const std::string u = upper(tdata);
        if (is_partition(u)) {
          deck.statements.push_back({Section::Bulk, u, fi, l.number});
          section = Section::PartBulk;
        } else {
          deck.problems.push_back({Problem::Severity::Warning, deck.location(fi, l.number),
                                   "'" + u + "' inside the bulk data (no SUPER, AUXMODEL, ... partition named): ignored"});
        }
        continue;
      }
      if (section == Section::PartBulk) {
        if (is_enddata(tdata))
          section = Section::AfterEnddata;
        continue;
      }
      if (is_enddata(tdata)) {
        finish_card(fi, emitted, true);
        section = Section::AfterEnddata;
        continue;
      }
      split_line(data, *deck.arena, lf, scratch);
      // A free-field line ended by a comma, with no continuation marker, continued by a
      // line of bare values (pyNastran's contact.bdf, which MSC Nastran ran: "BSURF, 1,
      // 1050, …, 1055," then "1054,1002,…,1131," rows of eight ids). The values are
      // fields 2-9 of the next row; a card name never starts with a digit, so no line
      // read as a card before is read otherwise.
      const bool implicit = pending && pending_file == fi && pending_free_comma && implicit_free_continuation(lf);
      if (!implicit && !lf.first.empty() && lf.first[0] == '=') {
        finish_card(fi, emitted, false);
        replicate(fi, l, emitted, tdata);
        continue;
      }
      if (!implicit && is_continuation(lf, data) && continues_earlier_card(fi, l, emitted)) continue;
      if (implicit || is_continuation(lf, data)) {
        if (!pending || pending_file != fi) {
          deck.problems.push_back({Problem::Severity::Error, deck.location(fi, l.number),
                                   "continuation line with no card before it (field 1 '" + std::string(lf.first) +
                                       "'); kept verbatim"});
          continue;
        }
        add_rows(lf, l.number);
        card.end = l.next;
        note_line_end(lf, data);
        continue;
      }
      finish_card(fi, emitted, false);
      repl_valid = repl_failed = false;
      pending = true;
      pending_file = fi;
      card.file = fi;
      card.line = l.number;
      card.begin = l.begin;
      card.end = l.next;
      card.format = lf.free ? FieldFormat::Free : (lf.large ? FieldFormat::Large : FieldFormat::Small);
      std::string_view name = lf.first;
      if (!name.empty() && name.back() == '*') name = trim(name.substr(0, name.size() - 1));  // "CORD2R *"
      card.name = std::string(name);
      fields.push_back(name);
      add_rows(lf, l.number);
      note_line_end(lf, data);
    }
    if (section == Section::Bulk || section == Section::PartBulk) {
      // The main file of a deck with BEGIN BULK ends inside the bulk data.
      const bool no_enddata = parent < 0 && deck.has_bulk_marker;
      if (no_enddata) check_cut_card(text);
      finish_card(fi, emitted, true);
      if (no_enddata) missing_enddata(fi, text);
    }
    SourceFile& f = deck.files[fi];
    if (emitted < f.text.size())
      f.chunks.push_back({Chunk::Kind::Verbatim, emitted, static_cast<std::uint32_t>(f.text.size()), 0});
    chain.pop_back();
    return fi;
  }

  /// A continuation line `l` (split in `lf`) whose marker answers the field 10 of an
  /// earlier card of this file rather than the card above: the line becomes that
  /// card's next row, and a Detached chunk of it. The card above is finished first,
  /// so the file's chunks stay in order. Small and free field only.
  bool continues_earlier_card(std::uint32_t fi, const Line& l, std::uint32_t& emitted) {
    const std::string_view m = lf.first;
    if (m.size() < 2 || lf.large || (pending && pending_file == fi && m == pending_marker)) return false;
    const std::pair<std::uint32_t, std::string> key{fi, std::string(m)};
    const auto it = open_markers.find(key);
    if (it == open_markers.end()) return false;
    const std::size_t idx = it->second;
    const Card& target = deck.cards[idx];
    // Only cards of full 8-field rows (small or free field, no large-field half rows, no
    // values past a row's field 9): the new row then starts at the next multiple of 8.
    if (target.format == FieldFormat::Large || large_cards.count(idx)) return false;
    for (std::uint32_t r = 0; r < target.m_nrows; ++r)
      if ((target.m_rows[r].second - 1) % 8 != 0) return false;
    const std::size_t row_start = 1 + 8 * static_cast<std::size_t>(target.m_nrows);
    if (target.size() > row_start) return false;
    if (++detached_rows[idx] > kMaxDetachedRows) {
      deck.problems.push_back({Problem::Severity::Error, deck.location(fi, l.number),
                               "continuation line '" + std::string(m) + "': more than " +
                                   std::to_string(kMaxDetachedRows) + " continuation lines matched by marker to " +
                                   target.name + " at line " + std::to_string(target.line) + "; not read"});
      return true;  // kept verbatim, in the chunk of text around it
    }
    finish_card(fi, emitted, false);
    Card& c = deck.cards[idx];
    std::vector<std::string_view> f(c.fields().begin(), c.fields().end());
    f.resize(row_start);  // rows are 8 fields wide; trailing blanks were trimmed
    std::vector<std::pair<std::uint32_t, std::uint32_t>> r(c.m_rows, c.m_rows + c.m_nrows);
    r.emplace_back(l.number, static_cast<std::uint32_t>(f.size()));
    f.insert(f.end(), lf.data.begin(), lf.data.end());
    if (lf.data.size() < 8) f.resize(f.size() + (8 - lf.data.size()));
    while (f.size() > 1 && f.back().empty()) f.pop_back();
    Arena& a = *deck.arena;
    auto* fa = a.make_array<std::string_view>(f.size());
    std::copy(f.begin(), f.end(), fa);
    auto* ra = a.make_array<std::pair<std::uint32_t, std::uint32_t>>(r.size());
    std::copy(r.begin(), r.end(), ra);
    c.m_fields = fa;
    c.m_nfields = static_cast<std::uint32_t>(f.size());
    c.m_rows = ra;
    c.m_nrows = static_cast<std::uint32_t>(r.size());
    SourceFile& sf = deck.files[fi];
    if (l.begin > emitted) sf.chunks.push_back({Chunk::Kind::Verbatim, emitted, l.begin, 0});
    sf.chunks.push_back({Chunk::Kind::Detached, l.begin, l.next, static_cast<std::uint32_t>(idx)});
    emitted = l.next;
    open_markers.erase(key);  // finish_card may have added to the map: no iterator kept
    if (!lf.marker.empty()) open_markers[{fi, std::string(lf.marker)}] = idx;
    return true;
  }

  /// A replication line (`lf`, line `l`): one entry for "=", n for "=(n)", each a card
  /// of its own from the card before it. The first takes the line's text; the others
  /// take none, so the file is written back as read. Errors are problems at the line.
  void replicate(std::uint32_t fi, const Line& l, std::uint32_t& emitted, std::string_view tdata) {
    // An "=n" line is read whole, not in 8-column fields: "=(100000)" is nine characters.
    const bool count_line = lf.first != "=";
    std::string first(lf.first);
    std::string_view rest;
    if (count_line && !lf.free) {
      const std::size_t end = std::min(tdata.find_first_of(" \t"), tdata.size());
      first = upper(tdata.substr(0, end));
      rest = trim(tdata.substr(end));
    }
    auto problem = [&](const std::string& msg) {
      deck.problems.push_back({Problem::Severity::Error, deck.location(fi, l.number),
                               "replication line '" + first + "': " + msg + "; not read"});
      repl_failed = true;
      repl_valid = false;
    };
    if (repl_failed) return problem("the replication line before it was not read");
    if (deck.cards.empty() || deck.cards.back().file != fi)
      return problem("no card before it to replicate");
    const Card& prev = deck.cards.back();
    if (prev.m_nrows > 1 || prev.size() > 9)
      return problem("the card before it, " + prev.name + " " + std::string(prev.field(1)) + " at line " +
                     std::to_string(prev.line) + ", has continuation lines, which ssid does not replicate");
    const bool more = lf.data.size() > 8 || !lf.marker.empty();
    std::size_t count = 1;
    if (first == "=") {
      if (more) return problem("a field 10 or more than nine fields: ssid replicates one-line entries only");
      repl_specs.assign(lf.data.begin(), lf.data.end());
    } else {
      count = replication_count(first);
      if (count == 0)
        return problem("expected =, =n or =(n) with n from 1 to " + std::to_string(kMaxReplicas));
      const bool other = lf.free ? more || std::any_of(lf.data.begin(), lf.data.end(),
                                                       [](std::string_view f) { return !f.empty(); })
                                 : !rest.empty();
      if (other) return problem("an =n line holds nothing else");
      if (!repl_valid) return problem("no \"=\" line before it whose increments it could repeat");
    }
    if (replicas_made + count > kMaxReplicasPerDeck)
      return problem("more than " + std::to_string(kMaxReplicasPerDeck) + " entries made by replication in this deck");
    replicas_made += count;
    std::vector<std::string_view> out;
    std::string why;
    for (std::size_t k = 0; k < count; ++k) {
      const auto root = deck.cards.back().replication_root >= 0 ? deck.cards.back().replication_root
                                                               : static_cast<std::int32_t>(deck.cards.size() - 1);
      if (!replicate_fields(deck.cards.back(), repl_specs, *deck.arena, out, why))
        return problem((count > 1 ? "entry " + std::to_string(k + 1) + " of " + std::to_string(count) + ", " : "") + why);
      deck.cards.back().replication_root = root;
      card = Card{};
      card.name = deck.cards.back().name;
      card.format = deck.cards.back().format;
      card.file = fi;
      card.line = l.number;
      card.begin = k == 0 ? l.begin : l.next;
      card.end = l.next;
      card.replication_root = root;
      fields = out;
      rows.assign(1, {l.number, 1});
      pending = true;
      pending_file = fi;
      pending_marker.clear();
      pending_half = pending_free_comma = false;
      finish_card(fi, emitted, false);
    }
    repl_valid = true;
  }

  /// With no ENDDATA, a card that runs to the end of the file is cut when its last
  /// line has no line ending or is the first half of a large-field row (a card
  /// whose field 10 announces a continuation is reported by finish_card). NASTRAN
  /// stops on the missing ENDDATA (missing_enddata); naming the cut card as well
  /// tells where the file was cut and that the card's values are not all there.
  void check_cut_card(const std::string& text) {
    if (!pending || !pending_marker.empty() || card.end != text.size()) return;
    const bool no_line_end = text.back() != '\n';
    if (!no_line_end && !pending_half) return;
    const std::string label = card.name + (fields.size() > 1 && !fields[1].empty() ? " " + std::string(fields[1]) : "");
    deck.problems.push_back({Problem::Severity::Error, deck.location(card.file, card.line),
                             label + ": card cut by the end of the file: " +
                                 (no_line_end ? std::string("its last line has no line ending")
                                              : std::string("a large-field card with no continuation line")) +
                                 ", and no ENDDATA follows"});
  }

  /// A deck with BEGIN BULK must end its bulk data with ENDDATA. NASTRAN-95 stops
  /// on reaching the end of the input first (mis/xsort.f: USER FATAL MESSAGE 219,
  /// MISSING ENDDATA CARD), and MSC/Autodesk Nastran require it ("BEGIN BULK and
  /// ENDDATA are required even if there are no Bulk Data entries", Autodesk Nastran
  /// Reference Guide, BEGIN BULK, remark 1). A deck cut short ends so: an error,
  /// reported at the last line.
  void missing_enddata(std::uint32_t fi, const std::string& text) {
    const auto lines = static_cast<std::uint32_t>(std::count(text.begin(), text.end(), '\n') +
                                                  (!text.empty() && text.back() != '\n' ? 1 : 0));
    deck.problems.push_back({Problem::Severity::Error, deck.location(fi, lines),
                             "missing ENDDATA: the bulk data" +
                                 (begin_bulk_line ? " begun at line " + std::to_string(begin_bulk_line) + " (BEGIN BULK)"
                                                  : std::string()) +
                                 " runs to the end of the file, as in a deck cut short"});
  }

  void handle_include(std::uint32_t fi, const Line& first, LineCursor& cursor, std::uint32_t& emitted,
                      const std::string& text) {
    // INCLUDE 'path' — the quoted path may continue over several lines.
    std::string_view content(text.data() + first.begin, first.end - first.begin);
    std::string_view rest = trim(content.substr(content.find_first_not_of(" \t") + 7));
    std::string name;
    std::uint32_t end = first.next;
    if (!rest.empty() && (rest[0] == '\'' || rest[0] == '"')) {
      char q = rest[0];
      std::string_view piece = rest.substr(1);
      Line l = first;
      while (true) {
        std::size_t close = piece.find(q);
        if (close != std::string_view::npos) {
          name += std::string(trim(piece.substr(0, close)));
          break;
        }
        name += std::string(trim(piece));
        if (!cursor.next(l))
          fail(fi, first.number, "INCLUDE: unterminated quoted path (no closing " + std::string(1, q) + " before end of file)");
        piece = std::string_view(text.data() + l.begin, l.end - l.begin);
        end = l.next;
      }
    } else {
      name = std::string(trim(strip_comment(rest)));
    }
    if (name.empty()) fail(fi, first.number, "INCLUDE: expected a file name");
    fs::path base = fs::path(deck.files[fi].path).parent_path();
    fs::path p = fs::path(name).is_absolute() ? fs::path(name) : base / name;
    if (first.begin > emitted)
      deck.files[fi].chunks.push_back({Chunk::Kind::Verbatim, emitted, first.begin, 0});
    std::size_t chunk_pos = deck.files[fi].chunks.size();
    deck.files[fi].chunks.push_back({Chunk::Kind::Include, first.begin, end, 0});
    emitted = end;
    std::uint32_t child = read_file(p.lexically_normal().string(), name, static_cast<std::int32_t>(fi), first.number, nullptr);
    deck.files[fi].chunks[chunk_pos].index = child;
  }
};

/// Where the main file starts: executive control if it has CEND before BEGIN BULK,
/// case control if it has only BEGIN BULK, else bulk data only.
Section initial_section(const std::string& text) {
  LineCursor c(text);
  Line l;
  bool cend = false;
  while (c.next(l)) {
    std::string_view t = trim(strip_comment(std::string_view(text.data() + l.begin, l.end - l.begin)));
    if (t.size() < 4 || (t[0] != 'C' && t[0] != 'c' && t[0] != 'B' && t[0] != 'b')) continue;
    std::string u = upper(t);
    if (u == "CEND") cend = true;
    if (u.rfind("BEGIN", 0) == 0 && u.find("BULK") != std::string::npos)
      return cend ? Section::Executive : Section::CaseControl;
  }
  return Section::Bulk;
}

Deck read_impl(std::string text, const std::string& path, const ReadOptions& options) {
  Deck deck;
  Reader r{deck, options};
  r.section = initial_section(text);
  deck.has_bulk_marker = r.section != Section::Bulk;
  deck.cards.reserve(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1);
  r.read_file(path, "", -1, 0, &text);
  return deck;
}

}  // namespace

Deck read_deck(const std::string& path, const ReadOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw ParseError(SourceLocation{path, 0, {}}, "file not found");
  if (fs::is_directory(path, ec)) throw ParseError(SourceLocation{path, 0, {}}, "is a directory, expected a NASTRAN deck");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw ParseError(SourceLocation{path, 0, {}}, "cannot open file for reading");
  std::string text(static_cast<std::size_t>(in.tellg()), '\0');
  in.seekg(0);
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  return read_impl(std::move(text), path, options);
}

Deck read_deck_text(std::string text, const std::string& name, const ReadOptions& options) {
  return read_impl(std::move(text), name, options);
}

}  // namespace ssid::formats
