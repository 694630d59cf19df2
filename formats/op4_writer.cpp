/// \file op4_writer.cpp
/// Writing OP4 files in every encoding, storage and precision.
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <type_traits>
#include <unistd.h>

#include <fmt/format.h>

#include "formats/op4.hpp"
#include "formats/parse_error.hpp"

namespace ssid::formats {

namespace {

bool host_big() {
  const std::uint16_t x = 1;
  unsigned char c;
  std::memcpy(&c, &x, 1);
  return c == 0;
}

/// Output buffer: flushed to a file descriptor when one is given, kept otherwise.
class Sink {
public:
  explicit Sink(int fd, std::string path) : m_fd(fd), m_path(std::move(path)) { m_buf.reserve(kChunk + 4096); }
  char* grow(std::size_t n) {
    if (m_fd >= 0 && m_buf.size() + n > kChunk) flush();
    const std::size_t old = m_buf.size();
    m_buf.resize(old + n);
    return m_buf.data() + old;
  }
  void append(const char* s, std::size_t n) { std::memcpy(grow(n), s, n); }
  void append(const std::string& s) { append(s.data(), s.size()); }
  void flush() {
    if (m_fd < 0) return;
    std::size_t done = 0;
    while (done < m_buf.size()) {
      const ssize_t w = ::write(m_fd, m_buf.data() + done, m_buf.size() - done);
      if (w < 0) {
        if (errno == EINTR) continue;
        throw InputError("error writing " + m_path + ": " + std::strerror(errno));
      }
      done += static_cast<std::size_t>(w);
    }
    m_buf.clear();
  }
  std::string& text() { return m_buf; }

private:
  static constexpr std::size_t kChunk = 4u << 20;
  int m_fd;
  std::string m_path;
  std::string m_buf;
};

inline double re_of(double v) { return v; }
inline double re_of(const std::complex<double>& v) { return v.real(); }
inline double im_of(double) { return 0.0; }
inline double im_of(const std::complex<double>& v) { return v.imag(); }

struct Layout {
  int type;       ///< NASTRAN TYPE 1-4
  bool cx;        ///< complex
  bool single;
  int npt;        ///< numbers per term
  int bpn;        ///< binary bytes per number
  int wpn;        ///< binary words per number
  Op4Storage storage;
};

/// A run of consecutive rows [first, first+count) of one column, with the index
/// of its first value in the column's value array.
struct Run {
  int first, count, k;
};

template <class T>
class MatrixWriter {
public:
  MatrixWriter(Sink& out, const Op4WriteOptions& o, const Layout& lay, const Eigen::SparseMatrix<T>& a)
      : m_out(out), m_o(o), m_l(lay), m_a(a), m_swap((o.endian == Endian::Big) != host_big()) {
    m_digits = o.digits > 0 ? o.digits : (lay.single ? 9 : 16);
    m_width = m_digits + 7;
    m_per_line = std::max(1, 80 / m_width);
  }

