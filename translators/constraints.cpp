#include "translators/constraints.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <unordered_map>

namespace ssid::translators {

namespace {
Eigen::Matrix3d skew(const Eigen::Vector3d& d) {
  Eigen::Matrix3d s;
  s << 0, -d.z(), d.y(), d.z(), 0, -d.x(), -d.y(), d.x(), 0;
  return s;
}
}  // namespace

Eigen::Matrix<double, 6, 6> rigid_body_rows(const Eigen::Vector3d& xp, const Eigen::Vector3d& x0) {
  Eigen::Matrix<double, 6, 6> r = Eigen::Matrix<double, 6, 6>::Identity();
  // u_p = u0 + θ0 × d = u0 − [d]× θ0
  r.block<3, 3>(0, 3) = -skew(xp - x0);
  return r;
}

Reduction build_reduction(std::size_t n, const std::vector<MpcEquation>& mpcs, const std::vector<std::size_t>& spc) {
  Reduction r;
  std::vector<long> eq_of(n, -1);
  for (std::size_t e = 0; e < mpcs.size(); ++e) {
    std::size_t d = mpcs[e].dependent;
    if (d >= n) throw std::invalid_argument(mpcs[e].source + ": dependent DOF out of range");
    if (eq_of[d] >= 0)
      throw std::invalid_argument("DOF made dependent twice: by " + mpcs[static_cast<std::size_t>(eq_of[d])].source +
                                  " and by " + mpcs[e].source);
    eq_of[d] = static_cast<long>(e);
  }
  std::vector<char> fixed(n, 0);
  for (std::size_t s : spc) {
    if (s >= n) throw std::invalid_argument("SPC DOF out of range");
    if (eq_of[s] >= 0)
      throw std::invalid_argument("a DOF constrained by SPC is dependent in " + mpcs[static_cast<std::size_t>(eq_of[s])].source);
    fixed[s] = 1;
  }
  r.g_to_a.assign(n, -1);
  for (std::size_t g = 0; g < n; ++g) {
    if (eq_of[g] >= 0) r.dependent.push_back(g);
    else if (fixed[g]) r.constrained.push_back(g);
    else {
      r.g_to_a[g] = static_cast<long>(r.a_to_g.size());
      r.a_to_g.push_back(g);
    }
  }
  // Expand each dependent DOF into a-set terms, substituting chained dependents.
  std::vector<std::unordered_map<std::size_t, double>> expanded(n);
  std::vector<char> state(n, 0);  // 0 new, 1 visiting, 2 done
  std::function<const std::unordered_map<std::size_t, double>&(std::size_t)> expand =
      [&](std::size_t g) -> const std::unordered_map<std::size_t, double>& {
    if (state[g] == 2) return expanded[g];
    const MpcEquation& eq = mpcs[static_cast<std::size_t>(eq_of[g])];
    if (state[g] == 1) throw std::invalid_argument("multipoint constraints form a cycle through " + eq.source);
    state[g] = 1;
    std::unordered_map<std::size_t, double> acc;
    for (const auto& [j, c] : eq.terms) {
      if (j >= n) throw std::invalid_argument(eq.source + ": independent DOF out of range");
      if (r.g_to_a[j] >= 0) acc[static_cast<std::size_t>(r.g_to_a[j])] += c;
      else if (eq_of[j] >= 0)
        for (const auto& [a, c2] : expand(j)) acc[a] += c * c2;
      // SPC'd independents contribute zero.
    }
    expanded[g] = std::move(acc);
    state[g] = 2;
    return expanded[g];
  };
  std::vector<Eigen::Triplet<double>> trip;
  for (std::size_t a = 0; a < r.a_to_g.size(); ++a) trip.emplace_back(static_cast<int>(r.a_to_g[a]), static_cast<int>(a), 1.0);
  for (std::size_t g : r.dependent)
    for (const auto& [a, c] : expand(g))
      if (c != 0.0) trip.emplace_back(static_cast<int>(g), static_cast<int>(a), c);
  r.T.resize(static_cast<int>(n), static_cast<int>(r.a_to_g.size()));
  r.T.setFromTriplets(trip.begin(), trip.end());
  return r;
}

SparseMatrix reduce(const SparseMatrix& A, const Reduction& r) {
  SparseMatrix AT = A * r.T;
  SparseMatrix out = SparseMatrix(r.T.transpose()) * AT;
  out.prune(0.0);
  return out;
}

namespace {
Eigen::Matrix<double, 6, 6> six(const Eigen::Matrix3d& t) {
  Eigen::Matrix<double, 6, 6> T = Eigen::Matrix<double, 6, 6>::Zero();
  T.topLeftCorner<3, 3>() = t;
  T.bottomRightCorner<3, 3>() = t;
  return T;
}
}  // namespace

std::vector<MpcEquation> rigid_equations(const std::vector<RigidGrid>& grids, const std::string& source) {
  if (grids.empty()) return {};
  const Eigen::Vector3d x0 = grids.front().x;
  std::vector<Eigen::Matrix<double, 1, 6>> ind_rows, dep_rows;
  std::vector<std::size_t> ind_g, dep_g;
  for (const RigidGrid& p : grids) {
    // Rows in the grid's displacement components: u_cd = frameᵀ u_basic.
    const Eigen::Matrix<double, 6, 6> R = six(p.frame).transpose() * rigid_body_rows(p.x, x0);
    for (char c : p.independent) {
      ind_rows.push_back(R.row(c - '1'));
      ind_g.push_back(p.g[static_cast<std::size_t>(c - '1')]);
    }
    for (char c : p.dependent) {
      dep_rows.push_back(R.row(c - '1'));
      dep_g.push_back(p.g[static_cast<std::size_t>(c - '1')]);
    }
  }
  const int ni = static_cast<int>(ind_rows.size());
  Eigen::MatrixXd RI(ni, 6);
  for (int i = 0; i < ni; ++i) RI.row(i) = ind_rows[static_cast<std::size_t>(i)];
  Eigen::FullPivLU<Eigen::MatrixXd> lu(RI);
  if (ni != 6 || lu.rank() != 6)
    throw std::invalid_argument(source + ": the independent components (" + std::to_string(ni) +
                                ") do not define a rigid-body motion: exactly 6 independent rigid-body DOFs are required");
  // u_D = R_D R_I^{-1} u_I
  Eigen::MatrixXd RIinv = lu.inverse();
  std::vector<MpcEquation> eqs;
  for (std::size_t k = 0; k < dep_rows.size(); ++k) {
    Eigen::Matrix<double, 1, 6> c = dep_rows[k] * RIinv;
    MpcEquation e;
    e.dependent = dep_g[k];
    e.source = source;
    for (int i = 0; i < 6; ++i)
      if (std::abs(c(i)) > 1e-13 * c.cwiseAbs().maxCoeff()) e.terms.emplace_back(ind_g[static_cast<std::size_t>(i)], c(i));
    eqs.push_back(std::move(e));
  }
  return eqs;
}

std::vector<MpcEquation> rbe3_equations(const Eigen::Vector3d& xref, const std::array<std::size_t, 6>& gref,
                                        const std::string& refc, const std::vector<Rbe3Group>& groups,
                                        const std::string& source, const Eigen::Matrix3d& ref_frame) {
  double lsum = 0;
  std::size_t count = 0;
  for (const auto& grp : groups)
    for (const auto& [x, g] : grp.grids) {
      lsum += (x - xref).norm();
      ++count;
    }
  if (count == 0) throw std::invalid_argument(source + ": no independent grids");
  const double lc = lsum / static_cast<double>(count);
  const double lc2 = lc > 0 ? lc * lc : 1.0;
  std::vector<Eigen::Matrix<double, 1, 6>> rows;
  std::vector<double> w;
  std::vector<std::size_t> gi;
  for (const auto& grp : groups)
    for (std::size_t q = 0; q < grp.grids.size(); ++q) {
      const auto& [x, g] = grp.grids[q];
      const Eigen::Matrix3d f = grp.frames.empty() ? Eigen::Matrix3d::Identity() : grp.frames.at(q);
      const Eigen::Matrix<double, 6, 6> R = six(f).transpose() * rigid_body_rows(x, xref);
      for (char c : grp.components) {
        int k = c - '1';
        rows.push_back(R.row(k));
        w.push_back(k < 3 ? grp.weight : grp.weight * lc2);
        gi.push_back(g[static_cast<std::size_t>(k)]);
      }
    }
  const int n = static_cast<int>(rows.size());
  Eigen::MatrixXd S(n, 6);
  Eigen::VectorXd W(n);
  for (int i = 0; i < n; ++i) {
    S.row(i) = rows[static_cast<std::size_t>(i)];
    W(i) = w[static_cast<std::size_t>(i)];
  }
  Eigen::MatrixXd A = S.transpose() * W.asDiagonal() * S;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
  // Only the components of REFC need to be determined; A may be singular in others.
  Eigen::MatrixXd G;
  if (lu.rank() == 6) {
    G = lu.solve(S.transpose() * W.asDiagonal());
  } else {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
    G = cod.solve(Eigen::MatrixXd(S.transpose() * W.asDiagonal()));
    // A rigid-body component in the null space of A cannot be interpolated.
    Eigen::MatrixXd N = six(ref_frame).transpose() * lu.kernel();
    for (char c : refc)
      if (N.row(c - '1').cwiseAbs().maxCoeff() > 1e-9)
        throw std::invalid_argument(source + ": reference component " + std::string(1, c) +
                                    " is not determined by the independent grids and components");
  }
  // G gives the reference's rigid-body motion in basic; its components in the
  // reference's displacement frame are six(ref_frame)ᵀ G.
  G = six(ref_frame).transpose() * G;
  std::vector<MpcEquation> eqs;
  for (char c : refc) {
    int k = c - '1';
    MpcEquation e;
    e.dependent = gref[static_cast<std::size_t>(k)];
    e.source = source;
    double scale = G.row(k).cwiseAbs().maxCoeff();
    for (int j = 0; j < n; ++j)
      if (std::abs(G(k, j)) > 1e-14 * scale) e.terms.emplace_back(gi[static_cast<std::size_t>(j)], G(k, j));
    eqs.push_back(std::move(e));
  }
  return eqs;
}

std::vector<std::size_t> find_singular_dofs(const SparseMatrix& Kg, const Reduction& mpc_only, const DofMap& dofs,
                                            double eps) {
  SparseMatrix Kn = reduce(Kg, mpc_only);
  const Eigen::VectorXd diag = Kn.diagonal();
  const double kmax = diag.size() ? diag.cwiseAbs().maxCoeff() : 0.0;
  std::vector<std::size_t> out;
  // Group a-set DOFs of each grid by translations / rotations.
  std::unordered_map<std::int64_t, std::array<long, 6>> by_grid;
  for (std::size_t a = 0; a < mpc_only.a_to_g.size(); ++a) {
    const Dof& d = dofs.at(mpc_only.a_to_g[a]);
    if (d.component == 0) {
      if (std::abs(diag(static_cast<int>(a))) <= eps * kmax) out.push_back(mpc_only.a_to_g[a]);
      continue;
    }
    auto it = by_grid.try_emplace(d.point).first;
    it->second[static_cast<std::size_t>(d.component - 1)] = static_cast<long>(a) + 1;  // 1-based, 0 = absent
  }
  for (const auto& entry : by_grid) {
    // Not a structured binding: C++17 lambdas cannot capture one (clang refuses, GCC allows).
    const auto& idx = entry.second;
    for (int block = 0; block < 2; ++block) {
      std::vector<int> comps;
      for (int c = 0; c < 3; ++c)
        if (idx[static_cast<std::size_t>(3 * block + c)] > 0) comps.push_back(c);
      if (comps.empty()) continue;
      const int m = static_cast<int>(comps.size());
      Eigen::MatrixXd B(m, m);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < m; ++j)
          B(i, j) = Kn.coeff(static_cast<int>(idx[static_cast<std::size_t>(3 * block + comps[static_cast<std::size_t>(i)])] - 1),
                             static_cast<int>(idx[static_cast<std::size_t>(3 * block + comps[static_cast<std::size_t>(j)])] - 1));
      const double bmax = B.diagonal().cwiseAbs().maxCoeff();
      std::vector<char> taken(static_cast<std::size_t>(m), 0);
      auto take = [&](int i) {
        taken[static_cast<std::size_t>(i)] = 1;
        out.push_back(mpc_only.a_to_g[static_cast<std::size_t>(idx[static_cast<std::size_t>(3 * block + comps[static_cast<std::size_t>(i)])] - 1)]);
      };
      if (bmax <= eps * kmax) {
        for (int i = 0; i < m; ++i) take(i);
        continue;
      }
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(B);
      for (int e = 0; e < m; ++e) {
        if (es.eigenvalues()(e) > eps * bmax) continue;
        // Constrain the free component most aligned with the singular direction.
        int best = -1;
        double bestv = -1;
        for (int i = 0; i < m; ++i)
          if (!taken[static_cast<std::size_t>(i)] && std::abs(es.eigenvectors()(i, e)) > bestv) {
            bestv = std::abs(es.eigenvectors()(i, e));
            best = i;
          }
        if (best >= 0) take(best);
      }
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace ssid::translators
