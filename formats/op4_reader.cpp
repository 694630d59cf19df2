/// \file op4_reader.cpp
/// Reading OP4 files: encoding detection, the ASCII and the binary record parsers,
/// and the assembly of columns into Eigen sparse matrices.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <memory>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "formats/op4.hpp"
#include "formats/parse_error.hpp"
#include "formats/text_util.hpp"

namespace ssid::formats {

namespace {

bool complex_type(int t) { return t == 3 || t == 4; }
bool single_type(int t) { return t == 1 || t == 3; }

/// Asks the kernel for transparent huge pages on a large fresh allocation: the
/// first touch of hundreds of MB in 4 KiB pages costs more than parsing them
/// (measured in bench_op4, docs/performance.md). Advisory; no effect elsewhere.
void advise_huge_pages(void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t huge = 2u << 20;
  if (bytes < 4 * huge) return;
  const std::uintptr_t b = (reinterpret_cast<std::uintptr_t>(p) + huge - 1) & ~(huge - 1);
  const std::uintptr_t e = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(huge - 1);
  if (e > b) ::madvise(reinterpret_cast<void*>(b), e - b, MADV_HUGEPAGE);
#else
  (void)p;
  (void)bytes;
#endif
}

/// Compressed-column storage of one Eigen sparse matrix, filled in place (no
/// intermediate copy: at hundreds of MB the copy and its page faults cost more
/// than the parsing).
template <class T>
class CscTarget {
public:
  void start(Eigen::Index rows, Eigen::Index cols) {
    m.resize(rows, cols);  // compressed, outer indices zero
    m_outer = m.outerIndexPtr();
  }
  void reserve(std::size_t n) {
    if (n > m_cap) grow(n);
  }
  void push(int row, const T& v) {
    if (m_n == m_cap) grow(std::max<std::size_t>(1024, 2 * m_cap));
    m_inner[m_n] = row;
    m_val[m_n] = v;
    ++m_n;
  }
  /// Room for `extra` more terms (push_unchecked may then be used that many times).
  void ensure(std::size_t extra) {
    if (m_n + extra > m_cap) grow(std::max<std::size_t>(m_n + extra, 2 * m_cap));
  }
  /// Stores a term unless it is an exact zero; ensure() first.
  void push_unchecked(int row, const T& v) {
    m_inner[m_n] = row;
    m_val[m_n] = v;
    m_n += v != T(0);
  }
  std::size_t size() const { return m_n; }
  /// Drops the terms from position n on (n <= size()).
  void truncate(std::size_t n) { m_n = n; }
  int* outer() { return m_outer; }
  int* inner_data() { return m_inner; }
  T* values_data() { return m_val; }
  const int* inner() const { return m_inner; }
  const T* values() const { return m_val; }
  /// Sets the final size; frees the unused reserve when it is large.
  Eigen::SparseMatrix<T>& done() {
    m.data().resize(static_cast<Eigen::Index>(m_n));
    if (m_cap > m_n + m_n / 4 + 4096) m.data().squeeze();
    return m;
  }
  Eigen::SparseMatrix<T> m;

private:
  void grow(std::size_t cap) {
    m.data().resize(static_cast<Eigen::Index>(m_n));  // the terms so far (no reallocation)
    m.data().resize(static_cast<Eigen::Index>(cap));  // reallocates keeping them
    m_cap = cap;
    m_inner = m.innerIndexPtr();
    m_val = m.valuePtr();
    advise_huge_pages(m_inner + m_n, (cap - m_n) * sizeof(int));
    advise_huge_pages(m_val + m_n, (cap - m_n) * sizeof(T));
  }
  int* m_outer = nullptr;
  int* m_inner = nullptr;
  T* m_val = nullptr;
  std::size_t m_n = 0, m_cap = 0;
};

/// Collects the terms of one matrix column by column (columns arrive in increasing
/// order) straight into the matrix's compressed-column arrays; exact zeros are dropped.
class ColumnBuilder {
public:
  ColumnBuilder(Eigen::Index rows, Eigen::Index cols, bool is_complex)
      : m_rows(rows), m_cols(cols), m_complex(is_complex) {
    if (m_complex) m_cx.start(rows, cols);
    else m_re.start(rows, cols);
  }

  /// Starts column c (0-based); columns must increase.
  void begin_column(Eigen::Index c) {
    int* outer = m_complex ? m_cx.outer() : m_re.outer();
    const int n = static_cast<int>(m_complex ? m_cx.size() : m_re.size());
    for (Eigen::Index k = m_current + 1; k <= c; ++k) outer[k] = n;
    m_current = c;
    m_last_row = -1;
  }
  void add(Eigen::Index row, double re) {
    if (re == 0.0) return;
    note_row(row);
    m_re.push(static_cast<int>(row), re);
  }
  void add(Eigen::Index row, double re, double im) {
    if (re == 0.0 && im == 0.0) return;
    note_row(row);
    m_cx.push(static_cast<int>(row), std::complex<double>(re, im));
  }
  void reserve(std::size_t n) {
    if (m_complex) m_cx.reserve(n);
    else m_re.reserve(n);
  }
  /// Real terms of rows row0, row0+1, ... (0-based), value(t) for t < terms; zeros dropped.
  template <class Value>
  void add_run(Eigen::Index row0, std::int64_t terms, Value value) {
    if (terms <= 0) return;
    if (row0 <= m_last_row) m_sorted = false;
    m_last_row = row0 + terms - 1;
    m_re.ensure(static_cast<std::size_t>(terms));
    for (std::int64_t t = 0; t < terms; ++t) m_re.push_unchecked(static_cast<int>(row0 + t), value(t));
  }

