#include "estimator/pretest/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <fmt/format.h>
#include <limits>

#include "estimator/identification/era.hpp"
#include "formats/parse_error.hpp"
#include "translators/synthetic_modes.hpp"

namespace ssid::estimator::pretest {

namespace id = identification;
using formats::InputError;

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

double hz_of(double lambda) { return lambda > 0 ? std::sqrt(lambda) / kTwoPi : 0.0; }
}  // namespace

Eigen::MatrixXd exciter_inputs(Eigen::Index n, const std::vector<CandidateDof>& candidates,
                               const std::vector<std::vector<Eigen::Index>>& groups, const std::vector<Exciter>& exciters) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(exciters.size()));
  for (std::size_t e = 0; e < exciters.size(); ++e)
    for (const auto p : groups.at(static_cast<std::size_t>(exciters[e].group))) {
      const auto& c = candidates[static_cast<std::size_t>(p)];
      B(c.row, static_cast<Eigen::Index>(e)) = exciters[e].direction(c.dof.component - 1);
    }
  return B;
}

std::vector<Eigen::MatrixXd> impulse_accelerations(const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                                   const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, double zeta,
                                                   const std::vector<Eigen::Index>& outputs,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt,
                                                   Eigen::Index samples, double cutoff_hz) {
  if (!(zeta > 0 && zeta < 1)) throw InputError(fmt::format("simulated test: damping ratio {} (expected in (0, 1))", zeta));
  if (!(dt > 0) || samples < 1) throw InputError(fmt::format("simulated test: {} samples every {} s", samples, dt));
  const Eigen::MatrixXd Phi_o = take_rows(Phi, outputs);
  const Eigen::MatrixXd gamma = Phi.transpose() * inputs;  // r x E: modal participation of each input
  std::vector<Eigen::MatrixXd> Y(static_cast<std::size_t>(samples),
                                 Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(outputs.size()), inputs.cols()));
  const double root = std::sqrt(1 - zeta * zeta);
  for (Eigen::Index r = 0; r < Phi.cols(); ++r) {
    const double lambda = eigenvalues(r);
    if (!(lambda > 0) || hz_of(lambda) > cutoff_hz) continue;
    const double w = std::sqrt(lambda), wd = w * root;
    const double c_cos = -2 * zeta * w, c_sin = w * (2 * zeta * zeta - 1) / root;
    const Eigen::MatrixXd residue = Phi_o.col(r) * gamma.row(r);  // outputs x E
    for (Eigen::Index k = 0; k < samples; ++k) {
      const double t = static_cast<double>(k) * dt;
      const double g = std::exp(-zeta * w * t) * (c_cos * std::cos(wd * t) + c_sin * std::sin(wd * t));
      Y[static_cast<std::size_t>(k)] += g * residue;
    }
  }
  return Y;
}

void add_measurement_noise(std::vector<Eigen::MatrixXd>& Y, double noise_pct, int adc_bits, std::uint64_t seed) {
  if (!(noise_pct >= 0)) throw InputError(fmt::format("simulated test: noise {} % (expected ≥ 0)", noise_pct));
  if (adc_bits < 0 || adc_bits > 52) throw InputError(fmt::format("simulated test: {} converter bits (expected 0 … 52)", adc_bits));
  if (Y.empty()) return;
  const Eigen::Index no = Y[0].rows(), ni = Y[0].cols();
  Eigen::MatrixXd rms = Eigen::MatrixXd::Zero(no, ni);
  for (const auto& y : Y) rms += y.cwiseAbs2();
  rms = (rms / static_cast<double>(Y.size())).cwiseSqrt();
  if (noise_pct > 0) {
    translators::NormalDeviates normal(seed);
    const Eigen::MatrixXd sigma = rms * (noise_pct / 100);
    for (auto& y : Y)
      for (Eigen::Index i = 0; i < ni; ++i)
        for (Eigen::Index o = 0; o < no; ++o) y(o, i) += sigma(o, i) * normal();
  }
  if (adc_bits > 0) {
    Eigen::MatrixXd peak = Eigen::MatrixXd::Zero(no, ni);
    for (const auto& y : Y) peak = peak.cwiseMax(y.cwiseAbs());
    // Full scale ±peak over 2^bits levels: a step of 2 peak / 2^bits.
    const Eigen::MatrixXd step = peak * std::ldexp(2.0, -adc_bits);
    for (auto& y : Y)
      for (Eigen::Index i = 0; i < ni; ++i)
        for (Eigen::Index o = 0; o < no; ++o)
          if (step(o, i) > 0) y(o, i) = std::round(y(o, i) / step(o, i)) * step(o, i);
  }
}

