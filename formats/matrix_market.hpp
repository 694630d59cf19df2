#pragma once
/// \file matrix_market.hpp
/// MatrixMarket coordinate files (`.mtx`) for scipy.io.mmread and MATLAB's mmread.
///
/// Layout (https://math.nist.gov/MatrixMarket/formats.html):
///
///     %%MatrixMarket matrix coordinate real|complex general|symmetric
///     % comment lines
///     ROWS COLS NNZ
///     i j re [im]          (1-based, one entry per line)
///
/// Symmetric files hold the lower triangle only (i >= j). Values are written in
/// the shortest decimal form that reads back to the same double, so files are exact.
#include <complex>
#include <string>

#include <Eigen/SparseCore>

namespace ssid::formats {

enum class MtxSymmetry { General, Symmetric };

/// Writes a real sparse matrix. Symmetric requires an exactly symmetric square
/// matrix (std::invalid_argument otherwise). Exact zeros stored in `a` are left out.
/// Throws std::runtime_error when the file cannot be written.
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& a,
                         MtxSymmetry symmetry = MtxSymmetry::General, const std::string& comment = "");
void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<std::complex<double>>& a,
                         MtxSymmetry symmetry = MtxSymmetry::General, const std::string& comment = "");
/// The same, into a string.
std::string matrix_market_string(const Eigen::SparseMatrix<double>& a, MtxSymmetry symmetry = MtxSymmetry::General,
                                 const std::string& comment = "");
std::string matrix_market_string(const Eigen::SparseMatrix<std::complex<double>>& a,
                                 MtxSymmetry symmetry = MtxSymmetry::General, const std::string& comment = "");

/// True when `a` is square and equal to its transpose, value for value.
bool is_exactly_symmetric(const Eigen::SparseMatrix<double>& a);
bool is_exactly_symmetric(const Eigen::SparseMatrix<std::complex<double>>& a);

}  // namespace ssid::formats
