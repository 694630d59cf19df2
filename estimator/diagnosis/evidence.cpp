#include "estimator/diagnosis/evidence.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "estimator/correlation/measures.hpp"
#include "estimator/eigen/eigen_solver.hpp"

namespace ssid::estimator::diagnosis {

namespace {

/// Shares of a sensor vector per grid, largest first.
std::vector<GridShare> shares(const std::vector<std::int64_t>& grids, const Eigen::VectorXd& v,
                              std::size_t keep) {
  std::map<std::int64_t, double> by;
  double total = 0;
  for (std::size_t k = 0; k < grids.size(); ++k) {
    const double x = v(static_cast<Eigen::Index>(k)) * v(static_cast<Eigen::Index>(k));
    by[grids[k]] += x;
    total += x;
  }
  std::vector<GridShare> out;
  for (const auto& [g, x] : by) out.push_back({g, total > 0 ? x / total : 0.0});
  std::sort(out.begin(), out.end(), [](const GridShare& a, const GridShare& b) { return a.share > b.share; });
  if (out.size() > keep) out.resize(keep);
  return out;
}

}  // namespace

Evidence gather_evidence(PreparedConfiguration& pb, const Eigen::VectorXd& r, const std::vector<UpdatePair>& pairs) {
  const ModalSolution sol = pb.model->solve(r);
  Evidence ev;
  const auto& test = pb.test;
  std::vector<bool> fem_paired(static_cast<std::size_t>(sol.eigenvalues.size()), false);
  std::map<int, const UpdatePair*> by_test;
  for (const auto& p : pairs) {
    by_test[p.test] = &p;
    fem_paired[static_cast<std::size_t>(p.fem)] = true;
  }
  // Unit columns of the analysis shapes at the sensors, for MEMS.
  Eigen::MatrixXd U = sol.sensor_shapes;
  for (Eigen::Index j = 0; j < U.cols(); ++j)
    if (U.col(j).norm() > 0) U.col(j).normalize();
  const auto ns = static_cast<double>(pb.sensor_grids.size());
  std::map<std::int64_t, double> grid_e;
  double max_test_hz = 0;
  std::vector<double> errs, freqs;
  for (std::size_t i = 0; i < test.size(); ++i) {
    const auto& t = test[i];
    max_test_hz = std::max(max_test_hz, t.frequency_hz);
    ModeEvidence me;
    me.test_id = t.id;
    me.test_hz = t.frequency_hz;
    Eigen::VectorXd z;
    if (t.shape.size()) {
      z = t.shape / t.shape.norm();
      const MemsResult m = mems(z, U);
      me.mems_error = m.error_squared;
    }
    auto it = by_test.find(static_cast<int>(i));
    if (it != by_test.end()) {
      const auto& p = *it->second;
      me.fem = p.fem + 1;
      me.fem_hz = eigenvalue_to_hz(sol.eigenvalues(p.fem));
      me.error_pct = (me.fem_hz - t.frequency_hz) / t.frequency_hz * 100.0;
      me.mac = p.mac;
      errs.push_back(me.error_pct);
      freqs.push_back(t.frequency_hz);
      if (z.size()) {
        Eigen::VectorXd u = sol.sensor_shapes.col(p.fem);
        u.normalize();
        if (u.dot(z) < 0) u = -u;
        const Eigen::VectorXd e = z - u;
        me.error_grids = shares(pb.sensor_grids, e, 3);
        const double s2 = t.shape_std > 0 ? t.shape_std * t.shape_std : 1.0 / ns;
        for (std::size_t k = 0; k < pb.sensor_grids.size(); ++k)
          grid_e[pb.sensor_grids[k]] += e(static_cast<Eigen::Index>(k)) * e(static_cast<Eigen::Index>(k)) / s2;
      }
    } else {
      UnpairedTestMode u;
      u.id = t.id;
      u.frequency_hz = t.frequency_hz;
      if (z.size()) u.moves = shares(pb.sensor_grids, z, 5);
      u.mems_error = me.mems_error;
      ev.unpaired_test.push_back(u);
    }
    ev.modes.push_back(me);
  }
  for (Eigen::Index j = 0; j < sol.eigenvalues.size(); ++j) {
    const double f = eigenvalue_to_hz(sol.eigenvalues(j));
    if (fem_paired[static_cast<std::size_t>(j)] || f > 1.1 * max_test_hz || f < 0.5 * test.front().frequency_hz) continue;
    ev.unpaired_fe.push_back({static_cast<int>(j + 1), f});
  }
  // Frequency error pattern.
  if (!errs.empty()) {
    double sum = 0, sum2 = 0;
    for (double e : errs) { sum += e; sum2 += e * e; }
    const auto n = static_cast<double>(errs.size());
    ev.mean_error_pct = sum / n;
    ev.rms_error_pct = std::sqrt(sum2 / n);
    double fm = 0;
    for (double f : freqs) fm += f / n;
    double sxy = 0, sxx = 0;
    for (std::size_t k = 0; k < errs.size(); ++k) {
      sxy += (freqs[k] - fm) * (errs[k] - ev.mean_error_pct);
      sxx += (freqs[k] - fm) * (freqs[k] - fm);
    }
    ev.error_slope_pct_per_hz = sxx > 0 ? sxy / sxx : 0.0;
  }
  double total = 0;
  for (const auto& [g, e] : grid_e) total += e;
  for (const auto& [g, e] : grid_e) ev.grid_misfit.push_back({g, total > 0 ? e / total : 0.0});
  std::sort(ev.grid_misfit.begin(), ev.grid_misfit.end(), [](const GridShare& a, const GridShare& b) { return a.share > b.share; });

  // Readings.
  for (const auto& u : ev.unpaired_test) {
    std::string s = "test mode " + std::to_string(u.id) + " at " + fixed(u.frequency_hz, 2) +
                    " Hz has no analysis partner (MEMS e^2 = " + fixed(u.mems_error, 2) + ")";
    if (!u.moves.empty())
      s += "; it moves grid " + std::to_string(u.moves[0].grid) + " most (" + fixed(100 * u.moves[0].share, 0) + " %)";
    ev.findings.push_back(s);
  }
  if (!ev.unpaired_fe.empty())
    ev.findings.push_back(std::to_string(ev.unpaired_fe.size()) + " analysis mode(s) in the tested band have no test partner");
  if (!errs.empty())
    ev.findings.push_back("paired frequency errors: mean " + fixed(ev.mean_error_pct, 2) + " %, RMS " +
                          fixed(ev.rms_error_pct, 2) + " %, slope " + fixed(ev.error_slope_pct_per_hz, 4) + " %/Hz");
  if (ev.grid_misfit.size() > 3) {
    const double top = ev.grid_misfit[0].share;
    const double even = 1.0 / static_cast<double>(ev.grid_misfit.size());
    if (top > 4 * even)
      ev.findings.push_back("shape errors concentrate at grid " + std::to_string(ev.grid_misfit[0].grid) + " (" +
                            fixed(100 * top, 0) + " % of the shape misfit; " + fixed(100 * even, 1) + " % if even)");
  }
  return ev;
}

}  // namespace ssid::estimator::diagnosis
