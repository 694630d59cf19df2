#include "formats/uff_fields.hpp"

#include <algorithm>
#include <optional>

#include "formats/nastran_number.hpp"
#include "formats/text_util.hpp"

namespace ssid::formats::uff::detail {

Line Scanner::next() {
  Line l;
  l.begin = m_pos;
  std::size_t e = m_text.find('\n', m_pos);
  std::size_t stop = e == std::string::npos ? m_text.size() : e;
  l.end = e == std::string::npos ? m_text.size() : e + 1;
  std::size_t t = stop;
  if (t > m_pos && m_text[t - 1] == '\r') --t;
  l.text = std::string_view(m_text).substr(m_pos, t - m_pos);
  l.number = ++m_line;
  m_pos = l.end;
  return l;
}

void Scanner::skip_bytes(std::size_t n) {
  const std::size_t stop = std::min(m_text.size(), m_pos + n);
  for (std::size_t i = m_pos; i < stop; ++i)
    if (m_text[i] == '\n') ++m_line;
  m_pos = stop;
}

bool is_blank(std::string_view line) { return formats::detail::trim(line).empty(); }

bool is_delimiter(std::string_view line) {
  auto t = formats::detail::trim(line);
  if (t != "-1") return false;
  // `-1` must end within columns 1-6 (I6); a "-1" further right is data.
  return line.find('1') < 6;
}

std::string rtrim(std::string_view s) {
  std::size_t e = s.size();
  while (e > 0 && (s[e - 1] == ' ' || s[e - 1] == '\r' || s[e - 1] == '\t')) --e;
  return std::string(s.substr(0, e));
}

std::optional<std::size_t> first_non_text(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto c = static_cast<unsigned char>(line[i]);
    if ((c < 0x20 && c != '\t' && c != '\r' && c != '\f') || c == 0x7f) return i;
  }
  return std::nullopt;
}

void RecordContext::fail(const Line& line, const std::string& message) const {
  throw ParseError(at(line), "dataset " + std::to_string(dataset) + " record " + std::to_string(record) + ": " +
                                 message);
}

void RecordContext::fail_field(const Line& line, int field, const char* name, const std::string& expected,
                               std::string_view got) const {
  throw ParseError(at(line), "dataset " + std::to_string(dataset) + " record " + std::to_string(record) +
                                 " field " + std::to_string(field) + " (" + name + "): expected " + expected +
                                 ", got " + quoted(rtrim(got)));
}