  void finish(Op4Matrix& m) {
    begin_column(m_cols);  // outer[last+1 .. cols] = number of terms
    if (m_complex) fill(m.complex, m_cx);
    else fill(m.real, m_re);
  }

private:
  void note_row(Eigen::Index row) {
    if (row <= m_last_row) m_sorted = false;
    m_last_row = row;
  }
  template <class T>
  void fill(Eigen::SparseMatrix<T>& out, CscTarget<T>& a) {
    if (!m_sorted) {
      // Strings given out of row order (allowed by the format, never written by
      // NASTRAN): each column sorted in place, a row given twice keeping its last
      // value. Column by column, so the cost follows the terms and the columns,
      // never the row count (a header may declare 2^31 rows).
      int* outer = a.outer();
      int* inner = a.inner_data();
      T* val = a.values_data();
      std::vector<std::pair<int, T>> col;
      int kept = 0;
      for (Eigen::Index c = 0; c < m_cols; ++c) {
        col.clear();
        for (int k = outer[c]; k < outer[c + 1]; ++k) col.emplace_back(inner[k], val[k]);
        std::stable_sort(col.begin(), col.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        outer[c] = kept;
        for (std::size_t k = 0; k < col.size(); ++k) {
          if (k + 1 < col.size() && col[k + 1].first == col[k].first) continue;  // a later value of the same row wins
          inner[kept] = col[k].first;
          val[kept] = col[k].second;
          ++kept;
        }
      }
      outer[m_cols] = kept;
      a.truncate(static_cast<std::size_t>(kept));
    }
    out.swap(a.done());
  }

  Eigen::Index m_rows, m_cols;
  bool m_complex;
  Eigen::Index m_current = -1, m_last_row = -1;
  bool m_sorted = true;
  CscTarget<double> m_re;
  CscTarget<std::complex<double>> m_cx;
};

/// A compressed-column matrix from terms sorted by column, then row, built in
/// O(columns + terms): setFromTriplets would also cost O(rows) for its transposed
/// copy, and a header may declare 2^31 rows for a matrix of one column.
template <class T>
Eigen::SparseMatrix<T> from_sorted(Eigen::Index rows, Eigen::Index cols, const std::vector<Eigen::Triplet<T>>& t) {
  Eigen::SparseMatrix<T> a(rows, cols);  // compressed, outer indices zero
  a.resizeNonZeros(static_cast<Eigen::Index>(t.size()));
  int* outer = a.outerIndexPtr();
  for (const auto& e : t) ++outer[e.col() + 1];
  for (Eigen::Index c = 0; c < cols; ++c) outer[c + 1] += outer[c];
  for (std::size_t k = 0; k < t.size(); ++k) {
    a.innerIndexPtr()[k] = t[k].row();
    a.valuePtr()[k] = t[k].value();
  }
  return a;
}

/// Form-specific completion (documented in docs/op4.md).
void complete_forms(Op4Matrix& m, const Op4ReadOptions& opt) {
  auto mirror = [&](auto& a) {
    using T = typename std::decay_t<decltype(a)>::Scalar;
    bool upper = false, lower = false;
    for (int c = 0; c < a.outerSize(); ++c)
      for (typename std::decay_t<decltype(a)>::InnerIterator it(a, c); it; ++it) {
        if (it.row() < it.col()) upper = true;
        if (it.row() > it.col()) lower = true;
      }
    if (upper == lower) return;  // complete (or diagonal): kept as stored
    Eigen::SparseMatrix<T> t = a.transpose();
    Eigen::SparseMatrix<T> d = a;
    d.prune([](Eigen::Index r, Eigen::Index c, const T&) { return r == c; });
    a = Eigen::SparseMatrix<T>(a + t - d);
  };
  if (opt.expand_symmetric && m.form == op4_form::Symmetric && m.rows == m.cols) {
    if (m.is_complex()) mirror(m.complex);
    else mirror(m.real);
  }
  const bool identity = m.form == op4_form::Identity && m.rows == m.cols;
  const bool pseudo = m.form == op4_form::PseudoIdentity;
  if (opt.expand_identity && (identity || pseudo) && m.nonzeros() == 0) {
    auto ones = [&](auto& a) {
      using T = typename std::decay_t<decltype(a)>::Scalar;
      std::vector<Eigen::Triplet<T>> t;
      for (Eigen::Index k = 0; k < std::min(m.rows, m.cols); ++k) t.emplace_back(k, k, T(1));
      a = from_sorted(m.rows, m.cols, t);
    };
    if (m.is_complex()) ones(m.complex);
    else ones(m.real);
  }
  if (opt.expand_diagonal && m.form == op4_form::Diagonal && m.cols == 1 && m.rows > 1) {
    auto diag = [&](auto& a) {
      using T = typename std::decay_t<decltype(a)>::Scalar;
      std::vector<Eigen::Triplet<T>> t;
      for (typename std::decay_t<decltype(a)>::InnerIterator it(a, 0); it; ++it)
        t.emplace_back(it.row(), it.row(), it.value());
      a = from_sorted(m.rows, m.rows, t);
    };
    if (m.is_complex()) diag(m.complex);
    else diag(m.real);
    m.cols = m.rows;
  }
}

/// A header's column count (or, for a diagonal matrix kept as one column, its row
/// count) sizes the column index array, 4 bytes per column, before any data is
/// seen. A lying header in a small file must not allocate gigabytes: the count
/// is refused when that array would exceed both 256 MiB and 16 times the file.
/// Returns the message, or "" when the size is plausible.
std::string implausible_size(std::int64_t ncol, std::int64_t nrow, std::int64_t form, std::size_t file_size) {
  const std::int64_t n = (form == op4_form::Diagonal && ncol == 1) ? std::max(ncol, nrow) : ncol;
  const std::uint64_t bytes = 4u * static_cast<std::uint64_t>(n);
  if (bytes <= (256u << 20) || bytes <= 16u * static_cast<std::uint64_t>(file_size)) return "";
  return "header gives " + std::to_string(n) + " columns, implausible for a file of " + std::to_string(file_size) +
         " bytes (more than 64 M columns and 4 per byte of the file)";
}

/// An identity (form 8) or pseudo-identity (form 9) stored without terms is built
/// by complete_forms, about 32 bytes per diagonal term at its peak: as for the
/// column count, a header asking for gigabytes from a small file is refused — when
/// those bytes exceed both 256 MiB and 16 times the file. Returns the message, or
/// "" when the expansion is plausible or not needed.
std::string implausible_expansion(const Op4Matrix& m, const Op4ReadOptions& opt, std::size_t file_size) {
  const bool identity = m.form == op4_form::Identity && m.rows == m.cols;
  const bool pseudo = m.form == op4_form::PseudoIdentity;
  if (!opt.expand_identity || !(identity || pseudo) || m.nonzeros() != 0) return "";
  const auto n = static_cast<std::uint64_t>(std::min(m.rows, m.cols));
  const std::uint64_t bytes = 32u * n;
  if (bytes <= (256u << 20) || bytes <= 16u * static_cast<std::uint64_t>(file_size)) return "";
  return op4_form::name(m.form) + " matrix stored without terms: its " + std::to_string(n) +
         " diagonal terms are implausible for a file of " + std::to_string(file_size) +
         " bytes (more than 8 M terms and 1 per 2 bytes of the file)";
}

std::string clean_name(std::string_view raw) {
  std::string s;
  for (char c : raw)
    if (c != ' ' && c != '\0' && c != '\t') s += c;
  return s;
}

// ---------------------------------------------------------------------------
// ASCII

/// One number in Fortran E/D output: optional sign, mantissa, exponent with E, D
/// or only a sign (Fortran drops the letter for 3-digit exponents). Values may
/// abut ("-3.9E+02-4.6E+07"). Returns the end of the number, nullptr on garbage.
const char* scan_number(const char* p, const char* end, double& value) {
  const char* start = p;
  if (p < end && (*p == '+' || *p == '-')) ++p;
  const char* digits = p;
  while (p < end && *p >= '0' && *p <= '9') ++p;
  if (p < end && *p == '.') {
    ++p;
    while (p < end && *p >= '0' && *p <= '9') ++p;
  }
  if (p == digits || (p == digits + 1 && *digits == '.')) return nullptr;
  const char* mant_end = p;
  char letter = 0;
  const char* exp_begin = nullptr;
  if (p < end && (*p == 'E' || *p == 'e' || *p == 'D' || *p == 'd')) {
    letter = *p;
    ++p;
    exp_begin = p;
    if (p < end && (*p == '+' || *p == '-')) ++p;
    const char* ed = p;
    while (p < end && *p >= '0' && *p <= '9') ++p;
    if (p == ed) return nullptr;
  } else if (p + 1 < end && (*p == '+' || *p == '-') && p[1] >= '0' && p[1] <= '9') {
    const char* q = p + 1;
    while (q < end && *q >= '0' && *q <= '9') ++q;
    if (q == end || *q != '.') {  // not the sign of the next value
      exp_begin = p;
      p = q;
    }
  }
  const char* b = start;
  if (*b == '+') ++b;
  if ((letter == 'E' || letter == 'e' || exp_begin == nullptr) && b == start) {
    auto r = std::from_chars(b, p, value);
    if (r.ec != std::errc() || r.ptr != p) return nullptr;
    return p;
  }
  char buf[64];
  std::size_t n = 0;
  for (const char* q = b; q < mant_end && n < 60; ++q) buf[n++] = *q;
  if (exp_begin) {
    buf[n++] = 'E';
    for (const char* q = exp_begin; q < p && n < 63; ++q) buf[n++] = *q;
  }
  auto r = std::from_chars(buf, buf + n, value);
  if (r.ec != std::errc() || r.ptr != buf + n) return nullptr;
  return p;
}

class AsciiReader {
public:
  AsciiReader(const char* data, std::size_t size, const std::string& file, const Op4ReadOptions& opt)
      : m_begin(data), m_p(data), m_end(data + size), m_file(file), m_opt(opt) {}

