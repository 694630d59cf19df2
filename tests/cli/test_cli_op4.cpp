// `ssid op4` and `ssid dmig` on the shipped samples.
#include <catch2/catch.hpp>

#include <cmath>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli_run.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kOp4 = std::string(SSID_SOURCE_DIR) + "/samples/two_matrices.op4";
const std::string kDmig = std::string(SSID_SOURCE_DIR) + "/samples/dmig_sample.bdf";

fs::path scratch() { return cli_scratch("op4"); }

json read_json(const fs::path& p) { return json::parse(cli_slurp(p)); }

// KAA of the sample, 1-based triplets by column then row (symmetric, stored fully).
const json kKaaEntries = json::parse(
    "[[1,1,4.0,0.0],[2,1,-1.0,0.0],[1,2,-1.0,0.0],[2,2,3.0,0.0],[3,2,2.0,0.0],[2,3,2.0,0.0],[3,3,5.0,0.0]]");
// BHH: complex single, column 1 row 1; column 2 rows 3-4 (row 3 = 0 + 1i, row 4 = 0.75).
const json kBhhEntries = json::parse("[[1,1,1.5,-0.25],[3,2,0.0,1.0],[4,2,0.75,0.0]]");

}  // namespace

TEST_CASE("ssid op4 list: name, rows, columns, form, precision, storage, non-zeros", "[cli][op4]") {
  auto r = run_ssid("op4 list " + kOp4);
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("(ASCII): 2 matrices") != std::string::npos);
  CHECK(r.out.find("KAA                 3          3  6 symmetric            2 real double    dense              7") !=
        std::string::npos);
  CHECK(r.out.find("BHH                 4          2  2 rectangular          3 complex single sparse             3") !=
        std::string::npos);
  r = run_ssid("op4 list " + kOp4 + " --json -");
  REQUIRE(r.code == 0);
  const json j = json::parse(r.out);
  CHECK(j["format"]["encoding"] == "ascii");
  REQUIRE(j["matrices"].size() == 2);
  CHECK(j["matrices"][0] == json::parse(R"({"name":"KAA","rows":3,"cols":3,"form":6,"form_name":"symmetric",
      "precision":2,"precision_name":"real double","storage":"dense","nonzeros":7})"));
  CHECK(j["matrices"][1]["storage"] == "sparse");
  CHECK(j["matrices"][1]["nonzeros"] == 3);
}

