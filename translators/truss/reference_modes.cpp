/// \file reference_modes.cpp
#include "translators/truss/reference_modes.hpp"

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/MatOp/SymShiftInvert.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace ssid::translators::truss {

namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

Eigen::Matrix3d skew(const Eigen::Vector3d& r) {
  Eigen::Matrix3d s;
  s << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return s;
}

/// Euler-Bernoulli frame element in local axes (x along the bar).
Eigen::Matrix<double, 12, 12> frame_local(double E, double G, double A, double Iy, double Iz, double J, double L) {
  Eigen::Matrix<double, 12, 12> k = Eigen::Matrix<double, 12, 12>::Zero();
  const double a = E * A / L, t = G * J / L;
  k(0, 0) = k(6, 6) = a;
  k(0, 6) = k(6, 0) = -a;
  k(3, 3) = k(9, 9) = t;
  k(3, 9) = k(9, 3) = -t;
  // Bending in the x-y plane (about z, inertia Iz): DOFs v1 (1), rz1 (5), v2 (7), rz2 (11).
  auto bend = [&](int v1, int r1, int v2, int r2, double EI, double sign) {
    const double c1 = 12 * EI / (L * L * L), c2 = 6 * EI / (L * L), c3 = 4 * EI / L, c4 = 2 * EI / L;
    const int d[4] = {v1, r1, v2, r2};
    const double m[4][4] = {{c1, sign * c2, -c1, sign * c2},
                            {sign * c2, c3, -sign * c2, c4},
                            {-c1, -sign * c2, c1, -sign * c2},
                            {sign * c2, c4, -sign * c2, c3}};
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) k(d[i], d[j]) += m[i][j];
  };
  bend(1, 5, 7, 11, E * Iz, +1.0);
  // Bending in the x-z plane (about y): w and ry = -dw/dx, hence the sign flip.
  bend(2, 4, 8, 10, E * Iy, -1.0);
  return k;
}

}  // namespace

