#include "estimator/correlation/measures.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <cstdio>

namespace ssid::estimator {

double mac(const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Ref<const Eigen::VectorXd>& e, MacForm form) {
  const double aa = a.squaredNorm(), ee = e.squaredNorm();
  if (aa == 0 || ee == 0) return 0.0;
  const double ae = a.dot(e);
  return form == MacForm::Squared ? ae * ae / (aa * ee) : std::abs(ae) / std::sqrt(aa * ee);
}

Eigen::MatrixXd mac_matrix(const Eigen::Ref<const Eigen::MatrixXd>& A, const Eigen::Ref<const Eigen::MatrixXd>& E,
                           MacForm form) {
  if (A.rows() != E.rows()) throw std::invalid_argument("mac_matrix: shapes have different DOF counts");
  Eigen::MatrixXd R(A.cols(), E.cols());
  for (Eigen::Index i = 0; i < A.cols(); ++i)
    for (Eigen::Index j = 0; j < E.cols(); ++j) R(i, j) = mac(A.col(i), E.col(j), form);
  return R;
}

Eigen::MatrixXd auto_mac(const Eigen::Ref<const Eigen::MatrixXd>& A, MacForm form) { return mac_matrix(A, A, form); }

double modal_scale_factor(const Eigen::Ref<const Eigen::VectorXd>& reference,
                          const Eigen::Ref<const Eigen::VectorXd>& other) {
  const double oo = other.squaredNorm();
  return oo == 0 ? 0.0 : other.dot(reference) / oo;
}

namespace {

/// Checks the a-set and returns the omitted DOFs, or an error message.
std::optional<std::string> split_sets(Eigen::Index n, const std::vector<Eigen::Index>& a_set,
                                      std::vector<Eigen::Index>& o_set) {
  std::vector<char> in_a(static_cast<std::size_t>(n), 0);
  for (auto i : a_set) {
    if (i < 0 || i >= n) return "a-set index " + std::to_string(i) + " outside 0.." + std::to_string(n - 1);
    if (in_a[static_cast<std::size_t>(i)]) return "a-set index " + std::to_string(i) + " repeated";
    in_a[static_cast<std::size_t>(i)] = 1;
  }
  o_set.clear();
  for (Eigen::Index i = 0; i < n; ++i)
    if (!in_a[static_cast<std::size_t>(i)]) o_set.push_back(i);
  return std::nullopt;
}

/// Sparse n x k selection matrix S with S(idx[j], j) = 1.
Eigen::SparseMatrix<double> selector(Eigen::Index n, const std::vector<Eigen::Index>& idx) {
  Eigen::SparseMatrix<double> S(n, static_cast<Eigen::Index>(idx.size()));
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t j = 0; j < idx.size(); ++j) t.emplace_back(idx[j], static_cast<Eigen::Index>(j), 1.0);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

void project(ReducedModel& r, const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M) {
  const Eigen::MatrixXd MT = M * r.T, KT = K * r.T;
  r.M = r.T.transpose() * MT;
  r.K = r.T.transpose() * KT;
  // Symmetric up to round-off; make it exact so eigen-solvers see a symmetric matrix.
  r.M = 0.5 * (r.M + r.M.transpose()).eval();
  r.K = 0.5 * (r.K + r.K.transpose()).eval();
}

}  // namespace

ReducedModel guyan_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                          const std::vector<Eigen::Index>& a_set) {
  ReducedModel r;
  const Eigen::Index n = K.rows();
  std::vector<Eigen::Index> o_set;
  if (K.cols() != n || M.rows() != n || M.cols() != n) {
    r.status = ReductionStatus::BadInput;
    r.message = "K and M must be square and of the same size";
    return r;
  }
  if (auto err = split_sets(n, a_set, o_set)) {
    r.status = ReductionStatus::BadInput;
    r.message = *err;
    return r;
  }
  const auto na = static_cast<Eigen::Index>(a_set.size());
  r.T = Eigen::MatrixXd::Zero(n, na);
  for (Eigen::Index j = 0; j < na; ++j) r.T(a_set[static_cast<std::size_t>(j)], j) = 1.0;
  if (!o_set.empty()) {
    const auto Sa = selector(n, a_set), So = selector(n, o_set);
    const Eigen::SparseMatrix<double> Koo = So.transpose() * K * So;
    const Eigen::SparseMatrix<double> Koa = So.transpose() * K * Sa;
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(Koo);
    if (llt.info() != Eigen::Success) {
      r.status = ReductionStatus::SingularOmittedStiffness;
      r.message = "the stiffness of the " + std::to_string(o_set.size()) +
                  " omitted DOFs is not positive definite: the a-set does not restrain them";
      return r;
    }
    const Eigen::MatrixXd X = llt.solve(Eigen::MatrixXd(Koa));
    for (std::size_t i = 0; i < o_set.size(); ++i) r.T.row(o_set[i]) = -X.row(static_cast<Eigen::Index>(i));
  }
  project(r, K, M);
  return r;
}

