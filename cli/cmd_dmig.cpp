/// \file cmd_dmig.cpp
/// `ssid dmig list|dump`: DMIG matrices of a deck or punch file.
#include <cstdio>
#include <iostream>

#include "cli/cli_util.hpp"
#include "cli/matrix_json.hpp"
#include "formats/dmig.hpp"
#include "formats/matrix_market.hpp"
#include "formats/op4.hpp"
#include "formats/parse_error.hpp"
#include "translators/dmig_assembly.hpp"

namespace ssid::cli {

namespace {

using formats::Dmig;

const char* ifo_name(int ifo) {
  switch (ifo) {
    case 1: return "square";
    case 2: return "rectangular";
    case 6: return "symmetric";
    case 9: return "rectangular (columns by number)";
    default: return "?";
  }
}

nlohmann::json dofs_json(const translators::DofMap& m) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& d : m.dofs()) j.push_back({d.point, d.component});
  return j;
}

/// The matrix on its own DOFs (sorted grid/component), in the op4 dump layout,
/// plus the DOF of each row and column.
nlohmann::json dmig_json(const Dmig& m, const formats::Deck& deck) {
  const translators::DmigDofs dofs = translators::dmig_dofs(m);
  const auto a = translators::assemble_dmig_complex(m, dofs.rows, dofs.cols, &deck);
  nlohmann::json j = matrix_json(m.name, m.ifo, ifo_name(m.ifo), m.tin, a);
  j["tout"] = m.tout;
  j["polar_input"] = m.polar;
  j["row_dofs"] = dofs_json(dofs.rows);
  j["col_dofs"] = dofs_json(dofs.cols);
  j["location"] = deck.location(deck.cards[m.card]).str();
  return j;
}

int dmig_list(const Args& args) {
  po::options_description desc("ssid dmig list options");
  desc.add_options()("deck", po::value<std::string>()->required(), "deck or punch file (.bdf, .dat, .pch)")(
      "json", po::value<std::string>(), "write the listing as JSON to this file ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid dmig list DECK [--json OUT]", desc, pos, vm, rc)) return rc;
  const std::string path = vm["deck"].as<std::string>();
  const formats::Deck deck = formats::read_deck(path);
  const auto mats = formats::read_dmigs(deck);
  nlohmann::json j{{"file", path}, {"matrices", nlohmann::json::array()}};
  for (const Dmig& m : mats) {
    const auto dofs = translators::dmig_dofs(m);
    const auto full = formats::expand_dmig(m, &deck);
    j["matrices"].push_back({{"name", m.name},
                             {"form", m.ifo},
                             {"form_name", ifo_name(m.ifo)},
                             {"precision", m.tin},
                             {"precision_name", precision_name(m.tin)},
                             {"tout", m.tout},
                             {"polar_input", m.polar},
                             {"rows", dofs.rows.size()},
                             {"cols", dofs.cols.size()},
                             {"column_entries", m.columns.size()},
                             {"terms_given", m.terms()},
                             {"nonzeros", full.size()},
                             {"location", deck.location(deck.cards[m.card]).str()}});
  }
  const std::string json_path = vm.count("json") ? vm["json"].as<std::string>() : "";
  if (json_path == "-") {
    write_json("-", j);
    return 0;
  }
  std::cout << path << ": " << mats.size() << " DMIG matri" << (mats.size() == 1 ? "x" : "ces") << "\n";
  if (!mats.empty())
    std::printf("  %-8s %-34s %-22s %8s %8s %8s %10s  %s\n", "name", "form (IFO)", "precision (TIN)", "rows", "cols",
                "terms", "nonzeros", "header");
  for (const auto& e : j["matrices"])
    std::printf("  %-8s %-34s %-22s %8zu %8zu %8zu %10zu  %s\n", e["name"].get<std::string>().c_str(),
                (std::to_string(e["form"].get<int>()) + " " + e["form_name"].get<std::string>()).c_str(),
                (std::to_string(e["precision"].get<int>()) + " " + e["precision_name"].get<std::string>() +
                 (e["polar_input"].get<bool>() ? " polar" : ""))
                    .c_str(),
                e["rows"].get<std::size_t>(), e["cols"].get<std::size_t>(), e["terms_given"].get<std::size_t>(),
                e["nonzeros"].get<std::size_t>(), e["location"].get<std::string>().c_str());
  std::fflush(stdout);
  if (!json_path.empty()) write_json(json_path, j);
  return 0;
}

