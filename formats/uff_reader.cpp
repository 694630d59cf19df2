/// \file uff_reader.cpp
/// Universal-file reader: frames datasets between delimiters, then parses the
/// known ones record by record (layouts in uff.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>
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

/// Record 12 of a 58b: the raw bytes after the ASCII records.
struct BinaryPayload {
  std::string_view bytes;
  int byte_order = 1;  ///< 1 little endian, 2 big endian
  Line header;         ///< the "    58b ..." line, where a size mismatch is reported
};

/// IEEE 754 value of `size` (4 or 8) bytes at `b` in byte order `order`.
double decode_ieee(const char* b, int size, int order) {
  std::uint64_t u = 0;
  for (int k = 0; k < size; ++k) {
    const int at = order == 1 ? size - 1 - k : k;  // most significant byte first
    u = (u << 8) | static_cast<unsigned char>(b[at]);
  }
  if (size == 4) {
    const auto u32 = static_cast<std::uint32_t>(u);
    float v;
    std::memcpy(&v, &u32, 4);
    return v;
  }
  double v;
  std::memcpy(&v, &u, 8);
  return v;
}

Function58 parse_58(DatasetParser& p, const BinaryPayload* bin = nullptr) {
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
  if (!bin && static_cast<std::uint64_t>(n) > p.characters_left())
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
  std::vector<double> v;
  if (bin) {
    f.binary = true;
    f.byte_order = bin->byte_order;
    p.finish(11);
    const std::size_t size = f.is_double() ? 8 : 4;
    // A count above the byte count is refused before it is multiplied (no overflow).
    const bool fits = static_cast<std::uint64_t>(n) <= bin->bytes.size();
    if (!fits || static_cast<std::uint64_t>(n) * stride * size != bin->bytes.size()) {
      const std::size_t point = stride * size;
      p.ctx(7).fail_field(l7, 2, "number of data values",
                          (bin->bytes.size() % point == 0 ? std::to_string(bin->bytes.size() / point)
                                                          : std::string("a count whose points fill them")) +
                              " (the 58b header at line " + std::to_string(bin->header.number) + " declares " +
                              std::to_string(bin->bytes.size()) + " bytes; a point is " + std::to_string(stride) +
                              " value(s) of " + std::to_string(size) + " bytes)",
                          std::to_string(n));
    }
    v.resize(static_cast<std::size_t>(n) * stride);
    for (std::size_t k = 0; k < v.size(); ++k)
      v[k] = decode_ieee(bin->bytes.data() + k * size, static_cast<int>(size), bin->byte_order);
  }
  std::vector<int> widths;
  if (!f.is_double()) widths.assign(6, 13);
  else if (f.even) widths.assign(4, 20);
  else if (!cplx) widths = {13, 20, 13, 20};
  else widths = {13, 20, 20};
  if (!bin)
    v = detail::read_real_stream(p.ctx(12), p.lines(), p.pos(), static_cast<std::size_t>(n) * stride, widths,
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
  if (!bin) p.finish(12);
  return f;
}

Qualifiers1858 parse_1858(DatasetParser& p) {
  Qualifiers1858 q;
  q.where = p.where();
  auto r1 = detail::read_fields(p.ctx(1), p.next(1, "set record number"),
                                std::vector<FieldSpec>(6, FieldSpec{12, Kind::IntegerOrBlank, "record 1 integer"}));
  for (int k = 0; k < 6; ++k) q.r1[k] = r1[k].i;
  auto r2 = detail::read_fields(p.ctx(2), p.next(2, "weighting, window, units and qualifiers"),
                                std::vector<FieldSpec>(12, FieldSpec{6, Kind::IntegerOrBlank, "record 2 integer"}));
  for (int k = 0; k < 12; ++k) q.r2[k] = r2[k].i;
  for (int r = 0; r < 3; ++r) {
    auto v = detail::read_real_stream(p.ctx(3 + r), p.lines(), p.pos(), 5, std::vector<int>(5, 15),
                                      r == 0 ? "z RPM, time, order, samples" : r == 1 ? "user values, window damping"
                                                                                      : "unused reals");
    std::copy(v.begin(), v.end(), q.reals.begin() + 5 * r);
  }
  q.directions = detail::rtrim(p.next(6, "response and reference direction").text);
  if (!p.done()) q.r7 = detail::rtrim(p.next(7, "unused text").text);
  p.finish(7);
  return q;
}

/// Dataset 2414 at nodes into NodalData55 (layouts in uff.hpp); nullopt for the
/// other dataset locations, which the caller keeps verbatim.
std::optional<NodalData55> parse_2414(DatasetParser& p) {
  NodalData55 d;
  Analysis2414 a;
  d.where = p.where();
  a.label = detail::read_fields(p.ctx(1), p.next(1, "analysis dataset label"),
                                {{10, Kind::Integer, "analysis dataset label"}})[0].i;
  a.name = detail::rtrim(p.next(2, "analysis dataset name").text);
  const Line& l3 = p.next(3, "dataset location");
  a.location = static_cast<int>(detail::read_fields(p.ctx(3), l3, {{10, Kind::Integer, "dataset location"}})[0].i);
  if (a.location < 1 || a.location > 5)
    p.ctx(3).fail_field(l3, 1, "dataset location", "1 (nodes), 2 (elements), 3 (nodes on elements) or 5 (points)",
                        std::to_string(a.location));
  if (a.location != 1) return std::nullopt;
  for (int r = 0; r < 5; ++r) d.id_lines[r] = detail::rtrim(p.next(4 + r, "ID line").text);
  const Line& l9 = p.next(9, "data description");
  auto r9 = detail::read_fields(p.ctx(9), l9,
                                {{10, Kind::IntegerOrBlank, "model type"},
                                 {10, Kind::Integer, "analysis type"},
                                 {10, Kind::IntegerOrBlank, "data characteristic"},
                                 {10, Kind::IntegerOrBlank, "result type"},
                                 {10, Kind::Integer, "data type"},
                                 {10, Kind::Integer, "number of data values per node"}});
  d.model_type = static_cast<int>(r9[0].i);
  d.analysis_type = static_cast<int>(r9[1].i);
  d.data_characteristic = static_cast<int>(r9[2].i);
  d.specific_data_type = static_cast<int>(r9[3].i);
  d.data_type = static_cast<int>(r9[4].i);
  d.values_per_node = static_cast<int>(r9[5].i);
  if (d.data_type != 2 && d.data_type != 4 && d.data_type != 5 && d.data_type != 6)
    p.ctx(9).fail_field(l9, 5, "data type", "2, 4 (real) or 5, 6 (complex)", std::to_string(d.data_type));
  if (d.values_per_node < 1 || d.values_per_node > 99)
    p.ctx(9).fail_field(l9, 6, "number of data values per node", "1 to 99", std::to_string(d.values_per_node));
  auto r10 = detail::read_fields(p.ctx(10), p.next(10, "design set, iteration, ... frequency number"),
                                 std::vector<FieldSpec>(8, FieldSpec{10, Kind::IntegerOrBlank, "record 10 integer"}));
  for (int k = 0; k < 8; ++k) a.r10[k] = r10[k].i;
  auto r11 = detail::read_fields(p.ctx(11), p.next(11, "creation option, number retained"),
                                 std::vector<FieldSpec>(2, FieldSpec{10, Kind::IntegerOrBlank, "record 11 integer"}));
  a.r11 = {r11[0].i, r11[1].i};
  auto r12 = detail::read_real_stream(p.ctx(12), p.lines(), p.pos(), 6, std::vector<int>(6, 13),
                                      "time, frequency, eigenvalue, modal mass, damping");
  auto r13 = detail::read_real_stream(p.ctx(13), p.lines(), p.pos(), 6, std::vector<int>(6, 13),
                                      "complex eigenvalue, modal A and B");
  std::copy(r12.begin(), r12.end(), a.r12.begin());
  std::copy(r13.begin(), r13.end(), a.r13.begin());
  // The type-specific parameters as a 55 of the same analysis type carries them.
  const std::int64_t load_set = a.r10[4], mode = a.r10[5];
  switch (d.analysis_type) {
    case 2: d.int_params = {load_set, mode}; d.real_params = {a.r12[1], a.r12[3], a.r12[4], a.r12[5]}; break;
    case 3: case 7: d.int_params = {load_set, mode}; d.real_params.assign(a.r13.begin(), a.r13.end()); break;
    case 5: d.int_params = {load_set, a.r10[7]}; d.real_params = {a.r12[1]}; break;
    case 4: d.int_params = {load_set, a.r10[6]}; d.real_params = {a.r12[0]}; break;
    default: d.int_params = {load_set}; d.real_params = {0.0}; break;
  }
  const int ndv = d.values_per_node;
  const std::size_t per_node = static_cast<std::size_t>(d.is_complex() ? 2 * ndv : ndv);
  const bool dbl = d.data_type == 4 || d.data_type == 6;
  std::vector<double> flat;
  while (!p.done()) {
    const Line& l14 = p.next(14, "node number");
    if (detail::is_blank(l14.text)) continue;
    d.nodes.push_back(detail::read_fields(p.ctx(14), l14, {{10, Kind::Integer, "node number"}})[0].i);
    auto v = detail::read_real_stream(p.ctx(15), p.lines(), p.pos(), per_node,
                                      dbl ? std::vector<int>(3, 25) : std::vector<int>(6, 13), "data at node");
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
  d.analysis2414 = std::move(a);
  return d;
}

ElementSet2412 parse_2412(DatasetParser& p) {
  ElementSet2412 s;
  s.where = p.where();
  while (!p.done()) {
    const Line& l = p.next(1, "element");
    if (detail::is_blank(l.text)) continue;
    auto v = detail::read_fields(p.ctx(1), l,
                                 {{10, Kind::Integer, "element label"},
                                  {10, Kind::Integer, "FE descriptor id"},
                                  {10, Kind::IntegerOrBlank, "physical property table"},
                                  {10, Kind::IntegerOrBlank, "material property table"},
                                  {10, Kind::IntegerOrBlank, "color"},
                                  {10, Kind::Integer, "number of nodes"}});
    Element2412 e;
    e.id = v[0].i;
    e.descriptor = static_cast<int>(v[1].i);
    e.physical = v[2].i;
    e.material = v[3].i;
    e.color = static_cast<int>(v[4].i);
    if (v[5].i < 1 || v[5].i > 10000)
      p.ctx(1).fail_field(l, 6, "number of nodes", "1 to 10000", std::to_string(v[5].i));
    if (Element2412::is_beam_descriptor(e.descriptor)) {
      auto b = detail::read_fields(p.ctx(2), p.next(2, "beam orientation node and cross sections"),
                                   {{10, Kind::IntegerOrBlank, "beam orientation node"},
                                    {10, Kind::IntegerOrBlank, "fore-end cross section"},
                                    {10, Kind::IntegerOrBlank, "aft-end cross section"}});
      e.beam = std::array<std::int64_t, 3>{b[0].i, b[1].i, b[2].i};
    }
    e.nodes = detail::read_integer_stream(p.ctx(e.beam ? 3 : 2), p.lines(), p.pos(), static_cast<std::size_t>(v[5].i),
                                          8, 10, "element node");
    s.elements.push_back(std::move(e));
  }
  return s;
}

TraceLine82 parse_82(DatasetParser& p) {
  TraceLine82 t;
  t.where = p.where();
  const Line& l1 = p.next(1, "trace line number");
  auto v = detail::read_fields(p.ctx(1), l1,
                               {{10, Kind::Integer, "trace line number"},
                                {10, Kind::Integer, "number of nodes"},
                                {10, Kind::IntegerOrBlank, "color"}});
  t.id = v[0].i;
  t.color = static_cast<int>(v[2].i);
  if (v[1].i < 0 || v[1].i > 1000000)
    p.ctx(1).fail_field(l1, 2, "number of nodes", "0 to 1000000", std::to_string(v[1].i));
  t.label = detail::rtrim(p.next(2, "identification line").text);
  t.nodes = detail::read_integer_stream(p.ctx(3), p.lines(), p.pos(), static_cast<std::size_t>(v[1].i), 8, 10,
                                        "trace line node");
  // Writers fill the last 8I10 line with zeros (pen lifts) past the count.
  while (!p.done()) {
    const Line& l = p.lines()[p.pos()];
    bool zeros = true;
    for (char c : l.text) zeros = zeros && (c == ' ' || c == '0' || c == '\r');
    if (!zeros) break;
    ++p.pos();
  }
  p.finish(3);
  return t;
}

CoordinateSystems18 parse_18(DatasetParser& p) {
  CoordinateSystems18 s;
  s.where = p.where();
  while (!p.done()) {
    const Line& l = p.next(1, "coordinate system number");
    if (detail::is_blank(l.text)) continue;
    auto v = detail::read_fields(p.ctx(1), l,
                                 {{10, Kind::Integer, "coordinate system number"},
                                  {10, Kind::IntegerOrBlank, "coordinate system type"},
                                  {10, Kind::IntegerOrBlank, "reference coordinate system number"},
                                  {10, Kind::IntegerOrBlank, "color"},
                                  {10, Kind::IntegerOrBlank, "method of definition"}});
    Cs18 c;
    c.id = v[0].i;
    c.type = static_cast<int>(v[1].i);
    c.reference = v[2].i;
    c.color = static_cast<int>(v[3].i);
    c.method = static_cast<int>(v[4].i);
    if (c.type < 0 || c.type > 2)
      p.ctx(1).fail_field(l, 2, "coordinate system type", "0 (Cartesian), 1 (cylindrical) or 2 (spherical)",
                          std::to_string(c.type));
    c.name = detail::rtrim(p.next(2, "coordinate system name").text);
    auto r3 = detail::read_real_stream(p.ctx(3), p.lines(), p.pos(), 6, std::vector<int>(6, 13),
                                       "origin and point on +X");
    auto r4 = detail::read_real_stream(p.ctx(4), p.lines(), p.pos(), 3, std::vector<int>(3, 13), "point in +XZ plane");
    c.origin = {r3[0], r3[1], r3[2]};
    c.x_point = {r3[3], r3[4], r3[5]};
    c.xz_point = {r4[0], r4[1], r4[2]};
    s.systems.push_back(std::move(c));
  }
  return s;
}

CoordinateSystems2420 parse_2420(DatasetParser& p) {
  CoordinateSystems2420 s;
  s.where = p.where();
  s.part_uid = detail::read_fields(p.ctx(1), p.next(1, "part UID"), {{10, Kind::IntegerOrBlank, "part UID"}})[0].i;
  s.part_name = detail::rtrim(p.next(2, "part name").text);
  while (!p.done()) {
    const Line& l = p.next(3, "coordinate system label");
    if (detail::is_blank(l.text)) continue;
    auto v = detail::read_fields(p.ctx(3), l,
                                 {{10, Kind::Integer, "coordinate system label"},
                                  {10, Kind::IntegerOrBlank, "coordinate system type"},
                                  {10, Kind::IntegerOrBlank, "coordinate system color"}});
    Cs2420 c;
    c.id = v[0].i;
    c.type = static_cast<int>(v[1].i);
    c.color = static_cast<int>(v[2].i);
    if (c.type < 0 || c.type > 2)
      p.ctx(3).fail_field(l, 2, "coordinate system type", "0 (Cartesian), 1 (cylindrical) or 2 (spherical)",
                          std::to_string(c.type));
    c.name = detail::rtrim(p.next(4, "coordinate system name").text);
    for (int r = 0; r < 4; ++r) {
      auto x = detail::read_real_stream(p.ctx(5 + r), p.lines(), p.pos(), 3, {25, 25, 25},
                                        r < 3 ? "transformation matrix row" : "origin");
      (r < 3 ? c.rows[r] : c.origin) = {x[0], x[1], x[2]};
    }
    s.systems.push_back(std::move(c));
  }
  return s;
}

/// Blanks, or the DOS end-of-file mark (0x1A) that old lab software leaves after the last delimiter.
bool is_blank_text(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\x1a';
  });
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
  // A byte-order mark (Windows editors) is no part of the first delimiter.
  if (text.compare(0, 3, "\xEF\xBB\xBF") == 0) sc.skip_bytes(3);
  const auto only_blanks_left = [&] { return is_blank_text(std::string_view(text).substr(sc.offset())); };
  while (!sc.at_end()) {
    if (only_blanks_left()) break;
    Line open = next_text("where a dataset delimiter is expected");
    if (detail::is_blank(open.text)) continue;
    if (!detail::is_delimiter(open.text)) {
      if (!framed) refuse_binary(text, name);
      throw ParseError(SourceLocation{name, open.number, {}},
                       "expected the dataset delimiter \"    -1\" (-1 in columns 1-6), got " +
                           detail::quoted(detail::rtrim(open.text)));
    }
    // A trailing lone delimiter (maybe followed by blank lines) ends the file.
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
    std::optional<BinaryPayload> payload;
    if (binary) {
      // Header (I6,1A1,I6,I6,I12,I12,...): byte order, floating-point format,
      // number of ASCII lines, number of bytes after them.
      RecordContext ctx;
      ctx.file = &name;
      ctx.dataset = b.number;
      auto v = detail::read_fields(ctx, b.header,
                                   {{6, Kind::Integer, "dataset number"}, {1, Kind::Skip, ""},
                                    {6, Kind::IntegerOrBlank, "byte ordering"},
                                    {6, Kind::IntegerOrBlank, "floating point format"},
                                    {12, Kind::Integer, "number of ASCII lines"},
                                    {12, Kind::Integer, "number of bytes"}});
      // The number line is no record: its errors say "header field N".
      const auto header_fail = [&](int field, const char* what, const std::string& expected, std::int64_t got) {
        throw ParseError(SourceLocation{name, b.header.number, {}},
                         "dataset " + std::to_string(b.number) + "b header field " + std::to_string(field) + " (" +
                             what + "): expected " + expected + ", got \"" + std::to_string(got) + "\"");
      };
      if (v[4].i < 0 || v[4].i > 1000)
        header_fail(5, "number of ASCII lines", "0 to 1000 (11 for dataset 58b)", v[4].i);
      if (v[5].i < 0) header_fail(6, "number of bytes", "a count >= 0", v[5].i);
      const auto nbytes = static_cast<std::size_t>(v[5].i);
      if (b.number == 58) {
        if (v[2].i != 1 && v[2].i != 2)
          header_fail(3, "byte ordering", "1 (little endian) or 2 (big endian)", v[2].i);
        if (v[3].i != 2)
          header_fail(4, "floating point format", "2 (IEEE 754; 1 DEC VMS and 3 IBM 370 are not read)", v[3].i);
        if (v[4].i != 11) header_fail(5, "number of ASCII lines", "11 (records 1-11 of dataset 58)", v[4].i);
        const std::string in58b = "dataset 58b opened at line " + std::to_string(b.header.number);
        for (int k = 0; k < 11; ++k) {
          if (sc.at_end())
            throw ParseError(SourceLocation{name, sc.line_number(), {}},
                             in58b + " ends after " + std::to_string(k) + " of its 11 ASCII records");
          b.body.push_back(next_text(in58b.c_str()));
        }
        const std::size_t at = sc.offset();
        if (text.size() - at < nbytes)
          throw ParseError(SourceLocation{name, b.header.number, {}},
                           "dataset 58 record 12: the 58b header declares " + std::to_string(nbytes) +
                               " bytes of binary data after the ASCII records, the file holds only " +
                               std::to_string(text.size() - at));
        payload = BinaryPayload{std::string_view(text).substr(at, nbytes), static_cast<int>(v[2].i), b.header};
      } else {
        for (std::int64_t k = 0; k < v[4].i && !sc.at_end(); ++k) sc.next();
      }
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
      // After 58b's bytes only a line end may come before the delimiter (some
      // writers put one there); anything else means the byte count is wrong.
      if (payload && !detail::is_blank(l.text))
        throw ParseError(SourceLocation{name, l.number, {}},
                         "dataset 58b (opened at line " + std::to_string(b.header.number) +
                             "): expected the closing delimiter \"    -1\" right after the " +
                             std::to_string(payload->bytes.size()) + " bytes of binary data the header declares, got " +
                             detail::quoted(detail::rtrim(l.text)));
      if (!binary) b.body.push_back(l);
    }
    if (!closed)
      throw ParseError(SourceLocation{name, sc.line_number(), {}},
                       "dataset " + std::to_string(b.number) + " (opened at line " +
                           std::to_string(b.header.number) + ") has no closing delimiter \"    -1\"");
    if (binary && !payload) {
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
      case 58: out.datasets.push_back(parse_58(p, payload ? &*payload : nullptr)); break;
      case 1858: out.datasets.push_back(parse_1858(p)); break;
      case 2412: out.datasets.push_back(parse_2412(p)); break;
      case 82: out.datasets.push_back(parse_82(p)); break;
      case 18: out.datasets.push_back(parse_18(p)); break;
      case 2420: out.datasets.push_back(parse_2420(p)); break;
      case 2414:
        if (auto d = parse_2414(p)) {
          out.datasets.push_back(std::move(*d));
          break;
        }
        [[fallthrough]];
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
    int operator()(const NodalData55& m) const { return m.analysis2414 ? 2414 : 55; }
    int operator()(const Function58&) const { return 58; }
    int operator()(const Qualifiers1858&) const { return 1858; }
    int operator()(const ElementSet2412&) const { return 2412; }
    int operator()(const TraceLine82&) const { return 82; }
    int operator()(const CoordinateSystems18&) const { return 18; }
    int operator()(const CoordinateSystems2420&) const { return 2420; }
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
