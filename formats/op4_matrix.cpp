/// \file op4_matrix.cpp
/// Op4Matrix accessors and form names.
#include <stdexcept>

#include "formats/op4.hpp"

namespace ssid::formats {

std::string op4_form::name(int form) {
  switch (form) {
    case Square: return "square";
    case Rectangular: return "rectangular";
    case Diagonal: return "diagonal";
    case LowerTriangular: return "lower triangular";
    case UpperTriangular: return "upper triangular";
    case Symmetric: return "symmetric";
    case RowVector: return "row vector";
    case Identity: return "identity";
    case PseudoIdentity: return "pseudo-identity";
    case CholeskyFactor: return "Cholesky factor";
    case Trapezoidal: return "trapezoidal factor";
    case SparseLowerTriangular: return "sparse lower triangular factor";
    case SparseUpperTriangular: return "sparse upper triangular factor";
    default: return "form " + std::to_string(form);
  }
}

Eigen::MatrixXd Op4Matrix::dense_real() const {
  if (is_complex()) throw std::logic_error("OP4 matrix " + name + " is complex; use dense_complex()");
  return Eigen::MatrixXd(real);
}

Eigen::MatrixXcd Op4Matrix::dense_complex() const { return Eigen::MatrixXcd(as_complex()); }

SparseComplex Op4Matrix::as_complex() const {
  if (is_complex()) return complex;
  return real.cast<std::complex<double>>();
}

Op4Matrix Op4Matrix::from_real(std::string name, const SparseReal& m, int form, Op4Precision precision) {
  Op4Matrix r;
  r.name = std::move(name);
  r.rows = m.rows();
  r.cols = m.cols();
  r.form = form;
  r.precision = precision;
  r.real = m;
  r.real.makeCompressed();
  if (r.is_complex()) {
    r.complex = m.cast<std::complex<double>>();
    r.real.resize(0, 0);
  }
  return r;
}

Op4Matrix Op4Matrix::from_complex(std::string name, const SparseComplex& m, int form, Op4Precision precision) {
  if (precision == Op4Precision::RealSingle || precision == Op4Precision::RealDouble)
    throw std::invalid_argument("OP4 matrix " + name + ": a complex matrix needs precision 3 or 4");
  Op4Matrix r;
  r.name = std::move(name);
  r.rows = m.rows();
  r.cols = m.cols();
  r.form = form;
  r.precision = precision;
  r.complex = m;
  r.complex.makeCompressed();
  return r;
}

}  // namespace ssid::formats
