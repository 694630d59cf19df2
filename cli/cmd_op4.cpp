/// \file cmd_op4.cpp
/// `ssid op4 list|dump|convert`: OP4 matrix files (NASTRAN OUTPUT4/INPUTT4).
#include <cstdio>
#include <iostream>
#include <map>

#include "cli/cli_util.hpp"
#include "cli/matrix_json.hpp"
#include "formats/matrix_market.hpp"
#include "formats/op4.hpp"
#include "formats/parse_error.hpp"
#include "translators/dmig_assembly.hpp"

#include <fstream>

namespace ssid::cli {

namespace {

using formats::Op4Matrix;

const char* storage_name(formats::Op4Storage s) {
  switch (s) {
    case formats::Op4Storage::Dense: return "dense";
    case formats::Op4Storage::Sparse: return "sparse";
    case formats::Op4Storage::BigMat: return "bigmat";
  }
  return "?";
}

std::string encoding_text(const formats::Op4FileInfo& fi) {
  if (fi.encoding == formats::Op4Encoding::Ascii) return "ASCII";
  return std::string("binary, ") + (fi.endian == formats::Endian::Little ? "little" : "big") + "-endian, " +
         std::to_string(fi.marker_bytes) + "-byte record markers, " + std::to_string(fi.word_bytes) + "-byte words";
}

nlohmann::json info_json(const formats::Op4FileInfo& fi) {
  nlohmann::json j{{"encoding", fi.encoding == formats::Op4Encoding::Ascii ? "ascii" : "binary"}};
  if (fi.encoding == formats::Op4Encoding::Binary) {
    j["endian"] = fi.endian == formats::Endian::Little ? "little" : "big";
    j["marker_bytes"] = fi.marker_bytes;
    j["word_bytes"] = fi.word_bytes;
  }
  return j;
}

int op4_list(const Args& args) {
  po::options_description desc("ssid op4 list options");
  desc.add_options()("file", po::value<std::string>()->required(), "OP4 file (ASCII or binary)")(
      "json", po::value<std::string>(), "write the listing as JSON to this file ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid op4 list FILE [--json OUT]", desc, pos, vm, rc)) return rc;
  const std::string path = vm["file"].as<std::string>();
  formats::Op4FileInfo fi;
  const auto mats = formats::read_op4(path, {}, &fi);
  nlohmann::json j{{"file", path}, {"format", info_json(fi)}, {"matrices", nlohmann::json::array()}};
  for (const Op4Matrix& m : mats)
    j["matrices"].push_back({{"name", m.name},
                             {"rows", m.rows},
                             {"cols", m.cols},
                             {"form", m.form},
                             {"form_name", formats::op4_form::name(m.form)},
                             {"precision", static_cast<int>(m.precision)},
                             {"precision_name", precision_name(static_cast<int>(m.precision))},
                             {"storage", storage_name(m.storage)},
                             {"nonzeros", m.nonzeros()}});
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  if (json_path == "-") {
    write_json("-", j);
    return 0;
  }
  std::cout << "OP4 file " << path << " (" << encoding_text(fi) << "): " << mats.size() << " matri"
            << (mats.size() == 1 ? "x" : "ces") << "\n";
  std::printf("  %-10s %10s %10s  %-22s %-16s %-7s %12s\n", "name", "rows", "cols", "form", "precision", "storage",
              "nonzeros");
  for (const Op4Matrix& m : mats)
    std::printf("  %-10s %10lld %10lld  %-22s %-16s %-7s %12lld\n", m.name.c_str(), static_cast<long long>(m.rows),
                static_cast<long long>(m.cols),
                (std::to_string(m.form) + " " + formats::op4_form::name(m.form)).c_str(),
                (std::to_string(static_cast<int>(m.precision)) + " " + precision_name(static_cast<int>(m.precision))).c_str(),
                storage_name(m.storage), static_cast<long long>(m.nonzeros()));
  std::fflush(stdout);
  if (!json_path.empty()) write_json(json_path, j);
  return 0;
}

/// The matrices chosen by --name (all of that name) or all.
std::vector<const Op4Matrix*> select(const std::vector<Op4Matrix>& mats, const po::variables_map& vm,
                                     const std::string& path) {
  std::vector<const Op4Matrix*> out;
  const std::string name = vm.count("name") ? vm["name"].as<std::string>() : "";
  for (const Op4Matrix& m : mats)
    if (name.empty() || m.name == name) out.push_back(&m);
  if (!name.empty() && out.empty()) {
    std::string have;
    for (const Op4Matrix& m : mats) have += (have.empty() ? "" : ", ") + m.name;
    throw formats::InputError(path + ": no matrix named " + name + " (the file holds: " + have + ")");
  }
  return out;
}

int op4_dump(const Args& args) {
  po::options_description desc("ssid op4 dump options");
  desc.add_options()("file", po::value<std::string>()->required(), "OP4 file (ASCII or binary)")(
      "name", po::value<std::string>(), "only this matrix (an object; several of that name: the first, see --index)")(
      "index", po::value<int>(), "with --name: the k-th matrix of that name (1-based)")(
      "json", po::value<std::string>()->required(), "JSON output file ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("file", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid op4 dump FILE [--name NAME [--index K]] --json OUT", desc, pos, vm, rc)) return rc;
  const std::string path = vm["file"].as<std::string>();
  const auto mats = formats::read_op4(path);
  const auto chosen = select(mats, vm, path);
  if (vm.count("name")) {
    const int k = vm.count("index") ? vm["index"].as<int>() : 1;
    if (k < 1 || k > static_cast<int>(chosen.size()))
      throw formats::InputError(path + ": --index " + std::to_string(k) + " but " + std::to_string(chosen.size()) +
                               " matri" + (chosen.size() == 1 ? "x is" : "ces are") + " named " +
                               vm["name"].as<std::string>());
    write_matrix_json(vm["json"].as<std::string>(), matrix_json(*chosen[static_cast<std::size_t>(k - 1)]));
    return 0;
  }
  nlohmann::json j = nlohmann::json::array();
  for (const Op4Matrix* m : chosen) j.push_back(matrix_json(*m));
  write_matrix_json(vm["json"].as<std::string>(), j);
  return 0;
}