ReducedModel irs_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                        const std::vector<Eigen::Index>& a_set) {
  ReducedModel r = guyan_reduce(K, M, a_set);
  if (r.status != ReductionStatus::Ok) return r;
  const Eigen::Index n = K.rows();
  std::vector<Eigen::Index> o_set;
  split_sets(n, a_set, o_set);  // checked by guyan_reduce
  if (o_set.empty()) return r;  // nothing omitted: T = I
  Eigen::LDLT<Eigen::MatrixXd> mg(r.M);
  if (mg.info() != Eigen::Success || mg.vectorD().minCoeff() <= 0) {
    r.status = ReductionStatus::SingularOmittedStiffness;
    r.message = "the Guyan mass of the " + std::to_string(a_set.size()) + " a-set DOFs is singular; IRS needs it";
    return r;
  }
  // Z = M T_G M_G⁻¹ K_G, then the o rows of S Z = K_oo⁻¹ Z_o.
  const Eigen::MatrixXd Z = (M * r.T) * mg.solve(r.K);
  const auto So = selector(n, o_set);
  const Eigen::SparseMatrix<double> Koo = So.transpose() * K * So;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> llt(Koo);  // positive definite: guyan_reduce factored it
  const Eigen::MatrixXd Zo = So.transpose() * Z;
  const Eigen::MatrixXd C = llt.solve(Zo);
  for (std::size_t i = 0; i < o_set.size(); ++i) r.T.row(o_set[i]) += C.row(static_cast<Eigen::Index>(i));
  project(r, K, M);
  return r;
}

ReducedModel serep_reduce(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                          const Eigen::Ref<const Eigen::MatrixXd>& Phi, const std::vector<Eigen::Index>& a_set) {
  ReducedModel r;
  const Eigen::Index n = K.rows();
  std::vector<Eigen::Index> o_set;
  if (K.cols() != n || M.rows() != n || M.cols() != n || Phi.rows() != n) {
    r.status = ReductionStatus::BadInput;
    r.message = "K, M and the modes must have the same number of DOFs";
    return r;
  }
  if (auto err = split_sets(n, a_set, o_set)) {
    r.status = ReductionStatus::BadInput;
    r.message = *err;
    return r;
  }
  const auto na = static_cast<Eigen::Index>(a_set.size());
  Eigen::MatrixXd Phi_a(na, Phi.cols());
  for (Eigen::Index j = 0; j < na; ++j) Phi_a.row(j) = Phi.row(a_set[static_cast<std::size_t>(j)]);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Phi_a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const auto& s = svd.singularValues();
  const double smax = s.size() ? s(0) : 0.0;
  const double tol = std::max<double>(na, Phi.cols()) * 1e-12 * smax;
  if (Phi.cols() == 0 || na < Phi.cols() || s(s.size() - 1) <= tol) {
    r.status = ReductionStatus::RankDeficientModes;
    r.message = "the " + std::to_string(Phi.cols()) + " modes are not independent at the " + std::to_string(na) +
                " a-set DOFs (smallest singular value " + std::to_string(s.size() ? s(s.size() - 1) : 0.0) +
                "); SEREP needs at least as many independent sensors as modes";
    return r;
  }
  // Φ_a⁺ = V Σ⁻¹ Uᵀ
  const Eigen::MatrixXd pinv = svd.matrixV() * s.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  r.T = Phi * pinv;
  project(r, K, M);
  return r;
}

