#pragma once
// The 3-DOF chain's receptance FRFs as a universal file: the input of the
// `ssid identify modes` tests (test_cli_identify.cpp) and of its report's
// (test_cli_report.cpp).
#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <complex>
#include <string>

#include "estimator/identification/chain_model.hpp"
#include "formats/uff.hpp"

/// Receptance FRFs of the chain (Rayleigh damping) from each driven DOF d to every DOF,
/// 0 … 500 Hz every 0.25 Hz, as dataset 58 (complex double) written to `path`; DOF i is
/// node first_node + i in +X (the reference node first_node + d).
inline void write_chain_frf(const ident_test::ChainModel& model, const std::string& path, int first_node = 1) {
  namespace uff = ssid::formats::uff;
  using cd = std::complex<double>;
  uff::UffFile f;
  int id = 0;
  for (const Eigen::Index d : model.drive)
    for (int o = 0; o < 3; ++o) {
      uff::Function58 fn;
      fn.function_type = 4;
      fn.function_id = ++id;
      fn.response_node = o + first_node;
      fn.response_direction = 1;
      fn.reference_node = static_cast<std::int64_t>(d) + first_node;
      fn.reference_direction = 1;
      fn.ordinate_type = 6;
      fn.even = true;
      fn.abscissa_min = 0;
      fn.abscissa_increment = 0.25;
      for (int k = 0; k <= 2000; ++k) {
        const double w = 2 * M_PI * 0.25 * k;
        const Eigen::MatrixXcd H =
            (model.K.cast<cd>() - w * w * model.M.cast<cd>() + cd(0, w) * model.C.cast<cd>()).inverse();
        fn.x.push_back(0.25 * k);
        fn.y.push_back(H(o, d));
      }
      f.datasets.emplace_back(fn);
    }
  uff::write_uff(f, path, uff::Precision::Extended);
}