/// "out.mtx" -> "out_KAA.mtx" (several matrices written as MatrixMarket).
std::string mtx_path(const std::string& out, const std::string& name, int repeat) {
  const std::size_t dot = out.rfind('.');
  const std::size_t slash = out.rfind('/');
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = has_ext ? out.substr(0, dot) : out;
  const std::string ext = has_ext ? out.substr(dot) : ".mtx";
  return stem + "_" + (name.empty() ? "unnamed" : name) + (repeat > 1 ? "_" + std::to_string(repeat) : "") + ext;
}

int op4_convert(const Args& args) {
  po::options_description desc("ssid op4 convert options");
  desc.add_options()("in", po::value<std::string>()->required(), "input OP4 file")(
      "out", po::value<std::string>()->required(), "output file")("ascii", "write ASCII")(
      "binary", "write binary (Fortran unformatted)")("dense", "dense columns")("sparse", "sparse strings (non-BIGMAT)")(
      "bigmat", "sparse BIGMAT strings")("precision", po::value<int>(),
                                          "1 real single, 2 real double, 3 complex single, 4 complex double "
                                          "(default: each matrix's own)")(
      "big-endian", "binary: big-endian (default little)")("marker", po::value<int>()->default_value(4),
                                                           "binary: record marker bytes, 4 or 8")(
      "word", po::value<int>()->default_value(4), "binary: word bytes, 4 (32-bit NASTRAN) or 8 (64-bit)")(
      "name", po::value<std::string>(), "only the matrices of this name")(
      "mtx", "write MatrixMarket coordinate files instead (one per matrix: OUT, or OUT_NAME.mtx when several)");
  po::positional_options_description pos;
  pos.add("in", 1).add("out", 1);
  po::variables_map vm;
  int rc = 0;
  const std::string usage =
      "ssid op4 convert IN OUT [--ascii|--binary] [--dense|--sparse|--bigmat] [--precision N] [--big-endian] "
      "[--marker 4|8] [--word 4|8] [--name NAME] [--mtx]";
  if (!parse_options(args, usage, desc, pos, vm, rc)) return rc;
  if (vm.count("ascii") + vm.count("binary") > 1 || vm.count("dense") + vm.count("sparse") + vm.count("bigmat") > 1) {
    std::cerr << "ssid: choose one of --ascii/--binary and one of --dense/--sparse/--bigmat\nusage: " << usage << "\n";
    return 2;
  }
  const std::string in = vm["in"].as<std::string>(), out = vm["out"].as<std::string>();
  formats::Op4FileInfo fi;
  const auto mats = formats::read_op4(in, {}, &fi);
  const auto chosen = select(mats, vm, in);
  if (vm.count("mtx")) {
    std::map<std::string, int> seen;
    for (const Op4Matrix* m : chosen) {
      const std::string p = chosen.size() == 1 ? out : mtx_path(out, m->name, ++seen[m->name]);
      const std::string comment = m->name + " from " + in + " (OP4 form " + std::to_string(m->form) + " " +
                                  formats::op4_form::name(m->form) + ", " +
                                  precision_name(static_cast<int>(m->precision)) + ")";
      if (m->is_complex()) {
        const auto s = m->form == formats::op4_form::Symmetric && formats::is_exactly_symmetric(m->complex)
                           ? formats::MtxSymmetry::Symmetric
                           : formats::MtxSymmetry::General;
        formats::write_matrix_market(p, m->complex, s, comment);
      } else {
        const auto s = m->form == formats::op4_form::Symmetric && formats::is_exactly_symmetric(m->real)
                           ? formats::MtxSymmetry::Symmetric
                           : formats::MtxSymmetry::General;
        formats::write_matrix_market(p, m->real, s, comment);
      }
      std::cout << "wrote " << p << " (" << m->name << ", " << m->rows << " x " << m->cols << ", " << m->nonzeros()
                << " nonzeros)\n";
    }
    return 0;
  }
  formats::Op4WriteOptions o;
  o.encoding = vm.count("ascii") ? formats::Op4Encoding::Ascii
               : vm.count("binary") ? formats::Op4Encoding::Binary
                                    : fi.encoding;
  o.storage = vm.count("dense") ? formats::Op4Storage::Dense
              : vm.count("bigmat") ? formats::Op4Storage::BigMat
              : vm.count("sparse") ? formats::Op4Storage::Sparse
                                   : (chosen.empty() ? formats::Op4Storage::Sparse : chosen.front()->storage);
  o.precision = vm.count("precision") ? vm["precision"].as<int>() : 0;
  o.endian = vm.count("big-endian") ? formats::Endian::Big : formats::Endian::Little;
  o.marker_bytes = vm["marker"].as<int>();
  o.word_bytes = vm["word"].as<int>();
  std::vector<Op4Matrix> copy;
  copy.reserve(chosen.size());
  for (const Op4Matrix* m : chosen) copy.push_back(*m);
  formats::write_op4(out, copy, o);
  std::cout << "wrote " << out << ": " << copy.size() << " matri" << (copy.size() == 1 ? "x" : "ces") << ", "
            << (o.encoding == formats::Op4Encoding::Ascii ? "ASCII" : "binary") << ", " << storage_name(o.storage)
            << "\n";
  return 0;
}