  std::vector<Op4Matrix> read_all() {
    std::vector<Op4Matrix> out;
    std::string_view line;
    while (next_line(line)) {
      if (detail::trim(line).empty()) continue;
      out.push_back(read_matrix(line));
    }
    return out;
  }

private:
  [[noreturn]] void fail(const std::string& msg, std::uint32_t line = 0) const {
    const bool name_column = m_col > 0 && msg.compare(0, 7, "column ") != 0;
    throw ParseError(SourceLocation{m_file, line ? line : m_line, {}},
                     m_context + (name_column ? "column " + std::to_string(m_col) + ": " : std::string()) + msg);
  }

  bool next_line(std::string_view& line) {
    if (m_p >= m_end) return false;
    const char* nl = static_cast<const char*>(std::memchr(m_p, '\n', static_cast<std::size_t>(m_end - m_p)));
    const char* e = nl ? nl : m_end;
    line = std::string_view(m_p, static_cast<std::size_t>(e - m_p));
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    m_p = nl ? nl + 1 : m_end;
    ++m_line;
    return true;
  }
  /// The next line without consuming it.
  bool peek_line(std::string_view& line) {
    const char* p = m_p;
    std::uint32_t l = m_line;
    bool ok = next_line(line);
    m_p = p;
    m_line = l;
    return ok;
  }

