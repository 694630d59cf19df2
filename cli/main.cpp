/// \file main.cpp
/// `ssid`: structural system identification. Git-style subcommands; this file
/// only dispatches. Exceptions that escape a subcommand become a one-line error
/// on stderr and the exit code of their kind (exit_codes.hpp), never a crash.
#include <exception>
#include <iostream>

#include "cli/cli_util.hpp"
#include "cli/exit_codes.hpp"
#include "cli/version.hpp"
#include "estimator/eigen/multilevel/block_ops.hpp"
#include "estimator/linalg/allocation_policy.hpp"
#include "estimator/reporting/progress.hpp"
#include "formats/parse_error.hpp"

namespace ssid::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> list = {
      {"deck", "read, check and write NASTRAN bulk data (summary, write)", cmd_deck},
      {"uff", "universal files: list datasets, nodes, modes, functions", cmd_uff},
      {"correlate", "pair analysis and test modes: MAC table, unpaired modes", cmd_correlate},
      {"modes", "solve a deck's modes: NASTRAN's real eigenvalue table, JSON, synthetic test (UFF)", cmd_modes},
      {"assemble", "write K, M and their parameter derivatives as OP4 with a manifest (or import them)", cmd_assemble},
      {"truss", "generate MPI-like truss decks, rod or beam, in the report's configurations", cmd_truss},
      {"op4", "OP4 matrix files: list, dump as JSON, convert (encoding, storage, precision, MatrixMarket)", cmd_op4},
      {"dmig", "DMIG matrices of a deck or punch file: list, dump as JSON", cmd_dmig},
      {"estimate", "Bayesian model updating: deck + measured modes in, parameters with uncertainty out", cmd_estimate},
      {"translate", "gather operators, priors and measured modes into a problem file", cmd_translate},
      {"update-deck", "write estimated parameters into a deck (DESVAR and designed fields)", cmd_update_deck},
      {"diagnose", "find what the model form gets wrong: test extensions, name the cause, measure the gain", cmd_diagnose},
      {"identify", "a modal test's records (UFF 58): modes by ERA or the seed's ARMAX (modes), FRFs and coherences from time histories (frf), data-quality checks (check)", cmd_identify},
      {"frf", "FRFs synthesized from a deck's modes (modal superposition), UFF 58, overlay on measured FRFs (SVG)", cmd_frf},
      {"pretest", "plan a modal test: sensor placement (EI, KE, AKE, EVP), TAMs, exciters by MIF and a GA", cmd_pretest},
  };
  return list;
}

}  // namespace ssid::cli

namespace {
void print_usage(std::ostream& o) {
  o << "usage: ssid <command> [<args>] (each command has --help)\n\n"
       "Structural system identification: NASTRAN models, modal tests, Bayesian updating.\n\ncommands:\n";
  for (const auto& c : ssid::cli::commands()) {
    std::string n = c.name;
    o << "  " << n << std::string(n.size() < 14 ? 14 - n.size() : 1, ' ') << c.summary << "\n";
  }
  o << "\n" << ssid::cli::kExitCodesHelp;
  o << "\nenvironment:\n"
       "  SSID_HUGE_PAGE_HEAP=0  do not restart ssid with glibc's heap in transparent huge pages\n"
       "                         (it restarts once, with GLIBC_TUNABLES=glibc.malloc.hugetlb=1, unless\n"
       "                         GLIBC_TUNABLES is already set: faster page faults on large models)\n"
       "  SSID_KERNEL_ISA=NAME   run the multilevel eigen-solver's own kernels in the version for\n"
       "                         generic, avx2 or avx512 (default: the widest this CPU supports)\n";
}
}  // namespace

int main(int argc, char** argv) {
  // Large models: glibc's heap in transparent huge pages (allocation_policy.hpp);
  // re-executes ssid once with the tunable set, or does nothing.
  ssid::estimator::restart_with_huge_page_heap(argv);
  if (argc < 2) {
    print_usage(std::cerr);
    return 2;
  }
  std::string name = argv[1];
  if (name == "--help" || name == "-h" || name == "help") {
    print_usage(std::cout);
    return 0;
  }
  if (name == "--version") {
    std::cout << "ssid " << ssid::cli::kSsidVersion << "\n";
    return 0;
  }
  // One job per process: freed blocks stay in the heap (allocation_policy.hpp).
  ssid::estimator::keep_freed_memory();
  try {
    ssid::estimator::multilevel::apply_kernel_isa_environment();
  } catch (const ssid::formats::InputError& e) {
    ssid::cli::print_error(std::string("SSID_KERNEL_ISA: ") + e.what());
    return ssid::cli::kExitBadInput;
  }
  ssid::cli::Args args(argv + 2, argv + argc);
  for (const auto& c : ssid::cli::commands()) {
    if (name != c.name) continue;
    try {
      return c.run(args);
    } catch (const ssid::formats::InputError& e) {
      ssid::cli::print_error(e.what());
      return ssid::cli::kExitBadInput;
    } catch (const boost::program_options::error& e) {
      ssid::cli::print_error(e.what());
      return ssid::cli::kExitBadInput;
    } catch (const ssid::formats::NumericalError& e) {
      ssid::cli::print_error(e.what());
      return ssid::cli::kExitUntrusted;
    } catch (const ssid::estimator::Interrupted& e) {  // a command with nothing partial to write
      ssid::cli::print_error(e.what());
      return ssid::cli::kExitInterrupted;
    } catch (const std::exception& e) {
      ssid::cli::print_error(e.what());
      return ssid::cli::kExitFailure;
    }
  }
  std::cerr << "ssid: '" << name << "' is not a command\n";
  print_usage(std::cerr);
  return 2;
}