/// A DOF list [[grid, component], ...] from JSON.
translators::DofMap dof_list(const nlohmann::json& j, const std::string& what) {
  translators::DofMap m;
  if (!j.is_array()) throw formats::InputError(what + ": expected a list of [grid, component]");
  for (const auto& d : j) {
    if (!d.is_array() || d.size() != 2 || !d[0].is_number_integer() || !d[1].is_number_integer())
      throw formats::InputError(what + ": expected [grid, component], got " + d.dump());
    const std::size_t before = m.size();
    m.add({d[0].get<std::int64_t>(), d[1].get<int>()});
    if (m.size() == before) throw formats::InputError(what + ": DOF " + d.dump() + " listed twice");
  }
  return m;
}

/// `ssid op4 to-dmig IN OUT`: OP4 matrices as DMIG cards.
int op4_to_dmig(const Args& args) {
  po::options_description desc("ssid op4 to-dmig options");
  desc.add_options()("in", po::value<std::string>()->required(), "input OP4 file")(
      "out", po::value<std::string>()->required(), "output bulk data file (DMIG cards)")(
      "name", po::value<std::string>(), "only the matrices of this name")(
      "dofs", po::value<std::string>(),
      "JSON DOFs: [[grid, component], ...] for rows and columns, or the list written by `ssid dmig convert "
      "--dofs` ({name, row_dofs, col_dofs} per matrix). Default: scalar points 1..N")(
      "large", "large field (default small, promoted to large where 8 characters cannot hold a value exactly)");
  po::positional_options_description pos;
  pos.add("in", 1).add("out", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid op4 to-dmig IN OUT [--name NAME] [--dofs JSON] [--large]", desc, pos, vm, rc))
    return rc;
  const std::string in = vm["in"].as<std::string>(), out = vm["out"].as<std::string>();
  const auto mats = formats::read_op4(in);
  const auto chosen = select(mats, vm, in);
  nlohmann::json dofs;
  if (vm.count("dofs")) {
    std::ifstream f(vm["dofs"].as<std::string>());
    if (!f) throw formats::InputError("cannot read " + vm["dofs"].as<std::string>());
    dofs = nlohmann::json::parse(f);
  }
  std::string text = "$ DMIG from " + in + " (ssid op4 to-dmig)\n";
  for (const Op4Matrix* m : chosen) {
    translators::DofMap rows, cols;
    bool by_list = false;
    if (dofs.is_array() && !dofs.empty() && dofs[0].is_object()) {
      for (const auto& e : dofs)
        if (e.value("name", "") == m->name) {
          rows = dof_list(e.at("row_dofs"), "--dofs " + m->name + " row_dofs");
          cols = dof_list(e.at("col_dofs"), "--dofs " + m->name + " col_dofs");
          by_list = true;
          break;
        }
      if (!by_list) throw formats::InputError("--dofs has no entry for matrix " + m->name);
    } else if (dofs.is_array()) {
      rows = cols = dof_list(dofs, "--dofs");
      by_list = true;
    } else {
      for (Eigen::Index i = 1; i <= std::max(m->rows, m->cols); ++i) {
        if (i <= m->rows) rows.add({i, 0});
        if (i <= m->cols) cols.add({i, 0});
      }
    }
    translators::DmigFromMatrix o;
    o.name = m->name;
    const bool square_dofs =
        rows.size() == cols.size() && std::equal(rows.dofs().begin(), rows.dofs().end(), cols.dofs().begin());
    const bool symmetric = m->form == formats::op4_form::Symmetric && square_dofs &&
                           (m->is_complex() ? formats::is_exactly_symmetric(m->complex)
                                            : formats::is_exactly_symmetric(m->real));
    o.ifo = symmetric ? formats::dmig_form::Symmetric
            : square_dofs && m->rows == m->cols ? formats::dmig_form::Square
            : by_list                           ? formats::dmig_form::Rectangular
                                                : formats::dmig_form::RectangularByColumnNumber;
    o.tin = static_cast<int>(m->precision);
    const formats::Dmig d = m->is_complex() ? translators::dmig_from_matrix(m->complex, rows, cols, o)
                                            : translators::dmig_from_matrix(m->real, rows, cols, o);
    text += formats::format_dmig(d, vm.count("large") ? formats::FieldFormat::Large : formats::FieldFormat::Small);
    std::cout << m->name << ": IFO " << d.ifo << ", " << d.columns.size() << " column entries, " << d.terms()
              << " terms\n";
  }
  std::ofstream f(out, std::ios::binary);
  if (!f) throw formats::InputError("cannot write " + out);
  f << text;
  if (!f) throw formats::InputError("error writing " + out);
  std::cout << "wrote " << out << "\n";
  return 0;
}

}  // namespace