  /// Numeric data lines start with a number holding a decimal point; header,
  /// column and string lines hold integers only.
  static bool is_numeric(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && line[i] == ' ') ++i;
    bool dot = false;
    for (; i < line.size() && line[i] != ' '; ++i) {
      const char c = line[i];
      if (c == '.') dot = true;
      else if (!((c >= '0' && c <= '9') || c == '+' || c == '-' || c == 'E' || c == 'e' || c == 'D' || c == 'd'))
        return false;
    }
    return dot;
  }

  /// Integers of a line: whitespace separated, or in fixed 8-column fields when
  /// they touch. Fails the read when the line does not hold exactly `n` of them.
  void ints(std::string_view line, std::size_t n, std::int64_t* out, const char* what) {
    std::size_t k = 0, i = 0;
    bool ok = true;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
      if (i >= line.size()) break;
      std::size_t j = i;
      while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
      if (k == n) { ok = false; break; }
      const char* b = line.data() + i;
      if (*b == '+') ++b;
      auto r = std::from_chars(b, line.data() + j, out[k]);
      if (r.ec != std::errc() || r.ptr != line.data() + j) { ok = false; break; }
      ++k;
      i = j;
    }
    if (ok && k == n) return;
    // Fixed I8 fields (values that fill their field touch the next one).
    if (line.size() >= 8 * n - 7 && line.size() <= 8 * n) {
      bool fixed = true;
      for (std::size_t f = 0; f < n && fixed; ++f) {
        std::string_view s = detail::trim(line.substr(8 * f, 8));
        if (!s.empty() && s[0] == '+') s.remove_prefix(1);
        auto r = std::from_chars(s.data(), s.data() + s.size(), out[f]);
        fixed = !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
      }
      if (fixed) return;
    }
    fail(std::string("expected ") + what + " (" + std::to_string(n) + " integer" + (n > 1 ? "s" : "") + "), got " +
         detail::quoted(detail::trim(line)));
  }

  /// Reads the numeric lines that follow into `values`; returns how many.
  std::size_t numbers(std::vector<double>& values) {
    values.clear();
    std::string_view line;
    while (true) {
      // One scan per line: find its end, consume it only when it holds numbers.
      if (m_p >= m_end) break;
      const char* nl = static_cast<const char*>(std::memchr(m_p, '\n', static_cast<std::size_t>(m_end - m_p)));
      const char* le = nl ? nl : m_end;
      line = std::string_view(m_p, static_cast<std::size_t>(le - m_p));
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (!is_numeric(line)) break;
      m_p = nl ? nl + 1 : m_end;
      ++m_line;
      const char* p = line.data();
      const char* e = p + line.size();
      while (true) {
        while (p < e && (*p == ' ' || *p == '\t')) ++p;
        if (p >= e) break;
        double v;
        const char* q = scan_number(p, e, v);
        if (!q) {
          const char* t = p;
          while (t < e && *t != ' ') ++t;
          fail("expected a number at column " + std::to_string(p - line.data() + 1) + ", got " +
               detail::quoted(std::string_view(p, static_cast<std::size_t>(t - p))));
        }
        values.push_back(v);
        p = q;
      }
    }
    return values.size();
  }

