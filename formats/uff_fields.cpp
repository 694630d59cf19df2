#include "formats/uff_fields.hpp"

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

void RecordContext::fail(const Line& line, const std::string& message) const {
  throw ParseError(at(line), "dataset " + std::to_string(dataset) + " record " + std::to_string(record) + ": " +
                                 message);
}

void RecordContext::fail_field(const Line& line, int field, const char* name, const std::string& expected,
                               std::string_view got) const {
  throw ParseError(at(line), "dataset " + std::to_string(dataset) + " record " + std::to_string(record) +
                                 " field " + std::to_string(field) + " (" + name + "): expected " + expected +
                                 ", got \"" + rtrim(got) + "\"");
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

std::string describe(Kind k, int width, std::size_t col) {
  std::string cols = "columns " + std::to_string(col + 1) + "-" + std::to_string(col + width);
  switch (k) {
    case Kind::Integer:
    case Kind::IntegerOrBlank: return "integer (I" + std::to_string(width) + ", " + cols + ")";
    default: return "real (E" + std::to_string(width) + ", " + cols + ")";
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

std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> r;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t' || s[i] == ',')) ++i;
    std::size_t b = i;
    while (i < s.size() && s[i] != ' ' && s[i] != '\t' && s[i] != ',') ++i;
    if (i > b) r.push_back(s.substr(b, i - b));
  }
  return r;
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
      auto v = parse_integer(tok[t]);
      if (!v) return false;
      out[k].i = *v;
    } else {
      auto v = to_real(tok[t]);
      if (!v) return false;
      out[k].d = *v;
    }
    ++t;
  }
  return true;
}

}  // namespace

std::vector<Value> read_fields(const RecordContext& ctx, const Line& line, const std::vector<FieldSpec>& specs,
                               int first_field_number) {
  std::vector<Value> out(specs.size());
  std::size_t col = 0;
  int field = first_field_number;
  // The first failure is remembered; free format gets a chance before it is thrown.
  struct Failure {
    int field = 0;
    const char* name = nullptr;
    std::string expected;
    std::string got;
  };
  std::optional<Failure> failure;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const auto& f = specs[k];
    std::string_view raw = column_text(line.text, col, f.width);
    std::string_view t = formats::detail::trim(raw);
    switch (f.kind) {
      case Kind::Skip: break;
      case Kind::Text: out[k].s = rtrim(raw); break;
      case Kind::Integer:
      case Kind::IntegerOrBlank: {
        if (t.empty()) {
          // Fortran reads a blank integer field as 0; a required one is still reported.
          if (f.kind == Kind::Integer && !failure) failure = Failure{field, f.name, describe(f.kind, f.width, col), ""};
          break;
        }
        auto v = parse_integer(t);
        if (v) out[k].i = *v;
        else if (!failure) failure = Failure{field, f.name, describe(f.kind, f.width, col), std::string(raw)};
        break;
      }
      case Kind::Real:
      case Kind::RealOrBlank: {
        if (t.empty()) {
          if (f.kind == Kind::Real && !failure) failure = Failure{field, f.name, describe(f.kind, f.width, col), ""};
          break;
        }
        auto v = to_real(t);
        if (v) out[k].d = *v;
        else if (!failure) failure = Failure{field, f.name, describe(f.kind, f.width, col), std::string(raw)};
        break;
      }
    }
    auto is_numeric = [&](std::size_t j) {
      return j < specs.size() && specs[j].kind != Kind::Text && specs[j].kind != Kind::Skip;
    };
    const bool cut_left = k > 0 && is_numeric(k - 1) && cuts_token(line.text, col);
    const bool cut_right = (k + 1 == specs.size() || is_numeric(k + 1)) && cuts_token(line.text, col + f.width);
    if (is_numeric(k) && !failure && (cut_left || cut_right))
      failure = Failure{field, f.name, describe(f.kind, f.width, col), std::string(raw)};
    col += f.width;
    if (f.kind != Kind::Skip) ++field;
  }
  if (!failure) return out;
  std::vector<Value> free;
  if (read_free(line.text, specs, free)) return free;
  ctx.fail_field(line, failure->field, failure->name, failure->expected, failure->got);
}

std::vector<double> read_real_stream(const RecordContext& ctx, const std::vector<Line>& lines, std::size_t& pos,
                                     std::size_t count, const std::vector<int>& widths, const char* name) {
  std::vector<double> out;
  out.reserve(count);
  while (out.size() < count) {
    if (pos >= lines.size()) {
      Line end;
      end.number = ctx.end_line;
      ctx.fail(end, std::string("dataset ended after ") + std::to_string(out.size()) + " of " +
                        std::to_string(count) + " values (" + name + ")");
    }
    const Line& l = lines[pos++];
    const std::size_t remaining = count - out.size();
    const std::size_t k = std::min(remaining, widths.size());
    std::size_t col = 0;
    bool ok = true;
    std::size_t bad = 0;
    std::size_t bad_col = 0;
    std::vector<double> vals;
    for (std::size_t i = 0; i < k; ++i) {
      auto v = to_real(column_text(l.text, col, widths[i]));
      if (!v) {
        ok = false;
        bad = i;
        bad_col = col;
        break;
      }
      if (cuts_token(l.text, col) || cuts_token(l.text, col + widths[i])) {
        ok = false;
        bad = i;
        bad_col = col;
        break;
      }
      vals.push_back(*v);
      col += widths[i];
    }
    if (ok && text_after(l.text, col)) {
      ok = false;
      bad = k - 1;
      bad_col = col - widths[k - 1];
    }
    if (ok) {
      out.insert(out.end(), vals.begin(), vals.end());
      continue;
    }
    // Free format: any number of values up to what is still expected.
    auto tok = tokens(l.text);
    bool free_ok = !tok.empty() && tok.size() <= remaining;
    vals.clear();
    for (auto t : tok) {
      auto v = free_ok ? to_real(t) : std::nullopt;
      if (!v) {
        free_ok = false;
        break;
      }
      vals.push_back(*v);
    }
    if (free_ok) {
      out.insert(out.end(), vals.begin(), vals.end());
      continue;
    }
    const std::string expected = describe(Kind::Real, widths[bad], bad_col) + ", value " +
                                 std::to_string(out.size() + bad + 1) + " of " + std::to_string(count);
    ctx.fail_field(l, static_cast<int>(bad) + 1, name, expected, column_text(l.text, bad_col, widths[bad]));
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
