/// \file matrix_market.cpp
/// MatrixMarket coordinate writer.
#include "formats/matrix_market.hpp"

#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "formats/parse_error.hpp"

namespace ssid::formats {

namespace {

template <class T>
bool symmetric(const Eigen::SparseMatrix<T>& a) {
  if (a.rows() != a.cols()) return false;
  Eigen::SparseMatrix<T> t = a.transpose();
  Eigen::SparseMatrix<T> d = a - t;
  d.prune(T(0));
  return d.nonZeros() == 0;
}

inline void put_value(fmt::memory_buffer& b, double v) { fmt::format_to(std::back_inserter(b), " {}", v); }
inline void put_value(fmt::memory_buffer& b, const std::complex<double>& v) {
  fmt::format_to(std::back_inserter(b), " {} {}", v.real(), v.imag());
}

template <class T>
void write(std::string& out, const Eigen::SparseMatrix<T>& a, MtxSymmetry s, const std::string& comment,
           bool is_complex) {
  if (s == MtxSymmetry::Symmetric && !symmetric(a))
    throw InputError("MatrixMarket: symmetric output asked for a matrix that is not exactly symmetric (" +
                                std::to_string(a.rows()) + " x " + std::to_string(a.cols()) + ")");
  Eigen::Index nnz = 0;
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(a, j); it; ++it)
      if (it.value() != T(0) && (s == MtxSymmetry::General || it.row() >= j)) ++nnz;
  fmt::memory_buffer b;
  fmt::format_to(std::back_inserter(b), "%%MatrixMarket matrix coordinate {} {}\n", is_complex ? "complex" : "real",
                 s == MtxSymmetry::Symmetric ? "symmetric" : "general");
  if (!comment.empty()) {
    std::size_t p = 0;
    while (p <= comment.size()) {
      std::size_t e = comment.find('\n', p);
      if (e == std::string::npos) e = comment.size();
      fmt::format_to(std::back_inserter(b), "% {}\n", comment.substr(p, e - p));
      p = e + 1;
    }
  }
  fmt::format_to(std::back_inserter(b), "{} {} {}\n", a.rows(), a.cols(), nnz);
  for (Eigen::Index j = 0; j < a.outerSize(); ++j)
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(a, j); it; ++it) {
      if (it.value() == T(0) || (s == MtxSymmetry::Symmetric && it.row() < j)) continue;
      fmt::format_to(std::back_inserter(b), "{} {}", it.row() + 1, j + 1);
      put_value(b, it.value());
      b.push_back('\n');
    }
  out.assign(b.data(), b.size());
}

void to_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw InputError("cannot write " + path);
  f.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!f) throw InputError("error writing " + path);
}

}  // namespace

std::string matrix_market_string(const Eigen::SparseMatrix<double>& a, MtxSymmetry s, const std::string& c) {
  std::string out;
  write(out, a, s, c, false);
  return out;
}
std::string matrix_market_string(const Eigen::SparseMatrix<std::complex<double>>& a, MtxSymmetry s,
                                 const std::string& c) {
  std::string out;
  write(out, a, s, c, true);
  return out;
}
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& a, MtxSymmetry s,
                         const std::string& c) {
  to_file(path, matrix_market_string(a, s, c));
}
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<std::complex<double>>& a, MtxSymmetry s,
                         const std::string& c) {
  to_file(path, matrix_market_string(a, s, c));
}
bool is_exactly_symmetric(const Eigen::SparseMatrix<double>& a) { return symmetric(a); }
bool is_exactly_symmetric(const Eigen::SparseMatrix<std::complex<double>>& a) { return symmetric(a); }

}  // namespace ssid::formats