Eigen::MatrixXd cross_orthogonality(const Eigen::Ref<const Eigen::MatrixXd>& Phi_a,
                                    const Eigen::Ref<const Eigen::MatrixXd>& M_r,
                                    const Eigen::Ref<const Eigen::MatrixXd>& Phi_e, bool normalize) {
  if (Phi_a.rows() != M_r.rows() || Phi_e.rows() != M_r.rows() || M_r.cols() != M_r.rows())
    throw std::invalid_argument("cross_orthogonality: shapes and reduced mass differ in DOF count");
  const Eigen::MatrixXd MPe = M_r * Phi_e;
  Eigen::MatrixXd X = Phi_a.transpose() * MPe;
  if (!normalize) return X;
  const Eigen::MatrixXd MPa = M_r * Phi_a;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    const double mi = Phi_a.col(i).dot(MPa.col(i));
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      const double mj = Phi_e.col(j).dot(MPe.col(j));
      X(i, j) = (mi > 0 && mj > 0) ? X(i, j) / std::sqrt(mi * mj) : 0.0;
    }
  }
  return X;
}

MemsResult mems(const Eigen::Ref<const Eigen::VectorXd>& reference, const Eigen::Ref<const Eigen::MatrixXd>& comparison,
                ComparisonScaling scaling, const Eigen::MatrixXd* M_r, MacForm form) {
  if (comparison.rows() != reference.size())
    throw std::invalid_argument("mems: reference and comparison modes differ in DOF count");
  MemsResult r;
  r.comparison = comparison;
  for (Eigen::Index i = 0; i < r.comparison.cols(); ++i) {
    double s = 1.0;
    if (scaling == ComparisonScaling::UnitNorm) {
      s = r.comparison.col(i).norm();
    } else if (scaling == ComparisonScaling::UnitMass) {
      if (!M_r || M_r->rows() != reference.size())
        throw std::invalid_argument("mems: unit-mass scaling needs the reduced mass matrix of the test DOFs");
      const double m = r.comparison.col(i).dot(*M_r * r.comparison.col(i));
      s = m > 0 ? std::sqrt(m) : 0.0;
    }
    if (s > 0) r.comparison.col(i) /= s;
  }
  // Least squares, rank-revealing so dependent comparison modes do not blow up.
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(r.comparison);
  r.alpha = cod.solve(reference);
  const Eigen::VectorXd fit = r.comparison * r.alpha;
  r.error_mode = reference - fit;
  const double rr = reference.squaredNorm();
  r.error_squared = rr > 0 ? r.error_mode.squaredNorm() / rr : 0.0;
  r.mac_superposition = mac(reference, fit, form);
  return r;
}

