#include "estimator/progress.hpp"

namespace ssid::estimator {

void report(const Progress& p, const std::string& message, double fraction) {
  if (p) p(message, fraction);
}

}  // namespace ssid::estimator