int dmig_dump(const Args& args) {
  po::options_description desc("ssid dmig dump options");
  desc.add_options()("deck", po::value<std::string>()->required(), "deck or punch file (.bdf, .dat, .pch)")(
      "name", po::value<std::string>(), "only this matrix (an object); all when not given (a list)")(
      "json", po::value<std::string>()->required(), "JSON output file ('-' for stdout)");
  po::positional_options_description pos;
  pos.add("deck", 1);
  po::variables_map vm;
  int rc = 0;
  if (!parse_options(args, "ssid dmig dump DECK [--name NAME] --json OUT", desc, pos, vm, rc)) return rc;
  const std::string path = vm["deck"].as<std::string>();
  const formats::Deck deck = formats::read_deck(path);
  const auto mats = formats::read_dmigs(deck);
  if (vm.count("name")) {
    const std::string name = vm["name"].as<std::string>();
    for (const Dmig& m : mats)
      if (m.name == name) {
        write_matrix_json(vm["json"].as<std::string>(), dmig_json(m, deck));
        return 0;
      }
    std::string have;
    for (const Dmig& m : mats) have += (have.empty() ? "" : ", ") + m.name;
    throw formats::InputError(path + ": no DMIG named " + name + " (the deck holds: " + (have.empty() ? "none" : have) +
                             ")");
  }
  nlohmann::json j = nlohmann::json::array();
  for (const Dmig& m : mats) j.push_back(dmig_json(m, deck));
  write_matrix_json(vm["json"].as<std::string>(), j);
  return 0;
}

