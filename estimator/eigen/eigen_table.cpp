#include "estimator/eigen/eigen_table.hpp"

#include <cstdio>

namespace ssid::estimator {

std::string format_real_eigenvalues(const EigenResult& r) {
  std::string s =
      "                                              R E A L   E I G E N V A L U E S\n"
      "   MODE    EXTRACTION      EIGENVALUE            RADIANS             CYCLES            GENERALIZED         "
      "GENERALIZED\n"
      "    NO.       ORDER                                                                       MASS              "
      "STIFFNESS\n";
  char line[160];
  for (int i = 0; i < r.size(); ++i) {
    const double gm = i < r.generalized_mass.size() ? r.generalized_mass(i) : 0.0;
    const double gk = i < r.generalized_stiffness.size() ? r.generalized_stiffness(i) : 0.0;
    std::snprintf(line, sizeof line, "%9d%10d%20.6E%20.6E%20.6E%20.6E%20.6E\n", i + 1, i + 1, r.eigenvalues(i),
                  r.radians(i), r.cycles(i), gm, gk);
    s += line;
  }
  return s;
}

}  // namespace ssid::estimator
