/// \file uff_writer.cpp
/// Universal-file writer: the fixed-column layouts of uff.hpp, 1P E-format
/// reals (one digit before the point, as Fortran's 1PE13.5 writes them).
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "formats/parse_error.hpp"
#include "formats/uff.hpp"

namespace ssid::formats::uff {

namespace {

const char* kDelimiter = "    -1\n";

/// An integer in an Iw field. One wider than the field would run into the next and
/// the file would not read back (fuzz finding uff-1): refused.
void put_int(std::string& o, std::int64_t v, int width) {
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%*lld", width, static_cast<long long>(v));
  if (n > width)
    throw InputError("universal file: the integer " + std::string(buf) + " does not fit its I" + std::to_string(width) +
                     " field (" + std::to_string(n) + " characters)");
  o += buf;
}

/// 1P Ew.d: "%w.dE"; with `d_exponent` the exponent letter is D (Fortran double).
void put_real(std::string& o, double v, int width, int decimals, bool d_exponent = false) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%*.*E", width, decimals, v);
  std::string s(buf);
  if (d_exponent)
    for (auto& c : s)
      if (c == 'E') c = 'D';
  o += s;
}

void put_text(std::string& o, const std::string& s, int width) {
  std::string t = s.substr(0, static_cast<std::size_t>(width));
  o += t;
  o.append(static_cast<std::size_t>(width) - t.size(), ' ');
}

void put_line(std::string& o, const std::string& s) {
  o += s.empty() ? std::string("NONE") : s;
  o += '\n';
}

/// Values written `per_line` to a line, each as put_real(width, decimals).
void put_reals(std::string& o, const double* v, std::size_t n, std::size_t per_line, int width, int decimals) {
  for (std::size_t i = 0; i < n; ++i) {
    put_real(o, v[i], width, decimals);
    if ((i + 1) % per_line == 0 || i + 1 == n) o += '\n';
  }
}

struct RealFormat {
  std::size_t per_line;
  int width, decimals;
};
RealFormat single_format(Precision p) { return p == Precision::Standard ? RealFormat{6, 13, 5} : RealFormat{3, 25, 16}; }

/// Node i's values of a 55/2414 dataset in file order: real and imaginary
/// parts interleaved when complex.
void node_row(const NodalData55& d, std::size_t i, int ndv, bool cplx, std::vector<double>& row) {
  const auto ii = static_cast<Eigen::Index>(i);
  for (int c = 0; c < ndv; ++c) {
    if (cplx) {
      row[2 * c] = d.complex_values(ii, c).real();
      row[2 * c + 1] = d.complex_values(ii, c).imag();
    } else {
      row[c] = d.values(ii, c);
    }
  }
}

void write_151(std::string& o, const Header151& h) {
  for (const auto& l : h.lines) o += l + "\n";
}

void write_164(std::string& o, const Units164& u) {
  put_int(o, u.code, 10);
  put_text(o, u.description, 20);
  put_int(o, u.temperature_mode, 10);
  o += '\n';
  put_real(o, u.length, 25, 17, true);
  put_real(o, u.force, 25, 17, true);
  put_real(o, u.temperature, 25, 17, true);
  o += '\n';
  put_real(o, u.temperature_offset, 25, 17, true);
  o += '\n';
}

void write_nodes(std::string& o, const NodeSet& s, Precision p) {
  for (const auto& n : s.nodes) {
    put_int(o, n.id, 10);
    put_int(o, n.definition_cs, 10);
    put_int(o, n.displacement_cs, 10);
    put_int(o, n.color, 10);
    if (s.dataset == 2411) {
      o += '\n';
      for (double x : n.xyz) put_real(o, x, 25, 16, true);
    } else {
      const auto f = single_format(p);
      for (double x : n.xyz) put_real(o, x, f.width, f.decimals);
    }
    o += '\n';
  }
}

void write_55(std::string& o, const NodalData55& d, Precision p) {
  for (const auto& l : d.id_lines) put_line(o, l);
  const bool cplx = d.is_complex();
  // Data are written in the precision this writer knows: real 2, complex 5.
  const int data_type = cplx ? 5 : 2;
  const int ndv = static_cast<int>(cplx ? d.complex_values.cols() : d.values.cols());
  for (int v : {d.model_type, d.analysis_type, d.data_characteristic, d.specific_data_type, data_type, ndv}) put_int(o, v, 10);
  o += '\n';
  // R7 (8I10): NINT, NREAL and the integers, eight to a line.
  std::vector<std::int64_t> r7{static_cast<std::int64_t>(d.int_params.size()),
                               static_cast<std::int64_t>(d.real_params.size())};
  r7.insert(r7.end(), d.int_params.begin(), d.int_params.end());
  for (std::size_t k = 0; k < r7.size(); ++k) {
    put_int(o, r7[k], 10);
    if ((k + 1) % 8 == 0 || k + 1 == r7.size()) o += '\n';
  }
  const auto f = single_format(p);
  put_reals(o, d.real_params.data(), d.real_params.size(), f.per_line, f.width, f.decimals);
  const std::size_t nn = d.nodes.size();
  std::vector<double> row(static_cast<std::size_t>(cplx ? 2 * ndv : ndv));
  for (std::size_t i = 0; i < nn; ++i) {
    put_int(o, d.nodes[i], 10);
    o += '\n';
    node_row(d, i, ndv, cplx, row);
    put_reals(o, row.data(), row.size(), f.per_line, f.width, f.decimals);
  }
}

void write_axis(std::string& o, const Axis58& a) {
  put_int(o, a.specific_data_type, 10);
  put_int(o, a.length_exponent, 5);
  put_int(o, a.force_exponent, 5);
  put_int(o, a.temperature_exponent, 5);
  o += ' ';
  put_text(o, a.label.empty() ? "NONE" : a.label, 20);
  o += ' ';
  put_text(o, a.units.empty() ? "NONE" : a.units, 20);
  o += '\n';
}

/// IEEE 754 bytes of v as a float (size 4) or double (8) in byte order `order`
/// (1 little endian, 2 big endian).
void put_ieee(std::string& o, double v, int size, int order) {
  std::uint64_t u = 0;
  if (size == 4) {
    const float x = static_cast<float>(v);
    std::uint32_t u32;
    std::memcpy(&u32, &x, 4);
    u = u32;
  } else {
    std::memcpy(&u, &v, 8);
  }
  char b[8];
  for (int k = 0; k < size; ++k) {
    const auto byte = static_cast<char>((u >> (8 * k)) & 0xff);  // k-th least significant
    b[order == 1 ? k : size - 1 - k] = byte;
  }
  o.append(b, static_cast<std::size_t>(size));
}

/// The values of record 12 in record order: x (uneven), re, im (complex).
std::vector<double> record12_values(const Function58& f) {
  std::vector<double> v;
  const bool cplx = f.is_complex();
  for (std::size_t i = 0; i < f.y.size(); ++i) {
    if (!f.even) v.push_back(i < f.x.size() ? f.x[i] : 0.0);
    v.push_back(f.y[i].real());
    if (cplx) v.push_back(f.y[i].imag());
  }
  return v;
}

void write_58(std::string& o, const Function58& f, Precision p) {
  for (const auto& l : f.id_lines) put_line(o, l);
  put_int(o, f.function_type, 5);
  put_int(o, f.function_id, 10);
  put_int(o, f.version, 5);
  put_int(o, f.load_case, 10);
  o += ' ';
  put_text(o, f.response_entity.empty() ? "NONE" : f.response_entity, 10);
  put_int(o, f.response_node, 10);
  put_int(o, f.response_direction, 4);
  o += ' ';
  put_text(o, f.reference_entity.empty() ? "NONE" : f.reference_entity, 10);
  put_int(o, f.reference_node, 10);
  put_int(o, f.reference_direction, 4);
  o += '\n';
  const std::size_t n = f.y.size();
  put_int(o, f.ordinate_type, 10);
  put_int(o, static_cast<std::int64_t>(n), 10);
  put_int(o, f.even ? 1 : 0, 10);
  put_real(o, f.even ? f.abscissa_min : 0.0, 13, 5);
  put_real(o, f.even ? f.abscissa_increment : 0.0, 13, 5);
  put_real(o, f.z_value, 13, 5);
  o += '\n';
  for (const auto& a : f.axes) write_axis(o, a);

  const bool cplx = f.is_complex();
  const std::vector<double> v = record12_values(f);
  if (f.binary) {
    // 58b: the values right after the ASCII records; the closing delimiter follows them directly.
    const int size = f.is_double() ? 8 : 4;
    for (double x : v) put_ieee(o, x, size, f.byte_order == 2 ? 2 : 1);
    return;
  }
  if (!f.is_double()) {
    const auto w = single_format(p);
    put_reals(o, v.data(), v.size(), w.per_line, w.width, w.decimals);
    return;
  }
  // Double precision: even 4E20.12; uneven real 2(E13.5,E20.12); uneven complex E13.5,2E20.12.
  const std::size_t stride = f.even ? 4 : (cplx ? 3 : 4);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::size_t k = i % stride;
    const bool abscissa = !f.even && (cplx ? k == 0 : k % 2 == 0);
    if (abscissa) put_real(o, v[i], 13, 5);
    else put_real(o, v[i], 20, 12);
    if (k + 1 == stride || i + 1 == v.size()) o += '\n';
  }
}

