#include "estimator/identification/armax_order.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "formats/parse_error.hpp"

namespace ssid::estimator::identification {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string list_outputs(const std::vector<int>& outputs) {
  std::string text;
  for (const int o : outputs) text += (text.empty() ? "" : ", ") + std::to_string(o + 1);
  return text;
}

/// Why a pole can never be a structural mode, or "" when it can.
std::string unfit_reason(const ArmaxPole& pole, const RecurrenceOptions& o) {
  if (pole.real) return "real root";
  if (std::abs(std::arg(pole.z)) >= (1 - o.nyquist_margin) * kPi) return "at the Nyquist frequency";
  if (!(pole.zeta > 0)) return "unstable (negative damping)";
  return "";
}

/// A candidate pairing of a reference pole with a pole of another run.
struct Pairing {
  double distance;
  std::size_t reference, other;
};

/// Closest-first one-to-one matching of the reference poles to one other run's poles.
/// Returns, per reference pole, the matched index or npos.
std::vector<std::size_t> match_run(const std::vector<ArmaxPole>& reference, const std::vector<bool>& fit_reference,
                                   const std::vector<ArmaxPole>& other, const std::vector<bool>& fit_other,
                                   const RecurrenceOptions& o) {
  constexpr auto npos = std::numeric_limits<std::size_t>::max();
  std::vector<Pairing> pairs;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!fit_reference[i]) continue;
    for (std::size_t k = 0; k < other.size(); ++k) {
      if (!fit_other[k]) continue;
      const ArmaxPole &a = reference[i], &b = other[k];
      const double dh = std::abs(a.hz - b.hz) / a.hz;
      const double dz = std::abs(a.zeta - b.zeta) / std::max(a.zeta, b.zeta);
      if (dh <= o.hz_tolerance && dz <= o.zeta_tolerance)
        pairs.push_back({dh / o.hz_tolerance + dz / o.zeta_tolerance, i, k});
    }
  }
  std::sort(pairs.begin(), pairs.end(), [](const Pairing& x, const Pairing& y) { return x.distance < y.distance; });
  std::vector<std::size_t> match(reference.size(), npos);
  std::vector<bool> used(other.size(), false);
  for (const auto& pr : pairs) {
    if (match[pr.reference] != npos || used[pr.other]) continue;
    match[pr.reference] = pr.other;
    used[pr.other] = true;
  }
  return match;
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / double(v.size()); }

/// Sample standard deviation (n − 1); 0 for a single value.
double sample_std(const std::vector<double>& v) {
  if (v.size() < 2) return 0;
  const double m = mean(v);
  double sum = 0;
  for (const double x : v) sum += (x - m) * (x - m);
  return std::sqrt(sum / double(v.size() - 1));
}

}  // namespace

std::vector<ArmaxRun> single_output_runs(int outputs, const ArmaxOptions& all_outputs) {
  if (outputs < 1) throw formats::InputError("ARMAX order rule: no response records");
  std::vector<ArmaxRun> runs;
  ArmaxRun all;
  all.outputs.resize(static_cast<std::size_t>(outputs));
  std::iota(all.outputs.begin(), all.outputs.end(), 0);
  all.options = all_outputs;
  runs.push_back(all);
  for (int j = 0; j < outputs; ++j) {
    ArmaxRun one;
    one.outputs = {j};
    one.options = all_outputs;
    one.options.ar_order = all_outputs.ar_order * outputs;
    one.options.arx_order = all_outputs.arx_order * outputs;
    runs.push_back(one);
  }
  return runs;
}