  Op4Matrix read_matrix(std::string_view header) {
    const std::uint32_t header_line = m_line;
    m_context.clear();
    m_col = 0;
    std::int64_t h[4];
    std::string_view rest;
    {
      // NCOL, NROW, FORM, TYPE in I8 fields (columns 1-32), then the name and format.
      bool fixed = header.size() > 32;
      for (int f = 0; f < 4 && fixed; ++f) {
        std::string_view s = detail::trim(header.substr(8 * f, 8));
        auto r = std::from_chars(s.data(), s.data() + s.size(), h[f]);
        fixed = !s.empty() && r.ec == std::errc() && r.ptr == s.data() + s.size();
      }
      if (fixed) {
        rest = header.substr(32);
      } else {
        // Free spacing: four integer tokens, then the rest.
        std::size_t i = 0;
        for (int f = 0; f < 4; ++f) {
          while (i < header.size() && header[i] == ' ') ++i;
          std::size_t j = i;
          while (j < header.size() && ((header[j] >= '0' && header[j] <= '9') || header[j] == '-' || header[j] == '+')) ++j;
          const char* b = header.data() + i;
          if (b < header.data() + j && *b == '+') ++b;
          auto r = std::from_chars(b, header.data() + j, h[f]);
          if (i == j || r.ec != std::errc() || r.ptr != header.data() + j)
            fail("expected a matrix header (NCOL NROW FORM TYPE NAME), got " + detail::quoted(detail::trim(header)));
          i = j;
        }
        rest = header.substr(i);
      }
    }
    // Name (possibly longer than 8 characters) and the optional Fortran format.
    std::string name;
    {
      std::string up = detail::upper(rest);
      std::size_t k = up.find("1P,");
      std::string_view nm = rest;
      if (k != std::string::npos) nm = rest.substr(0, k);
      else {
        std::string_view t = detail::trim(rest);
        std::size_t sp = t.find_last_of(' ');
        if (sp != std::string_view::npos) {
          std::string_view last = t.substr(sp + 1);
          bool fmt = !last.empty() && last.find('.') != std::string_view::npos &&
                     last.find_first_of("EeDd") != std::string_view::npos;
          if (fmt) nm = t.substr(0, sp);
        }
      }
      name = clean_name(nm);
      // Declared width of a number ("1P,5E16.9" -> 16), for a reserve hint only.
      if (k != std::string::npos) {
        const std::size_t e = up.find_first_of("ED", k + 3);
        if (e != std::string::npos) {
          int w = 0;
          // At most 6 digits: a width beyond is no hint (and would overflow).
          for (std::size_t i = e + 1; i < up.size() && up[i] >= '0' && up[i] <= '9' && w < 100000; ++i)
            w = w * 10 + (up[i] - '0');
          m_declared_width = w;
        }
      }
    }
    const std::int64_t ncol = h[0], nrow_signed = h[1], form = h[2], type = h[3];
    m_context = "matrix " + (name.empty() ? std::string("(unnamed)") : detail::printable(name)) + ": ";
    if (ncol < 0 || nrow_signed == 0 || nrow_signed < -2147483647 || nrow_signed > 2147483647 || ncol > 2147483647)
      fail("header gives " + std::to_string(ncol) + " columns and " + std::to_string(nrow_signed) + " rows", header_line);
    if (type < 1 || type > 4) fail("TYPE must be 1-4 (precision), got " + std::to_string(type), header_line);
    if (auto msg = implausible_size(ncol, std::llabs(nrow_signed), form, static_cast<std::size_t>(m_end - m_begin));
        !msg.empty())
      fail(msg, header_line);

    Op4Matrix m;
    m.name = name;
    m.rows = std::llabs(nrow_signed);
    m.cols = ncol;
    m.form = static_cast<int>(form);
    m.precision = static_cast<Op4Precision>(type);
    const bool bigmat = nrow_signed < 0 || m.rows >= 65536;
    m.storage = Op4Storage::Dense;
    const bool cx = complex_type(static_cast<int>(type));
    const bool single = single_type(static_cast<int>(type));
    const int npt = cx ? 2 : 1;                           // numbers per term
    const int wpn = single ? 1 : 2;                       // words per number
    ColumnBuilder b(m.rows, m.cols, cx);
    if (m_declared_width >= 8) {
      // Numbers are at least as wide as declared: an upper bound on the terms left in the file.
      const std::size_t left = static_cast<std::size_t>(m_end - m_p) / static_cast<std::size_t>(m_declared_width * npt);
      b.reserve(std::min<std::size_t>(left, static_cast<std::size_t>(m.rows) * static_cast<std::size_t>(m.cols)));
    }
    m_declared_width = 0;
    std::vector<double> vals;
    std::int64_t last_col = 0;
    bool sparse_seen = false, dense_seen = false;

    auto put = [&](std::int64_t col, std::int64_t row0, std::size_t n) {
      if (n % npt) fail("column " + std::to_string(col) + ": an odd count of numbers (" + std::to_string(n) + ") in a complex matrix");
      const std::int64_t terms = static_cast<std::int64_t>(n) / npt;
      if (row0 < 1 || row0 + terms - 1 > m.rows)
        fail("column " + std::to_string(col) + ": rows " + std::to_string(row0) + ".." + std::to_string(row0 + terms - 1) +
             " lie outside 1.." + std::to_string(m.rows));
      // Single precision: the value NASTRAN holds is the float nearest the text.
      // (Rounded in place first: g++ 12 -O2 mis-vectorised the per-pair rounding.)
      if (single)
        for (std::size_t k = 0; k < n; ++k) vals[k] = static_cast<double>(static_cast<float>(vals[k]));
      if (!cx) {
        b.add_run(row0 - 1, terms, [&](std::int64_t t) { return vals[static_cast<std::size_t>(t)]; });
        return;
      }
      for (std::int64_t t = 0; t < terms; ++t) b.add(row0 - 1 + t, vals[2 * t], vals[2 * t + 1]);
    };

    std::string_view line;
    while (true) {
      if (!next_line(line))
        fail("file ends inside the matrix after column " + std::to_string(last_col) + " (no closing record NCOL+1)");
      if (detail::trim(line).empty()) continue;
      if (is_numeric(line)) fail("numbers where a column record (ICOL IROW NW) was expected");
      std::int64_t c[3];
      ints(line, 3, c, "a column record ICOL IROW NW");
      const std::int64_t icol = c[0], irow = c[1], nw = c[2];
      if (icol == ncol + 1) {  // closing record: skip its value(s)
        numbers(vals);
        break;
      }
      if (icol < 1 || icol > ncol) fail("column " + std::to_string(icol) + " out of range 1.." + std::to_string(ncol));
      if (icol <= last_col) fail("column " + std::to_string(icol) + " follows column " + std::to_string(last_col));
      if (nw < 0) fail("column " + std::to_string(icol) + ": negative word count NW=" + std::to_string(nw));
      last_col = icol;
      m_col = icol;
      b.begin_column(icol - 1);
      const std::uint32_t col_line = m_line;
      if (irow > 0) {
        dense_seen = true;
        const std::size_t n = numbers(vals);
        // NASTRAN counts ASCII dense columns in numbers; some writers count words.
        if (static_cast<std::int64_t>(n) != nw && static_cast<std::int64_t>(n) * wpn != nw)
          fail("column " + std::to_string(icol) + ": record says NW=" + std::to_string(nw) + " but " + std::to_string(n) +
                   " numbers follow",
               col_line);
        put(icol, irow, n);
      } else if (irow == 0) {
        sparse_seen = true;
        std::int64_t left = nw;
        while (left > 0) {
          if (!next_line(line) || is_numeric(line))
            fail("column " + std::to_string(icol) + ": expected a string header (" + std::to_string(left) +
                 " words of NW=" + std::to_string(nw) + " still to come)");
          std::int64_t L, row;
          std::int64_t two[2];
          bool big = bigmat;
          if (!big) {
            // A line with two integers is a BIGMAT string header whatever NROW says.
            std::string_view t = detail::trim(line);
            big = t.find(' ') != std::string_view::npos;
          }
          if (big) {
            ints(line, 2, two, "a BIGMAT string header L+1 IROW");
            L = two[0] - 1;
            row = two[1];
            left -= 2 + L;
          } else {
            std::int64_t is;
            ints(line, 1, &is, "a string header IS=(L+1)*65536+IROW");
            L = is / 65536 - 1;
            row = is - 65536 * (L + 1);
            left -= 1 + L;
          }
          if (L < 0) fail("column " + std::to_string(icol) + ": string header gives a negative length");
          const std::size_t n = numbers(vals);
          if (static_cast<std::int64_t>(n) * wpn != L && static_cast<std::int64_t>(n) != L)
            fail("column " + std::to_string(icol) + ": string header says " + std::to_string(L) + " words but " +
                 std::to_string(n) + " numbers follow");
          put(icol, row, n);
        }
        if (left != 0)
          fail("column " + std::to_string(icol) + ": strings hold more words than NW=" + std::to_string(nw), col_line);
      } else {
        fail("column " + std::to_string(icol) + ": negative IROW " + std::to_string(irow));
      }
    }
    m.storage = sparse_seen ? (bigmat ? Op4Storage::BigMat : Op4Storage::Sparse)
                            : (dense_seen ? Op4Storage::Dense : (bigmat ? Op4Storage::BigMat : Op4Storage::Sparse));
    b.finish(m);
    if (auto msg = implausible_expansion(m, m_opt, static_cast<std::size_t>(m_end - m_begin)); !msg.empty())
      fail(msg, header_line);
    complete_forms(m, m_opt);
    return m;
  }