TEST_CASE("ssid op4 dump: 1-based triplets, one matrix by name or all as a list", "[cli][op4]") {
  const fs::path d = scratch();
  auto r = run_ssid("op4 dump " + kOp4 + " --name KAA --json " + (d / "kaa.json").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  json k = read_json(d / "kaa.json");
  CHECK(k["name"] == "KAA");
  CHECK(k["rows"] == 3);
  CHECK(k["cols"] == 3);
  CHECK(k["form"] == 6);
  CHECK(k["precision"] == 2);
  CHECK(k["entries"] == kKaaEntries);
  r = run_ssid("op4 dump " + kOp4 + " --json " + (d / "all.json").string());
  REQUIRE(r.code == 0);
  json all = read_json(d / "all.json");
  REQUIRE(all.is_array());
  REQUIRE(all.size() == 2);
  CHECK(all[1]["name"] == "BHH");
  CHECK(all[1]["precision"] == 3);
  CHECK(all[1]["entries"] == kBhhEntries);
  r = run_ssid("op4 dump " + kOp4 + " --name NOPE --json -");
  CHECK(r.code == 2);
  CHECK(r.err.find("no matrix named NOPE (the file holds: KAA, BHH)") != std::string::npos);
  r = run_ssid("op4 dump " + kOp4);
  CHECK(r.code == 2);  // --json is required
}

TEST_CASE("ssid op4 convert: every encoding/storage/precision choice keeps the values", "[cli][op4]") {
  const fs::path d = scratch();
  struct Case {
    const char* flags;
    const char* encoding;
    const char* storage;
  } cases[] = {{"--binary --dense", "binary", "dense"},
               {"--binary --bigmat --big-endian --marker 8", "binary", "bigmat"},
               {"--binary --sparse --word 8 --precision 4", "binary", "sparse"},
               {"--ascii --bigmat --precision 4", "ascii", "bigmat"},
               {"--ascii --dense", "ascii", "dense"}};
  int k = 0;
  for (const Case& c : cases) {
    INFO(c.flags);
    const fs::path out = d / ("c" + std::to_string(k++) + ".op4");
    auto r = run_ssid("op4 convert " + kOp4 + " " + out.string() + " " + c.flags);
    INFO(r.err);
    REQUIRE(r.code == 0);
    r = run_ssid("op4 list " + out.string() + " --json -");
    REQUIRE(r.code == 0);
    json l = json::parse(r.out);
    CHECK(l["format"]["encoding"] == c.encoding);
    CHECK(l["matrices"][0]["storage"] == c.storage);
    r = run_ssid("op4 dump " + out.string() + " --json -");
    REQUIRE(r.code == 0);
    json all = json::parse(r.out);
    CHECK(all[0]["entries"] == kKaaEntries);
    CHECK(all[1]["entries"] == kBhhEntries);  // single-precision values of the sample are exact
  }
  auto r = run_ssid("op4 convert " + kOp4 + " " + (d / "x.op4").string() + " --precision 2");
  CHECK(r.code == 2);
  CHECK(r.err.find("complex") != std::string::npos);
  r = run_ssid("op4 convert " + kOp4 + " " + (d / "x.op4").string() + " --ascii --binary");
  CHECK(r.code == 2);
}

TEST_CASE("ssid op4 convert --mtx: MatrixMarket per matrix, read back by scipy when available", "[cli][op4]") {
  const fs::path d = scratch();
  auto r = run_ssid("op4 convert " + kOp4 + " " + (d / "m.mtx").string() + " --mtx");
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(cli_slurp(d / "m_KAA.mtx") ==
        "%%MatrixMarket matrix coordinate real symmetric\n"
        "% KAA from " + kOp4 + " (OP4 form 6 symmetric, real double)\n"
        "3 3 5\n1 1 4\n2 1 -1\n2 2 3\n3 2 2\n3 3 5\n");
  CHECK(cli_slurp(d / "m_BHH.mtx") ==
        "%%MatrixMarket matrix coordinate complex general\n"
        "% BHH from " + kOp4 + " (OP4 form 2 rectangular, complex single)\n"
        "4 2 3\n1 1 1.5 -0.25\n3 2 0 1\n4 2 0.75 0\n");
  // scipy check (skipped with a warning where /usr/bin/python3 has no scipy).
  if (std::system("/usr/bin/python3 -c 'import scipy.io' >/dev/null 2>&1") != 0) {
    WARN("scipy not available to /usr/bin/python3: MatrixMarket not cross-checked");
    return;
  }
  const std::string py =
      "import scipy.io, numpy as np, sys\n"
      "k = scipy.io.mmread(sys.argv[1]).toarray()\n"
      "b = scipy.io.mmread(sys.argv[2]).toarray()\n"
      "ok = np.array_equal(k, [[4,-1,0],[-1,3,2],[0,2,5]])\n"
      "e = np.zeros((4,2), complex); e[0,0] = 1.5-0.25j; e[2,1] = 1j; e[3,1] = 0.75\n"
      "ok = ok and np.array_equal(b, e)\n"
      "sys.exit(0 if ok else 3)\n";
  { std::ofstream(d / "check.py") << py; }
  const int rc = std::system(("/usr/bin/python3 " + (d / "check.py").string() + " " + (d / "m_KAA.mtx").string() +
                              " " + (d / "m_BHH.mtx").string())
                                 .c_str());
  CHECK(rc == 0);
}

TEST_CASE("ssid op4: a bad file is an error naming the file and the place", "[cli][op4]") {
  const fs::path d = scratch();
  { std::ofstream(d / "bad.op4") << "       2       2       1       2K       1P,3E23.16\n       5       1       1\n 1.0E+00\n"; }
  auto r = run_ssid("op4 list " + (d / "bad.op4").string());
  CHECK(r.code == 2);
  CHECK(r.err == "ssid: error: " + (d / "bad.op4").string() + ":2: matrix K: column 5 out of range 1..2\n");
}

TEST_CASE("ssid dmig list and dump: complete matrices on their own DOFs", "[cli][dmig]") {
  auto r = run_ssid("dmig list " + kDmig + " --json -");
  INFO(r.err);
  REQUIRE(r.code == 0);
  json l = json::parse(r.out);
  REQUIRE(l["matrices"].size() == 3);
  CHECK(l["matrices"][0]["name"] == "KAAX");
  CHECK(l["matrices"][0]["nonzeros"] == 9);
  CHECK(l["matrices"][0]["terms_given"] == 6);
  CHECK(l["matrices"][1]["polar_input"] == true);
  CHECK(l["matrices"][2]["form"] == 9);
  CHECK(l["matrices"][2]["cols"] == 3);
  r = run_ssid("dmig list " + kDmig);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("3 DMIG matrices") != std::string::npos);

  const fs::path d = scratch();
  r = run_ssid("dmig dump " + kDmig + " --name KAAX --json " + (d / "k.json").string());
  REQUIRE(r.code == 0);
  json k = read_json(d / "k.json");
  CHECK(k["rows"] == 3);
  CHECK(k["form"] == 6);
  CHECK(k["precision"] == 2);
  CHECK(k["row_dofs"] == json::parse("[[10,1],[10,2],[20,0]]"));
  CHECK(k["entries"] == json::parse("[[1,1,4.0,0.0],[2,1,-1.0,0.0],[3,1,0.5,0.0],[1,2,-1.0,0.0],[2,2,3.0,0.0],"
                                    "[3,2,2.0,0.0],[1,3,0.5,0.0],[2,3,2.0,0.0],[3,3,5.0,0.0]]"));
  r = run_ssid("dmig dump " + kDmig + " --name BAAX --json -");
  REQUIRE(r.code == 0);
  json b = json::parse(r.out);
  REQUIRE(b["entries"].size() == 2);
  CHECK(b["entries"][0][2].get<double>() == Approx(std::sqrt(3.0)).epsilon(1e-15));
  CHECK(b["entries"][0][3].get<double>() == Approx(1.0).epsilon(1e-15));
  CHECK(b["entries"][1] == json::parse("[2,1,0.0,1.5]"));
  r = run_ssid("dmig dump " + kDmig + " --json -");
  REQUIRE(r.code == 0);
  json all = json::parse(r.out);
  REQUIRE(all.size() == 3);
  CHECK(all[2]["entries"] == json::parse("[[1,2,1.25,0.0]]"));
  CHECK(all[2]["col_dofs"] == json::parse("[[1,0],[2,0],[3,0]]"));
  r = run_ssid("dmig dump " + kDmig + " --name NOPE --json -");
  CHECK(r.code == 2);
  CHECK(r.err.find("no DMIG named NOPE (the deck holds: KAAX, BAAX, MCOL)") != std::string::npos);
}

