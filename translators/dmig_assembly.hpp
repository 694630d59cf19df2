#pragma once
/// \file dmig_assembly.hpp
/// DMIG matrices <-> Eigen matrices on a DOF map (grid/scalar point, component) -> index.
///
/// A DMIG term at row (Gi, Ci), column (GJ, CJ) goes to
/// A(rows.find(Gi, Ci), cols.find(GJ, CJ)); polar terms become A e^{i B pi/180};
/// a symmetric DMIG (IFO 6) is completed to A + A^T - diag(A) first (formats::expand_dmig).
/// For IFO 9 the column key is (column number, 0).
#include <complex>
#include <string>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "formats/deck.hpp"
#include "formats/dmig.hpp"
#include "translators/dof_map.hpp"

namespace ssid::translators {

using SparseReal = Eigen::SparseMatrix<double>;
using SparseComplex = Eigen::SparseMatrix<std::complex<double>>;

/// The DOFs a DMIG refers to, in increasing (point, component) order: for square
/// and symmetric forms (IFO 1, 6) rows and columns are the same set (the union);
/// for IFO 2 the row and column keys found; for IFO 9 columns 1..NCOL.
struct DmigDofs {
  DofMap rows, cols;
};
DmigDofs dmig_dofs(const formats::Dmig& m);

/// Assembles the complete matrix on the given maps. A DOF of the DMIG missing
/// from a map is an error (std::invalid_argument naming the matrix, the DOF and
/// the card location when `deck` is given). Duplicate terms: see expand_dmig.
/// `assemble_dmig_real` of a complex DMIG with a nonzero imaginary part throws.
SparseReal assemble_dmig_real(const formats::Dmig& m, const DofMap& rows, const DofMap& cols,
                              const formats::Deck* deck = nullptr);
SparseComplex assemble_dmig_complex(const formats::Dmig& m, const DofMap& rows, const DofMap& cols,
                                    const formats::Deck* deck = nullptr);
/// Dense copies, for callers that want them.
Eigen::MatrixXd assemble_dmig_dense(const formats::Dmig& m, const DofMap& rows, const DofMap& cols,
                                    const formats::Deck* deck = nullptr);
Eigen::MatrixXcd assemble_dmig_dense_complex(const formats::Dmig& m, const DofMap& rows, const DofMap& cols,
                                             const formats::Deck* deck = nullptr);

/// Options for writing a matrix as DMIG.
struct DmigFromMatrix {
  std::string name;
  int ifo = formats::dmig_form::Square;  ///< 1, 2, 6 (upper triangle written) or 9 (columns by number)
  int tin = 0;                           ///< 0: 2 for a real matrix, 4 for a complex one
  int tout = 0;
};

/// A matrix as a DMIG: one column entry per non-null column, exact zeros left out.
/// IFO 6 requires rows and cols to be the same map and the matrix to be exactly
/// symmetric (std::invalid_argument otherwise); only the upper triangle
/// (row index <= column index) is written. IFO 9 ignores `cols` (column j is GJ = j+1).
formats::Dmig dmig_from_matrix(const SparseReal& a, const DofMap& rows, const DofMap& cols, const DmigFromMatrix& o);
formats::Dmig dmig_from_matrix(const SparseComplex& a, const DofMap& rows, const DofMap& cols, const DmigFromMatrix& o);

}  // namespace ssid::translators