int cmd_op4(const Args& args) {
  const std::string usage =
      "usage: ssid op4 list FILE [--json OUT]\n"
      "       ssid op4 dump FILE [--name NAME] --json OUT\n"
      "       ssid op4 convert IN OUT [--ascii|--binary] [--dense|--sparse|--bigmat] [--precision N] [--mtx]\n"
      "       ssid op4 to-dmig IN OUT [--name NAME] [--dofs JSON] [--large]\n";
  if (args.empty()) {
    std::cerr << usage;
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    std::cout << usage
              << "\n  list      name, rows, columns, form, precision, storage, non-zeros of every matrix"
                 "\n  dump      the values as 1-based triplets [row, col, re, im] in JSON"
                 "\n  convert   rewrite in another encoding, storage or precision, or as MatrixMarket (--mtx)"
                 "\n  to-dmig   write the matrices as DMIG cards (on DOFs from --dofs, or scalar points 1..N)\n"
                 "\nEach subcommand has --help. See docs/op4.md.\n";
    return 0;
  }
  const Args rest(args.begin() + 1, args.end());
  if (args[0] == "list") return op4_list(rest);
  if (args[0] == "dump") return op4_dump(rest);
  if (args[0] == "convert") return op4_convert(rest);
  if (args[0] == "to-dmig") return op4_to_dmig(rest);
  std::cerr << "ssid op4: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