  void write(const std::string& name, int form) {
    const Eigen::Index rows = m_a.rows(), cols = m_a.cols();
    const bool big = m_l.storage == Op4Storage::BigMat;
    const std::int64_t nrow = big ? -static_cast<std::int64_t>(rows) : static_cast<std::int64_t>(rows);
    if (m_o.encoding == Op4Encoding::Ascii) {
      m_out.append(fmt::format("{:8d}{:8d}{:8d}{:8d}{:<8s}1P,{}E{}.{}\n", cols, nrow, form, m_l.type, name, m_per_line,
                               m_width, m_digits));
    } else {
      const int wb = m_o.word_bytes;
      const std::size_t name_bytes = wb == 4 ? 8 : 16;
      const std::size_t len = 4 * wb + name_bytes;
      marker(len);
      word(cols);
      word(nrow);
      word(form);
      word(m_l.type);
      std::string nm = name;
      nm.resize(name_bytes, ' ');
      m_out.append(nm.data(), nm.size());
      marker(len);
    }
    std::vector<Run> runs;
    for (Eigen::Index c = 0; c < cols; ++c) {
      const int b = m_a.outerIndexPtr()[c], e = m_a.outerIndexPtr()[c + 1];
      if (b == e) continue;  // null columns are not written
      if (m_l.storage == Op4Storage::Dense) dense_column(c, b, e);
      else {
        split_runs(b, e, runs);
        sparse_column(c, runs, big);
      }
    }
    closing(cols);
  }

private:
  // -- binary primitives
  void marker(std::size_t len) { uint_bytes(len, m_o.marker_bytes); }
  void word(std::int64_t v) { uint_bytes(static_cast<std::uint64_t>(v), m_o.word_bytes); }
  void uint_bytes(std::uint64_t v, int n) {
    char* p = m_out.grow(static_cast<std::size_t>(n));
    if (n == 4) {
      std::uint32_t u = static_cast<std::uint32_t>(v);
      if (m_swap) u = __builtin_bswap32(u);
      std::memcpy(p, &u, 4);
    } else {
      std::uint64_t u = v;
      if (m_swap) u = __builtin_bswap64(u);
      std::memcpy(p, &u, 8);
    }
  }
  /// A value rounded to single precision; one beyond its range is refused, not written as infinity.
  static double to_single(double v) {
    const float f = static_cast<float>(v);
    if (std::isinf(f) && std::isfinite(v))
      throw InputError("OP4 value " + fmt::format("{:.17g}", v) + " overflows single precision");
    return f;
  }
  /// Writes one number at p (bpn bytes).
  void put_number(char* p, double v) const {
    if (m_l.bpn == 4) {
      const float f = static_cast<float>(to_single(v));
      std::uint32_t u;
      std::memcpy(&u, &f, 4);
      if (m_swap) u = __builtin_bswap32(u);
      std::memcpy(p, &u, 4);
    } else {
      const double d = m_l.single ? to_single(v) : v;
      std::uint64_t u;
      std::memcpy(&u, &d, 8);
      if (m_swap) u = __builtin_bswap64(u);
      std::memcpy(p, &u, 8);
    }
  }
  void binary_terms(const T* values, const int* rows, int count, int first_row, int nrows_span) {
    // nrows_span terms starting at first_row; rows not in `rows` are zero (dense gaps).
    const std::size_t bytes = static_cast<std::size_t>(nrows_span) * m_l.npt * m_l.bpn;
    char* p = m_out.grow(bytes);
    if constexpr (std::is_same_v<T, double>) {
      if (count == nrows_span && m_l.bpn == 8 && !m_l.single && !m_swap) {
        std::memcpy(p, values, bytes);  // real double in the host's byte order: the values as they are
        return;
      }
    }
    if (count == nrows_span) {
      for (int t = 0; t < count; ++t) {
        put_number(p, re_of(values[t]));
        p += m_l.bpn;
        if (m_l.cx) { put_number(p, im_of(values[t])); p += m_l.bpn; }
      }
      return;
    }
    std::memset(p, 0, bytes);  // +0.0 in either byte order
    for (int t = 0; t < count; ++t) {
      char* q = p + static_cast<std::size_t>(rows[t] - first_row) * m_l.npt * m_l.bpn;
      put_number(q, re_of(values[t]));
      if (m_l.cx) put_number(q + m_l.bpn, im_of(values[t]));
    }
  }

