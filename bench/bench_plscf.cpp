/// \file bench_plscf.cpp
/// pLSCF on issue 22's benchmark case: 2 references × 60 responses × 4000 spectral lines
/// (0 … 399.9 Hz every 0.1 Hz), model orders 1 … 100, then the stabilisation diagram and LSFD
/// for the chosen modes. The FRFs are synthesised from a known modal model (30 modes, 10 …
/// 370 Hz, damping 0.5 … 2 %, shapes of a beam-like sine family, slightly complex, random
/// participation factors; fixed seed) with 2 % complex Gaussian noise per FRF's RMS, so the
/// run also says how well the modes come back. Prints wall and CPU time per phase.
///
/// usage: bench_plscf [--max-order P] [--min-fraction F] [--era] [--export DIR]
///   --era: also ERA on the same FRFs (as `ssid identify modes --method era`), state
///   dimensions 2 … 2P, and the same stabilisation.
///   --min-fraction F: the stabilisation's recurrence rule (StabilisationOptions::min_fraction,
///   default 0.5: a mode must be stable at half the orders).
///   --export DIR: writes DIR/frf.bin (the data, for bench/plscf_reference.py and
///   bench/era_reference.py; with --era also DIR/era_poles_ssid.txt, ERA's largest order) and
///   DIR/poles_ssid.txt (the poles of the largest order: Re λ, Im λ per line, rad/s).
#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "estimator/identification/era.hpp"
#include "estimator/identification/modal_indicators.hpp"
#include "estimator/identification/plscf.hpp"
#include "estimator/identification/stabilisation.hpp"

namespace {

namespace id = ssid::estimator::identification;
using cd = std::complex<double>;

struct Case {
  Eigen::VectorXd hz;                 ///< line frequencies, Hz
  std::vector<Eigen::MatrixXcd> frf;  ///< no × ni per line
  std::vector<cd> lambda;             ///< exact poles
  Eigen::MatrixXcd psi;               ///< exact shapes, no × modes
};

Case make_case() {
  const Eigen::Index nf = 4000, no = 60, ni = 2, modes = 30;
  const double df = 0.1;
  Case c;
  c.hz = Eigen::VectorXd::LinSpaced(nf, 0.0, df * static_cast<double>(nf - 1));
  std::mt19937_64 gen(2026);
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u01;
  c.psi.resize(no, modes);
  Eigen::MatrixXcd l(ni, modes);
  for (Eigen::Index r = 0; r < modes; ++r) {
    const double f = 10.0 + 12.3 * static_cast<double>(r) + 2.0 * u01(gen);
    const double zeta = 0.005 + 0.015 * u01(gen);
    const double w = 2 * M_PI * f;
    c.lambda.emplace_back(-zeta * w, w * std::sqrt(1 - zeta * zeta));
    for (Eigen::Index o = 0; o < no; ++o) {
      const double x = (static_cast<double>(o) + 0.5) / static_cast<double>(no);
      c.psi(o, r) = cd(std::sin(static_cast<double>(r + 1) * M_PI * x), 0.02 * n01(gen));
    }
    for (Eigen::Index j = 0; j < ni; ++j) l(j, r) = cd(n01(gen), 0.1 * n01(gen));
  }
  c.frf.assign(static_cast<std::size_t>(nf), Eigen::MatrixXcd::Zero(no, ni));
  for (Eigen::Index k = 0; k < nf; ++k) {
    const cd iw(0, 2 * M_PI * c.hz(k));
    for (Eigen::Index r = 0; r < modes; ++r) {
      const Eigen::MatrixXcd res = c.psi.col(r) * l.col(r).transpose();
      c.frf[static_cast<std::size_t>(k)] += res / (iw - c.lambda[static_cast<std::size_t>(r)]) +
                                            res.conjugate() / (iw - std::conj(c.lambda[static_cast<std::size_t>(r)]));
    }
  }
  Eigen::MatrixXd rms = Eigen::MatrixXd::Zero(no, ni);
  for (const auto& h : c.frf) rms += h.cwiseAbs2();
  rms = (rms / static_cast<double>(nf)).cwiseSqrt();
  for (auto& h : c.frf)
    for (Eigen::Index o = 0; o < no; ++o)
      for (Eigen::Index j = 0; j < ni; ++j) h(o, j) += 0.02 * rms(o, j) * cd(n01(gen), n01(gen)) / std::sqrt(2.0);
  return c;
}

struct Clock {
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  std::clock_t cpu = std::clock();
  void print(const char* what) const {
    const double w = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
    const double c = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    std::printf("%-36s %8.3f s wall %8.3f s CPU\n", what, w, c);
  }
};

/// How many exact modes the identified ones match within 0.5 % in frequency, and how well.
void report_modes(const Case& c, const std::vector<id::IdentifiedPole>& modes) {
  std::size_t found = 0;
  double worst_f = 0, worst_z = 0, worst_mac = 1;
  for (std::size_t r = 0; r < c.lambda.size(); ++r) {
    const double f = std::abs(c.lambda[r]) / (2 * M_PI), z = -c.lambda[r].real() / std::abs(c.lambda[r]);
    const id::IdentifiedPole* best = nullptr;
    for (const auto& p : modes)
      if (!best || std::abs(p.hz - f) < std::abs(best->hz - f)) best = &p;
    if (!best || std::abs(best->hz - f) > 0.005 * f) {
      std::printf("  exact mode %zu (%.3f Hz, zeta %.4f) not found\n", r + 1, f, z);
      continue;
    }
    ++found;
    const double mac = id::complex_mac(best->shape, c.psi.col(static_cast<Eigen::Index>(r)));
    if (mac < 0.99) std::printf("  exact mode %zu (%.3f Hz): MAC %.4f\n", r + 1, f, mac);
    worst_f = std::max(worst_f, std::abs(best->hz - f) / f);
    worst_z = std::max(worst_z, std::abs(best->zeta - z) / z);
    worst_mac = std::min(worst_mac, mac);
  }
  std::printf("%zu modes chosen, %zu of %zu exact modes found within 0.5 %%: worst frequency error %.2e, damping %.2e, "
              "lowest MAC %.5f\n",
              modes.size(), found, c.lambda.size(), worst_f, worst_z, worst_mac);
}

}  // namespace

