#include "estimator/single_factor.hpp"

#include <cblas.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace ssid::estimator {

void SingleSupernodalFactor::solve(const float* b, float* x, long nrhs, Work& w) const {
  if (empty()) throw std::logic_error("SingleSupernodalFactor::solve on an empty factor");
  if (nrhs <= 0) return;
  // The right-hand sides in L's order, row-major: row k (nrhs values) is also
  // column k of the nrhs x n column-major matrix Yᵀ the BLAS calls below work on,
  // so a supernode's rows are one contiguous nrhs x nscol block of Yᵀ.
  w.y.resize(static_cast<size_t>(n * nrhs));
  float* y = w.y.data();
  for (long k = 0; k < n; ++k) std::memcpy(y + k * nrhs, b + perm[static_cast<size_t>(k)] * nrhs, sizeof(float) * static_cast<size_t>(nrhs));
  const long nsuper = static_cast<long>(super.size()) - 1;
  long max_off = 0;
  for (long s = 0; s < nsuper; ++s)
    max_off = std::max(max_off, (pi[static_cast<size_t>(s) + 1] - pi[static_cast<size_t>(s)]) -
                                    (super[static_cast<size_t>(s) + 1] - super[static_cast<size_t>(s)]));
  w.t.resize(static_cast<size_t>(max_off * nrhs));
  float* t = w.t.data();
  const int m = static_cast<int>(nrhs);
  // Forward: L z = y, i.e. Zᵀ Lᵀ = Yᵀ, supernode by supernode.
  for (long s = 0; s < nsuper; ++s) {
    const long k1 = super[static_cast<size_t>(s)], nscol = super[static_cast<size_t>(s) + 1] - k1;
    const long p0 = pi[static_cast<size_t>(s)], nsrow = pi[static_cast<size_t>(s) + 1] - p0, noff = nsrow - nscol;
    const float* Ls = values.data() + px[static_cast<size_t>(s)];
    float* Xs = y + k1 * nrhs;
    cblas_strsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, m, static_cast<int>(nscol), 1.0f,
                Ls, static_cast<int>(nsrow), Xs, m);
    if (noff == 0) continue;
    cblas_sgemm(CblasColMajor, CblasNoTrans, CblasTrans, m, static_cast<int>(noff), static_cast<int>(nscol), 1.0f,
                Xs, m, Ls + nscol, static_cast<int>(nsrow), 0.0f, t, m);
    const long* r = rows.data() + p0 + nscol;
    for (long q = 0; q < noff; ++q) {
      float* yr = y + r[q] * nrhs;
      const float* tq = t + q * nrhs;
      for (long c = 0; c < nrhs; ++c) yr[c] -= tq[c];
    }
  }
  // Backward: Lᵀ x = z, i.e. Xᵀ L = Zᵀ, supernodes in reverse.
  for (long s = nsuper - 1; s >= 0; --s) {
    const long k1 = super[static_cast<size_t>(s)], nscol = super[static_cast<size_t>(s) + 1] - k1;
    const long p0 = pi[static_cast<size_t>(s)], nsrow = pi[static_cast<size_t>(s) + 1] - p0, noff = nsrow - nscol;
    const float* Ls = values.data() + px[static_cast<size_t>(s)];
    float* Xs = y + k1 * nrhs;
    if (noff > 0) {
      const long* r = rows.data() + p0 + nscol;
      for (long q = 0; q < noff; ++q) std::memcpy(t + q * nrhs, y + r[q] * nrhs, sizeof(float) * static_cast<size_t>(nrhs));
      cblas_sgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, static_cast<int>(nscol), static_cast<int>(noff), -1.0f,
                  t, m, Ls + nscol, static_cast<int>(nsrow), 1.0f, Xs, m);
    }
    cblas_strsm(CblasColMajor, CblasRight, CblasLower, CblasNoTrans, CblasNonUnit, m, static_cast<int>(nscol), 1.0f,
                Ls, static_cast<int>(nsrow), Xs, m);
  }
  for (long k = 0; k < n; ++k) std::memcpy(x + perm[static_cast<size_t>(k)] * nrhs, y + k * nrhs, sizeof(float) * static_cast<size_t>(nrhs));
}

}  // namespace ssid::estimator