Eigen::VectorXd realised_shape(const Eigen::Ref<const Eigen::VectorXcd>& psi) {
  const std::complex<double> s = (psi.array() * psi.array()).sum();
  const double theta = 0.5 * std::arg(s);
  return (psi * std::polar(1.0, -theta)).real();
}

double evaluation_bandwidth(const Eigen::Ref<const Eigen::VectorXd>& eigenvalues, const std::vector<Eigen::Index>& targets,
                            const SimulatedTestOptions& o) {
  double f_max = 0;
  for (const auto t : targets) f_max = std::max(f_max, hz_of(eigenvalues(t)));
  return o.bandwidth_factor * f_max;
}

PlacementEvaluation evaluate_placement(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                                       const Eigen::Ref<const Eigen::MatrixXd>& Phi,
                                       const Eigen::Ref<const Eigen::VectorXd>& eigenvalues,
                                       const std::vector<Eigen::Index>& targets, const std::vector<Eigen::Index>& sensors,
                                       const Eigen::Ref<const Eigen::MatrixXd>& inputs, const SimulatedTestOptions& o) {
  if (targets.empty()) throw InputError("simulated test: no target modes");
  if (sensors.empty()) throw InputError("simulated test: no sensors");
  if (inputs.cols() < 1) throw InputError("simulated test: no exciters");
  if (!(o.bandwidth_factor >= 1) || !(o.sampling_factor > 2))
    throw InputError(fmt::format("simulated test: band factor {} (expected ≥ 1) and sampling factor {} (expected > 2)",
                                 o.bandwidth_factor, o.sampling_factor));
  PlacementEvaluation ev;
  double f_min = std::numeric_limits<double>::infinity();
  for (const auto t : targets) f_min = std::min(f_min, hz_of(eigenvalues(t)));
  ev.bandwidth_hz = evaluation_bandwidth(eigenvalues, targets, o);
  if (!(f_min > 0)) throw InputError("simulated test: a target mode has no positive frequency");
  const double highest_solved = hz_of(eigenvalues.maxCoeff());
  if (Phi.cols() < Phi.rows() && highest_solved <= ev.bandwidth_hz)
    throw InputError(fmt::format("simulated test: the {} solved modes reach {:.4g} Hz, below the test's band of {:.4g} Hz "
                                 "(solve for more modes)",
                                 Phi.cols(), highest_solved, ev.bandwidth_hz));
  const double fs = o.sampling_factor * ev.bandwidth_hz;
  ev.dt = 1 / fs;
  ev.samples = std::max<Eigen::Index>(o.min_samples, static_cast<Eigen::Index>(std::ceil(o.min_periods * fs / f_min)));
  for (Eigen::Index r = 0; r < eigenvalues.size(); ++r)
    if (eigenvalues(r) > 0 && hz_of(eigenvalues(r)) <= ev.bandwidth_hz) ++ev.response_modes;

  // --- the test: responses, noise
  auto Y = impulse_accelerations(Phi, eigenvalues, o.damping, sensors, inputs, ev.dt, ev.samples, ev.bandwidth_hz);
  add_measurement_noise(Y, o.noise_pct, o.adc_bits, o.seed);

  // --- ERA over orders 2m … 4m (m = modes in the response: every order can hold them all)
  // and the stabilisation diagram's modes
  const Eigen::Index m2 = 2 * std::max(ev.response_modes, 1);
  for (Eigen::Index n = m2; n <= 2 * m2; n += 2) ev.orders.push_back(n);
  id::EraOptions eo;
  eo.dt = ev.dt;
  const auto results = id::era_orders(Y, eo, ev.orders);
  id::StabilisationOptions so;
  const id::StabilisationResult st = id::stabilise(id::order_poles(results), so);
  ev.identified = st.modes;

  // --- match the targets: the best MAC within the frequency tolerance, each mode once
  const Eigen::MatrixXd Phi_s = take_rows(Phi, sensors);
  std::vector<Eigen::VectorXd> real_shapes;
  for (const auto& md : ev.identified) real_shapes.push_back(realised_shape(md.shape));
  struct Candidate {
    double mac;
    std::size_t target, mode;
  };
  std::vector<Candidate> cands;
  for (std::size_t t = 0; t < targets.size(); ++t) {
    const double f = hz_of(eigenvalues(targets[t]));
    for (std::size_t i = 0; i < ev.identified.size(); ++i) {
      if (std::abs(ev.identified[i].hz - f) > o.match_freq_tol * f) continue;
      const double a = mac(real_shapes[i], Phi_s.col(targets[t]));
      if (a >= o.match_mac_min) cands.push_back({a, t, i});
    }
  }
  std::stable_sort(cands.begin(), cands.end(), [](const Candidate& a, const Candidate& b) { return a.mac > b.mac; });
  ev.targets.assign(targets.size(), TargetMatch{});
  std::vector<bool> used(ev.identified.size(), false);
  for (const auto& c : cands) {
    TargetMatch& tm = ev.targets[c.target];
    if (tm.identified || used[c.mode]) continue;
    used[c.mode] = true;
    const auto& md = ev.identified[c.mode];
    const double f = hz_of(eigenvalues(targets[c.target]));
    tm = {true, static_cast<int>(c.mode), md.hz, md.zeta, 100 * (md.hz - f) / f, c.mac};
  }
  ev.max_frequency_error_pct = kNaN;
  for (const auto& tm : ev.targets)
    if (tm.identified) {
      ++ev.identified_count;
      const double e = std::abs(tm.frequency_error_pct);
      ev.max_frequency_error_pct = std::isnan(ev.max_frequency_error_pct) ? e : std::max(ev.max_frequency_error_pct, e);
    }

  // --- cross-orthogonality with the SEREP mass of the targets on the sensors
  ev.min_diagonal_xor = ev.max_offdiagonal_xor = kNaN;
  const Eigen::MatrixXd Phi_t = [&] {
    Eigen::MatrixXd P(Phi.rows(), static_cast<Eigen::Index>(targets.size()));
    for (std::size_t t = 0; t < targets.size(); ++t) P.col(static_cast<Eigen::Index>(t)) = Phi.col(targets[t]);
    return P;
  }();
  const ReducedModel serep = serep_reduce(K, M, Phi_t, sensors);
  ev.xor_status = serep.status;
  ev.xor_message = serep.message;
  if (serep.status != ReductionStatus::Ok || ev.identified_count == 0) return ev;
  Eigen::MatrixXd Psi(static_cast<Eigen::Index>(sensors.size()), ev.identified_count);
  for (std::size_t t = 0; t < targets.size(); ++t)
    if (ev.targets[t].identified) {
      Psi.col(static_cast<Eigen::Index>(ev.xor_rows.size())) = real_shapes[static_cast<std::size_t>(ev.targets[t].mode)];
      ev.xor_rows.push_back(static_cast<int>(t));
    }
  ev.xor_matrix = cross_orthogonality(Psi, serep.M, take_rows(Phi_t, sensors), true);
  ev.min_diagonal_xor = std::numeric_limits<double>::infinity();
  ev.max_offdiagonal_xor = 0;
  for (Eigen::Index i = 0; i < ev.xor_matrix.rows(); ++i)
    for (Eigen::Index j = 0; j < ev.xor_matrix.cols(); ++j) {
      const double x = std::abs(ev.xor_matrix(i, j));
      if (j == ev.xor_rows[static_cast<std::size_t>(i)]) ev.min_diagonal_xor = std::min(ev.min_diagonal_xor, x);
      else ev.max_offdiagonal_xor = std::max(ev.max_offdiagonal_xor, x);
    }
  return ev;
}

}  // namespace ssid::estimator::pretest