TEST_CASE("ssid dmig convert: DMIG to OP4 and MatrixMarket on the matrices' own DOFs", "[cli][dmig]") {
  const fs::path d = scratch();
  auto r = run_ssid("dmig convert " + kDmig + " " + (d / "dm.op4").string() + " --precision 4 --dofs " +
                    (d / "dofs.json").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  r = run_ssid("op4 dump " + (d / "dm.op4").string() + " --json -");
  REQUIRE(r.code == 0);
  json op4 = json::parse(r.out);
  r = run_ssid("dmig dump " + kDmig + " --json -");
  REQUIRE(r.code == 0);
  json dmig = json::parse(r.out);
  REQUIRE(op4.size() == 3);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(op4[k]["name"] == dmig[k]["name"]);
    CHECK(op4[k]["entries"] == dmig[k]["entries"]);  // complex double: the polar values exactly
  }
  json dofs = read_json(d / "dofs.json");
  CHECK(dofs[0]["row_dofs"] == dmig[0]["row_dofs"]);
  r = run_ssid("dmig convert " + kDmig + " " + (d / "k.mtx").string() + " --mtx --name KAAX");
  REQUIRE(r.code == 0);
  CHECK(cli_slurp(d / "k.mtx") ==
        "%%MatrixMarket matrix coordinate real symmetric\n"
        "% DMIG KAAX from " + kDmig + "\n"
        "3 3 6\n1 1 4\n2 1 -1\n3 1 0.5\n2 2 3\n3 2 2\n3 3 5\n");
}

