#include "estimator/linalg/single_factor.hpp"

#include <cblas.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

extern "C" {
// LAPACK (Fortran ABI; the trailing length is the hidden character-argument length).
void spotrf_(const char* uplo, const int* n, float* a, const int* lda, int* info, size_t);
}

namespace ssid::estimator {

double SingleSupernodalFactor::rcond_estimate() const {
  float dmin = 0.0f, dmax = 0.0f;
  for (size_t sn = 0; sn + 1 < super.size(); ++sn) {
    const long nsrow = pi[sn + 1] - pi[sn];
    for (long c = 0; c < super[sn + 1] - super[sn]; ++c) {
      const float d = values[static_cast<size_t>(px[sn] + c * nsrow + c)];
      dmin = (sn == 0 && c == 0) ? d : std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
  }
  return dmax > 0.0f ? static_cast<double>(dmin / dmax) * static_cast<double>(dmin / dmax) : 0.0;
}

void SingleSupernodalFactor::solve_columns(const float* b, float* x, long ld, long c0, long c1, Work& w) const {
  if (empty()) throw std::logic_error("SingleSupernodalFactor::solve on an empty factor");
  if (c0 < 0 || c1 > ld || c0 > c1) throw std::invalid_argument("SingleSupernodalFactor::solve_columns: bad column range");
  const long nrhs = c1 - c0;
  if (nrhs == 0) return;
  const size_t bytes = sizeof(float) * static_cast<size_t>(nrhs);
  // The right-hand sides in L's order, row-major: row k (nrhs values) is also
  // column k of the nrhs x n column-major matrix Yᵀ the BLAS calls below work on,
  // so a supernode's rows are one contiguous nrhs x nscol block of Yᵀ.
  w.y.resize(static_cast<size_t>(n * nrhs));
  float* y = w.y.data();
  for (long k = 0; k < n; ++k) std::memcpy(y + k * nrhs, b + perm[static_cast<size_t>(k)] * ld + c0, bytes);
  const long nsuper = static_cast<long>(super.size()) - 1;
  long max_off = 0;
  for (long s = 0; s < nsuper; ++s)
    max_off = std::max(max_off, (pi[static_cast<size_t>(s) + 1] - pi[static_cast<size_t>(s)]) -
                                    (super[static_cast<size_t>(s) + 1] - super[static_cast<size_t>(s)]));
  w.t.resize(static_cast<size_t>(max_off * nrhs));
  float* t = w.t.data();
  const int m = static_cast<int>(nrhs);
  // Supernode s: its first column, columns, rows, rows below its columns, values
  // (column-major, nsrow x nscol) and its rows of Yᵀ.
  struct Node {
    long k1, nscol, p0, nsrow, noff;
    const float* Ls;
    float* Xs;
  };
  auto node = [&](long s) {
    const long k1 = super[static_cast<size_t>(s)], nscol = super[static_cast<size_t>(s) + 1] - k1;
    const long p0 = pi[static_cast<size_t>(s)], nsrow = pi[static_cast<size_t>(s) + 1] - p0;
    return Node{k1, nscol, p0, nsrow, nsrow - nscol, values.data() + px[static_cast<size_t>(s)], y + k1 * nrhs};
  };
  // Forward: L z = y, i.e. Zᵀ Lᵀ = Yᵀ, supernode by supernode.
  for (long s = 0; s < nsuper; ++s) {
    const auto [k1, nscol, p0, nsrow, noff, Ls, Xs] = node(s);
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
    const auto [k1, nscol, p0, nsrow, noff, Ls, Xs] = node(s);
    if (noff > 0) {
      const long* r = rows.data() + p0 + nscol;
      for (long q = 0; q < noff; ++q) std::memcpy(t + q * nrhs, y + r[q] * nrhs, sizeof(float) * static_cast<size_t>(nrhs));
      cblas_sgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, m, static_cast<int>(nscol), static_cast<int>(noff), -1.0f,
                  t, m, Ls + nscol, static_cast<int>(nsrow), 1.0f, Xs, m);
    }
    cblas_strsm(CblasColMajor, CblasRight, CblasLower, CblasNoTrans, CblasNonUnit, m, static_cast<int>(nscol), 1.0f,
                Ls, static_cast<int>(nsrow), Xs, m);
  }
  for (long k = 0; k < n; ++k) std::memcpy(x + perm[static_cast<size_t>(k)] * ld + c0, y + k * nrhs, bytes);
}

long factorize_supernodal_single(const std::vector<long>& Cp, const std::vector<long>& Ci,
                                 const std::vector<double>& Cx, SingleSupernodalFactor& f) {
  const long n = f.n, nsuper = static_cast<long>(f.super.size()) - 1;
  auto at = [](const std::vector<long>& v, long i) { return v[static_cast<size_t>(i)]; };
  f.values.assign(static_cast<size_t>(f.px.back()), 0.0f);
  std::vector<long> super_of(static_cast<size_t>(n));  // supernode of each column
  for (long s = 0; s < nsuper; ++s)
    for (long k = at(f.super, s); k < at(f.super, s + 1); ++k) super_of[static_cast<size_t>(k)] = s;
  // map: a row's place in the current supernode. head/next: the supernodes whose
  // next update goes to supernode s (linked lists); next_row: where in its rows a
  // supernode's next update starts.
  std::vector<long> map(static_cast<size_t>(n), 0), head(static_cast<size_t>(nsuper), -1),
      next(static_cast<size_t>(nsuper), -1), next_row(static_cast<size_t>(nsuper), 0);
  std::vector<float> C;
  auto link = [&](long d, long row_pos) {
    next_row[static_cast<size_t>(d)] = row_pos;
    const long t = super_of[static_cast<size_t>(f.rows[static_cast<size_t>(at(f.pi, d) + row_pos)])];
    next[static_cast<size_t>(d)] = head[static_cast<size_t>(t)];
    head[static_cast<size_t>(t)] = d;
  };
  for (long s = 0; s < nsuper; ++s) {
    const long k1 = at(f.super, s), k2 = at(f.super, s + 1), nscol = k2 - k1;
    const long p0 = at(f.pi, s), nsrow = at(f.pi, s + 1) - p0;
    const long* srows = f.rows.data() + p0;
    float* Ls = f.values.data() + at(f.px, s);
    for (long q = 0; q < nsrow; ++q) map[static_cast<size_t>(srows[q])] = q;
    for (long j = k1; j < k2; ++j)
      for (long p = at(Cp, j); p < at(Cp, j + 1); ++p)
        Ls[map[static_cast<size_t>(at(Ci, p))] + (j - k1) * nsrow] = static_cast<float>(Cx[static_cast<size_t>(p)]);
    // Updates from the supernodes that reach this one.
    for (long d = head[static_cast<size_t>(s)]; d >= 0;) {
      const long dnext = next[static_cast<size_t>(d)];
      const long pd = at(f.pi, d), ndrow = at(f.pi, d + 1) - pd, ndcol = at(f.super, d + 1) - at(f.super, d);
      const long* drows = f.rows.data() + pd;
      const long pos = next_row[static_cast<size_t>(d)];
      long pos2 = pos;
      while (pos2 < ndrow && drows[pos2] < k2) ++pos2;
      const long n1 = pos2 - pos, n2 = ndrow - pos;  // rows in this supernode's columns; rows from there down
      const float* Ld = f.values.data() + at(f.px, d);
      C.resize(std::max(C.size(), static_cast<size_t>(n1 * n2)));
      const int ld = static_cast<int>(ndrow), ldc = static_cast<int>(n2);
      cblas_ssyrk(CblasColMajor, CblasLower, CblasNoTrans, static_cast<int>(n1), static_cast<int>(ndcol), 1.0f,
                  Ld + pos, ld, 0.0f, C.data(), ldc);
      if (n2 > n1)
        cblas_sgemm(CblasColMajor, CblasNoTrans, CblasTrans, static_cast<int>(n2 - n1), static_cast<int>(n1),
                    static_cast<int>(ndcol), 1.0f, Ld + pos2, ld, Ld + pos, ld, 0.0f, C.data() + n1, ldc);
      for (long c = 0; c < n1; ++c) {
        float* col = Ls + (drows[pos + c] - k1) * nsrow;
        const float* u = C.data() + c * n2;
        for (long r = c; r < n2; ++r) col[map[static_cast<size_t>(drows[pos + r])]] -= u[r];
      }
      if (pos2 < ndrow) link(d, pos2);
      d = dnext;
    }
    // The supernode itself: L_d L_dᵀ = its diagonal block, then the rows below.
    const int nc = static_cast<int>(nscol), ldl = static_cast<int>(nsrow);
    int info = 0;
    spotrf_("L", &nc, Ls, &ldl, &info, 1);
    if (info < 0) throw std::logic_error("factorize_supernodal_single: spotrf argument " + std::to_string(-info) + " illegal");
    if (info > 0) return k1 + info - 1;
    if (nsrow > nscol) {
      cblas_strsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, static_cast<int>(nsrow - nscol), nc,
                  1.0f, Ls, ldl, Ls + nscol, ldl);
      link(s, nscol);
    }
  }
  return -1;
}

}  // namespace ssid::estimator