Assembled assemble_reference(const TrussCards& fe) {
  const std::size_t ng = fe.grids.size();
  const Eigen::Index n = static_cast<Eigen::Index>(6 * ng);
  std::unordered_map<int, std::size_t> idx;
  for (std::size_t i = 0; i < ng; ++i) idx[fe.grids[i].id] = i;
  auto at = [&](int id) {
    auto it = idx.find(id);
    if (it == idx.end()) throw std::invalid_argument("reference assembler: no grid " + std::to_string(id));
    return static_cast<Eigen::Index>(6 * it->second);
  };
  Triplets kt, mt;
  const double E = fe.mat.E, G = fe.mat.E / (2.0 * (1.0 + fe.mat.nu));

  std::unordered_map<int, const FeRodProp*> rodp;
  for (const auto& p : fe.rod_props) rodp[p.id] = &p;
  for (const auto& r : fe.rods) {
    const FeRodProp& p = *rodp.at(r.pid);
    const Eigen::Vector3d d = fe.grids[idx.at(r.g2)].x - fe.grids[idx.at(r.g1)].x;
    const double L = d.norm();
    const Eigen::Vector3d e = d / L;
    const Eigen::Matrix3d kk = E * p.A / L * e * e.transpose();
    const Eigen::Index a = at(r.g1), b = at(r.g2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        kt.emplace_back(a + i, a + j, kk(i, j));
        kt.emplace_back(b + i, b + j, kk(i, j));
        kt.emplace_back(a + i, b + j, -kk(i, j));
        kt.emplace_back(b + i, a + j, -kk(i, j));
      }
    const double half = 0.5 * (fe.mat.rho * p.A + p.nsm) * L;
    for (int i = 0; i < 3; ++i) {
      mt.emplace_back(a + i, a + i, half);
      mt.emplace_back(b + i, b + i, half);
    }
  }

  std::unordered_map<int, const FeBarProp*> barp;
  for (const auto& p : fe.bar_props) barp[p.id] = &p;
  for (const auto& br : fe.bars) {
    const FeBarProp& p = *barp.at(br.pid);
    const Eigen::Vector3d d = fe.grids[idx.at(br.g2)].x - fe.grids[idx.at(br.g1)].x;
    const double L = d.norm();
    const Eigen::Vector3d ex = d / L;
    const Eigen::Vector3d ez = ex.cross(br.v).normalized();
    const Eigen::Vector3d ey = ez.cross(ex);
    Eigen::Matrix3d R;
    R.row(0) = ex;
    R.row(1) = ey;
    R.row(2) = ez;
    Eigen::Matrix<double, 12, 12> Tr = Eigen::Matrix<double, 12, 12>::Zero();
    for (int b = 0; b < 4; ++b) Tr.block<3, 3>(3 * b, 3 * b) = R;
    // PBAR: I1 bends in plane 1 (element x-y, about z), I2 in plane 2 (about y).
    const Eigen::Matrix<double, 12, 12> kg = Tr.transpose() * frame_local(E, G, p.A, p.I2, p.I1, p.J, L) * Tr;
    const Eigen::Index off[2] = {at(br.g1), at(br.g2)};
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j)
        if (kg(i, j) != 0) kt.emplace_back(off[i / 6] + i % 6, off[j / 6] + j % 6, kg(i, j));
    const double half = 0.5 * (fe.mat.rho * p.A + p.nsm) * L;
    for (int i = 0; i < 3; ++i) {
      mt.emplace_back(off[0] + i, off[0] + i, half);
      mt.emplace_back(off[1] + i, off[1] + i, half);
    }
  }

  for (const auto& c : fe.masses) {
    const Eigen::Index a = at(c.grid);
    for (int i = 0; i < 3; ++i) mt.emplace_back(a + i, a + i, c.m);
    if (c.inertia != 0)
      for (int i = 3; i < 6; ++i) mt.emplace_back(a + i, a + i, c.inertia);
  }

  std::unordered_map<int, double> springk;
  for (const auto& p : fe.spring_props) springk[p.id] = p.k;
  for (const auto& s : fe.springs) {
    const double k = springk.at(s.pid);
    const Eigen::Index a = at(s.g1) + s.c1 - 1;
    kt.emplace_back(a, a, k);
    if (s.g2 != 0) {
      const Eigen::Index b = at(s.g2) + s.c2 - 1;
      kt.emplace_back(b, b, k);
      kt.emplace_back(a, b, -k);
      kt.emplace_back(b, a, -k);
    }
  }

  Assembled out;
  out.K.resize(n, n);
  out.M.resize(n, n);
  out.K.setFromTriplets(kt.begin(), kt.end());
  out.M.setFromTriplets(mt.begin(), mt.end());

  // Reduction: fixed DOFs (PS, SPC, AUTOSPC) get no column; RBE2 dependents follow their independent grid.
  std::vector<char> fixed(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < ng; ++i)
    for (char c : fe.grids[i].ps) fixed[6 * i + static_cast<std::size_t>(c - '1')] = 1;
  for (const auto& s : fe.spcs)
    for (char c : s.components) fixed[static_cast<std::size_t>(at(s.grid)) + static_cast<std::size_t>(c - '1')] = 1;
  std::vector<int> master(ng, -1);  // independent grid index for dependents
  for (const auto& r : fe.rigids)
    for (int g : r.gm) master[idx.at(g)] = static_cast<int>(idx.at(r.gn));
  const Eigen::VectorXd kd = out.K.diagonal(), md = out.M.diagonal();
  // AUTOSPC: a DOF of an independent grid with no stiffness and no mass anywhere it is
  // reached (its own, plus the rigid elements hanging on it) is singular.
  Eigen::VectorXd kd_tot = kd.cwiseAbs(), md_tot = md.cwiseAbs();
  for (std::size_t i = 0; i < ng; ++i)
    if (master[i] >= 0)
      for (int c = 0; c < 6; ++c) {
        kd_tot(6 * master[i] + c) += 1.0;  // a rigid element connects every component of its independent grid
      }
  std::vector<Eigen::Index> col(static_cast<std::size_t>(n), -1);
  Eigen::Index na = 0;
  for (std::size_t i = 0; i < ng; ++i) {
    if (master[i] >= 0) continue;
    for (int c = 0; c < 6; ++c) {
      const std::size_t d = 6 * i + static_cast<std::size_t>(c);
      if (fixed[d] || (kd_tot(static_cast<Eigen::Index>(d)) == 0 && md_tot(static_cast<Eigen::Index>(d)) == 0)) continue;
      col[d] = na++;
    }
  }
  Triplets tt;
  for (std::size_t i = 0; i < ng; ++i) {
    if (master[i] < 0) {
      for (int c = 0; c < 6; ++c)
        if (col[6 * i + c] >= 0) tt.emplace_back(static_cast<Eigen::Index>(6 * i + c), col[6 * i + c], 1.0);
      continue;
    }
    const std::size_t m = static_cast<std::size_t>(master[i]);
    const Eigen::Matrix3d S = -skew(fe.grids[i].x - fe.grids[m].x);  // theta x r = -r x theta
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index row = static_cast<Eigen::Index>(6 * i + c);
      if (col[6 * m + c] >= 0) tt.emplace_back(row, col[6 * m + c], 1.0);
      for (int r = 0; r < 3; ++r)
        if (S(c, r) != 0 && col[6 * m + 3 + r] >= 0) tt.emplace_back(row, col[6 * m + 3 + r], S(c, r));
      if (col[6 * m + 3 + c] >= 0) tt.emplace_back(static_cast<Eigen::Index>(6 * i + 3 + c), col[6 * m + 3 + c], 1.0);
    }
  }
  out.T.resize(n, na);
  out.T.setFromTriplets(tt.begin(), tt.end());
  return out;
}