void write_1858(std::string& o, const Qualifiers1858& q) {
  for (auto v : q.r1) put_int(o, v, 12);
  o += '\n';
  for (auto v : q.r2) put_int(o, v, 6);
  o += '\n';
  for (std::size_t k = 0; k < q.reals.size(); ++k) {
    put_real(o, q.reals[k], 15, 7);
    if (k % 5 == 4) o += '\n';
  }
  put_line(o, q.directions);
  put_line(o, q.r7);
}

void write_ints(std::string& o, const std::vector<std::int64_t>& v, std::size_t per_line, int width) {
  for (std::size_t k = 0; k < v.size(); ++k) {
    put_int(o, v[k], width);
    if ((k + 1) % per_line == 0 || k + 1 == v.size()) o += '\n';
  }
}

void write_2412(std::string& o, const ElementSet2412& s) {
  for (const auto& e : s.elements) {
    for (std::int64_t v : {e.id, static_cast<std::int64_t>(e.descriptor), e.physical, e.material,
                           static_cast<std::int64_t>(e.color), static_cast<std::int64_t>(e.nodes.size())})
      put_int(o, v, 10);
    o += '\n';
    if (e.beam) write_ints(o, {(*e.beam)[0], (*e.beam)[1], (*e.beam)[2]}, 3, 10);
    write_ints(o, e.nodes, 8, 10);
  }
}