  const char* m_begin;
  const char* m_p;
  const char* m_end;
  const std::string& m_file;
  const Op4ReadOptions& m_opt;
  std::uint32_t m_line = 0;
  std::int64_t m_col = 0;  ///< column being read, for messages
  int m_declared_width = 0;  ///< width of a number in the header's format, 0 when unknown
  std::string m_context;
};

// ---------------------------------------------------------------------------
// Binary

class BinaryReader {
public:
  BinaryReader(const unsigned char* data, std::size_t size, const std::string& file, const Op4ReadOptions& opt,
               const Op4FileInfo& info)
      : m_d(data), m_size(size), m_file(file), m_opt(opt), m_mb(info.marker_bytes), m_wb(info.word_bytes),
        m_swap((info.endian == Endian::Big) != host_big()) {}

  static bool host_big() {
    const std::uint16_t x = 1;
    unsigned char c;
    std::memcpy(&c, &x, 1);
    return c == 0;
  }

  std::vector<Op4Matrix> read_all() {
    std::vector<Op4Matrix> out;
    while (m_pos < m_size) out.push_back(read_matrix());
    return out;
  }

  /// Unsigned integer of `n` bytes (4 or 8) at `p` in the file's byte order.
  std::uint64_t raw(const unsigned char* p, int n) const {
    if (n == 4) {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return m_swap ? __builtin_bswap32(v) : v;
    }
    std::uint64_t v;
    std::memcpy(&v, p, 8);
    return m_swap ? __builtin_bswap64(v) : v;
  }
  std::int64_t word(const unsigned char* p) const {
    return m_wb == 4 ? static_cast<std::int64_t>(static_cast<std::int32_t>(raw(p, 4)))
                     : static_cast<std::int64_t>(raw(p, 8));
  }

private:
  struct Record {
    const unsigned char* p;
    std::size_t len;
    std::size_t offset;  ///< byte offset of the leading marker
  };

  [[noreturn]] void fail(const std::string& msg, std::size_t offset) const {
    throw ParseError(SourceLocation{m_file, 0, {}}, m_context + "byte offset " + std::to_string(offset) + ": " + msg);
  }

  Record record(const char* what) {
    const std::size_t off = m_pos;
    if (m_size - m_pos < static_cast<std::size_t>(m_mb))
      fail("file ends inside a record marker while reading " + std::string(what), off);
    const std::uint64_t len = m_mb == 4 ? raw(m_d + m_pos, 4) : raw(m_d + m_pos, 8);
    if (len > m_size - m_pos - m_mb || m_size - m_pos - m_mb - len < static_cast<std::size_t>(m_mb))
      fail("record marker announces " + std::to_string(len) + " bytes of " + what + " but only " +
               std::to_string(m_size - m_pos - m_mb) + " bytes remain (truncated file or wrong record marker)",
           off);
    const std::uint64_t tail = raw(m_d + m_pos + m_mb + len, m_mb);
    if (tail != len)
      fail("record markers disagree: " + std::to_string(len) + " before the record, " + std::to_string(tail) +
               " after it at byte offset " + std::to_string(m_pos + m_mb + len),
           off);
    Record r{m_d + m_pos + m_mb, static_cast<std::size_t>(len), off};
    m_pos += static_cast<std::size_t>(len) + 2 * m_mb;
    return r;
  }

