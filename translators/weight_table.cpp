#include "translators/weight_table.hpp"

#include <Eigen/Eigenvalues>
#include <cstdio>

namespace ssid::translators {

namespace {
std::string e(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%14.6E", v == 0.0 ? 0.0 : v);  // no "-0.000000E+00"
  return b;
}
std::string pad(int n) { return std::string(static_cast<std::size_t>(n), ' '); }
}  // namespace

std::string format_grid_point_weight(const WeightSummary& w, std::int64_t reference) {
  std::string s;
  s += pad(27) + "O U T P U T   F R O M   G R I D   P O I N T   W E I G H T   G E N E R A T O R\n";
  char line[160];
  std::snprintf(line, sizeof line, "%s REFERENCE POINT = %8lld\n", pad(52).c_str(), static_cast<long long>(reference));
  s += line;
  s += pad(64) + "M O\n";
  for (int i = 0; i < 6; ++i) {
    s += pad(22) + "*";
    for (int j = 0; j < 6; ++j) s += e(w.M0(i, j));
    s += " *\n";
  }
  s += pad(65) + "S\n";
  for (int i = 0; i < 3; ++i) {
    s += pad(43) + "*";
    for (int j = 0; j < 3; ++j) s += e(i == j ? 1.0 : 0.0);
    s += " *\n";
  }
  s += pad(31) + "DIRECTION\n";
  s += pad(26) + "MASS AXIS SYSTEM (S)     MASS              X-C.G.        Y-C.G.        Z-C.G.\n";
  const char* axis[3] = {"X", "Y", "Z"};
  for (int i = 0; i < 3; ++i) {
    // C.G. in basic: the reference point plus the offsets this direction's mass sees.
    s += pad(34) + axis[i] + pad(4) + e(w.mass(i)) + pad(4) + e(w.cg(i, 0)) + e(w.cg(i, 1)) + e(w.cg(i, 2)) + "\n";
  }
  s += pad(64) + "I(S)\n";
  for (int i = 0; i < 3; ++i) {
    s += pad(43) + "*";
    for (int j = 0; j < 3; ++j) s += e(w.inertia_cg(i, j));
    s += " *\n";
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(w.inertia_cg);
  s += pad(64) + "I(Q)\n";
  for (int i = 0; i < 3; ++i) {
    s += pad(43) + "*";
    for (int j = 0; j < 3; ++j) s += j == i ? e(es.eigenvalues()(i)) : pad(14);
    s += " *\n";
  }
  s += pad(65) + "Q\n";
  for (int i = 0; i < 3; ++i) {
    s += pad(43) + "*";
    for (int j = 0; j < 3; ++j) s += e(es.eigenvectors()(i, j));
    s += " *\n";
  }
  return s;
}

}  // namespace ssid::translators
