/// \file uff_reader.cpp
/// Universal-file reader: frames datasets between delimiters, then parses the
/// known ones record by record (layouts in uff.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "formats/nastran_number.hpp"
#include "formats/text_util.hpp"
#include "formats/uff.hpp"
#include "formats/uff_fields.hpp"

namespace ssid::formats::uff {

using detail::FieldSpec;
using detail::Kind;
using detail::Line;
using detail::RecordContext;

namespace {

/// The lines of one dataset between its number line and the closing delimiter.
struct Block {
  int number = 0;
  Line header;
  std::vector<Line> body;
  Line closing;
  std::size_t body_begin = 0, body_end = 0;  ///< byte range of the body
};

class DatasetParser {
public:
  DatasetParser(const std::string& file, const Block& b) : m_file(file), m_b(b) {
    m_ctx.file = &m_file;
    m_ctx.dataset = b.number;
    m_ctx.end_line = b.closing.number;
  }

  /// Next line as record `record`; "ended early" when the body is exhausted.
  const Line& next(int record, const char* what) {
    m_ctx.record = record;
    if (m_pos >= m_b.body.size())
      m_ctx.fail(m_b.closing, std::string("dataset ended before this record (") + what + ")");
    return m_b.body[m_pos++];
  }
  RecordContext& ctx(int record) {
    m_ctx.record = record;
    return m_ctx;
  }
  bool done() const { return m_pos >= m_b.body.size(); }
  /// Skips trailing blank lines; anything else left over is an error.
  void finish(int record) {
    while (m_pos < m_b.body.size() && detail::is_blank(m_b.body[m_pos].text)) ++m_pos;
    if (m_pos < m_b.body.size())
      ctx(record).fail(m_b.body[m_pos],
                       "unexpected line " + detail::quoted(detail::rtrim(m_b.body[m_pos].text)) + " after the last record");
  }
  std::size_t& pos() { return m_pos; }
  /// Characters on the lines not read yet.
  std::uint64_t characters_left() const {
    std::uint64_t n = 0;
    for (std::size_t k = m_pos; k < m_b.body.size(); ++k) n += m_b.body[k].text.size();
    return n;
  }
  const std::vector<Line>& lines() const { return m_b.body; }
  SourceLocation where() const { return SourceLocation{m_file, m_b.header.number, {}}; }

private:
  const std::string& m_file;
  const Block& m_b;
  RecordContext m_ctx;
  std::size_t m_pos = 0;
};

Header151 parse_151(DatasetParser& p) {
  Header151 h;
  h.where = p.where();
  while (!p.done()) h.lines.push_back(detail::rtrim(p.next(1, "header").text));
  return h;
}

Units164 parse_164(DatasetParser& p) {
  Units164 u;
  u.where = p.where();
  auto r1 = detail::read_fields(p.ctx(1), p.next(1, "units code"),
                                {{10, Kind::Integer, "units code"},
                                 {20, Kind::Text, "units description"},
                                 {10, Kind::IntegerOrBlank, "temperature mode"}});
  u.code = static_cast<int>(r1[0].i);
  u.description = std::string(formats::detail::trim(r1[1].s));
  u.temperature_mode = static_cast<int>(r1[2].i);
  auto f = detail::read_real_stream(p.ctx(2), p.lines(), p.pos(), 3, {25, 25, 25},
                                    "length, force and temperature factors");
  u.length = f[0];
  u.force = f[1];
  u.temperature = f[2];
  u.temperature_offset = detail::read_real_stream(p.ctx(3), p.lines(), p.pos(), 1, {25}, "temperature offset")[0];
  p.finish(3);
  return u;
}

NodeSet parse_15(DatasetParser& p) {
  NodeSet s;
  s.dataset = 15;
  s.where = p.where();
  while (!p.done()) {
    const Line& l = p.next(1, "node");
    if (detail::is_blank(l.text)) continue;
    auto v = detail::read_fields(p.ctx(1), l,
                                 {{10, Kind::Integer, "node label"},
                                  {10, Kind::IntegerOrBlank, "definition coordinate system"},
                                  {10, Kind::IntegerOrBlank, "displacement coordinate system"},
                                  {10, Kind::IntegerOrBlank, "color"},
                                  {13, Kind::Real, "X"},
                                  {13, Kind::Real, "Y"},
                                  {13, Kind::Real, "Z"}});
    Node n;
    n.id = v[0].i;
    n.definition_cs = static_cast<int>(v[1].i);
    n.displacement_cs = static_cast<int>(v[2].i);
    n.color = static_cast<int>(v[3].i);
    n.xyz = {v[4].d, v[5].d, v[6].d};
    s.nodes.push_back(n);
  }
  return s;
}

NodeSet parse_2411(DatasetParser& p) {
  NodeSet s;
  s.dataset = 2411;
  s.where = p.where();
  while (!p.done()) {
    const Line& l = p.next(1, "node label");
    if (detail::is_blank(l.text)) continue;
    auto v = detail::read_fields(p.ctx(1), l,
                                 {{10, Kind::Integer, "node label"},
                                  {10, Kind::IntegerOrBlank, "export coordinate system"},
                                  {10, Kind::IntegerOrBlank, "displacement coordinate system"},
                                  {10, Kind::IntegerOrBlank, "color"}});
    Node n;
    n.id = v[0].i;
    n.definition_cs = static_cast<int>(v[1].i);
    n.displacement_cs = static_cast<int>(v[2].i);
    n.color = static_cast<int>(v[3].i);
    auto x = detail::read_real_stream(p.ctx(2), p.lines(), p.pos(), 3, {25, 25, 25}, "node coordinates");
    n.xyz = {x[0], x[1], x[2]};
    s.nodes.push_back(n);
  }
  return s;
}

NodalData55 parse_55(DatasetParser& p) {
  NodalData55 d;
  d.where = p.where();
  for (int r = 0; r < 5; ++r) d.id_lines[r] = detail::rtrim(p.next(r + 1, "ID line").text);
  const Line& l6 = p.next(6, "data description");
  auto r6 = detail::read_fields(p.ctx(6), l6,
                                {{10, Kind::IntegerOrBlank, "model type"},
                                 {10, Kind::Integer, "analysis type"},
                                 {10, Kind::IntegerOrBlank, "data characteristic"},
                                 {10, Kind::IntegerOrBlank, "specific data type"},
                                 {10, Kind::Integer, "data type"},
                                 {10, Kind::Integer, "values per node"}});
  d.model_type = static_cast<int>(r6[0].i);
  d.analysis_type = static_cast<int>(r6[1].i);
  d.data_characteristic = static_cast<int>(r6[2].i);
  d.specific_data_type = static_cast<int>(r6[3].i);
  d.data_type = static_cast<int>(r6[4].i);
  d.values_per_node = static_cast<int>(r6[5].i);
  if (d.data_type != 2 && d.data_type != 4 && d.data_type != 5 && d.data_type != 6)
    p.ctx(6).fail_field(l6, 5, "data type", "2 (real) or 5 (complex)", std::to_string(d.data_type));
  if (d.values_per_node < 1 || d.values_per_node > 9)
    p.ctx(6).fail_field(l6, 6, "values per node", "1 to 9 (3: translations, 6: with rotations)",
                        std::to_string(d.values_per_node));

  // R7 (8I10): NINT, NREAL, then the type-specific integers, continued 8 per line.
  const Line& l7 = p.next(7, "number of integer and real parameters");
  std::vector<FieldSpec> s7{{10, Kind::Integer, "number of integer values"},
                            {10, Kind::Integer, "number of real values"}};
  for (int k = 0; k < 6; ++k) s7.push_back({10, Kind::IntegerOrBlank, "type-specific integer"});
  auto r7 = detail::read_fields(p.ctx(7), l7, s7);
  const auto nint = r7[0].i, nreal = r7[1].i;
  if (nint < 0 || nint > 100) p.ctx(7).fail_field(l7, 1, "number of integer values", "0 to 100", std::to_string(nint));
  if (nreal < 0 || nreal > 100) p.ctx(7).fail_field(l7, 2, "number of real values", "0 to 100", std::to_string(nreal));
  for (std::int64_t k = 0; k < std::min<std::int64_t>(nint, 6); ++k) d.int_params.push_back(r7[2 + k].i);
  if (nint > 6) {
    auto more = detail::read_integer_stream(p.ctx(7), p.lines(), p.pos(), static_cast<std::size_t>(nint - 6), 8, 10,
                                            "type-specific integer");
    d.int_params.insert(d.int_params.end(), more.begin(), more.end());
  }
  d.real_params = detail::read_real_stream(p.ctx(8), p.lines(), p.pos(), static_cast<std::size_t>(nreal),
                                           std::vector<int>(6, 13), "type-specific real");
  if (d.is_normal_mode() && d.int_params.size() < 2)
    p.ctx(7).fail_field(l7, 1, "number of integer values", "2 for a normal mode (load case, mode number)",
                        std::to_string(nint));
  if (d.is_normal_mode() && d.real_params.empty())
    p.ctx(7).fail_field(l7, 2, "number of real values", "at least 1 for a normal mode (frequency)",
                        std::to_string(nreal));

  const int ndv = d.values_per_node;
  const std::size_t per_node = static_cast<std::size_t>(d.is_complex() ? 2 * ndv : ndv);
  std::vector<double> flat;
  while (!p.done()) {
    const Line& l9 = p.next(9, "node number");
    if (detail::is_blank(l9.text)) continue;
    auto n = detail::read_fields(p.ctx(9), l9, {{10, Kind::Integer, "node number"}});
    d.nodes.push_back(n[0].i);
    auto v = detail::read_real_stream(p.ctx(10), p.lines(), p.pos(), per_node, std::vector<int>(6, 13),
                                      "data at node");
    flat.insert(flat.end(), v.begin(), v.end());
  }
  const auto nn = static_cast<Eigen::Index>(d.nodes.size());
  if (d.is_complex()) {
    d.complex_values.resize(nn, ndv);
    for (Eigen::Index i = 0; i < nn; ++i)
      for (int c = 0; c < ndv; ++c)
        d.complex_values(i, c) = {flat[i * per_node + 2 * c], flat[i * per_node + 2 * c + 1]};
  } else {
    d.values.resize(nn, ndv);
    for (Eigen::Index i = 0; i < nn; ++i)
      for (int c = 0; c < ndv; ++c) d.values(i, c) = flat[i * per_node + c];
  }
  return d;
}

Axis58 parse_axis(DatasetParser& p, int record, const char* what) {
  auto v = detail::read_fields(p.ctx(record), p.next(record, what),
                               {{10, Kind::IntegerOrBlank, "specific data type"},
                                {5, Kind::IntegerOrBlank, "length units exponent"},
                                {5, Kind::IntegerOrBlank, "force units exponent"},
                                {5, Kind::IntegerOrBlank, "temperature units exponent"},
                                {1, Kind::Skip, ""},
                                {20, Kind::Text, "axis label"},
                                {1, Kind::Skip, ""},
                                {20, Kind::Text, "axis units label"}});
  Axis58 a;
  a.specific_data_type = static_cast<int>(v[0].i);
  a.length_exponent = static_cast<int>(v[1].i);
  a.force_exponent = static_cast<int>(v[2].i);
  a.temperature_exponent = static_cast<int>(v[3].i);
  a.label = std::string(formats::detail::trim(v[5].s));
  a.units = std::string(formats::detail::trim(v[7].s));
  return a;
}

Function58 parse_58(DatasetParser& p) {
  Function58 f;
  f.where = p.where();
  for (int r = 0; r < 5; ++r) f.id_lines[r] = detail::rtrim(p.next(r + 1, "ID line").text);
  auto r6 = detail::read_fields(p.ctx(6), p.next(6, "DOF identification"),
                                {{5, Kind::Integer, "function type"},
                                 {10, Kind::IntegerOrBlank, "function identification number"},
                                 {5, Kind::IntegerOrBlank, "version number"},
                                 {10, Kind::IntegerOrBlank, "load case identification number"},
                                 {1, Kind::Skip, ""},
                                 {10, Kind::Text, "response entity name"},
                                 {10, Kind::Integer, "response node"},
                                 {4, Kind::IntegerOrBlank, "response direction"},
                                 {1, Kind::Skip, ""},
                                 {10, Kind::Text, "reference entity name"},
                                 {10, Kind::IntegerOrBlank, "reference node"},
                                 {4, Kind::IntegerOrBlank, "reference direction"}});
  f.function_type = static_cast<int>(r6[0].i);
  f.function_id = r6[1].i;
  f.version = static_cast<int>(r6[2].i);
  f.load_case = r6[3].i;
  f.response_entity = std::string(formats::detail::trim(r6[5].s));
  f.response_node = r6[6].i;
  f.response_direction = static_cast<int>(r6[7].i);
  f.reference_entity = std::string(formats::detail::trim(r6[9].s));
  f.reference_node = r6[10].i;
  f.reference_direction = static_cast<int>(r6[11].i);

  const Line& l7 = p.next(7, "data form");
  auto r7 = detail::read_fields(p.ctx(7), l7,
                                {{10, Kind::Integer, "ordinate data type"},
                                 {10, Kind::Integer, "number of data values"},
                                 {10, Kind::Integer, "abscissa spacing"},
                                 {13, Kind::RealOrBlank, "abscissa minimum"},
                                 {13, Kind::RealOrBlank, "abscissa increment"},
                                 {13, Kind::RealOrBlank, "z-axis value"}});
  f.ordinate_type = static_cast<int>(r7[0].i);
  const std::int64_t n = r7[1].i;
  f.even = r7[2].i == 1;
  f.abscissa_min = r7[3].d;
  f.abscissa_increment = r7[4].d;
  f.z_value = r7[5].d;
  if (f.ordinate_type != 2 && f.ordinate_type != 4 && f.ordinate_type != 5 && f.ordinate_type != 6)
    p.ctx(7).fail_field(l7, 1, "ordinate data type", "2, 4 (real) or 5, 6 (complex)", std::to_string(f.ordinate_type));
  if (n < 0) p.ctx(7).fail_field(l7, 2, "number of data values", "a count >= 0", std::to_string(n));
  // Each value takes at least one character of the lines left: a larger count is a
  // damaged record, not a reason to allocate.
  if (static_cast<std::uint64_t>(n) > p.characters_left())
    p.ctx(7).fail_field(l7, 2, "number of data values",
                        "a count the dataset's remaining " + std::to_string(p.characters_left()) + " characters can hold",
                        std::to_string(n));
  if (r7[2].i != 0 && r7[2].i != 1)
    p.ctx(7).fail_field(l7, 3, "abscissa spacing", "0 (uneven) or 1 (even)", std::to_string(r7[2].i));

  f.axes[0] = parse_axis(p, 8, "abscissa data characteristics");
  f.axes[1] = parse_axis(p, 9, "ordinate (numerator) data characteristics");
  f.axes[2] = parse_axis(p, 10, "ordinate denominator data characteristics");
  f.axes[3] = parse_axis(p, 11, "z-axis data characteristics");

  const bool cplx = f.is_complex();
  const std::size_t stride = (f.even ? 0 : 1) + (cplx ? 2 : 1);
  std::vector<int> widths;
  if (!f.is_double()) widths.assign(6, 13);
  else if (f.even) widths.assign(4, 20);
  else if (!cplx) widths = {13, 20, 13, 20};
  else widths = {13, 20, 20};
  auto v = detail::read_real_stream(p.ctx(12), p.lines(), p.pos(), static_cast<std::size_t>(n) * stride, widths,
                                    "data values");
  f.x.resize(static_cast<std::size_t>(n));
  f.y.resize(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
    const double* e = &v[i * stride];
    std::size_t k = 0;
    f.x[i] = f.even ? f.abscissa_min + static_cast<double>(i) * f.abscissa_increment : e[k++];
    const double re = e[k++];
    const double im = cplx ? e[k] : 0.0;
    f.y[i] = {re, im};
  }
  p.finish(12);
  return f;
}

/// Binary 58b: header (I6,1A1,I6,I6,I12,I12,...) gives the byte count after the
/// ASCII records; the dataset is kept verbatim.
std::size_t binary_byte_count(const std::string& file, const Line& header) {
  RecordContext ctx;
  ctx.file = &file;
  ctx.dataset = 58;
  ctx.record = 0;
  auto v = detail::read_fields(ctx, header,
                               {{6, Kind::Integer, "dataset number"},
                                {1, Kind::Skip, ""},
                                {6, Kind::IntegerOrBlank, "byte ordering"},
                                {6, Kind::IntegerOrBlank, "floating point format"},
                                {12, Kind::Integer, "number of ASCII lines"},
                                {12, Kind::Integer, "number of bytes"}});
  if (v[5].i < 0) ctx.fail_field(header, 5, "number of bytes", "a count >= 0", std::to_string(v[5].i));
  return static_cast<std::size_t>(v[5].i);
}

bool is_blank_text(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; });
}