namespace {

std::string_view column_text(std::string_view line, std::size_t col, std::size_t width) {
  if (col >= line.size()) return {};
  return line.substr(col, width);
}

std::optional<double> to_real(std::string_view t) {
  std::string u = formats::detail::upper(formats::detail::trim(t));
  return parse_real(u);
}

std::string columns(std::size_t col, std::size_t width) {
  return "columns " + std::to_string(col + 1) + "-" + std::to_string(col + width);
}

std::string describe(Kind k, int width, std::size_t col) {
  switch (k) {
    case Kind::Integer:
    case Kind::IntegerOrBlank: return "integer (I" + std::to_string(width) + ", " + columns(col, width) + ")";
    default: return "real (E" + std::to_string(width) + ", " + columns(col, width) + ")";
  }
}

/// True when a fixed-column boundary at `col` cuts through a number (both sides
/// non-blank and the right side does not start a new signed value): the writer
/// used other widths, so the fixed reading is wrong even where its pieces parse.
bool cuts_token(std::string_view line, std::size_t col) {
  if (col == 0 || col >= line.size()) return false;
  const char l = line[col - 1], r = line[col];
  if (l == ' ' || r == ' ' || r == '-' || r == '+') return false;
  return true;
}

/// True when non-blank text follows column `col`.
bool text_after(std::string_view line, std::size_t col) {
  return col < line.size() && !formats::detail::trim(line.substr(col)).empty();
}

bool separator(char c) { return c == ' ' || c == '\t' || c == ','; }

/// One blank-separated value of a line: its text and its column span [begin, end).
struct Token {
  std::string_view text;
  std::size_t begin = 0, end = 0;
};

std::vector<Token> tokens(std::string_view s, std::size_t from = 0) {
  std::vector<Token> r;
  std::size_t i = from;
  while (i < s.size()) {
    while (i < s.size() && separator(s[i])) ++i;
    std::size_t b = i;
    while (i < s.size() && !separator(s[i])) ++i;
    if (i > b) r.push_back(Token{s.substr(b, i - b), b, i});
  }
  return r;
}

/// The width w of equal right-justified fields that the values after column
/// `start` sit in (value k ends at column start + (k+1) w), as a writer that
/// widened the fields lays them out (ssid's 1P E25.16); nullopt when they do not.
/// Callers use it only when w is wider than the standard columns.
std::optional<int> uniform_width(std::string_view line, std::size_t start) {
  const auto tok = tokens(line, start);
  if (tok.empty()) return std::nullopt;
  const std::size_t w = tok[0].end - start;
  for (std::size_t k = 0; k < tok.size(); ++k)
    if (tok[k].end != start + (k + 1) * w || tok[k].begin < start + k * w) return std::nullopt;
  return static_cast<int>(w);
}

/// Free-format reading of a numeric record; false when the line does not fit.
bool read_free(std::string_view line, const std::vector<FieldSpec>& specs, std::vector<Value>& out) {
  auto tok = tokens(line);
  std::size_t needed = 0, required = 0;
  for (const auto& f : specs) {
    if (f.kind == Kind::Skip) continue;
    if (f.kind == Kind::Text) return false;
    ++needed;
    if (f.kind == Kind::Integer || f.kind == Kind::Real) required = needed;
  }
  if (tok.size() > needed || tok.size() < required) return false;
  out.assign(specs.size(), Value{});
  std::size_t t = 0;
  for (std::size_t k = 0; k < specs.size() && t < tok.size(); ++k) {
    const auto& f = specs[k];
    if (f.kind == Kind::Skip) continue;
    if (f.kind == Kind::Integer || f.kind == Kind::IntegerOrBlank) {
      auto v = parse_integer(tok[t].text);
      if (!v) return false;
      out[k].i = *v;
    } else {
      auto v = to_real(tok[t].text);
      if (!v) return false;
      out[k].d = *v;
    }
    ++t;
  }
  return true;
}

/// The first field of a fixed-column reading that failed.
struct Failure {
  int field = 0;
  const char* name = nullptr;
  std::string expected;
  std::string got;
};

/// Reads the fields of `line` in the fixed columns of `specs`.
std::optional<Failure> read_fixed(std::string_view line, const std::vector<FieldSpec>& specs, int first_field_number,
                                  std::vector<Value>& out) {
  out.assign(specs.size(), Value{});
  std::size_t col = 0;
  int field = first_field_number;
  std::optional<Failure> failure;
  auto is_numeric = [&](std::size_t j) {
    return j < specs.size() && specs[j].kind != Kind::Text && specs[j].kind != Kind::Skip;
  };
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const auto& f = specs[k];
    std::string_view raw = column_text(line, col, f.width);
    std::string_view t = formats::detail::trim(raw);
    const std::string expected = describe(f.kind, f.width, col);
    switch (f.kind) {
      case Kind::Skip: break;
      case Kind::Text: out[k].s = rtrim(raw); break;
      case Kind::Integer:
      case Kind::IntegerOrBlank: {
        if (t.empty()) {
          // Fortran reads a blank integer field as 0; a required one is still reported.
          if (f.kind == Kind::Integer && !failure) failure = Failure{field, f.name, expected, ""};
          break;
        }
        auto v = parse_integer(t);
        if (v) out[k].i = *v;
        else if (!failure) failure = Failure{field, f.name, expected, std::string(raw)};
        break;
      }
      case Kind::Real:
      case Kind::RealOrBlank: {
        if (t.empty()) {
          if (f.kind == Kind::Real && !failure) failure = Failure{field, f.name, expected, ""};
          break;
        }
        auto v = to_real(t);
        if (v) out[k].d = *v;
        else if (!failure) failure = Failure{field, f.name, expected, std::string(raw)};
        break;
      }
    }
    const bool cut_left = k > 0 && is_numeric(k - 1) && cuts_token(line, col);
    const bool cut_right = (k + 1 == specs.size() || is_numeric(k + 1)) && cuts_token(line, col + f.width);
    if (is_numeric(k) && !failure && (cut_left || cut_right)) failure = Failure{field, f.name, expected, std::string(raw)};
    col += f.width;
    if (f.kind != Kind::Skip) ++field;
  }
  return failure;
}