void write_82(std::string& o, const TraceLine82& t) {
  put_int(o, t.id, 10);
  put_int(o, static_cast<std::int64_t>(t.nodes.size()), 10);
  put_int(o, t.color, 10);
  o += '\n';
  put_line(o, t.label);
  write_ints(o, t.nodes, 8, 10);
}

void write_18(std::string& o, const CoordinateSystems18& s) {
  for (const auto& c : s.systems) {
    for (std::int64_t v : {c.id, static_cast<std::int64_t>(c.type), c.reference, static_cast<std::int64_t>(c.color),
                           static_cast<std::int64_t>(c.method)})
      put_int(o, v, 10);
    o += '\n';
    put_line(o, c.name);
    for (double x : c.origin) put_real(o, x, 13, 5);
    for (double x : c.x_point) put_real(o, x, 13, 5);
    o += '\n';
    for (double x : c.xz_point) put_real(o, x, 13, 5);
    o += '\n';
  }
}

void write_2420(std::string& o, const CoordinateSystems2420& s) {
  put_int(o, s.part_uid, 10);
  o += '\n';
  put_line(o, s.part_name);
  for (const auto& c : s.systems) {
    for (std::int64_t v : {c.id, static_cast<std::int64_t>(c.type), static_cast<std::int64_t>(c.color)}) put_int(o, v, 10);
    o += '\n';
    put_line(o, c.name);
    for (int r = 0; r < 4; ++r) {
      for (double x : r < 3 ? c.rows[r] : c.origin) put_real(o, x, 25, 16, true);
      o += '\n';
    }
  }
}