  // -- ASCII primitives
  void number_text(char* p, double v) {
    if (!std::isfinite(v)) throw InputError("OP4 ASCII cannot hold the value " + std::to_string(v));
    if (m_l.single) v = to_single(v);
    if (fast_number_text(p, v)) return;
    char buf[64];
    auto r = fmt::format_to_n(buf, sizeof buf - 1, "{:.{}E}", v, m_digits);
    std::size_t n = r.size;
    // A 3-digit exponent: Fortran drops the 'E' ("1.5-100") to keep the field width.
    char* e = static_cast<char*>(std::memchr(buf, 'E', n));
    if (e && buf + n - e == 5) {
      std::memmove(e, e + 1, static_cast<std::size_t>(buf + n - e - 1));
      --n;
    }
    const std::size_t pad = static_cast<std::size_t>(m_width) > n ? m_width - n : 0;
    std::memset(p, ' ', pad);
    std::memcpy(p + pad, buf, n);
  }
  /// The fast path: the shortest digits that read back to the value (Ryu, through
  /// std::to_chars; of the float for single precision), padded with zeros
  /// to the field's digits. The text reads back to exactly the same value as the
  /// correctly rounded "%.*E" would (both are exact), at a tenth of the cost.
  /// Returns false when the shortest form has more digits than the field.
  bool fast_number_text(char* p, double v) const {
    // std::to_chars without precision: the shortest round-trip form ("5.4532186e+16").
    char buf[48];
    const std::to_chars_result r =
        m_l.single ? std::to_chars(buf, buf + sizeof buf, static_cast<float>(v), std::chars_format::scientific)
                   : std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
    if (r.ec != std::errc()) return false;
    const char* q = buf;
    const char* end = r.ptr;
    const bool neg = *q == '-';
    if (neg) ++q;
    char digits[40];
    int nd = 0, point = -1;
    for (; q < end && *q != 'e'; ++q) {
      if (*q == '.') {
        point = nd;
        continue;
      }
      if (*q < '0' || *q > '9' || nd == 40) return false;  // inf, nan
      digits[nd++] = *q;
    }
    if (nd == 0) return false;
    if (point < 0) point = nd;
    int ex = 0;
    if (q < end) {  // 'e', sign, digits
      ++q;
      const bool eneg = q < end && *q == '-';
      if (q < end && (*q == '-' || *q == '+')) ++q;
      for (; q < end; ++q) ex = ex * 10 + (*q - '0');
      if (eneg) ex = -ex;
    }
    // Normalise to d.ddd x 10^ex10: drop leading and trailing zeros.
    int first = 0;
    while (first < nd - 1 && digits[first] == '0') ++first;
    int last = nd;
    while (last > first + 1 && digits[last - 1] == '0') --last;
    const bool zero = digits[first] == '0';
    const int ex10 = zero ? 0 : point - first - 1 + ex;
    const int nsig = last - first;
    if (nsig > m_digits + 1) return false;
    char out[48];
    std::size_t n = 0;
    if (neg) out[n++] = '-';
    out[n++] = digits[first];
    out[n++] = '.';
    for (int k = 1; k <= m_digits; ++k) out[n++] = k < nsig ? digits[first + k] : '0';
    const int aex = ex10 < 0 ? -ex10 : ex10;
    if (aex < 100) out[n++] = 'E';  // Fortran drops the letter for 3-digit exponents
    out[n++] = ex10 < 0 ? '-' : '+';
    if (aex >= 100) out[n++] = static_cast<char>('0' + aex / 100);
    out[n++] = static_cast<char>('0' + aex / 10 % 10);
    out[n++] = static_cast<char>('0' + aex % 10);
    const std::size_t pad = static_cast<std::size_t>(m_width) > n ? m_width - n : 0;
    std::memset(p, ' ', pad);
    std::memcpy(p + pad, out, n);
    return true;
  }
  /// Writes `numbers` (already flattened re/im) as lines of m_per_line fields.
  void ascii_numbers(const std::vector<double>& numbers) {
    const std::size_t n = numbers.size();
    const std::size_t lines = (n + m_per_line - 1) / m_per_line;
    char* p = m_out.grow(n * m_width + lines);
    for (std::size_t i = 0; i < n; ++i) {
      number_text(p, numbers[i]);
      p += m_width;
      if ((i + 1) % m_per_line == 0 || i + 1 == n) *p++ = '\n';
    }
  }
  void flatten(const T* values, const int* rows, int count, int first_row, int span, std::vector<double>& out) {
    out.assign(static_cast<std::size_t>(span) * m_l.npt, 0.0);
    for (int t = 0; t < count; ++t) {
      const std::size_t i = static_cast<std::size_t>(rows[t] - first_row) * m_l.npt;
      out[i] = re_of(values[t]);
      if (m_l.cx) out[i + 1] = im_of(values[t]);
    }
  }