TEST_CASE("ssid op4 to-dmig: DMIG -> OP4 -> DMIG through the CLI gives the same matrices", "[cli][dmig]") {
  const fs::path d = scratch();
  auto r = run_ssid("dmig convert " + kDmig + " " + (d / "rt.op4").string() + " --precision 4 --dofs " +
                    (d / "rt.json").string());
  REQUIRE(r.code == 0);
  r = run_ssid("op4 to-dmig " + (d / "rt.op4").string() + " " + (d / "rt.bdf").string() + " --dofs " +
               (d / "rt.json").string());
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("KAAX: IFO 6, 3 column entries, 6 terms") != std::string::npos);
  r = run_ssid("dmig dump " + (d / "rt.bdf").string() + " --json -");
  REQUIRE(r.code == 0);
  json back = json::parse(r.out);
  r = run_ssid("dmig dump " + kDmig + " --json -");
  json orig = json::parse(r.out);
  for (std::size_t k = 0; k < 2; ++k) {  // KAAX (symmetric), BAAX (complex, from polar input)
    CHECK(back[k]["name"] == orig[k]["name"]);
    CHECK(back[k]["form"] == orig[k]["form"]);
    CHECK(back[k]["row_dofs"] == orig[k]["row_dofs"]);
    CHECK(back[k]["col_dofs"] == orig[k]["col_dofs"]);
    if (k == 0) {
      CHECK(back[k]["entries"] == orig[k]["entries"]);
      continue;
    }
    // sqrt(3) needs 17 digits: a 16-character DMIG field holds 15 of them, 5e-15 relative (docs/op4.md).
    REQUIRE(back[k]["entries"].size() == orig[k]["entries"].size());
    for (std::size_t e = 0; e < orig[k]["entries"].size(); ++e)
      for (std::size_t i = 0; i < 4; ++i)
        CHECK(back[k]["entries"][e][i].get<double>() ==
              Approx(orig[k]["entries"][e][i].get<double>()).epsilon(5e-15).margin(1e-300));
  }
  // Without --dofs: scalar points 1..N, a rectangular matrix by column number (IFO 9).
  r = run_ssid("op4 to-dmig " + kOp4 + " " + (d / "s.bdf").string() + " --name BHH");
  REQUIRE(r.code == 0);
  r = run_ssid("dmig dump " + (d / "s.bdf").string() + " --name BHH --json -");
  REQUIRE(r.code == 0);
  json b = json::parse(r.out);
  CHECK(b["form"] == 9);
  CHECK(b["row_dofs"] == json::parse("[[1,0],[3,0],[4,0]]"));  // a DMIG holds only rows with terms
  CHECK(b["entries"] == json::parse("[[1,1,1.5,-0.25],[2,2,0.0,1.0],[3,2,0.75,0.0]]"));
}
