/// \file bench_op4.cpp
/// Writes and reads a large sparse OP4 matrix in each encoding and compares the
/// throughput (MB of file per second) with copying the same file (read + write
/// through a 4 MiB buffer, the page cache warm for both); best of three runs each.
///
/// usage: bench_op4 [TARGET_MB] [--dir DIR] [--only binary-sparse|binary-bigmat|ascii-sparse]
///        (default 200 MB per file, /tmp, all three)
/// The matrix: real double, columns of 4 runs of 30 consecutive rows each
/// (a banded FE-like pattern); the number of columns is chosen so each file is
/// about TARGET_MB. The files are deleted at the end.
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <sys/stat.h>
#include <vector>

#include "formats/op4.hpp"

namespace {

using namespace ssid::formats;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double file_mb(const std::string& p) {
  struct stat st {};
  ::stat(p.c_str(), &st);
  return static_cast<double>(st.st_size) / 1e6;
}

/// Plain copy through a 4 MiB buffer; returns seconds.
double copy_file(const std::string& from, const std::string& to) {
  const auto t0 = Clock::now();
  const int in = ::open(from.c_str(), O_RDONLY);
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<char> buf(4u << 20);
  for (;;) {
    const ssize_t n = ::read(in, buf.data(), buf.size());
    if (n <= 0) break;
    ssize_t done = 0;
    while (done < n) {
      const ssize_t w = ::write(out, buf.data() + done, static_cast<std::size_t>(n - done));
      if (w <= 0) break;
      done += w;
    }
  }
  ::close(in);
  ::close(out);
  return seconds_since(t0);
}

SparseReal make_matrix(Eigen::Index cols, Eigen::Index rows) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SparseReal a(rows, cols);
  a.reserve(Eigen::VectorXi::Constant(cols, 120));
  for (Eigen::Index c = 0; c < cols; ++c)
    for (int run = 0; run < 4; ++run) {
      const Eigen::Index first = (c + run * (rows / 4)) % (rows - 40);
      for (int k = 0; k < 30; ++k) a.insert(first + k, c) = u(rng) * std::pow(10.0, static_cast<int>(u(rng) * 6));
    }
  a.makeCompressed();
  return a;
}

void bench(const std::string& label, const Op4WriteOptions& o, double target_mb, const std::string& dir) {
  // Bytes per non-zero: binary 8 (+ string headers), ASCII 23 characters + newlines.
  const double bytes_per_nz = o.encoding == Op4Encoding::Binary ? 8.1 : 24.0;
  const Eigen::Index rows = 60000;
  const Eigen::Index cols = static_cast<Eigen::Index>(target_mb * 1e6 / (120 * bytes_per_nz));
  const SparseReal a = make_matrix(cols, rows);
  std::vector<Op4Matrix> ms{Op4Matrix::from_real("KBIG", a, op4_form::Rectangular, Op4Precision::RealDouble)};
  const std::string path = dir + "/ssid_bench_op4_" + label + ".op4";
  const std::string copy = path + ".copy";

  // Best of three of each (the machine is shared; the best run is the least disturbed).
  double tw = 1e30, tr = 1e30, tc = 1e30;
  bool same = true;
  for (int rep = 0; rep < 3; ++rep) {
    auto t0 = Clock::now();
    write_op4(path, ms, o);
    tw = std::min(tw, seconds_since(t0));
    t0 = Clock::now();
    auto back = read_op4(path);
    tr = std::min(tr, seconds_since(t0));
    if (rep == 0)
      same = back.size() == 1 && back[0].real.nonZeros() == a.nonZeros() &&
             back[0].real.isApprox(a, 0.0);  // exact: a - back == 0
    back.clear();
    tc = std::min(tc, copy_file(path, copy));
    std::remove(copy.c_str());
  }
  const double mb = file_mb(path);
  std::printf("%-16s %8.1f MB  %10lld nnz  write %6.2f s %7.1f MB/s  read %6.2f s %7.1f MB/s  copy %6.2f s %7.1f MB/s"
              "  write/copy %.2f  read/copy %.2f  %s\n",
              label.c_str(), mb, static_cast<long long>(a.nonZeros()), tw, mb / tw, tr, mb / tr, tc, mb / tc, tw / tc,
              tr / tc, same ? "exact" : "MISMATCH");
  std::fflush(stdout);
  std::remove(path.c_str());
  std::remove(copy.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  double target = 200.0;
  std::string dir = "/tmp", only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--dir") && i + 1 < argc) dir = argv[++i];
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else target = std::stod(argv[i]);
  }
  Op4WriteOptions bin;
  bin.encoding = Op4Encoding::Binary;
  bin.storage = Op4Storage::Sparse;
  Op4WriteOptions big = bin;
  big.storage = Op4Storage::BigMat;
  Op4WriteOptions asc;
  asc.encoding = Op4Encoding::Ascii;
  asc.storage = Op4Storage::Sparse;
  if (only.empty() || only == "binary-sparse") bench("binary-sparse", bin, target, dir);
  if (only.empty() || only == "binary-bigmat") bench("binary-bigmat", big, target, dir);
  if (only.empty() || only == "ascii-sparse") bench("ascii-sparse", asc, target, dir);
  return 0;
}