  // -- columns
  void dense_column(Eigen::Index c, int b, int e) {
    const int* rows = m_a.innerIndexPtr() + b;
    const T* vals = m_a.valuePtr() + b;
    const int count = e - b;
    const int first = rows[0], span = rows[count - 1] - first + 1;
    if (m_o.encoding == Op4Encoding::Ascii) {
      m_out.append(fmt::format("{:8d}{:8d}{:8d}\n", c + 1, first + 1, static_cast<std::int64_t>(span) * m_l.npt));
      flatten(vals, rows, count, first, span, m_numbers);
      ascii_numbers(m_numbers);
      return;
    }
    const std::int64_t nw = static_cast<std::int64_t>(span) * m_l.npt * m_l.wpn;
    const std::size_t len = static_cast<std::size_t>(3 + nw) * m_o.word_bytes;
    marker(len);
    word(c + 1);
    word(first + 1);
    word(nw);
    binary_terms(vals, rows, count, first, span);
    marker(len);
  }

  /// Runs of consecutive rows, cut so each string header can encode its length.
  void split_runs(int b, int e, std::vector<Run>& runs) {
    runs.clear();
    const int* rows = m_a.innerIndexPtr();
    // Non-BIGMAT: IS=(L+1)*65536+IROW must fit a 32-bit word, and 8 digits in ASCII (I8).
    const int words_per_term = m_l.npt * m_l.wpn;
    int max_words = m_l.storage == Op4Storage::BigMat ? (1 << 30) : (m_o.encoding == Op4Encoding::Ascii ? 1523 : 32766);
    const int max_terms = std::max(1, max_words / words_per_term);
    for (int k = b; k < e;) {
      int j = k + 1;
      while (j < e && rows[j] == rows[j - 1] + 1 && j - k < max_terms) ++j;
      runs.push_back(Run{rows[k], j - k, k});
      k = j;
    }
  }

  void sparse_column(Eigen::Index c, const std::vector<Run>& runs, bool big) {
    const int hdr = big ? 2 : 1;
    std::int64_t nw = 0;
    for (const Run& r : runs) nw += hdr + static_cast<std::int64_t>(r.count) * m_l.npt * m_l.wpn;
    if (m_o.encoding == Op4Encoding::Ascii) {
      m_out.append(fmt::format("{:8d}{:8d}{:8d}\n", c + 1, 0, nw));
      for (const Run& r : runs) {
        const std::int64_t L = static_cast<std::int64_t>(r.count) * m_l.npt * m_l.wpn;
        if (big) m_out.append(fmt::format("{:8d}{:8d}\n", L + 1, r.first + 1));
        else m_out.append(fmt::format("{:8d}\n", (L + 1) * 65536 + r.first + 1));
        flatten(m_a.valuePtr() + r.k, m_a.innerIndexPtr() + r.k, r.count, r.first, r.count, m_numbers);
        ascii_numbers(m_numbers);
      }
      return;
    }
    const std::size_t len = static_cast<std::size_t>(3 + nw) * m_o.word_bytes;
    marker(len);
    word(c + 1);
    word(0);
    word(nw);
    for (const Run& r : runs) {
      const std::int64_t L = static_cast<std::int64_t>(r.count) * m_l.npt * m_l.wpn;
      if (big) {
        word(L + 1);
        word(r.first + 1);
      } else {
        word((L + 1) * 65536 + r.first + 1);
      }
      binary_terms(m_a.valuePtr() + r.k, m_a.innerIndexPtr() + r.k, r.count, r.first, r.count);
    }
    marker(len);
  }

