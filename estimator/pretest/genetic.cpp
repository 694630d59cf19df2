#include "estimator/pretest/genetic.hpp"

#include <algorithm>
#include <random>
#include <stdexcept>

namespace ssid::estimator::pretest {

namespace {

/// Uniform numbers from the 64-bit Mersenne twister, mapped the same way everywhere.
class Random {
public:
  explicit Random(std::uint64_t seed) : m_engine(seed) {}
  /// [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(m_engine() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// 0..n-1
  int below(int n) { return std::min(n - 1, static_cast<int>(uniform() * n)); }

private:
  std::mt19937_64 m_engine;
};

Design random_design(const GeneticProblem& p, Random& rng) {
  Design d;
  for (int n : p.discrete_sizes) d.discrete.push_back(rng.below(n));
  for (const auto& [lo, hi] : p.continuous_bounds) d.continuous.push_back(rng.uniform(lo, hi));
  return d;
}

}  // namespace

GeneticResult genetic_minimize(const GeneticProblem& problem, const std::function<double(const Design&)>& objective,
                               const GeneticOptions& o) {
  if (problem.discrete_sizes.empty() && problem.continuous_bounds.empty())
    throw std::invalid_argument("genetic_minimize: the problem has no genes");
  for (int n : problem.discrete_sizes)
    if (n < 1) throw std::invalid_argument("genetic_minimize: a discrete gene has no values");
  if (o.population < 2 || o.generations < 0 || o.elite < 0 || o.elite >= o.population || o.tournament < 1)
    throw std::invalid_argument("genetic_minimize: population >= 2, generations >= 0, 0 <= elite < population");
  Random rng(o.seed);
  GeneticResult res;
  auto evaluate = [&](Design& d) {
    d.objective = objective(d);
    ++res.evaluations;
  };
  auto by_objective = [](const Design& a, const Design& b) { return a.objective < b.objective; };
  std::vector<Design> pop;
  for (int i = 0; i < o.population; ++i) {
    pop.push_back(random_design(problem, rng));
    evaluate(pop.back());
  }
  std::stable_sort(pop.begin(), pop.end(), by_objective);
  res.best_per_generation.push_back(pop.front().objective);
  auto select = [&]() -> const Design& {
    int best = rng.below(o.population);
    for (int t = 1; t < o.tournament; ++t) best = std::min(best, rng.below(o.population));  // pop is sorted
    return pop[static_cast<std::size_t>(best)];
  };
  for (int gen = 0; gen < o.generations; ++gen) {
    std::vector<Design> next(pop.begin(), pop.begin() + o.elite);
    while (static_cast<int>(next.size()) < o.population) {
      Design a = select(), b = select();
      if (rng.uniform() < o.crossover_rate) {
        for (std::size_t g = 0; g < a.discrete.size(); ++g)
          if (rng.uniform() < 0.5) std::swap(a.discrete[g], b.discrete[g]);
        for (std::size_t g = 0; g < a.continuous.size(); ++g) {
          const auto [lo, hi] = problem.continuous_bounds[g];
          const double x = a.continuous[g], y = b.continuous[g], span = std::abs(x - y);
          const double l = std::min(x, y) - 0.5 * span, h = std::max(x, y) + 0.5 * span;
          a.continuous[g] = std::clamp(rng.uniform(l, h), lo, hi);
          b.continuous[g] = std::clamp(rng.uniform(l, h), lo, hi);
        }
      }
      for (Design* d : {&a, &b}) {
        for (std::size_t g = 0; g < d->discrete.size(); ++g)
          if (rng.uniform() < o.mutation_rate) d->discrete[g] = rng.below(problem.discrete_sizes[g]);
        for (std::size_t g = 0; g < d->continuous.size(); ++g)
          if (rng.uniform() < o.mutation_rate)
            d->continuous[g] = rng.uniform(problem.continuous_bounds[g].first, problem.continuous_bounds[g].second);
        if (static_cast<int>(next.size()) < o.population) {
          evaluate(*d);
          next.push_back(std::move(*d));
        }
      }
    }
    pop = std::move(next);
    std::stable_sort(pop.begin(), pop.end(), by_objective);
    res.best_per_generation.push_back(pop.front().objective);
  }
  res.best = pop.front();
  return res;
}

}  // namespace ssid::estimator::pretest
