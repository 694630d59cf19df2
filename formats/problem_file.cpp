#include "formats/problem_file.hpp"

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::formats {

namespace {

using json = nlohmann::json;
using Sparse = Eigen::SparseMatrix<double>;

static_assert(sizeof(double) == 8, "float64 expected");

bool little_endian() {
  const std::uint16_t one = 1;
  unsigned char b = 0;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

/// memcpy that accepts an empty block: an empty vector's data() may be null, and
/// memcpy's arguments must not be even for zero bytes (UBSan's nonnull check).
void copy_bytes(void* to, const void* from, std::size_t n) {
  if (n > 0) std::memcpy(to, from, n);
}

/// A block to write: a sparse or a dense matrix, by pointer (no copies).
struct OutBlock {
  const Sparse* sparse = nullptr;
  const Eigen::MatrixXd* dense = nullptr;
  const Eigen::VectorXd* vector = nullptr;
  std::uint64_t bytes() const {
    if (sparse) return 8 * (static_cast<std::uint64_t>(sparse->outerSize()) + 1) + 16 * static_cast<std::uint64_t>(sparse->nonZeros());
    if (dense) return 8 * static_cast<std::uint64_t>(dense->size());
    return 8 * static_cast<std::uint64_t>(vector->size());
  }
};

class Writer {
 public:
  json add(const Sparse& m) {
    if (!m.isCompressed()) throw std::invalid_argument("problem file: sparse matrix not compressed");
    return push(OutBlock{&m, nullptr, nullptr}, "csc", m.rows(), m.cols(), m.nonZeros());
  }
  json add(const Eigen::MatrixXd& m) { return push(OutBlock{nullptr, &m, nullptr}, "dense", m.rows(), m.cols(), m.size()); }
  json add(const Eigen::VectorXd& v) { return push(OutBlock{nullptr, nullptr, &v}, "dense", v.size(), 1, v.size()); }

  void write(std::ostream& out) const {
    for (const auto& b : m_blocks) {
      if (b.sparse) {
        const Sparse& m = *b.sparse;
        std::vector<std::int64_t> starts(static_cast<std::size_t>(m.outerSize()) + 1);
        for (Eigen::Index c = 0; c <= m.outerSize(); ++c) starts[static_cast<std::size_t>(c)] = m.outerIndexPtr()[c];
        std::vector<std::int64_t> rows(static_cast<std::size_t>(m.nonZeros()));
        for (Eigen::Index k = 0; k < m.nonZeros(); ++k) rows[static_cast<std::size_t>(k)] = m.innerIndexPtr()[k];
        out.write(reinterpret_cast<const char*>(starts.data()), static_cast<std::streamsize>(8 * starts.size()));
        out.write(reinterpret_cast<const char*>(rows.data()), static_cast<std::streamsize>(8 * rows.size()));
        out.write(reinterpret_cast<const char*>(m.valuePtr()), static_cast<std::streamsize>(8 * m.nonZeros()));
      } else if (b.dense) {
        out.write(reinterpret_cast<const char*>(b.dense->data()), static_cast<std::streamsize>(8 * b.dense->size()));
      } else {
        out.write(reinterpret_cast<const char*>(b.vector->data()), static_cast<std::streamsize>(8 * b.vector->size()));
      }
    }
  }

 private:
  json push(const OutBlock& b, const char* kind, Eigen::Index rows, Eigen::Index cols, Eigen::Index count) {
    json j = {{"block", m_blocks.size()}, {"kind", kind}, {"rows", rows}, {"cols", cols},
              {"count", count},           {"offset", m_offset}, {"bytes", b.bytes()}};
    m_offset += b.bytes();
    m_blocks.push_back(b);
    return j;
  }
  std::vector<OutBlock> m_blocks;
  std::uint64_t m_offset = 0;
};

class Reader {
 public:
  Reader(std::string path, std::string data, std::size_t base) : m_path(std::move(path)), m_data(std::move(data)), m_base(base) {}

  const char* span(const json& j, const std::string& what, std::uint64_t expected_bytes) const {
    const auto offset = j.at("offset").get<std::uint64_t>();
    const auto bytes = j.at("bytes").get<std::uint64_t>();
    if (bytes != expected_bytes)
      fail(what + ": block of " + std::to_string(bytes) + " bytes, " + std::to_string(expected_bytes) + " expected");
    if (m_base + offset + bytes > m_data.size())
      fail(what + ": truncated (block at byte " + std::to_string(m_base + offset) + " runs past the end of the file)");
    return m_data.data() + m_base + offset;
  }

  Sparse sparse(const json& j, const std::string& what) const {
    if (j.at("kind") != "csc") fail(what + ": a sparse (csc) block expected");
    const auto rows = j.at("rows").get<Eigen::Index>(), cols = j.at("cols").get<Eigen::Index>();
    const auto nnz = j.at("count").get<Eigen::Index>();
    if (rows < 0 || cols < 0 || nnz < 0) fail(what + ": negative size");
    const char* p = span(j, what, 8 * (static_cast<std::uint64_t>(cols) + 1) + 16 * static_cast<std::uint64_t>(nnz));
    std::vector<std::int64_t> starts(static_cast<std::size_t>(cols) + 1), idx(static_cast<std::size_t>(nnz));
    copy_bytes(starts.data(), p, 8 * starts.size());
    copy_bytes(idx.data(), p + 8 * starts.size(), 8 * idx.size());
    Sparse m(rows, cols);
    m.resizeNonZeros(nnz);
    if (starts.front() != 0 || starts.back() != nnz) fail(what + ": column starts inconsistent with the entry count");
    for (Eigen::Index c = 0; c <= cols; ++c) {
      const auto s = starts[static_cast<std::size_t>(c)];
      if (c > 0 && s < starts[static_cast<std::size_t>(c - 1)]) fail(what + ": column starts decrease at column " + std::to_string(c));
      m.outerIndexPtr()[c] = static_cast<Sparse::StorageIndex>(s);
    }
    for (Eigen::Index k = 0; k < nnz; ++k) {
      const auto r = idx[static_cast<std::size_t>(k)];
      if (r < 0 || r >= rows) fail(what + ": row index " + std::to_string(r) + " out of range 0.." + std::to_string(rows - 1));
      m.innerIndexPtr()[k] = static_cast<Sparse::StorageIndex>(r);
    }
    copy_bytes(m.valuePtr(), p + 8 * (starts.size() + idx.size()), 8 * static_cast<std::size_t>(nnz));
    return m;
  }

  Eigen::MatrixXd dense(const json& j, const std::string& what) const {
    if (j.at("kind") != "dense") fail(what + ": a dense block expected");
    const auto rows = j.at("rows").get<Eigen::Index>(), cols = j.at("cols").get<Eigen::Index>();
    if (rows < 0 || cols < 0) fail(what + ": negative size");
    const char* p = span(j, what, 8 * static_cast<std::uint64_t>(rows) * static_cast<std::uint64_t>(cols));
    Eigen::MatrixXd m(rows, cols);
    copy_bytes(m.data(), p, 8 * static_cast<std::size_t>(m.size()));
    return m;
  }

  [[noreturn]] void fail(const std::string& message) const { throw InputError(m_path + ": " + message); }

 private:
  std::string m_path;
  std::string m_data;
  std::size_t m_base;
};

/// Sizes that must agree; "" when they do.
std::string inconsistency(const ProblemFile& pf) {
  const std::size_t p = pf.parameters.size();
  if (pf.prior_correlation.size() &&
      (pf.prior_correlation.rows() != static_cast<Eigen::Index>(p) || pf.prior_correlation.cols() != static_cast<Eigen::Index>(p)))
    return "prior correlation is not " + std::to_string(p) + " x " + std::to_string(p);
  for (const auto& c : pf.configurations) {
    const auto n = c.K.rows();
    const std::string where = "configuration '" + c.name + "': ";
    if (c.K.cols() != n || c.M.rows() != n || c.M.cols() != n) return where + "K and M must be square and of one size";
    if (c.dK.size() != p || c.dM.size() != p)
      return where + "one dK and one dM per parameter expected (" + std::to_string(p) + ")";
    for (std::size_t j = 0; j < p; ++j)
      if (c.dK[j].rows() != n || c.dK[j].cols() != n || c.dM[j].rows() != n || c.dM[j].cols() != n)
        return where + "dK/dM of parameter '" + pf.parameters[j].name + "' is not " + std::to_string(n) + " x " +
               std::to_string(n);
    if (static_cast<Eigen::Index>(c.dofs.size()) != n)
      return where + std::to_string(c.dofs.size()) + " DOF labels for " + std::to_string(n) + " DOFs";
    if (c.sensors.cols() != n || c.sensors.rows() != static_cast<Eigen::Index>(c.sensor_labels.size()))
      return where + "sensor matrix must be (sensor labels) x (DOFs)";
    for (const auto& m : c.measured)
      if (m.shape.size() && m.shape.size() != c.sensors.rows())
        return where + "mode " + std::to_string(m.id) + " has " + std::to_string(m.shape.size()) +
               " shape components for " + std::to_string(c.sensors.rows()) + " sensors";
  }
  return {};
}

}  // namespace

void write_problem(const std::string& path, const ProblemFile& pf) {
  if (!little_endian()) throw std::runtime_error("problem file: big-endian hosts are not supported");
  if (const auto why = inconsistency(pf); !why.empty()) throw std::invalid_argument("problem file: " + why);
  const std::size_t p = pf.parameters.size();
  Writer w;
  json head;
  head["format"] = "ssid problem";
  head["version"] = ProblemFile::version;
  head["title"] = pf.title;
  for (const auto& q : pf.parameters)
    head["parameters"].push_back({{"name", q.name}, {"desvar", q.desvar}, {"initial", q.initial},
                                  {"prior_std", q.prior_std}, {"lower", q.lower}, {"upper", q.upper}});
  if (!head.contains("parameters")) head["parameters"] = json::array();
  if (pf.prior_correlation.size()) head["prior_correlation"] = w.add(pf.prior_correlation);
  const auto& o = pf.options;
  head["options"] = {{"max_iterations", o.max_iterations}, {"tolerance", o.tolerance},
                     {"mac_min", o.mac_min},               {"freq_tol_pct", o.freq_tol_pct},
                     {"track_mac_min", o.track_mac_min},   {"shape_derivatives", o.shape_derivatives},
                     {"shape_derivative", o.shape_derivative}, {"operators", o.operators}};
  head["configurations"] = json::array();
  for (const auto& c : pf.configurations) {
    json jc;
    jc["name"] = c.name;
    jc["deck"] = c.deck;
    jc["modes"] = c.modes;
    jc["dofs"] = json::array();
    for (const auto& [point, comp] : c.dofs) jc["dofs"].push_back({point, comp});
    jc["sensor_labels"] = c.sensor_labels;
    jc["sensors"] = w.add(c.sensors);
    jc["K"] = w.add(c.K);
    jc["M"] = w.add(c.M);
    jc["dK"] = json::array();
    jc["dM"] = json::array();
    for (std::size_t j = 0; j < p; ++j) {
      jc["dK"].push_back(w.add(c.dK[j]));
      jc["dM"].push_back(w.add(c.dM[j]));
    }
    jc["measured"] = json::array();
    for (const auto& m : c.measured) {
      json jm = {{"id", m.id},
                 {"frequency_hz", m.frequency_hz},
                 {"frequency_std_hz", m.frequency_std_hz},
                 {"shape_std", m.shape_std},
                 {"use_frequency", m.use_frequency},
                 {"use_shape", m.use_shape}};
      if (m.shape.size()) jm["shape"] = w.add(m.shape);
      jc["measured"].push_back(jm);
    }
    head["configurations"].push_back(jc);
  }
  std::string text = head.dump(1);
  // Pad so that the binary blocks start 8-byte aligned.
  const std::string magic = "SSIDPROB " + std::to_string(ProblemFile::version) + "\n";
  std::size_t total = magic.size() + 21 + text.size() + 1;
  text.append((8 - total % 8) % 8, ' ');
  text.push_back('\n');
  char len[32];
  std::snprintf(len, sizeof len, "%020zu\n", text.size());

  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path + ": cannot open for writing");
  out << magic << len << text;
  w.write(out);
  if (!out.flush()) throw InputError(path + ": write failed");
}

ProblemFile read_problem(const std::string& path) {
  if (!little_endian()) throw std::runtime_error("problem file: big-endian hosts are not supported");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  std::ostringstream ss;
  ss << in.rdbuf();
  std::string data = ss.str();
  const std::size_t nl = data.find('\n');
  if (nl == std::string::npos || data.compare(0, 9, "SSIDPROB ") != 0)
    throw InputError(path + ": not an ssid problem file (no SSIDPROB line)");
  const int version = std::atoi(data.substr(9, nl - 9).c_str());
  if (version != ProblemFile::version)
    throw InputError(path + ": problem file version " + std::to_string(version) + ", this ssid reads version " +
                             std::to_string(ProblemFile::version));
  const std::size_t nl2 = data.find('\n', nl + 1);
  if (nl2 == std::string::npos) throw InputError(path + ": truncated header");
  const auto header_len = std::strtoull(data.substr(nl + 1, nl2 - nl - 1).c_str(), nullptr, 10);
  const std::size_t base = nl2 + 1 + header_len;
  if (base > data.size()) throw InputError(path + ": truncated header (" + std::to_string(header_len) + " bytes announced)");
  json head;
  try {
    head = json::parse(data.begin() + static_cast<std::ptrdiff_t>(nl2 + 1), data.begin() + static_cast<std::ptrdiff_t>(base));
  } catch (const json::exception& e) {
    throw InputError(path + ": header is not valid JSON: " + e.what());
  }
  Reader r(path, std::move(data), base);
  ProblemFile pf;
  try {
    pf.title = head.at("title").get<std::string>();
    for (const auto& q : head.at("parameters"))
      pf.parameters.push_back({q.at("name").get<std::string>(), q.at("desvar").get<std::int64_t>(),
                               q.at("initial").get<double>(), q.at("prior_std").get<double>(),
                               q.at("lower").get<double>(), q.at("upper").get<double>()});
    const std::size_t p = pf.parameters.size();
    if (head.contains("prior_correlation")) pf.prior_correlation = r.dense(head["prior_correlation"], "prior_correlation");
    const auto& o = head.at("options");
    pf.options.max_iterations = o.at("max_iterations");
    pf.options.tolerance = o.at("tolerance");
    pf.options.mac_min = o.at("mac_min");
    pf.options.freq_tol_pct = o.at("freq_tol_pct");
    pf.options.track_mac_min = o.at("track_mac_min");
    pf.options.shape_derivatives = o.at("shape_derivatives");
    pf.options.shape_derivative = o.at("shape_derivative");
    pf.options.operators = o.at("operators");
    for (const auto& jc : head.at("configurations")) {
      ProblemConfiguration c;
      c.name = jc.at("name");
      c.deck = jc.at("deck");
      c.modes = jc.at("modes");
      const std::string where = "configuration '" + c.name + "'";
      for (const auto& d : jc.at("dofs")) c.dofs.emplace_back(d.at(0).get<std::int64_t>(), d.at(1).get<int>());
      c.sensor_labels = jc.at("sensor_labels").get<std::vector<std::string>>();
      c.sensors = r.sparse(jc.at("sensors"), where + " sensors");
      c.K = r.sparse(jc.at("K"), where + " K");
      c.M = r.sparse(jc.at("M"), where + " M");
      if (jc.at("dK").size() != p || jc.at("dM").size() != p)
        r.fail(where + ": " + std::to_string(p) + " parameters but " + std::to_string(jc.at("dK").size()) + " dK blocks");
      for (std::size_t j = 0; j < p; ++j) {
        c.dK.push_back(r.sparse(jc["dK"][j], where + " dK[" + pf.parameters[j].name + "]"));
        c.dM.push_back(r.sparse(jc["dM"][j], where + " dM[" + pf.parameters[j].name + "]"));
      }
      for (const auto& jm : jc.at("measured")) {
        ProblemMode m;
        m.id = jm.at("id");
        m.frequency_hz = jm.at("frequency_hz");
        m.frequency_std_hz = jm.at("frequency_std_hz");
        m.shape_std = jm.at("shape_std");
        m.use_frequency = jm.at("use_frequency");
        m.use_shape = jm.at("use_shape");
        if (jm.contains("shape")) {
          const Eigen::MatrixXd shape = r.dense(jm["shape"], where + " mode " + std::to_string(m.id) + " shape");
          if (shape.cols() != 1) r.fail(where + " mode " + std::to_string(m.id) + ": shape must be one column");
          m.shape = shape.col(0);
        }
        c.measured.push_back(std::move(m));
      }
      pf.configurations.push_back(std::move(c));
    }
  } catch (const json::exception& e) {
    throw InputError(path + ": header item missing or of the wrong type: " + e.what());
  }
  if (const auto why = inconsistency(pf); !why.empty()) r.fail(why);
  return pf;
}

}  // namespace ssid::formats