/// `ssid dmig convert DECK OUT`: DMIG matrices as OP4 (or MatrixMarket) on their own DOFs.
int dmig_convert(const Args& args) {
  po::options_description desc("ssid dmig convert options");
  desc.add_options()("deck", po::value<std::string>()->required(), "deck or punch file")(
      "out", po::value<std::string>()->required(), "output OP4 file (or .mtx with --mtx)")(
      "name", po::value<std::string>(), "only this matrix")("ascii", "OP4 in ASCII (default binary)")(
      "precision", po::value<int>(), "OP4 precision 1-4 (default: each DMIG's TIN)")(
      "mtx", "MatrixMarket instead of OP4 (one file per matrix: OUT, or OUT_NAME.mtx when several)")(
      "dofs", po::value<std::string>(), "write the row and column DOFs of each matrix as JSON here");
  po::positional_options_description pos;
  pos.add("deck", 1).add("out", 1);
  po::variables_map vm;
  int rc = 0;
  const std::string usage =
      "ssid dmig convert DECK OUT [--name NAME] [--ascii] [--precision N] [--mtx] [--dofs JSON]";
  if (!parse_options(args, usage, desc, pos, vm, rc)) return rc;
  const std::string path = vm["deck"].as<std::string>(), out = vm["out"].as<std::string>();
  const formats::Deck deck = formats::read_deck(path);
  const auto all = formats::read_dmigs(deck);
  std::vector<const Dmig*> mats;
  for (const Dmig& m : all)
    if (!vm.count("name") || m.name == vm["name"].as<std::string>()) mats.push_back(&m);
  if (mats.empty())
    throw formats::InputError(path + (vm.count("name") ? ": no DMIG named " + vm["name"].as<std::string>() : ": no DMIG"));
  std::vector<formats::Op4Matrix> op4;
  nlohmann::json dofs = nlohmann::json::array();
  for (const Dmig* m : mats) {
    const translators::DmigDofs d = translators::dmig_dofs(*m);
    const int form = m->ifo == formats::dmig_form::Symmetric ? formats::op4_form::Symmetric
                     : m->ifo == formats::dmig_form::Square  ? formats::op4_form::Square
                                                             : formats::op4_form::Rectangular;
    if (m->is_complex())
      op4.push_back(formats::Op4Matrix::from_complex(m->name, translators::assemble_dmig_complex(*m, d.rows, d.cols, &deck),
                                                     form, static_cast<formats::Op4Precision>(m->tin)));
    else
      op4.push_back(formats::Op4Matrix::from_real(m->name, translators::assemble_dmig_real(*m, d.rows, d.cols, &deck),
                                                  form, static_cast<formats::Op4Precision>(m->tin)));
    dofs.push_back({{"name", m->name}, {"row_dofs", dofs_json(d.rows)}, {"col_dofs", dofs_json(d.cols)}});
  }
  if (vm.count("mtx")) {
    for (const auto& m : op4) {
      std::string p = out;
      if (op4.size() > 1) {
        const std::size_t dot = out.rfind('.');
        p = (dot == std::string::npos ? out : out.substr(0, dot)) + "_" + m.name +
            (dot == std::string::npos ? ".mtx" : out.substr(dot));
      }
      const std::string comment = "DMIG " + m.name + " from " + path;
      if (m.is_complex())
        formats::write_matrix_market(p, m.complex,
                                     m.form == formats::op4_form::Symmetric ? formats::MtxSymmetry::Symmetric
                                                                             : formats::MtxSymmetry::General,
                                     comment);
      else
        formats::write_matrix_market(p, m.real,
                                     m.form == formats::op4_form::Symmetric ? formats::MtxSymmetry::Symmetric
                                                                             : formats::MtxSymmetry::General,
                                     comment);
      std::cout << "wrote " << p << " (" << m.name << ", " << m.rows << " x " << m.cols << ")\n";
    }
  } else {
    formats::Op4WriteOptions o;
    o.encoding = vm.count("ascii") ? formats::Op4Encoding::Ascii : formats::Op4Encoding::Binary;
    o.storage = formats::Op4Storage::Sparse;
    o.precision = vm.count("precision") ? vm["precision"].as<int>() : 0;
    formats::write_op4(out, op4, o);
    std::cout << "wrote " << out << ": " << op4.size() << " matri" << (op4.size() == 1 ? "x" : "ces") << "\n";
  }
  if (vm.count("dofs")) write_json(vm["dofs"].as<std::string>(), dofs);
  return 0;
}

}  // namespace

int cmd_dmig(const Args& args) {
  const std::string usage =
      "usage: ssid dmig list DECK [--json OUT]\n"
      "       ssid dmig dump DECK [--name NAME] --json OUT\n"
      "       ssid dmig convert DECK OUT [--name NAME] [--ascii] [--precision N] [--mtx] [--dofs JSON]\n";
  if (args.empty()) {
    std::cerr << usage;
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h") {
    std::cout << usage
              << "\n  list   name, form, precision, size and terms of every DMIG matrix of a deck or punch file"
                 "\n  dump   the complete matrix (symmetric forms expanded, polar input converted) as 1-based"
                 "\n         triplets [row, col, re, im] on the matrix's own DOFs (row_dofs, col_dofs: [grid, component])"
                 "\n  convert  the complete matrices as an OP4 file (in each DMIG's TIN precision unless --precision)"
                 "\n         or MatrixMarket, on their own DOFs (listed by --dofs)\n"
                 "\nSee docs/op4.md.\n";
    return 0;
  }
  const Args rest(args.begin() + 1, args.end());
  if (args[0] == "list") return dmig_list(rest);
  if (args[0] == "dump") return dmig_dump(rest);
  if (args[0] == "convert") return dmig_convert(rest);
  std::cerr << "ssid dmig: unknown subcommand '" << args[0] << "'\n" << usage;
  return 2;
}

}  // namespace ssid::cli
