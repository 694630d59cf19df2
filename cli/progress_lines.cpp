#include "cli/progress_lines.hpp"

#include <cmath>
#include <csignal>
#include <iostream>

namespace ssid::cli {

namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_sigint(int) { g_interrupted = 1; }

}  // namespace

InterruptFlag::InterruptFlag() {
  g_interrupted = 0;
  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;  // one-shot: a second Ctrl-C takes the default action
  sigaction(SIGINT, &sa, nullptr);
}

InterruptFlag::~InterruptFlag() { std::signal(SIGINT, SIG_DFL); }

bool InterruptFlag::raised() { return g_interrupted != 0; }

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string(s % 3600 / 60) + " min";
}

ProgressLines::ProgressLines(std::string prefix, bool quiet, double min_interval_s, double silent_s)
    : m_prefix(std::move(prefix)), m_quiet(quiet), m_min_interval(min_interval_s), m_silent(silent_s) {}

estimator::Progress ProgressLines::callback() {
  return [this](const estimator::ProgressEvent& e) { on_event(e); };
}

std::string ProgressLines::line(const estimator::ProgressEvent& e, double elapsed_s) const {
  std::string s = m_prefix + ": " + e.phase;
  if (!e.has_count()) return s + (e.detail.empty() ? "" : ": " + e.detail);
  if (!e.counted()) s += " " + std::to_string(e.done);
  else if (e.total_is_bound) s += " " + std::to_string(e.done) + " of at most " + std::to_string(e.total);
  else s += " " + std::to_string(e.done) + "/" + std::to_string(e.total);
  std::string timing = duration_text(elapsed_s) + " elapsed";
  if (e.counted() && e.done > 0 && e.done < e.total) {
    const double left = elapsed_s / static_cast<double>(e.done) * static_cast<double>(e.total - e.done);
    timing += std::string(", ") + (e.total_is_bound ? "at most " : "") + "~" + duration_text(left) + " left";
  }
  return e.detail.empty() ? s + ", " + timing : s + ": " + e.detail + " (" + timing + ")";
}

void ProgressLines::on_event(const estimator::ProgressEvent& e) {
  if (InterruptFlag::raised()) throw estimator::Interrupted("interrupted (Ctrl-C)");
  const auto now = Clock::now();
  if (e.phase != m_phase) {
    m_phase = e.phase;
    m_phase_start = now;
  }
  if (m_quiet || e.tick || std::chrono::duration<double>(now - m_start).count() < m_silent) return;
  const bool last_of_phase = e.counted() && e.done >= e.total;
  if (e.has_count() && !last_of_phase && e.phase == m_printed_phase &&
      std::chrono::duration<double>(now - m_printed_at).count() < m_min_interval)
    return;
  const std::string text = line(e, std::chrono::duration<double>(now - m_phase_start).count());
  if (text == m_last_line) return;
  std::cerr << text << "\n";
  m_last_line = text;
  m_printed_phase = e.phase;
  m_printed_at = now;
}

}  // namespace ssid::cli