Pairing pair_modes(const std::vector<double>& fe_hz, const std::vector<double>& test_hz,
                   const Eigen::Ref<const Eigen::MatrixXd>& mac_m, const PairingOptions& o) {
  const int nf = static_cast<int>(fe_hz.size()), nt = static_cast<int>(test_hz.size());
  if (mac_m.rows() != nf || mac_m.cols() != nt)
    throw std::invalid_argument("pair_modes: MAC matrix is not FE modes x test modes");
  Pairing p;
  p.mac = mac_m;
  // Best partner each way; ties go to the lower mode number.
  std::vector<int> best_t(static_cast<std::size_t>(nf), -1), best_f(static_cast<std::size_t>(nt), -1);
  for (int i = 0; i < nf; ++i)
    for (int j = 0; j < nt; ++j)
      if (best_t[i] < 0 || mac_m(i, j) > mac_m(i, best_t[i])) best_t[i] = j;
  for (int j = 0; j < nt; ++j)
    for (int i = 0; i < nf; ++i)
      if (best_f[j] < 0 || mac_m(i, j) > mac_m(best_f[j], j)) best_f[j] = i;

  std::vector<int> partner_of_fe(static_cast<std::size_t>(nf), -1), partner_of_test(static_cast<std::size_t>(nt), -1);
  std::vector<char> fe_ok(static_cast<std::size_t>(nf), 0), test_ok(static_cast<std::size_t>(nt), 0);
  for (int i = 0; i < nf; ++i) {
    const int j = best_t[i];
    if (j < 0 || best_f[j] != i) continue;
    ModePair mp;
    mp.fe = i;
    mp.test = j;
    mp.mac = mac_m(i, j);
    mp.error_pct = test_hz[j] != 0 ? 100.0 * (fe_hz[i] - test_hz[j]) / test_hz[j] : 0.0;
    mp.accepted = mp.mac >= o.min_mac && std::abs(mp.error_pct) <= o.max_frequency_error_pct;
    partner_of_fe[i] = j;
    partner_of_test[j] = i;
    fe_ok[i] = test_ok[j] = mp.accepted;
    p.pairs.push_back(mp);
  }
  for (int i = 0; i < nf; ++i)
    if (!fe_ok[i]) p.unpaired_fe.push_back(i);
  for (int j = 0; j < nt; ++j)
    if (!test_ok[j]) p.unpaired_test.push_back(j);

  // Table rows: walk both mode lists in order; a mode without a mutual partner is
  // listed before a pair that lies further on, as the paper's tables do.
  auto pair_row = [&](int i, int j) {
    PairingRow r;
    r.fe = i;
    r.test = j;
    r.max_fe_mac = mac_m(i, best_t[i]);
    r.max_test_mac = mac_m(best_f[j], j);
    for (const auto& mp : p.pairs)
      if (mp.fe == i) {
        r.error_pct = mp.error_pct;
        r.accepted = mp.accepted;
      }
    return r;
  };
  auto fe_row = [&](int i) {
    PairingRow r;
    r.fe = i;
    r.test_best = nt ? best_t[i] : -1;
    if (nt) r.max_fe_mac = mac_m(i, best_t[i]);
    return r;
  };
  auto test_row = [&](int j) {
    PairingRow r;
    r.test = j;
    r.fe_best = nf ? best_f[j] : -1;
    if (nf) r.max_test_mac = mac_m(best_f[j], j);
    return r;
  };
  std::vector<char> test_done(static_cast<std::size_t>(nt), 0);
  int i = 0, j = 0;
  while (i < nf || j < nt) {
    while (j < nt && test_done[j]) ++j;
    if (i >= nf && j >= nt) break;
    if (i < nf && j < nt && partner_of_fe[i] == j) {
      p.table.push_back(pair_row(i, j));
      test_done[j] = 1;
      ++i;
      ++j;
    } else if (j < nt && partner_of_test[j] < 0 &&
               (i >= nf || partner_of_fe[i] >= 0 || test_hz[j] <= fe_hz[i])) {
      p.table.push_back(test_row(j));
      test_done[j] = 1;
      ++j;
    } else if (i < nf && partner_of_fe[i] < 0) {
      p.table.push_back(fe_row(i));
      ++i;
    } else if (i < nf) {
      // Crossed pairs (FE i pairs with a later test mode while test j pairs with a
      // later FE mode): list FE i's pair now.
      p.table.push_back(pair_row(i, partner_of_fe[i]));
      test_done[partner_of_fe[i]] = 1;
      ++i;
    } else {
      // Test mode whose FE partner was listed already (crossing).
      test_done[j] = 1;
      ++j;
    }
  }
  return p;
}