std::vector<RecurringMode> recurring_modes(const std::vector<ArmaxModel>& models,
                                           const std::vector<std::vector<int>>& outputs,
                                           const RecurrenceOptions& options,
                                           std::vector<RejectedPole>& rejected) {
  constexpr auto npos = std::numeric_limits<std::size_t>::max();
  const std::size_t runs = models.size();
  std::vector<std::vector<bool>> fit(runs);
  std::vector<std::vector<bool>> in_mode(runs);
  for (std::size_t r = 0; r < runs; ++r) {
    const auto& poles = models[r].poles;
    in_mode[r].assign(poles.size(), false);
    for (std::size_t i = 0; i < poles.size(); ++i) {
      const std::string why = unfit_reason(poles[i], options);
      fit[r].push_back(why.empty());
      if (!why.empty()) rejected.push_back({r, poles[i], why});
    }
  }
  const auto& reference = models.at(0).poles;
  // matches[r][i]: run r's pole matched to reference pole i.
  std::vector<std::vector<std::size_t>> matches(runs);
  matches[0].resize(reference.size());
  std::iota(matches[0].begin(), matches[0].end(), std::size_t{0});
  for (std::size_t r = 1; r < runs; ++r)
    matches[r] = match_run(reference, fit[0], models[r].poles, fit[r], options);

  std::vector<RecurringMode> modes;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    if (!fit[0][i]) continue;
    std::size_t missing = npos;
    for (std::size_t r = 1; r < runs && missing == npos; ++r)
      if (matches[r][i] == npos) missing = r;
    if (missing != npos) {
      rejected.push_back({0, reference[i],
                          "not found in run " + std::to_string(missing + 1) + " (outputs " +
                              list_outputs(outputs.at(missing)) + ")"});
      continue;
    }
    RecurringMode mode;
    std::vector<double> hz, zeta;
    for (std::size_t r = 0; r < runs; ++r) {
      const ArmaxPole& p = models[r].poles[matches[r][i]];
      hz.push_back(p.hz);
      zeta.push_back(p.zeta);
      mode.pole.push_back(matches[r][i]);
      in_mode[r][matches[r][i]] = true;
    }
    mode.hz_mean = mean(hz);
    mode.hz_std = sample_std(hz);
    mode.zeta_mean = mean(zeta);
    mode.zeta_std = sample_std(zeta);
    mode.shape = reference[i].shape;
    mode.outputs = outputs.at(0);
    modes.push_back(std::move(mode));
  }
  for (std::size_t r = 1; r < runs; ++r)
    for (std::size_t k = 0; k < models[r].poles.size(); ++k)
      if (fit[r][k] && !in_mode[r][k])
        rejected.push_back({r, models[r].poles[k], "not a recurring pole of run 1 (outputs " +
                                                       list_outputs(outputs.at(0)) + ")"});
  std::sort(modes.begin(), modes.end(),
            [](const RecurringMode& a, const RecurringMode& b) { return a.hz_mean < b.hz_mean; });
  return modes;
}

ArmaxOrderResult armax_model_order(const Eigen::Ref<const Eigen::MatrixXd>& outputs,
                                   const Eigen::Ref<const Eigen::MatrixXd>& inputs, double dt,
                                   const std::vector<ArmaxRun>& runs, const RecurrenceOptions& options) {
  if (runs.size() < 2)
    throw formats::InputError("ARMAX order rule: at least two identifications (subsets of the records) are needed, got " +
                              std::to_string(runs.size()));
  ArmaxOrderResult result;
  result.runs = runs;
  std::vector<std::vector<int>> names;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const auto& cols = runs[r].outputs;
    if (cols.empty()) throw formats::InputError("ARMAX order rule: run " + std::to_string(r + 1) + " uses no records");
    Eigen::MatrixXd subset(outputs.rows(), static_cast<Eigen::Index>(cols.size()));
    for (std::size_t j = 0; j < cols.size(); ++j) {
      if (cols[j] < 0 || cols[j] >= outputs.cols())
        throw formats::InputError("ARMAX order rule: run " + std::to_string(r + 1) + " names response record " +
                                  std::to_string(cols[j] + 1) + " of " + std::to_string(outputs.cols()));
      subset.col(static_cast<Eigen::Index>(j)) = outputs.col(cols[j]);
    }
    result.models.push_back(identify_armax(subset, inputs, dt, runs[r].options));
    names.push_back(cols);
  }
  result.modes = recurring_modes(result.models, names, options, result.rejected);
  return result;
}

}  // namespace ssid::estimator::identification