  Op4Matrix read_matrix() {
    m_context.clear();
    const Record h = record("a matrix header");
    const std::size_t name_bytes = h.len > 4u * m_wb ? h.len - 4u * m_wb : 0;
    if (h.len < 4u * m_wb + 8 || h.len > 4u * m_wb + 16)
      fail("expected a matrix header record (NCOL NROW FORM TYPE NAME) but the record holds " + std::to_string(h.len) +
               " bytes",
           h.offset);
    const std::int64_t ncol = word(h.p), nrow_signed = word(h.p + m_wb), form = word(h.p + 2 * m_wb),
                       type = word(h.p + 3 * m_wb);
    const std::string name = clean_name(std::string_view(reinterpret_cast<const char*>(h.p + 4 * m_wb), name_bytes));
    m_context = "matrix " + (name.empty() ? std::string("(unnamed)") : detail::printable(name)) + ": ";
    if (ncol < 0 || nrow_signed == 0 || nrow_signed < -2147483647 || nrow_signed > 2147483647 || ncol > 2147483647)
      fail("header gives " + std::to_string(ncol) + " columns and " + std::to_string(nrow_signed) + " rows", h.offset);
    if (type < 1 || type > 4) fail("TYPE must be 1-4 (precision), got " + std::to_string(type), h.offset);
    if (auto msg = implausible_size(ncol, std::llabs(nrow_signed), form, m_size); !msg.empty()) fail(msg, h.offset);

    Op4Matrix m;
    m.name = name;
    m.rows = std::llabs(nrow_signed);
    m.cols = ncol;
    m.form = static_cast<int>(form);
    m.precision = static_cast<Op4Precision>(type);
    const bool bigmat = nrow_signed < 0 || m.rows >= 65536;
    const bool cx = complex_type(static_cast<int>(type));
    // 4-byte words: single precision numbers take one word, double two.
    // 8-byte words (64-bit NASTRAN): every number is one 8-byte real.
    const int bpn = (m_wb == 8 || !single_type(static_cast<int>(type))) ? 8 : 4;  // bytes per number
    const int wpn = bpn / m_wb > 0 ? bpn / m_wb : 1;                              // words per number
    const int npt = cx ? 2 : 1;
    const bool round_single = single_type(static_cast<int>(type));
    ColumnBuilder b(m.rows, m.cols, cx);
    // Reserve from the bytes left: an upper bound on the terms of this matrix.
    b.reserve(std::min<std::size_t>((m_size - m_pos) / (bpn * npt), static_cast<std::size_t>(m.rows) * m.cols));
    std::int64_t last_col = 0;
    bool sparse_seen = false, dense_seen = false;

    auto put = [&](std::int64_t col, std::int64_t row0, const unsigned char* p, std::int64_t words, std::size_t off) {
      if (words % (wpn * npt))
        fail("column " + std::to_string(col) + ": " + std::to_string(words) + " words do not make whole " +
                 (cx ? "complex " : "") + "terms",
             off);
      const std::int64_t terms = words / (wpn * npt);
      if (row0 < 1 || row0 + terms - 1 > m.rows)
        fail("column " + std::to_string(col) + ": rows " + std::to_string(row0) + ".." + std::to_string(row0 + terms - 1) +
                 " lie outside 1.." + std::to_string(m.rows),
             off);
      auto num = [&](const unsigned char* q) -> double {
        if (bpn == 4) {
          std::uint32_t u = static_cast<std::uint32_t>(raw(q, 4));
          float f;
          std::memcpy(&f, &u, 4);
          return f;
        }
        std::uint64_t u = raw(q, 8);
        double d;
        std::memcpy(&d, &u, 8);
        return round_single ? static_cast<double>(static_cast<float>(d)) : d;
      };
      if (!cx && bpn == 8 && !round_single && !m_swap) {
        // The common case (real double in the host's byte order): one tight loop.
        b.add_run(row0 - 1, terms, [p](std::int64_t t) {
          double d;
          std::memcpy(&d, p + 8 * t, 8);
          return d;
        });
        return;
      }
      if (!cx) {
        b.add_run(row0 - 1, terms, [&](std::int64_t t) { return num(p + t * bpn); });
        return;
      }
      for (std::int64_t t = 0; t < terms; ++t) b.add(row0 - 1 + t, num(p + 2 * t * bpn), num(p + (2 * t + 1) * bpn));
    };

    while (true) {
      if (m_pos >= m_size)
        fail("file ends inside the matrix after column " + std::to_string(last_col) + " (no closing record NCOL+1)",
             m_pos);
      const Record r = record("a column");
      if (r.len < 3u * m_wb) fail("column record of " + std::to_string(r.len) + " bytes is shorter than ICOL IROW NW", r.offset);
      const std::int64_t icol = word(r.p), irow = word(r.p + m_wb), nw = word(r.p + 2 * m_wb);
      if (icol == ncol + 1) break;  // closing record
      if (icol < 1 || icol > ncol)
        fail("column " + std::to_string(icol) + " out of range 1.." + std::to_string(ncol), r.offset);
      if (icol <= last_col) fail("column " + std::to_string(icol) + " follows column " + std::to_string(last_col), r.offset);
      if (nw < 0 || static_cast<std::uint64_t>(nw) * m_wb != r.len - 3u * m_wb)
        fail("column " + std::to_string(icol) + ": NW=" + std::to_string(nw) + " words but the record holds " +
                 std::to_string(r.len - 3u * m_wb) + " bytes of data",
             r.offset);
      last_col = icol;
      b.begin_column(icol - 1);
      const unsigned char* p = r.p + 3 * m_wb;
      if (irow > 0) {
        dense_seen = true;
        put(icol, irow, p, nw, r.offset);
      } else if (irow == 0) {
        sparse_seen = true;
        std::int64_t left = nw;
        while (left > 0) {
          std::int64_t L, row;
          const std::size_t off = static_cast<std::size_t>(p - m_d);
          if (bigmat) {
            if (left < 2) fail("column " + std::to_string(icol) + ": BIGMAT string header cut off", off);
            L = word(p) - 1;
            row = word(p + m_wb);
            p += 2 * m_wb;
            left -= 2;
          } else {
            const std::int64_t is = word(p);
            L = is / 65536 - 1;
            row = is - 65536 * (L + 1);
            p += m_wb;
            left -= 1;
          }
          if (L < 0 || L > left)
            fail("column " + std::to_string(icol) + ": string of " + std::to_string(L) + " words starting at row " +
                     std::to_string(row) + " does not fit the " + std::to_string(left) + " words left in the record",
                 off);
          put(icol, row, p, L, off);
          p += L * m_wb;
          left -= L;
        }
      } else {
        fail("column " + std::to_string(icol) + ": negative IROW " + std::to_string(irow), r.offset);
      }
    }
    m.storage = sparse_seen ? (bigmat ? Op4Storage::BigMat : Op4Storage::Sparse)
                            : (dense_seen ? Op4Storage::Dense : (bigmat ? Op4Storage::BigMat : Op4Storage::Sparse));
    b.finish(m);
    if (auto msg = implausible_expansion(m, m_opt, m_size); !msg.empty()) fail(msg, h.offset);
    complete_forms(m, m_opt);
    return m;
  }