Pairing pair_modes(const std::vector<double>& fe_hz, const Eigen::Ref<const Eigen::MatrixXd>& fe_shapes,
                   const std::vector<double>& test_hz, const Eigen::Ref<const Eigen::MatrixXd>& test_shapes,
                   const PairingOptions& options) {
  if (fe_shapes.cols() != static_cast<Eigen::Index>(fe_hz.size()) ||
      test_shapes.cols() != static_cast<Eigen::Index>(test_hz.size()))
    throw std::invalid_argument("pair_modes: one frequency per shape column expected");
  Pairing p = pair_modes(fe_hz, test_hz, mac_matrix(fe_shapes, test_shapes, options.form), options);
  for (auto& mp : p.pairs) mp.msf = modal_scale_factor(fe_shapes.col(mp.fe), test_shapes.col(mp.test));
  return p;
}

std::string format_pairing_table(const Pairing& p, const std::vector<double>& fe_hz,
                                 const std::vector<double>& test_hz, const std::vector<int>& fe_numbers,
                                 const std::vector<int>& test_numbers, const std::string& test_label) {
  auto fe_no = [&](int i) { return fe_numbers.empty() ? i + 1 : fe_numbers[static_cast<std::size_t>(i)]; };
  auto test_no = [&](int j) { return test_numbers.empty() ? j + 1 : test_numbers[static_cast<std::size_t>(j)]; };
  auto cell = [](const std::string& s, std::size_t w) { return s + std::string(s.size() < w ? w - s.size() : 1, ' '); };
  auto num = [](const char* fmt, double v) {
    char b[64];
    std::snprintf(b, sizeof b, fmt, v);
    return std::string(b);
  };
  // 7 significant digits, and at least the paper's two decimals (49.50, not 49.5).
  auto hz = [&](double v) {
    std::string t = num("%.7g", v);
    if (t.find_first_of("eE") != std::string::npos) return t;
    const auto dot = t.find('.');
    const std::size_t decimals = dot == std::string::npos ? 0 : t.size() - dot - 1;
    if (dot == std::string::npos) t += '.';
    if (decimals < 2) t += std::string(2 - decimals, '0');
    return t;
  };
  // Frequencies to 7 significant digits (the paper's tables round to 0.01 Hz, where
  // a 1.7 % error on a 0.6 Hz mode would hide): the error they show is the column's.
  const std::string test_head = test_label + " Frequency (Hz)/#";
  std::string o = cell("FEM Frequency (Hz)/#", 22) + cell(test_head, std::max<std::size_t>(22, test_head.size() + 2)) +
                  cell("Maximum FEM MAC", 18) + cell("Maximum Test MAC", 18) + "Frequency Error(%)\n";
  const std::size_t w2 = std::max<std::size_t>(22, test_head.size() + 2);
  const std::string dash = "\u2014";  // the paper's em dash for "not applicable"
  for (const auto& r : p.table) {
    std::string a = r.fe ? hz(fe_hz[*r.fe]) + "/" + std::to_string(fe_no(*r.fe))
                         : (r.fe_best >= 0 ? "-" + std::to_string(fe_no(r.fe_best)) + "-" : dash);
    std::string b = r.test ? hz(test_hz[*r.test]) + "/" + std::to_string(test_no(*r.test))
                           : (r.test_best >= 0 ? "-" + std::to_string(test_no(r.test_best)) + "-" : dash);
    std::string c = r.fe && r.test ? num("%.4f", *r.max_fe_mac) : (r.fe && r.max_fe_mac ? num("%.4f", *r.max_fe_mac) : dash);
    std::string d = r.fe && r.test ? num("%.4f", *r.max_test_mac)
                                   : (r.test && r.max_test_mac ? num("%.4f", *r.max_test_mac) : dash);
    std::string e = r.error_pct ? num("%.2f", *r.error_pct) + (r.accepted ? "(*)" : "") : dash;
    // The em dash is 3 bytes but one column wide: pad by display width.
    auto pad = [&](const std::string& s, std::size_t w) {
      std::size_t width = 0;
      for (unsigned char ch : s) width += (ch & 0xC0) != 0x80;
      return s + std::string(width < w ? w - width : 1, ' ');
    };
    o += pad(a, 22) + pad(b, w2) + pad(c, 18) + pad(d, 18) + e + "\n";
  }
  return o;
}

}  // namespace ssid::estimator