int main(int argc, char** argv) {
  Eigen::Index max_order = 100;
  std::string export_dir;
  bool era = false;
  id::StabilisationOptions so;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--max-order" && a + 1 < argc) {
      max_order = std::stol(argv[++a]);
    } else if (arg == "--min-fraction" && a + 1 < argc) {
      so.min_fraction = std::stod(argv[++a]);
    } else if (arg == "--era") {
      era = true;
    } else if (arg == "--export" && a + 1 < argc) {
      export_dir = argv[++a];
    } else {
      std::fprintf(stderr, "usage: bench_plscf [--max-order P] [--min-fraction F] [--era] [--export DIR]\n");
      return 2;
    }
  }
  const Case c = make_case();
  const Eigen::Index no = c.frf[0].rows(), ni = c.frf[0].cols();
  std::printf("pLSCF benchmark: %ld references x %ld responses x %ld lines, orders 1..%ld, %zu modes, 2 %% noise\n",
              static_cast<long>(ni), static_cast<long>(no), static_cast<long>(c.hz.size()), static_cast<long>(max_order),
              c.lambda.size());
  if (!export_dir.empty()) {
    std::ofstream f(export_dir + "/frf.bin", std::ios::binary);
    const double head[3] = {static_cast<double>(c.hz.size()), static_cast<double>(no), static_cast<double>(ni)};
    f.write(reinterpret_cast<const char*>(head), sizeof head);
    f.write(reinterpret_cast<const char*>(c.hz.data()), static_cast<std::streamsize>(sizeof(double) * c.hz.size()));
    for (const auto& h : c.frf)  // line-major, then response, then reference: re, im
      for (Eigen::Index o = 0; o < no; ++o)
        for (Eigen::Index j = 0; j < ni; ++j) {
          const double v[2] = {h(o, j).real(), h(o, j).imag()};
          f.write(reinterpret_cast<const char*>(v), sizeof v);
        }
  }
  std::vector<Eigen::Index> orders;
  for (Eigen::Index p = 1; p <= max_order; ++p) orders.push_back(p);

  const Clock all;
  Clock t;
  const auto poles = id::plscf_orders(c.hz, c.frf, {}, orders);
  t.print("pLSCF poles, all orders");
  t = Clock();
  const id::StabilisationResult st = id::stabilise(poles, so);
  t.print("stabilisation");
  t = Clock();
  id::LsfdResult fit;
  if (!st.modes.empty()) fit = id::lsfd(c.hz, c.frf, id::mode_poles(st, poles), {});
  t.print("LSFD");
  all.print("total");

  report_modes(c, fit.modes);
  std::printf("LSFD fit error %.3e\n", fit.fit_error);

  if (era) {
    // ERA on the same FRFs as `ssid identify modes --method era` runs it: the impulse response
    // by inverse FFT (its first half), ERA at the state dimensions 2, 4, …, 2P (as many poles
    // as pLSCF's order P), the same stabilisation.
    const Clock e;
    const auto Y = id::markov_from_frf(c.frf, c.hz(1) - c.hz(0));
    const double dt = 1.0 / (static_cast<double>(Y.size()) * (c.hz(1) - c.hz(0)));
    const std::vector<Eigen::MatrixXd> head(Y.begin(), Y.begin() + static_cast<std::ptrdiff_t>(Y.size() / 2));
    id::EraOptions eo;
    eo.dt = dt;
    std::vector<Eigen::Index> era_orders;
    for (Eigen::Index n = 2; n <= 2 * max_order; n += 2) era_orders.push_back(n);
    const std::vector<id::EraResult> realizations = id::era_orders(head, eo, era_orders);
    const id::StabilisationResult est = id::stabilise(id::order_poles(realizations), so);
    e.print("ERA, orders 2..2P, and stabilisation");
    if (!export_dir.empty()) {  // the largest order's poles, for bench/era_reference.py
      std::ofstream f(export_dir + "/era_poles_ssid.txt");
      f.precision(17);
      for (const auto& p : realizations.back().poles) f << p.lambda.real() << " " << p.lambda.imag() << "\n";
    }
    std::vector<id::IdentifiedPole> modes;
    for (const auto& m : est.modes) {
      id::IdentifiedPole p;
      p.hz = m.hz;
      p.zeta = m.zeta;
      p.shape = m.shape;
      modes.push_back(p);
    }
    report_modes(c, modes);
  }
  if (!export_dir.empty()) {
    std::ofstream f(export_dir + "/poles_ssid.txt");
    f.precision(17);
    for (const auto& p : poles.back().poles) f << p.lambda.real() << " " << p.lambda.imag() << "\n";
  }
  return 0;
}
