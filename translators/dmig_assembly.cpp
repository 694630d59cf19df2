/// \file dmig_assembly.cpp
/// DMIG <-> Eigen on DOF maps.
#include "translators/dmig_assembly.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::translators {

using formats::Dmig;
using formats::DmigEntry;
using formats::DmigKey;

DmigDofs dmig_dofs(const Dmig& m) {
  std::set<DmigKey> rows, cols;
  for (const auto& c : m.columns) {
    cols.insert(c.col);
    for (const auto& t : c.terms) rows.insert(t.row);
  }
  DmigDofs d;
  if (m.ifo == formats::dmig_form::Square || m.ifo == formats::dmig_form::Symmetric) {
    rows.insert(cols.begin(), cols.end());
    cols = rows;
  }
  for (const DmigKey& k : rows) d.rows.add({k.point, k.component});
  if (m.ifo == formats::dmig_form::RectangularByColumnNumber) {
    std::int64_t n = m.ncol;
    for (const DmigKey& k : cols) n = std::max(n, k.point);
    for (std::int64_t j = 1; j <= n; ++j) d.cols.add({j, 0});
  } else {
    for (const DmigKey& k : cols) d.cols.add({k.point, k.component});
  }
  return d;
}

namespace {

std::string dof_text(const DmigKey& k) {
  return "(" + std::to_string(k.point) + "," + std::to_string(k.component) + ")";
}

/// "file:line: " of the entry that gave a term, for messages.
std::string where(const Dmig& m, const DmigEntry& e, const formats::Deck* deck) {
  if (!deck || e.source >= m.columns.size() || m.columns[e.source].card >= deck->cards.size()) return "";
  return deck->location(deck->cards[m.columns[e.source].card]).str() + ": ";
}

template <class T, class F>
Eigen::SparseMatrix<T> assemble(const Dmig& m, const DofMap& rows, const DofMap& cols, const formats::Deck* deck,
                                F convert) {
  const std::vector<DmigEntry> e = formats::expand_dmig(m, deck);
  std::vector<Eigen::Triplet<T>> t;
  t.reserve(e.size());
  for (const DmigEntry& x : e) {
    const auto r = rows.find({x.row.point, x.row.component});
    if (!r)
      throw formats::InputError(where(m, x, deck) + "DMIG " + m.name + ": row DOF " + dof_text(x.row) +
                                  " (grid/point, component) is not in the row DOF map (" +
                                  std::to_string(rows.size()) + " DOFs)");
    const auto c = cols.find({x.col.point, x.col.component});
    if (!c)
      throw formats::InputError(where(m, x, deck) + "DMIG " + m.name + ": column DOF " + dof_text(x.col) +
                                  " is not in the column DOF map (" + std::to_string(cols.size()) + " DOFs)");
    t.emplace_back(static_cast<int>(*r), static_cast<int>(*c), convert(x));
  }
  Eigen::SparseMatrix<T> a(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

}  // namespace

SparseReal assemble_dmig_real(const Dmig& m, const DofMap& rows, const DofMap& cols, const formats::Deck* deck) {
  return assemble<double>(m, rows, cols, deck, [&](const DmigEntry& x) {
    if (x.value.imag() != 0.0)
      throw formats::InputError(where(m, x, deck) + "DMIG " + m.name + " is complex (term at row " +
                                  dof_text(x.row) + " column " + dof_text(x.col) +
                                  " has an imaginary part); assemble it as complex");
    return x.value.real();
  });
}

SparseComplex assemble_dmig_complex(const Dmig& m, const DofMap& rows, const DofMap& cols, const formats::Deck* deck) {
  return assemble<std::complex<double>>(m, rows, cols, deck, [](const DmigEntry& x) { return x.value; });
}

Eigen::MatrixXd assemble_dmig_dense(const Dmig& m, const DofMap& rows, const DofMap& cols, const formats::Deck* deck) {
  return Eigen::MatrixXd(assemble_dmig_real(m, rows, cols, deck));
}

Eigen::MatrixXcd assemble_dmig_dense_complex(const Dmig& m, const DofMap& rows, const DofMap& cols,
                                             const formats::Deck* deck) {
  return Eigen::MatrixXcd(assemble_dmig_complex(m, rows, cols, deck));
}

namespace {

template <class T>
Dmig from_matrix(const Eigen::SparseMatrix<T>& a0, const DofMap& rows, const DofMap& cols, const DmigFromMatrix& o,
                 bool is_complex) {
  if (o.name.empty() || o.name.size() > 8)
    throw formats::InputError("DMIG name must have 1 to 8 characters, got \"" + o.name + "\"");
  const bool by_number = o.ifo == formats::dmig_form::RectangularByColumnNumber;
  if (o.ifo != 1 && o.ifo != 2 && o.ifo != 6 && !by_number)
    throw formats::InputError("DMIG " + o.name + ": IFO must be 1, 2, 6 or 9, got " + std::to_string(o.ifo));
  if (static_cast<std::size_t>(a0.rows()) != rows.size() ||
      (!by_number && static_cast<std::size_t>(a0.cols()) != cols.size()))
    throw formats::InputError("DMIG " + o.name + ": matrix is " + std::to_string(a0.rows()) + " x " +
                                std::to_string(a0.cols()) + " but the DOF maps have " + std::to_string(rows.size()) +
                                " rows and " + std::to_string(cols.size()) + " columns");
  Eigen::SparseMatrix<T> a = a0;
  a.makeCompressed();
  if (o.ifo == 1 || o.ifo == 6) {
    if (rows.dofs().size() != cols.dofs().size() || !std::equal(rows.dofs().begin(), rows.dofs().end(), cols.dofs().begin()))
      throw formats::InputError("DMIG " + o.name + ": IFO " + std::to_string(o.ifo) +
                                  " needs the same DOF map for rows and columns");
  }
  if (o.ifo == 6) {
    Eigen::SparseMatrix<T> at = a.transpose();
    Eigen::SparseMatrix<T> d = a - at;
    d.prune(T(0));
    if (d.nonZeros() != 0)
      throw formats::InputError("DMIG " + o.name + ": IFO 6 (symmetric) but the matrix is not exactly symmetric");
  }
  Dmig m;
  m.name = o.name;
  m.ifo = o.ifo;
  m.tin = o.tin ? o.tin : (is_complex ? 4 : 2);
  if (m.tin < 1 || m.tin > 4) throw formats::InputError("DMIG " + o.name + ": TIN must be 1-4");
  if (is_complex && (m.tin == 1 || m.tin == 2))  // a real matrix may be written as complex (B = 0)
    throw formats::InputError("DMIG " + o.name + ": a complex matrix needs TIN 3 or 4");
  m.tout = o.tout;
  if (by_number) m.ncol = a.cols();
  for (Eigen::Index j = 0; j < a.outerSize(); ++j) {
    formats::DmigColumn c;
    if (by_number) c.col = {j + 1, 0};
    else c.col = {cols.at(static_cast<std::size_t>(j)).point, cols.at(static_cast<std::size_t>(j)).component};
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(a, j); it; ++it) {
      if (it.value() == T(0)) continue;
      if (o.ifo == 6 && it.row() > j) continue;
      const Dof& r = rows.at(static_cast<std::size_t>(it.row()));
      formats::DmigTerm t;
      t.row = {r.point, r.component};
      t.a = std::real(it.value());
      t.b = std::imag(it.value());
      c.terms.push_back(t);
    }
    if (!c.terms.empty()) {
      c.card = m.columns.size();
      m.columns.push_back(std::move(c));
    }
  }
  return m;
}

}  // namespace

Dmig dmig_from_matrix(const SparseReal& a, const DofMap& rows, const DofMap& cols, const DmigFromMatrix& o) {
  return from_matrix(a, rows, cols, o, false);
}
Dmig dmig_from_matrix(const SparseComplex& a, const DofMap& rows, const DofMap& cols, const DmigFromMatrix& o) {
  return from_matrix(a, rows, cols, o, true);
}

}  // namespace ssid::translators