  void closing(Eigen::Index cols) {
    // "A record with the last column number plus 1 and at least one value."
    if (m_o.encoding == Op4Encoding::Ascii) {
      m_out.append(fmt::format("{:8d}{:8d}{:8d}\n", cols + 1, 1, 1));
      m_numbers.assign(1, 1.0);
      ascii_numbers(m_numbers);
      return;
    }
    const std::size_t len = static_cast<std::size_t>(3 + m_l.wpn) * m_o.word_bytes;
    marker(len);
    word(cols + 1);
    word(1);
    word(m_l.wpn);
    put_number(m_out.grow(static_cast<std::size_t>(m_l.bpn)), 1.0);
    marker(len);
  }

  Sink& m_out;
  const Op4WriteOptions& m_o;
  Layout m_l;
  const Eigen::SparseMatrix<T>& m_a;
  bool m_swap;
  int m_digits = 16, m_width = 23, m_per_line = 3;
  std::vector<double> m_numbers;
};

void check_options(const Op4WriteOptions& o) {
  if (o.marker_bytes != 4 && o.marker_bytes != 8) throw InputError("OP4 record markers are 4 or 8 bytes");
  if (o.word_bytes != 4 && o.word_bytes != 8) throw InputError("OP4 words are 4 or 8 bytes");
  if (o.precision < 0 || o.precision > 4) throw InputError("OP4 precision must be 1-4 (0 keeps the matrix's)");
  if (o.digits < 0 || o.digits > 30) throw InputError("OP4 ASCII digits must be 1-30");
}

void write_all(Sink& sink, const std::vector<Op4Matrix>& matrices, const Op4WriteOptions& o) {
  check_options(o);
  for (const Op4Matrix& m : matrices) {
    if (m.name.empty()) throw InputError("OP4 matrix without a name");
    if (m.name.size() > 8 && o.encoding == Op4Encoding::Binary)
      throw InputError("OP4 matrix name '" + m.name + "' is longer than the 8 characters a binary header holds");
    const int type = o.precision ? o.precision : static_cast<int>(m.precision);
    const bool cx = type >= 3;
    if (m.is_complex() && !cx)
      throw InputError("OP4 matrix " + m.name + " is complex; precision " + std::to_string(type) +
                                  " would drop its imaginary part");
    Layout l;
    l.type = type;
    l.cx = cx;
    l.single = type == 1 || type == 3;
    l.npt = cx ? 2 : 1;
    l.bpn = (o.word_bytes == 8 || !l.single) ? 8 : 4;
    l.wpn = std::max(1, l.bpn / o.word_bytes);
    l.storage = o.storage;
    const Eigen::Index rows = m.is_complex() ? m.complex.rows() : m.real.rows();
    if (l.storage == Op4Storage::Sparse && rows >= 65536) l.storage = Op4Storage::BigMat;
    const std::string& name = m.name;
    if (cx) {
      SparseComplex a = m.as_complex();
      a.makeCompressed();
      MatrixWriter<std::complex<double>>(sink, o, l, a).write(name, m.form);
    } else if (m.real.isCompressed()) {
      MatrixWriter<double>(sink, o, l, m.real).write(name, m.form);
    } else {
      SparseReal a = m.real;
      a.makeCompressed();
      MatrixWriter<double>(sink, o, l, a).write(name, m.form);
    }
  }
}

}  // namespace

std::string write_op4_string(const std::vector<Op4Matrix>& matrices, const Op4WriteOptions& options) {
  Sink sink(-1, "");
  write_all(sink, matrices, options);
  return std::move(sink.text());
}

void write_op4(const std::string& path, const std::vector<Op4Matrix>& matrices, const Op4WriteOptions& options) {
  check_options(options);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw InputError("cannot write " + path + ": " + std::strerror(errno));
  try {
    Sink sink(fd, path);
    write_all(sink, matrices, options);
    sink.flush();
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw InputError("error closing " + path + ": " + std::strerror(errno));
}

}  // namespace ssid::formats
