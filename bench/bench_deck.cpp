/// \file bench_deck.cpp
/// Parses a generated deck of N cards (default one million) and reports cards
/// per second for reading (splitting into cards and fields), for the typed
/// parse, and memory per card (peak resident set growth / cards).
///
/// usage: bench_deck [N] [--keep FILE]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "formats/bulk_model.hpp"
#include "formats/deck.hpp"

namespace {
long peak_rss_kib() {
  struct rusage ru {};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}
long current_rss_kib() {
  std::ifstream s("/proc/self/statm");
  long size = 0, resident = 0;
  s >> size >> resident;
  return resident * 4;
}
}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 1000000;
  std::string path = "/tmp/ssid_bench_deck.bdf";
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--keep") && i + 1 < argc) path = argv[++i];
    else n = std::stoul(argv[i]);
  }
  {
    // A realistic mix: 40% GRID (small), 10% GRID (large, 2 lines), 10% GRID free,
    // 30% CROD, 10% CBAR with a continuation (pin flag and offset).
    std::ofstream o(path);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-100, 100);
    o << "SOL 103\nCEND\nBEGIN BULK\n";
    char buf[256];
    for (std::size_t i = 1; i <= n; ++i) {
      int k = static_cast<int>(i % 10);
      if (k < 4) std::snprintf(buf, sizeof buf, "GRID    %-8zu        %-8.3f%-8.3f%-8.3f\n", i, u(rng), u(rng), u(rng));
      else if (k == 4) std::snprintf(buf, sizeof buf, "GRID*   %16zu%16s%16.9f%16.9f\n*       %16.9f\n", i, "", u(rng), u(rng), u(rng));
      else if (k == 5) std::snprintf(buf, sizeof buf, "GRID,%zu,,%.4f,%.4f,%.4f\n", i, u(rng), u(rng), u(rng));
      else if (k < 9) std::snprintf(buf, sizeof buf, "CROD    %-8zu1       %-8zu%-8zu\n", i, i, i + 1);
      else std::snprintf(buf, sizeof buf, "CBAR    %-8zu2       %-8zu%-8zu0.      1.      0.      GGG\n        1               .1\n", i, i, i + 1);
      o << buf;
    }
    o << "ENDDATA\n";
  }
  long rss0 = current_rss_kib();
  auto t0 = std::chrono::steady_clock::now();
  ssid::formats::Deck deck = ssid::formats::read_deck(path);
  auto t1 = std::chrono::steady_clock::now();
  long rss1 = current_rss_kib();
  ssid::formats::BulkModel model = ssid::formats::parse_bulk(deck);
  auto t2 = std::chrono::steady_clock::now();
  long rss2 = current_rss_kib();
  double read_s = std::chrono::duration<double>(t1 - t0).count();
  double typed_s = std::chrono::duration<double>(t2 - t1).count();
  std::size_t cards = deck.cards.size();
  std::printf("cards                      %zu (file %s)\n", cards, path.c_str());
  std::printf("read (split into fields)   %.3f s  %.2f M cards/s\n", read_s, cards / read_s / 1e6);
  std::printf("typed parse                %.3f s  %.2f M cards/s\n", typed_s, cards / typed_s / 1e6);
  std::printf("read + typed               %.3f s  %.2f M cards/s\n", read_s + typed_s, cards / (read_s + typed_s) / 1e6);
  std::printf("memory: deck %.0f B/card, deck+typed %.0f B/card (resident growth); peak RSS %.1f MiB\n",
              (rss1 - rss0) * 1024.0 / cards, (rss2 - rss0) * 1024.0 / cards, peak_rss_kib() / 1024.0);
  std::printf("problems %zu\n", model.problems.size());
  return 0;
}