/// `specs` with the trailing real fields widened to the equal width their values
/// sit in on `line` (a writer's 1P E25.16 for E13.5); nullopt when the record has
/// no trailing reals or the values are not laid out that way.
std::optional<std::vector<FieldSpec>> widened(std::string_view line, const std::vector<FieldSpec>& specs) {
  std::size_t first_real = specs.size(), start = 0;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    if (specs[k].kind == Kind::Real || specs[k].kind == Kind::RealOrBlank) {
      first_real = k;
      break;
    }
    start += static_cast<std::size_t>(specs[k].width);
  }
  if (first_real == specs.size()) return std::nullopt;
  for (std::size_t k = first_real; k < specs.size(); ++k)
    if (specs[k].kind != Kind::Real && specs[k].kind != Kind::RealOrBlank) return std::nullopt;
  const auto w = uniform_width(line, start);
  if (!w || *w <= specs[first_real].width) return std::nullopt;
  auto wide = specs;
  for (std::size_t k = first_real; k < wide.size(); ++k) wide[k].width = *w;
  return wide;
}

}  // namespace

std::vector<Value> read_fields(const RecordContext& ctx, const Line& line, const std::vector<FieldSpec>& specs,
                               int first_field_number) {
  std::vector<Value> out;
  auto failure = read_fixed(line.text, specs, first_field_number, out);
  if (!failure) return out;
  // Free format gets a chance before the first failure is thrown.
  std::vector<Value> free;
  if (read_free(line.text, specs, free)) return free;
  // Values in wider equal columns: read (and reported) in those, not in the
  // standard columns that cut through them.
  if (auto wide = widened(line.text, specs)) {
    auto wide_failure = read_fixed(line.text, *wide, first_field_number, out);
    if (!wide_failure) return out;
    failure = wide_failure;
  }
  ctx.fail_field(line, failure->field, failure->name, failure->expected, failure->got);
}