/// Dataset 2414 at nodes (layout in uff.hpp): values in the file's precision,
/// 6E13.5 (single; 1PE25.16 three to a line with Precision::Extended) or 3D25.16 (double).
void write_2414(std::string& o, const NodalData55& d, Precision p) {
  const Analysis2414& a = *d.analysis2414;
  put_int(o, a.label, 10);
  o += '\n';
  put_line(o, a.name);
  put_int(o, 1, 10);
  o += '\n';
  for (const auto& l : d.id_lines) put_line(o, l);
  const bool cplx = d.is_complex();
  const bool dbl = d.data_type == 4 || d.data_type == 6;
  const int ndv = static_cast<int>(cplx ? d.complex_values.cols() : d.values.cols());
  for (int v : {d.model_type, d.analysis_type, d.data_characteristic, d.specific_data_type, d.data_type, ndv})
    put_int(o, v, 10);
  o += '\n';
  write_ints(o, std::vector<std::int64_t>(a.r10.begin(), a.r10.end()), 8, 10);
  write_ints(o, std::vector<std::int64_t>(a.r11.begin(), a.r11.end()), 8, 10);
  put_reals(o, a.r12.data(), 6, 6, 13, 5);
  put_reals(o, a.r13.data(), 6, 6, 13, 5);
  const auto f = single_format(p);
  std::vector<double> row(static_cast<std::size_t>(cplx ? 2 * ndv : ndv));
  for (std::size_t i = 0; i < d.nodes.size(); ++i) {
    put_int(o, d.nodes[i], 10);
    o += '\n';
    node_row(d, i, ndv, cplx, row);
    if (dbl) {
      for (std::size_t k = 0; k < row.size(); ++k) {
        put_real(o, row[k], 25, 16, true);
        if ((k + 1) % 3 == 0 || k + 1 == row.size()) o += '\n';
      }
    } else {
      put_reals(o, row.data(), row.size(), f.per_line, f.width, f.decimals);
    }
  }
}

}  // namespace

std::string format_uff(const UffFile& file, Precision precision) {
  std::string o;
  for (const auto& d : file.datasets) {
    o += kDelimiter;
    if (auto u = std::get_if<UnknownDataset>(&d)) {
      o += u->header_line + "\n" + u->body + kDelimiter;
      continue;
    }
    put_int(o, dataset_number(d), 6);
    if (auto f = std::get_if<Function58>(&d); f && f->binary) {
      // (I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12): 'b', byte order, IEEE 754, 11 ASCII lines, bytes, zeros.
      const std::size_t bytes = record12_values(*f).size() * (f->is_double() ? 8 : 4);
      o += 'b';
      put_int(o, f->byte_order == 2 ? 2 : 1, 6);
      put_int(o, 2, 6);
      put_int(o, 11, 12);
      put_int(o, static_cast<std::int64_t>(bytes), 12);
      o += "     0     0           0           0";
    }
    o += '\n';
    if (auto h = std::get_if<Header151>(&d)) write_151(o, *h);
    else if (auto u164 = std::get_if<Units164>(&d)) write_164(o, *u164);
    else if (auto s = std::get_if<NodeSet>(&d)) write_nodes(o, *s, precision);
    else if (auto m = std::get_if<NodalData55>(&d)) {
      if (m->analysis2414) write_2414(o, *m, precision);
      else write_55(o, *m, precision);
    } else if (auto f = std::get_if<Function58>(&d)) write_58(o, *f, precision);
    else if (auto q = std::get_if<Qualifiers1858>(&d)) write_1858(o, *q);
    else if (auto e = std::get_if<ElementSet2412>(&d)) write_2412(o, *e);
    else if (auto t = std::get_if<TraceLine82>(&d)) write_82(o, *t);
    else if (auto c18 = std::get_if<CoordinateSystems18>(&d)) write_18(o, *c18);
    else if (auto c2420 = std::get_if<CoordinateSystems2420>(&d)) write_2420(o, *c2420);
    o += kDelimiter;
  }
  return o;
}

void write_uff(const UffFile& file, const std::string& path, Precision precision) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw InputError("cannot write " + path);
  out << format_uff(file, precision);
  if (!out) throw InputError("error writing " + path);
}

}  // namespace ssid::formats::uff