  const unsigned char* m_d;
  std::size_t m_size;
  const std::string& m_file;
  const Op4ReadOptions& m_opt;
  int m_mb, m_wb;
  bool m_swap;
  std::size_t m_pos = 0;
  std::string m_context;
};

/// Finds marker size, byte order and word size from the first record, which must
/// be a matrix header of 24-32 bytes (4-byte words) or 40-48 bytes (8-byte words).
bool detect_binary(const unsigned char* d, std::size_t size, Op4FileInfo& info) {
  for (int mb : {4, 8})
    for (Endian e : {Endian::Little, Endian::Big}) {
      if (size < static_cast<std::size_t>(2 * mb)) continue;
      auto get = [&](std::size_t off) {
        std::uint64_t v = 0;
        for (int i = 0; i < mb; ++i) {
          const int shift = e == Endian::Little ? 8 * i : 8 * (mb - 1 - i);
          v |= static_cast<std::uint64_t>(d[off + i]) << shift;
        }
        return v;
      };
      const std::uint64_t len = get(0);
      // Four words and a name of 8 to 16 characters (longer names than NASTRAN's 8 included).
      const bool w4 = len >= 24 && len <= 32, w8 = len >= 40 && len <= 48;
      if (!w4 && !w8) continue;
      if (size < 2 * mb + len || get(mb + len) != len) continue;
      info.encoding = Op4Encoding::Binary;
      info.marker_bytes = mb;
      info.endian = e;
      info.word_bytes = w4 ? 4 : 8;
      return true;
    }
  return false;
}

bool looks_like_text(const char* d, std::size_t size) {
  const std::size_t n = std::min<std::size_t>(size, 32);
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(d[i]);
    if (!(c == '\t' || c == '\r' || c == '\n' || (c >= 0x20 && c < 0x7f))) return false;
  }
  return n > 0;
}

/// Read-only view of a whole file (memory-mapped; empty files are allowed).
class MappedFile {
public:
  explicit MappedFile(const std::string& path) {
    m_fd = ::open(path.c_str(), O_RDONLY);
    if (m_fd < 0) throw ParseError(SourceLocation{path, 0, {}}, "cannot open file: " + std::string(std::strerror(errno)));
    struct stat st {};
    if (::fstat(m_fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(m_fd);
      throw ParseError(SourceLocation{path, 0, {}}, "not a regular file");
    }
    m_size = static_cast<std::size_t>(st.st_size);
    if (m_size > 0) {
      void* p = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, m_fd, 0);
      if (p == MAP_FAILED) {
        ::close(m_fd);
        throw ParseError(SourceLocation{path, 0, {}}, "cannot map file: " + std::string(std::strerror(errno)));
      }
      ::madvise(p, m_size, MADV_SEQUENTIAL);
      m_data = static_cast<const char*>(p);
    }
  }
  ~MappedFile() {
    if (m_data) ::munmap(const_cast<char*>(m_data), m_size);
    if (m_fd >= 0) ::close(m_fd);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return m_data; }
  std::size_t size() const { return m_size; }

private:
  int m_fd = -1;
  const char* m_data = nullptr;
  std::size_t m_size = 0;
};

}  // namespace

std::vector<Op4Matrix> read_op4_buffer(const char* data, std::size_t size, const std::string& name,
                                       const Op4ReadOptions& options, Op4FileInfo* info) {
  if (size == 0) throw ParseError(SourceLocation{name, 0, {}}, "empty file (no OP4 matrix header)");
  Op4FileInfo fi;
  const auto* u = reinterpret_cast<const unsigned char*>(data);
  if (looks_like_text(data, size)) {
    fi.encoding = Op4Encoding::Ascii;
    if (info) *info = fi;
    return AsciiReader(data, size, name, options).read_all();
  }
  if (!detect_binary(u, size, fi)) {
    std::string first;
    for (std::size_t i = 0; i < std::min<std::size_t>(size, 8); ++i) {
      char b[4];
      std::snprintf(b, sizeof b, "%02x", u[i]);
      first += (i ? " " : "") + std::string(b);
    }
    throw ParseError(SourceLocation{name, 0, {}},
                     "byte offset 0: not an OP4 file: neither ASCII text nor a Fortran record holding a matrix header "
                     "(24-32 or 40-48 bytes) with 4- or 8-byte markers; first bytes " +
                         first);
  }
  if (info) *info = fi;
  return BinaryReader(u, size, name, options, fi).read_all();
}

std::vector<Op4Matrix> read_op4(const std::string& path, const Op4ReadOptions& options, Op4FileInfo* info) {
  MappedFile f(path);
  return read_op4_buffer(f.data(), f.size(), path, options, info);
}

}  // namespace ssid::formats