[[noreturn]] void not_text(const std::string& name, const Line& l, std::size_t column) {
  throw ParseError(SourceLocation{name, 0, {}}, "not a universal file: byte " + detail::byte_hex(l.text[column]) +
                                                    " at line " + std::to_string(l.number) + ", column " +
                                                    std::to_string(column + 1) + " is not text");
}

/// A file that does not start with a dataset: when its first 64 KiB hold a byte
/// that is not text, it is binary (an image, an archive, a binary export) and is
/// called that instead of having its first line quoted.
void refuse_binary(const std::string& text, const std::string& name) {
  detail::Scanner sc(text);
  while (!sc.at_end() && sc.offset() < (64u << 10)) {
    const Line l = sc.next();
    if (auto c = detail::first_non_text(l.text)) not_text(name, l, *c);
  }
}

}  // namespace

UffFile parse_uff(const std::string& text, const std::string& name) {
  UffFile out;
  out.path = name;
  detail::Scanner sc(text);
  // Every line read as text must be text: a binary file (or a binary dataset not
  // marked 'b') is said to be one, and none of its bytes is echoed. Until a
  // delimiter and a dataset number have been read, nothing says this is a
  // universal file at all.
  bool framed = false;
  auto next_text = [&](const char* where) {
    Line l = sc.next();
    if (auto c = detail::first_non_text(l.text)) {
      if (!framed) not_text(name, l, *c);
      throw ParseError(SourceLocation{name, l.number, {}},
                       "byte " + detail::byte_hex(l.text[*c]) + " at column " + std::to_string(*c + 1) + " is not text (" + where + ")");
    }
    return l;
  };
  while (!sc.at_end()) {
    Line open = next_text("where a dataset delimiter is expected");
    if (detail::is_blank(open.text)) continue;
    if (!detail::is_delimiter(open.text)) {
      if (!framed) refuse_binary(text, name);
      throw ParseError(SourceLocation{name, open.number, {}},
                       "expected the dataset delimiter \"    -1\" (-1 in columns 1-6), got " +
                           detail::quoted(detail::rtrim(open.text)));
    }
    // A trailing lone delimiter (maybe followed by blank lines) ends the file.
    const auto only_blanks_left = [&] { return is_blank_text(std::string_view(text).substr(sc.offset())); };
    if (only_blanks_left()) break;
    Block b;
    b.header = next_text("where a dataset number is expected");
    // Some writers leave an empty "-1 / -1" pair: a delimiter where a dataset number
    // should be opens the dataset afresh.
    while (detail::is_delimiter(b.header.text) && !only_blanks_left())
      b.header = next_text("where a dataset number is expected");
    if (detail::is_delimiter(b.header.text)) break;
    {
      std::string_view num = b.header.text.substr(0, std::min<std::size_t>(6, b.header.text.size()));
      auto n = parse_integer(formats::detail::trim(num));
      if (!n || *n <= 0 || *n > 999999)
        throw ParseError(SourceLocation{name, b.header.number, {}},
                         "expected a dataset number (I6, columns 1-6) after the delimiter, got " +
                             detail::quoted(detail::rtrim(b.header.text)));
      b.number = static_cast<int>(*n);
    }
    framed = true;
    const std::string in_dataset = "dataset " + std::to_string(b.number) + " opened at line " +
                                   std::to_string(b.header.number) + ", not marked binary";
    const bool binary = b.header.text.size() > 6 && (b.header.text[6] == 'b' || b.header.text[6] == 'B');
    b.body_begin = sc.offset();
    bool closed = false;
    if (binary) {
      const std::size_t nbytes = binary_byte_count(name, b.header);
      // The ASCII records of a binary dataset: 11 for 58b; count from the header when given.
      RecordContext ctx;
      ctx.file = &name;
      ctx.dataset = b.number;
      auto v = detail::read_fields(ctx, b.header,
                                   {{6, Kind::Integer, "dataset number"}, {1, Kind::Skip, ""},
                                    {6, Kind::IntegerOrBlank, "byte ordering"},
                                    {6, Kind::IntegerOrBlank, "floating point format"},
                                    {12, Kind::Integer, "number of ASCII lines"}});
      for (std::int64_t k = 0; k < v[4].i && !sc.at_end(); ++k) sc.next();
      sc.skip_bytes(nbytes);
    }
    while (!sc.at_end()) {
      Line l = binary ? sc.next() : next_text(in_dataset.c_str());
      if (detail::is_delimiter(l.text)) {
        b.closing = l;
        b.body_end = l.begin;
        closed = true;
        break;
      }
      if (!binary) b.body.push_back(l);
    }
    if (!closed)
      throw ParseError(SourceLocation{name, sc.line_number(), {}},
                       "dataset " + std::to_string(b.number) + " (opened at line " +
                           std::to_string(b.header.number) + ") has no closing delimiter \"    -1\"");
    if (binary) {
      UnknownDataset u;
      u.number = b.number;
      u.header_line = std::string(b.header.text);
      u.body = text.substr(b.body_begin, b.body_end - b.body_begin);
      u.where = SourceLocation{name, b.header.number, {}};
      out.datasets.push_back(std::move(u));
      continue;
    }
    DatasetParser p(name, b);
    switch (b.number) {
      case 151: out.datasets.push_back(parse_151(p)); break;
      case 164: out.datasets.push_back(parse_164(p)); break;
      case 15: out.datasets.push_back(parse_15(p)); break;
      case 2411: out.datasets.push_back(parse_2411(p)); break;
      case 55: out.datasets.push_back(parse_55(p)); break;
      case 58: out.datasets.push_back(parse_58(p)); break;
      default: {
        UnknownDataset u;
        u.number = b.number;
        u.header_line = std::string(b.header.text);
        u.body = text.substr(b.body_begin, b.body_end - b.body_begin);
        u.where = SourceLocation{name, b.header.number, {}};
        out.datasets.push_back(std::move(u));
      }
    }
  }
  // A file with nothing in it is never what was meant (a failed export, the wrong file).
  if (out.datasets.empty())
    throw ParseError(SourceLocation{name, 0, {}},
                     std::string(text.empty() ? "empty file" : "no dataset in the file") +
                         ": a universal file holds datasets, each opened by a line \"    -1\" and its dataset "
                         "number and closed by a line \"    -1\"");
  return out;
}