ReferenceModes reference_modes(const TrussCards& fe, int count) {
  const Assembled a = assemble_reference(fe);
  const Eigen::SparseMatrix<double> Ka = Eigen::SparseMatrix<double>(a.T.transpose() * a.K * a.T);
  const Eigen::SparseMatrix<double> Ma = Eigen::SparseMatrix<double>(a.T.transpose() * a.M * a.T);
  const Eigen::Index n = Ka.rows();
  ReferenceModes out;
  out.a_set_size = static_cast<std::size_t>(n);
  for (const auto& g : fe.grids) out.grid_ids.push_back(g.id);
  // Dense: every mode is available; Lanczos needs nev < n.
  const int nev = std::min<int>(count, static_cast<int>(n) - (n <= 3000 ? 0 : 1));
  Eigen::VectorXd lambda;
  Eigen::MatrixXd phi;
  if (n <= 3000) {
    // Shift so K + sM is positive definite even with rigid-body modes; the
    // pencil (M, K + sM) has mu = 1 / (lambda + s), mu = 0 for massless DOFs.
    const double s = std::pow(2.0 * M_PI * 1.0, 2);
    const Eigen::MatrixXd Kd(Ka), Md(Ma);
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Md, Kd + s * Md);
    if (es.info() != Eigen::Success) {
      out.converged = false;
      return out;
    }
    const Eigen::VectorXd mu = es.eigenvalues();  // ascending
    // mu = 0 belongs to massless DOFs (infinite frequency): never a mode.
    int finite = 0;
    while (finite < nev && mu(n - 1 - finite) > 1e-12 * mu(n - 1)) ++finite;
    lambda.resize(finite);
    phi.resize(n, finite);
    for (int j = 0; j < finite; ++j) {
      const Eigen::Index k = n - 1 - j;
      lambda(j) = 1.0 / mu(k) - s;
      Eigen::VectorXd v = es.eigenvectors().col(k);
      phi.col(j) = v / std::sqrt(v.dot(Md * v));
    }
  } else {
    using OpType = Spectra::SymShiftInvert<double, Eigen::Sparse, Eigen::Sparse>;
    using BOpType = Spectra::SparseSymMatProd<double>;
    OpType op(Ka, Ma);
    BOpType bop(Ma);
    const double sigma = -std::pow(2.0 * M_PI * 1.0, 2);
    Spectra::SymGEigsShiftSolver<OpType, BOpType, Spectra::GEigsMode::ShiftInvert> es(
        op, bop, nev, std::min<int>(static_cast<int>(n), std::max(2 * nev + 1, 60)), sigma);
    es.init();
    es.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10, Spectra::SortRule::SmallestAlge);
    if (es.info() != Spectra::CompInfo::Successful) {
      out.converged = false;
      return out;
    }
    lambda = es.eigenvalues();
    phi = es.eigenvectors();
    for (int j = 0; j < phi.cols(); ++j) phi.col(j) /= std::sqrt(phi.col(j).dot(Ma * phi.col(j)));
  }
  std::vector<int> order(static_cast<std::size_t>(lambda.size()));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int x, int y) { return lambda(x) < lambda(y); });
  out.shapes.resize(a.T.rows(), static_cast<Eigen::Index>(order.size()));
  for (std::size_t j = 0; j < order.size(); ++j) {
    const double l = lambda(order[j]);
    out.frequency_hz.push_back((l < 0 ? -1.0 : 1.0) * std::sqrt(std::fabs(l)) / (2.0 * M_PI));
    out.shapes.col(static_cast<Eigen::Index>(j)) = a.T * phi.col(order[j]);
  }
  return out;
}

double energy_fraction(const TrussCards& fe, const Assembled& a, const ReferenceModes& modes, int j,
                       const std::vector<int>& grids) {
  const Eigen::VectorXd v = modes.shapes.col(j);
  const Eigen::VectorXd mv = a.M * v;
  std::unordered_map<int, std::size_t> idx;
  for (std::size_t i = 0; i < fe.grids.size(); ++i) idx[fe.grids[i].id] = i;
  double s = 0;
  for (int g : grids)
    for (int c = 0; c < 3; ++c) {
      const Eigen::Index d = static_cast<Eigen::Index>(6 * idx.at(g) + c);
      s += v(d) * mv(d);
    }
  return s / v.dot(mv);
}

Eigen::Vector3d translational_energy(const Assembled& a, const ReferenceModes& modes, int j) {
  const Eigen::VectorXd v = modes.shapes.col(j);
  const Eigen::VectorXd mv = a.M * v;
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (Eigen::Index d = 0; d < v.size(); ++d)
    if (d % 6 < 3) e(d % 6) += v(d) * mv(d);
  return e / v.dot(mv);
}

std::pair<double, double> component_bending_axial(const TrussCards& fe, int count) {
  const Assembled a = assemble_reference(fe);
  const ReferenceModes m = reference_modes(fe, count);
  double bending = std::nan(""), axial = std::nan("");
  for (std::size_t j = 0; j < m.frequency_hz.size(); ++j) {
    if (m.frequency_hz[j] < 1.0) continue;
    const Eigen::Vector3d e = translational_energy(a, m, static_cast<int>(j));
    if (std::isnan(bending) && e.y() + e.z() > 0.5) bending = m.frequency_hz[j];
    if (std::isnan(axial) && e.x() > 0.5) axial = m.frequency_hz[j];
  }
  return {bending, axial};
}

}  // namespace ssid::translators::truss