namespace {

/// How the values of one line of a stream are laid out.
enum class Layout {
  Columns,  ///< fixed columns: the record's own, or the wider ones of its first line
  Uniform,  ///< equal right-justified columns of another width (a writer that widened them)
  Free      ///< blank-separated values in no columns
};

/// The values of one line of a stream, or its first bad field.
struct StreamLine {
  Layout layout = Layout::Free;
  int width = 0;  ///< Uniform: the column width
  std::vector<double> values;
  bool bad = false;
  bool too_many = false;      ///< the line holds more values than the record needs
  std::size_t bad_index = 0;  ///< 0-based position on the line of the bad value
  std::string expected, got;
};

bool holds_separator(std::string_view s) {
  return std::find_if(s.begin(), s.end(), separator) != s.end();
}

/// True when every value on the line is written as a real (with a point or an
/// exponent), as no integer record (a node number) is.
bool reals_only(std::string_view text) {
  for (const Token& t : tokens(text))
    if (t.text.find_first_of(".EeDd") == std::string_view::npos) return false;
  return true;
}

/// True when the line holds one integer and nothing else.
bool lone_integer(std::string_view text) {
  const auto t = tokens(text);
  return t.size() == 1 && parse_integer(t[0].text).has_value();
}

/// Reads the values of one line of a stream that still expects `remaining`
/// values: in the fixed columns `widths` when the line fits them, else in equal
/// columns of another width, else blank-separated.
StreamLine read_stream_line(std::string_view text, const std::vector<int>& widths, std::size_t remaining) {
  StreamLine r;
  const std::size_t k = std::min(remaining, widths.size());
  // Fixed columns, from the left; the line may end early (a short line, judged by the caller).
  std::size_t col = 0;
  bool fits = true;
  for (std::size_t i = 0; i < k; ++i) {
    const auto w = static_cast<std::size_t>(widths[i]);
    std::string_view raw = column_text(text, col, w);
    const std::string_view t = formats::detail::trim(raw);
    if (t.empty() && !text_after(text, col)) break;
    auto v = to_real(raw);
    const bool cut = cuts_token(text, col) || cuts_token(text, col + w);
    if (!v || cut) {
      fits = false;
      // A column holding one whole value that does not parse (or nothing) is
      // reported in these columns; other shapes are tried below.
      if (!cut && !holds_separator(t)) {
        r.bad = true;
        r.bad_index = i;
        r.expected = describe(Kind::Real, widths[i], col);
        r.got = std::string(raw);
      }
      break;
    }
    r.values.push_back(*v);
    col += w;
  }
  if (fits && text_after(text, col)) {
    fits = false;
    if (r.values.size() == remaining) {
      r.bad = r.too_many = true;
      r.bad_index = remaining;
      r.got = std::string(formats::detail::trim(text.substr(col)));
    }
  }
  if ((fits && !r.values.empty()) || r.bad) {
    r.layout = Layout::Columns;
    if (r.bad) r.values.clear();
    return r;
  }
  r.values.clear();
  const auto tok = tokens(text);
  // Aligned values no wider than the standard columns are read as blank-separated.
  const int w = uniform_width(text, 0).value_or(0);
  r.layout = w > widths[0] ? Layout::Uniform : Layout::Free;
  r.width = r.layout == Layout::Uniform ? w : 0;
  const auto uw = static_cast<std::size_t>(r.width);
  if (tok.empty()) {
    r.bad = true;
    r.expected = describe(Kind::Real, widths[0], 0);
    return r;
  }
  for (std::size_t i = 0; i < tok.size(); ++i) {
    if (i == remaining) {
      r.bad = r.too_many = true;
      r.bad_index = i;
      r.got = std::string(formats::detail::trim(text.substr(tok[i].begin)));
      return r;
    }
    auto v = to_real(tok[i].text);
    if (!v) {
      r.bad = true;
      r.bad_index = i;
      r.expected = uw ? describe(Kind::Real, r.width, i * uw) : "real (blank-separated)";
      r.got = std::string(uw ? column_text(text, i * uw, uw) : tok[i].text);
      return r;
    }
    r.values.push_back(*v);
  }
  return r;
}

}  // namespace

