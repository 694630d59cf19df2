#pragma once
/// \file genetic.hpp
/// A small genetic algorithm over mixed discrete/continuous designs (issue 23
/// item 4; pretest paper §2.4 and §4, after Holland 1975 and Zimmerman 1993),
/// seeded and reproducible: the same problem, options and seed give the same
/// result on every platform (the random numbers are drawn from std::mt19937_64
/// and mapped to integers and reals here, not by the library's distributions).
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace ssid::estimator::pretest {

struct GeneticProblem {
  std::vector<int> discrete_sizes;  ///< discrete gene d takes the values 0..discrete_sizes[d]-1
  std::vector<std::pair<double, double>> continuous_bounds;  ///< [low, high] of each continuous gene
};

struct Design {
  std::vector<int> discrete;
  std::vector<double> continuous;
  double objective = 0;  ///< the objective's value (minimised)
};

struct GeneticOptions {
  int population = 20;   ///< members (paper: 20)
  int generations = 40;  ///< generations after the initial population (paper: 40)
  std::uint64_t seed = 1;
  double crossover_rate = 0.8;  ///< probability that two parents are crossed (else copied)
  double mutation_rate = 0.1;   ///< per gene: a new uniform random value
  int elite = 2;                ///< best members carried over unchanged
  int tournament = 2;           ///< members drawn per selection; the fitter is a parent
};

struct GeneticResult {
  Design best;
  std::vector<double> best_per_generation;  ///< best objective after each generation (initial first)
  long evaluations = 0;
};

/// Minimises `objective` over the problem's genes: a random initial population,
/// then per generation elitism, tournament selection, uniform crossover of the
/// discrete genes, blend crossover (BLX-0.5, clipped to the bounds) of the
/// continuous ones, and uniform mutation. Throws std::invalid_argument for a
/// problem or options that make no sense (no genes, population < 2, elite ≥ population).
GeneticResult genetic_minimize(const GeneticProblem& problem, const std::function<double(const Design&)>& objective,
                               const GeneticOptions& options = {});

}  // namespace ssid::estimator::pretest