UffFile read_uff(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ParseError(SourceLocation{path, 0, {}}, "is a directory, expected a universal file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ParseError(SourceLocation{path, 0, {}}, "universal file not found or not readable");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_uff(ss.str(), path);
}

int dataset_number(const Dataset& d) {
  struct V {
    int operator()(const Header151&) const { return 151; }
    int operator()(const Units164&) const { return 164; }
    int operator()(const NodeSet& s) const { return s.dataset; }
    int operator()(const NodalData55&) const { return 55; }
    int operator()(const Function58&) const { return 58; }
    int operator()(const UnknownDataset& u) const { return u.number; }
  };
  return std::visit(V{}, d);
}

std::vector<Node> UffFile::nodes() const {
  std::vector<Node> r;
  for (const auto& d : datasets)
    if (auto s = std::get_if<NodeSet>(&d)) r.insert(r.end(), s->nodes.begin(), s->nodes.end());
  return r;
}

std::vector<const NodalData55*> UffFile::nodal_data() const {
  std::vector<const NodalData55*> r;
  for (const auto& d : datasets)
    if (auto s = std::get_if<NodalData55>(&d)) r.push_back(s);
  return r;
}

std::vector<const Function58*> UffFile::functions() const {
  std::vector<const Function58*> r;
  for (const auto& d : datasets)
    if (auto s = std::get_if<Function58>(&d)) r.push_back(s);
  return r;
}

std::map<int, std::size_t> UffFile::skipped() const {
  std::map<int, std::size_t> r;
  for (const auto& d : datasets)
    if (auto s = std::get_if<UnknownDataset>(&d)) ++r[s->number];
  return r;
}

double NodalData55::frequency_hz() const {
  if (is_complex_mode()) return std::abs(eigenvalue()) / (2 * M_PI);
  return real_params.empty() ? 0.0 : real_params[0];
}

std::complex<double> NodalData55::eigenvalue() const {
  if (!is_complex_mode() || real_params.size() < 2) return {};
  return {real_params[0], real_params[1]};
}

NodalData55 NodalData55::normal_mode(std::int64_t mode, double frequency_hz, std::vector<std::int64_t> nodes,
                                     Eigen::MatrixXd values, double modal_mass, double viscous_damping) {
  NodalData55 d;
  d.id_lines = {"NONE", "NONE", "NONE", "NONE", "NONE"};
  d.analysis_type = 2;
  d.values_per_node = static_cast<int>(values.cols());
  d.data_characteristic = d.values_per_node == 6 ? 3 : 2;
  d.specific_data_type = 8;
  d.data_type = 2;
  d.int_params = {1, mode};
  d.real_params = {frequency_hz, modal_mass, viscous_damping, 0.0};
  d.nodes = std::move(nodes);
  d.values = std::move(values);
  return d;
}

}  // namespace ssid::formats::uff
