/// \file dmig.cpp
/// DMIG entries: parse, complete (polar, symmetric), write.
#include "formats/dmig.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "formats/deck_writer.hpp"

namespace ssid::formats {

std::size_t Dmig::terms() const {
  std::size_t n = 0;
  for (const DmigColumn& c : columns) n += c.terms.size();
  return n;
}

std::complex<double> dmig_value(const Dmig& m, const DmigTerm& t) {
  if (!m.is_complex()) return {t.a, 0.0};
  if (!m.polar) return {t.a, t.b};
  // Exact quadrants so that 0, 90, 180, 270 degrees give exact real/imaginary parts.
  const double deg = std::fmod(t.b, 360.0);
  const double d = deg < 0 ? deg + 360.0 : deg;
  if (d == 0.0) return {t.a, 0.0};
  if (d == 90.0) return {0.0, t.a};
  if (d == 180.0) return {-t.a, 0.0};
  if (d == 270.0) return {0.0, -t.a};
  const double rad = t.b * (M_PI / 180.0);
  return {t.a * std::cos(rad), t.a * std::sin(rad)};
}

namespace {

int component(const FieldReader& r, std::size_t i, const char* name) {
  const std::int64_t c = r.integer_or(i, name, 0);
  if (c < 0 || c > 6) r.fail(i, name, "a component 1-6 (0 or blank for a scalar point)");
  return static_cast<int>(c);
}

}  // namespace

Dmig parse_dmig_header(const FieldReader& r) {
  Dmig m;
  m.name = r.text(1, "NAME");
  if (m.name.size() > 8) r.fail(1, "NAME", "a name of at most 8 characters");
  if (r.integer(2, "\"0\"") != 0) r.fail(2, "\"0\"", "0 (header entry)");
  const std::int64_t ifo = r.integer(3, "IFO");
  if (ifo != 1 && ifo != 2 && ifo != 6 && ifo != 9) r.fail(3, "IFO", "a form 1 (square), 2 or 9 (rectangular), 6 (symmetric)");
  m.ifo = static_cast<int>(ifo);
  const std::int64_t tin = r.integer(4, "TIN");
  if (tin < 1 || tin > 4) r.fail(4, "TIN", "a precision 1-4 (real single, real double, complex single, complex double)");
  m.tin = static_cast<int>(tin);
  const std::int64_t tout = r.integer_or(5, "TOUT", 0);
  if (tout < 0 || tout > 4) r.fail(5, "TOUT", "a precision 0-4 (0 or blank: by the PRECISION cell)");
  m.tout = static_cast<int>(tout);
  const std::int64_t polar = r.integer_or(6, "POLAR", 0);
  if (polar != 0 && polar != 1) r.fail(6, "POLAR", "0 (real, imaginary) or 1 (magnitude, phase)");
  if (polar == 1 && !m.is_complex()) r.fail(6, "POLAR", "0 or blank for a real matrix (TIN 1 or 2)");
  m.polar = polar == 1;
  if (!r.blank(7)) r.fail(7, "(blank)", "blank");
  if (m.ifo == dmig_form::RectangularByColumnNumber) {
    m.ncol = r.id(8, "NCOL");
  } else {
    const auto n = r.integer_or_blank(8, "NCOL");
    if (n && *n < 0) r.fail(8, "NCOL", "a non-negative number of columns");
    m.ncol = n ? *n : 0;
  }
  r.at_most(9);
  return m;
}

DmigColumn parse_dmig_column(const FieldReader& r, const Dmig& m) {
  DmigColumn c;
  c.col.point = r.id(2, "GJ");
  c.col.component = component(r, 3, "CJ");
  if (m.ifo == dmig_form::RectangularByColumnNumber) {
    if (c.col.component != 0) r.fail(3, "CJ", "0 or blank (IFO = 9: GJ is the column number)");
    if (c.col.point > m.ncol)
      r.fail(2, "GJ", "a column number 1.." + std::to_string(m.ncol) + " (NCOL of the header)");
  }
  if (!r.blank(4)) r.fail(4, "(blank)", "blank");
  // Terms of four fields from field index 5: G, C, A, B.
  for (std::size_t i = 5; i < r.size(); i += 4) {
    if (r.blank(i) && r.blank(i + 1) && r.blank(i + 2) && r.blank(i + 3)) continue;
    DmigTerm t;
    t.row.point = r.id(i, "Gi");
    t.row.component = component(r, i + 1, "Ci");
    t.a = r.real(i + 2, m.polar ? "Ai (magnitude)" : "Ai");
    if (m.is_complex()) {
      t.b = r.real_or(i + 3, m.polar ? "Bi (phase, degrees)" : "Bi", 0.0);
    } else if (!r.blank(i + 3) && r.real(i + 3, "Bi") != 0.0) {
      r.fail(i + 3, "Bi", "blank (the matrix is real: TIN = " + std::to_string(m.tin) + ")");
    }
    c.terms.push_back(t);
  }
  return c;
}

std::vector<DmigEntry> expand_dmig(const Dmig& m, const Deck* deck) {
  std::vector<DmigEntry> out;
  out.reserve(m.terms() * (m.ifo == dmig_form::Symmetric ? 2 : 1));
  // Position -> column index in m.columns (for the error location).
  std::map<std::pair<DmigKey, DmigKey>, std::size_t> seen;  // (col, row)
  auto duplicate = [&](std::size_t ci, const DmigKey& row, const DmigKey& col, std::size_t first, bool mirrored) {
    const std::string msg = "DMIG " + m.name + ": term at row (" + std::to_string(row.point) + "," +
                            std::to_string(row.component) + ") column (" + std::to_string(col.point) + "," +
                            std::to_string(col.component) + ") given twice" +
                            (mirrored ? " (both above and below the diagonal of a symmetric matrix)" : "");
    if (deck && ci < m.columns.size()) {
      const SourceLocation first_at = deck->location(deck->cards[m.columns[first].card]);
      throw ParseError(deck->location(deck->cards[m.columns[ci].card]), msg + "; first at " + first_at.str());
    }
    throw ParseError(SourceLocation{"DMIG " + m.name, 0, {}}, msg.substr(6 + m.name.size() + 2));
  };
  for (std::size_t ci = 0; ci < m.columns.size(); ++ci) {
    const DmigColumn& c = m.columns[ci];
    for (const DmigTerm& t : c.terms) {
      auto ins = seen.emplace(std::make_pair(c.col, t.row), ci);
      if (!ins.second) duplicate(ci, t.row, c.col, ins.first->second, false);
      if (m.ifo == dmig_form::Symmetric && t.row != c.col) {
        auto mir = seen.find(std::make_pair(t.row, c.col));
        if (mir != seen.end()) duplicate(ci, t.row, c.col, mir->second, true);
      }
      out.push_back({t.row, c.col, dmig_value(m, t), ci});
    }
  }
  if (m.ifo == dmig_form::Symmetric) {
    const std::size_t n = out.size();
    for (std::size_t k = 0; k < n; ++k)
      if (out[k].row != out[k].col) out.push_back({out[k].col, out[k].row, out[k].value, out[k].source});
  }
  std::sort(out.begin(), out.end(), [](const DmigEntry& x, const DmigEntry& y) {
    return x.col != y.col ? x.col < y.col : x.row < y.row;
  });
  return out;
}

std::vector<Dmig> read_dmigs(const Deck& deck) {
  std::vector<Dmig> out;
  std::map<std::string, std::size_t> by_name;
  // Headers first (column entries may precede them in the deck).
  for (std::size_t k = 0; k < deck.cards.size(); ++k) {
    const Card& card = deck.cards[k];
    if (card.name != "DMIG" || card.field(2) != "0") continue;
    FieldReader r(deck, card);
    Dmig m = parse_dmig_header(r);
    m.card = k;
    auto ins = by_name.emplace(m.name, out.size());
    if (!ins.second)
      r.fail_card("second header for matrix " + m.name + " (first at " +
                  deck.location(deck.cards[out[ins.first->second].card]).str() + ")");
    out.push_back(std::move(m));
  }
  for (std::size_t k = 0; k < deck.cards.size(); ++k) {
    const Card& card = deck.cards[k];
    if (card.name != "DMIG" || card.field(2) == "0") continue;
    FieldReader r(deck, card);
    const std::string name = r.text(1, "NAME");
    auto it = by_name.find(name);
    if (it == by_name.end())
      r.fail_card("column entry of matrix " + name + " which has no header entry (DMIG " + name + " 0 IFO TIN ...)");
    Dmig& m = out[it->second];
    DmigColumn c = parse_dmig_column(r, m);
    c.card = k;
    m.columns.push_back(std::move(c));
  }
  return out;
}

std::vector<Dmig> read_dmig_file(const std::string& path) { return read_dmigs(read_deck(path)); }

std::vector<FieldValue> write_dmig_header(const Dmig& m) {
  std::vector<FieldValue> v = {std::string("DMIG"), m.name, std::int64_t{0}, std::int64_t{m.ifo}, std::int64_t{m.tin}};
  v.push_back(m.tout ? FieldValue(std::int64_t{m.tout}) : FieldValue());
  v.push_back(m.polar ? FieldValue(std::int64_t{1}) : FieldValue());
  v.emplace_back();
  if (m.ncol > 0) v.emplace_back(m.ncol);
  while (std::holds_alternative<std::monostate>(v.back())) v.pop_back();
  return v;
}

std::vector<FieldValue> write_dmig_column(const Dmig& m, const DmigColumn& c) {
  std::vector<FieldValue> v = {std::string("DMIG"), m.name, c.col.point};
  v.push_back(c.col.component ? FieldValue(std::int64_t{c.col.component}) : FieldValue());
  v.emplace_back();
  for (const DmigTerm& t : c.terms) {
    v.emplace_back(t.row.point);
    v.push_back(t.row.component ? FieldValue(std::int64_t{t.row.component}) : FieldValue());
    v.emplace_back(t.a);
    v.push_back(m.is_complex() ? FieldValue(t.b) : FieldValue());
  }
  while (std::holds_alternative<std::monostate>(v.back())) v.pop_back();
  return v;
}

std::string format_dmig(const Dmig& m, FieldFormat format) {
  std::string s = format_card("DMIG", write_dmig_header(m), format);
  for (const DmigColumn& c : m.columns) s += format_card("DMIG", write_dmig_column(m, c), format);
  return s;
}

}  // namespace ssid::formats