std::vector<double> read_real_stream(const RecordContext& ctx, const std::vector<Line>& lines, std::size_t& pos,
                                     std::size_t count, const std::vector<int>& widths, const char* name) {
  std::vector<double> out;  // not reserved from `count`: it comes from the file and may be absurd
  const auto value_of = [&](std::size_t i) {
    return ", value " + std::to_string(i) + " of " + std::to_string(count);
  };
  // The layout of the record's first line holds for the rest of the record: a
  // writer lays out one record one way. Columns (the record's own, or the equal
  // wider ones of its first line) then fill every line but the last, so a line
  // that ends early is missing a value there. Blank-separated values may stop
  // at any line end, but then only more reals may continue them — not a line in
  // columns holding an integer — and the line where they stopped is blamed
  // otherwise. No record of reals is continued by a lone integer (the next
  // record's node number): the record's last line is blamed then too.
  std::vector<int> line_widths = widths;
  std::optional<Layout> record;
  const Line* stopped = nullptr;  // blank-separated values of this record stopped at the end of this line
  const Line* last = nullptr;     // the record's last line read
  auto fail_stopped = [&](const std::string& why) {
    ctx.fail(*stopped, std::to_string(out.size()) + " of the " + std::to_string(count) + " values (" + name +
                           ") by the end of this line; " + why);
  };
  while (out.size() < count) {
    if (pos >= lines.size()) {
      if (stopped) fail_stopped("the dataset ends after it");
      Line end;
      end.number = ctx.end_line;
      ctx.fail(end, std::string("dataset ended after ") + std::to_string(out.size()) + " of " +
                        std::to_string(count) + " values (" + name + ")");
    }
    const Line& l = lines[pos];
    const std::size_t remaining = count - out.size();
    StreamLine r = read_stream_line(l.text, line_widths, remaining);
    // A lone integer (the next record's node number, say) never continues a record of reals.
    if ((stopped && (r.bad || (r.layout == Layout::Columns && !reals_only(l.text)))) || (last && lone_integer(l.text))) {
      stopped = last;
      fail_stopped("line " + std::to_string(l.number) + " (" + quoted(rtrim(l.text)) + ") does not continue them");
    }
    if (record == Layout::Columns && r.layout != Layout::Columns && !r.bad) {
      // The record's columns, continued in another layout: reported in the record's columns.
      r.bad = true;
      r.bad_index = 0;
      r.expected = describe(Kind::Real, line_widths[0], 0);
      r.got = std::string(column_text(l.text, 0, static_cast<std::size_t>(line_widths[0])));
    }
    ++pos;
    const std::size_t first = out.size() + 1;
    if (r.bad) {
      const int field = static_cast<int>(r.bad_index) + 1;
      if (r.too_many)
        ctx.fail_field(l, field, name,
                       "the end of the line: the record needs " + std::to_string(remaining) + " more value(s)", r.got);
      ctx.fail_field(l, field, name, r.expected + value_of(first + r.bad_index), r.got);
    }
    if (!record) {
      record = r.layout;
      if (r.layout == Layout::Uniform) {
        // The equal columns of the first line: the rest of the record is read in them.
        record = Layout::Columns;
        const std::size_t per_line = std::max<std::size_t>(80 / static_cast<std::size_t>(r.width), r.values.size());
        line_widths.assign(std::max<std::size_t>(1, per_line), r.width);
        r.layout = Layout::Columns;
      }
    }
    if (record == Layout::Columns) {
      const std::size_t full = std::min(remaining, line_widths.size());
      if (r.values.size() < full) {
        // The line ends before its last column: a value is missing here.
        const std::size_t i = r.values.size();
        std::size_t col = 0;
        for (std::size_t j = 0; j < i; ++j) col += static_cast<std::size_t>(line_widths[j]);
        ctx.fail_field(l, static_cast<int>(i) + 1, name, describe(Kind::Real, line_widths[i], col) + value_of(first + i),
                       "");
      }
    }
    stopped = record != Layout::Columns && r.values.size() < remaining ? &l : nullptr;
    last = &l;
    out.insert(out.end(), r.values.begin(), r.values.end());
  }
  return out;
}

std::vector<std::int64_t> read_integer_stream(const RecordContext& ctx, const std::vector<Line>& lines,
                                              std::size_t& pos, std::size_t count, int per_line, int width,
                                              const char* name) {
  std::vector<std::int64_t> out;
  while (out.size() < count) {
    if (pos >= lines.size()) {
      Line end;
      end.number = ctx.end_line;
      ctx.fail(end, std::string("dataset ended after ") + std::to_string(out.size()) + " of " +
                        std::to_string(count) + " integers (" + name + ")");
    }
    const Line& l = lines[pos++];
    const std::size_t k = std::min<std::size_t>(count - out.size(), per_line);
    std::vector<FieldSpec> specs(k, FieldSpec{width, Kind::IntegerOrBlank, name});
    auto v = read_fields(ctx, l, specs);
    for (const auto& x : v) out.push_back(x.i);
  }
  return out;
}

}  // namespace ssid::formats::uff::detail
