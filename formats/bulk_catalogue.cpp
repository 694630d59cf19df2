/// \file bulk_catalogue.cpp
/// The catalogue of NASTRAN bulk data entry names.
///
/// Sources, as a union (a name in either is an entry a real deck may hold):
/// - MSC Nastran Quick Reference Guide, "Bulk Data Entries": the entry names of
///   its alphabetical list (2018-2021 editions), compiled by hand, with the NX /
///   Simcenter Nastran entries a deck from those solvers holds (CPLSTN*, CPLSTS*,
///   CTRAX*, CQUADX4/8, NXSTRAT);
/// - NASTRAN-95 User's Manual, section 2.4 "Bulk Data Deck" (um/BULK.TXT of
///   github.com/nasa/NASTRAN-95): every "NAME - title" entry heading, extracted
///   from the file; the PARAM names of its PARAM section left out (they are
///   values of PARAM, not entries).
/// - entries held by decks that MSC or Simcenter Nastran ran, with the run's .f06 or
///   .op2 beside them (pyNastran's models/: contact, nonlinear control, damage,
///   acoustics, random-variable and p-element geometry entries of recent editions,
///   and older ones, MSC's grid and element generators GRIDG, CGEN, SPCG with
///   their LIST and DELETE): ABSNMVS, ABSTRCT, ACPLNW, AMLREG, BCRPARA, BCSURF,
///   CGEN, DELETE, DMNCON, DMRLAW, DVTREL1, EGRID, GRIDG, GROUP, LIST, MATDMG,
///   NLCNTL2, NLCNTLG, PFASTT, PINTS, PLOADX, PLOTE, PLOTG, PLOTOPT, POINT, RANDVAR,
///   SPCG, TABLEM5. They are
///   known names kept verbatim; `ssid modes` refuses a deck holding one (it may
///   change K or M), PLOADX aside (a load, card_traits.cpp).
/// ENDDATA is in the list so that a misspelt ENDDATA gets it as a suggestion.
/// The list errs on the inclusive side: a real name missing from it would make a
/// real card an error, an extra name only keeps a misspelling of it verbatim.
/// tests/formats/test_bulk_catalogue.cpp checks that every card ssid types is here.
#include "formats/bulk_catalogue.hpp"

#include <algorithm>
#include <numeric>

#include "formats/bulk_model.hpp"

namespace ssid::formats {

const std::vector<std::string_view>& bulk_entry_names() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> v = {
    "ACCEL", "ACCEL1", "ACMODL", "ACPEMCP", "ACSRCE", "ACTRIM", "ADAPT", "AECOMP", "AECOMPL", "AEDW", "AEFACT",
    "AEFORCE", "AELINK", "AELIST", "AEPARM", "AEPRESS", "AERO", "AEROS", "AESCALE", "AESTAT", "AESURF", "AESURFS",
    "ASET", "ASET1", "AXIC", "AXIF", "AXSLOT", "BAROR", "BCBDPRP", "BCBMRAD", "BCBODY", "BCBODY1", "BCBOX",
    "BCHANGE", "BCMATL", "BCMOVE", "BCNURB2", "BCNURBS", "BCONECT", "BCONP", "BCONPRG", "BCONPRP", "BCPARA",
    "BCPATCH", "BCPROP", "BCRGSRF", "BCRIGID", "BCSCAP", "BCSEG", "BCTABL1", "BCTABLE", "BCTADD", "BCTPARA",
    "BCTPARM", "BCTRIM", "BCTSET", "BDYC", "BDYLIST", "BDYOR", "BDYS", "BDYS1", "BEAMOR", "BFIELD", "BFRIC", "BGADD",
    "BGPARM", "BGSET", "BLSEG", "BNDFIX", "BNDFIX1", "BNDFREE", "BNDFREE1", "BNDGRID", "BOLT", "BOLTFOR", "BOLTFRC",
    "BOLTLD", "BOLTSEQ", "BOUTPUT", "BRKSQL", "BSET", "BSET1", "BSQUEAL", "BSURF", "BSURFS", "BWIDTH", "CAABSF",
    "CACINF3", "CACINF4", "CAERO1", "CAERO2", "CAERO3", "CAERO4", "CAERO5", "CAMPBLL", "CBAR", "CBARAO", "CBEAM",
    "CBEAM3", "CBEND", "CBUSH", "CBUSH1D", "CBUSH2D", "CCONEAX", "CDAMP1", "CDAMP1D", "CDAMP2", "CDAMP2D", "CDAMP3",
    "CDAMP4", "CDAMP5", "CDUM1", "CDUM2", "CDUM3", "CDUM4", "CDUM5", "CDUM6", "CDUM7", "CDUM8", "CDUM9", "CE11",
    "CELAS1", "CELAS1D", "CELAS2", "CELAS2D", "CELAS3", "CELAS4", "CELBOW", "CEMLOOP", "CFAST", "CFFREE", "CFLSTR",
    "CFLUID2", "CFLUID3", "CFLUID4", "CFTETRA", "CFTUBE", "CFWEDGE", "CGAP", "CHACAB", "CHACBR", "CHBDY", "CHBDYE",
    "CHBDYG", "CHBDYP", "CHEXA", "CHEXCZ", "CIFHEX", "CIFPENT", "CIFQDX", "CIFQUAD", "CIHEX1", "CIHEX2", "CIHEX3",
    "CINTC", "CIS2D8", "CLOAD", "CMARKB2", "CMARKN1", "CMASS1", "CMASS2", "CMASS3", "CMASS4", "CMREBAI", "CMREBAR",
    "CNGRNT", "CONCT", "CONCT1", "CONM1", "CONM2", "CONROD", "CONSPOT", "CONTRLT", "CONV", "CONVM", "CORD1C",
    "CORD1R", "CORD1S", "CORD2C", "CORD2R", "CORD2S", "CORD3G", "CORD3R", "CPENTA", "CPENTCZ", "CPLSTN3", "CPLSTN4",
    "CPLSTN6", "CPLSTN8", "CPLSTS3", "CPLSTS4", "CPLSTS6", "CPLSTS8", "CPYRAM", "CQDMEM", "CQDMEM1", "CQDMEM2",
    "CQDPLT", "CQUAD", "CQUAD1", "CQUAD2", "CQUAD4", "CQUAD8", "CQUADR", "CQUADX", "CQUADX4", "CQUADX8", "CRAC2D",
    "CRAC3D", "CRBAR", "CRBE1", "CRBE2", "CRBE3", "CREEP", "CRIGD1", "CRIGD2", "CRIGD3", "CRIGDR", "CROD", "CRROD",
    "CRSPLINE", "CRTRPLT", "CSEAM", "CSET", "CSET1", "CSHEAR", "CSLOT3", "CSLOT4", "CSPH", "CSPOT", "CSSCHD",
    "CSUPER", "CSUPEXT", "CTETRA", "CTORDRG", "CTQUAD", "CTRAPAX", "CTRAPRG", "CTRAX3", "CTRAX6", "CTRBSC", "CTRIA1",
    "CTRIA2", "CTRIA3", "CTRIA6", "CTRIAAX", "CTRIAR", "CTRIARG", "CTRIAX", "CTRIAX6", "CTRIM6", "CTRMEM", "CTRPLT",
    "CTRPLT1", "CTRSHL", "CTTRIA", "CTUBE", "CTWIST", "CVISC", "CWEDGE", "CWELD", "CWSEAM", "CYAX", "CYJOIN",
    "CYLINDR", "CYSUP", "CYSYM", "DAMPGBL", "DAREA", "DAREAS", "DBREG", "DCONADD", "DCONSTR", "DDVAL", "DEACTEL",
    "DEFORM", "DEFUSET", "DELAY", "DELAYS", "DEQATN", "DESVAR", "DIVERG", "DLINK", "DLOAD", "DMI", "DMIAX", "DMIG",
    "DMIGOUT", "DMIGROT", "DMIJ", "DMIJI", "DMIK", "DOPTPRM", "DPHASE", "DPHASES", "DRESP1", "DRESP2", "DRESP3",
    "DSCREEN", "DSFACT", "DTABLE", "DTABLE2", "DTI", "DVBSHAP", "DVCREL1", "DVCREL2", "DVGRID", "DVLREL1", "DVMREL1",
    "DVMREL2", "DVPREL1", "DVPREL2", "DVPSURF", "DVSHAP", "ECHOOFF", "ECHOON", "EIGB", "EIGC", "EIGP", "EIGR",
    "EIGRL", "ELEMUDS", "ELIST", "ENDDATA", "EPOINT", "EXTRN", "FBODYLD", "FBODYSB", "FEEDGE", "FEFACE", "FLFACT",
    "FLSYM", "FLUTTER", "FORCE", "FORCE1", "FORCE2", "FORCEAX", "FREEPT", "FREQ", "FREQ1", "FREQ2", "FREQ3", "FREQ4",
    "FREQ5", "FSICTRL", "FSLIST", "GEMLOOP", "GENEL", "GMBC", "GMBNDC", "GMBNDS", "GMCONV", "GMCORD", "GMCURV",
    "GMINTC", "GMINTS", "GMLOAD", "GMNURB", "GMQVOL", "GMSPC", "GMSURF", "GRAV", "GRDSET", "GRID", "GRIDB", "GRIDF",
    "GRIDS", "GTRAN", "GUST", "GUST2", "HADACRI", "HADAPTL", "ITER", "LOAD", "LOADC", "LOADCLID", "LOADCYH",
    "LOADCYN", "LOADCYT", "LSEQ", "MARCIN", "MARCOUT", "MAT1", "MAT10", "MAT11", "MAT2", "MAT3", "MAT3D", "MAT4",
    "MAT5", "MAT6", "MAT8", "MAT9", "MATCID", "MATDIGI", "MATEP", "MATF", "MATFT", "MATG", "MATHE", "MATHED",
    "MATHP", "MATM", "MATNLE", "MATORT", "MATPE1", "MATPZ1", "MATPZ2", "MATRIG", "MATS1", "MATS3", "MATS8", "MATSMA",
    "MATSORT", "MATT1", "MATT11", "MATT2", "MATT3", "MATT4", "MATT5", "MATT6", "MATT8", "MATT9", "MATTEP", "MATTF",
    "MATTG", "MATTHE", "MATTORT", "MATTUSR", "MATTVE", "MATUDS", "MATUSR", "MATVE", "MATVP", "MBOLT", "MBOLTUS",
    "MCOHE", "MDIPOLE", "MDLPRM", "MFLUID", "MKAERO1", "MKAERO2", "MODTRAK", "MOMAX", "MOMENT", "MOMENT1", "MOMENT2",
    "MONCNCM", "MONDSP1", "MONGRP", "MONPNT1", "MONPNT2", "MONPNT3", "MONSUM", "MONSUM1", "MPC", "MPCADD", "MPCAX",
    "MPCD", "MPCREEP", "MPCS", "MPCY", "MTTPZ1", "MTTPZ2", "NFTUBE", "NLADAPT", "NLAUTO", "NLDAMP", "NLHEATC",
    "NLMOPTS", "NLOUT", "NLPARM", "NLPCI", "NLRGAP", "NLRSFD", "NLSTEP", "NLSTRAT", "NOLIN1", "NOLIN2", "NOLIN3",
    "NOLIN4", "NOLIN5", "NOLIN6", "NSM", "NSM1", "NSMADD", "NSML", "NSML1", "NTHICK", "NXSTRAT", "OMIT", "OMIT1",
    "OMITAX", "OUTPUT", "OUTRCV", "PAABSF", "PACABS", "PACBAR", "PACINF", "PAERO1", "PAERO2", "PAERO3", "PAERO4",
    "PAERO5", "PANEL", "PARAM", "PARAMARC", "PBAR", "PBARL", "PBARN1", "PBCOMP", "PBDISCR", "PBEAM", "PBEAM3",
    "PBEAML", "PBEMN1", "PBEND", "PBMSECT", "PBRSECT", "PBUSH", "PBUSH1D", "PBUSH2D", "PBUSHT", "PCOHE", "PCOMP",
    "PCOMP1", "PCOMP2", "PCOMPF", "PCOMPG", "PCOMPLS", "PCOMPS", "PCONEAX", "PCONV", "PCONV1", "PCONVM", "PDAMP",
    "PDAMP5", "PDAMPT", "PDUM1", "PDUM2", "PDUM3", "PDUM4", "PDUM5", "PDUM6", "PDUM7", "PDUM8", "PDUM9", "PELAS",
    "PELAST", "PELBOW", "PERMBDY", "PFAST", "PFTUBE", "PGAP", "PHBDY", "PIHEX", "PINTC", "PIS2D8", "PLCOMP",
    "PLFACT", "PLIMIT", "PLOAD", "PLOAD1", "PLOAD2", "PLOAD3", "PLOAD4", "PLOADB3", "PLOADE1", "PLOADX1", "PLOTEL", "PLOTEL3", "PLOTEL4", "PLOTEL6", "PLOTEL8", "PLOTHEX", "PLOTPEN", "PLOTPYR", "PLOTTET",
    "PLPLANE", "PLSOLID", "PMASS", "POINTAX", "POPT", "PPLANE", "PPSE", "PQDMEM", "PQDMEM1", "PQDMEM2", "PQDPLT",
    "PQUAD1", "PQUAD2", "PRAC2D", "PRAC3D", "PRESAX", "PRESPT", "PROD", "PRODN1", "PROLATE", "PSEAM", "PSET",
    "PSHEAR", "PSHEARN", "PSHELL", "PSHELL1", "PSHLN1", "PSHLN2", "PSLDN1", "PSOLID", "PSPH", "PTORDRG", "PTRAPAX",
    "PTRBSC", "PTRIA1", "PTRIA2", "PTRIAAX", "PTRIM6", "PTRMEM", "PTRPLT", "PTRPLT1", "PTRSHL", "PTSHELL", "PTUBE",
    "PTWIST", "PVAL", "PVISC", "PWELD", "PWSEAM", "QBDY1", "QBDY2", "QBDY3", "QHBDY", "QSET", "QSET1", "QVECT",
    "QVOL", "RADBC", "RADBND", "RADCAV", "RADLST", "RADM", "RADMT", "RADMTX", "RADSET", "RANDPS", "RANDT1", "RBAR",
    "RBAR1", "RBE1", "RBE2", "RBE2A", "RBE2GS", "RBE3", "RBE3D", "RBJOINT", "RCROSS", "READ", "RELEASE", "RELES",
    "REMFLUX", "RESTART", "RFORCE", "RFORCE1", "RGYRO", "RINGAX", "RINGFL", "RJOINT", "RLOAD1", "RLOAD2", "ROTORB",
    "ROTORD", "ROTORG", "ROTSEQ", "RROD", "RSPINR", "RSPINT", "RSPLINE", "RSSCON", "RTRPLT", "RTRPLT1", "RVDOF",
    "RVDOF1", "SE11", "SEBNDRY", "SEBSET", "SEBSET1", "SEBULK", "SECONCT", "SECSET", "SECSET1", "SECTAX", "SEDLINK",
    "SEDRSP2", "SEDRSP3", "SEELT", "SEEXCLD", "SELABEL", "SELOAD", "SELOC", "SEMPLN", "SENQSET", "SEQEP", "SEQGP",
    "SEQSEP", "SEQSET", "SEQSET1", "SESET", "SESUP", "SET1", "SET2", "SET3", "SET4", "SETREE", "SEUSET", "SEUSET1",
    "SLBDY", "SLOAD", "SNORM", "SNORMDT", "SPBLND1", "SPBLND2", "SPC", "SPC1", "SPCADD", "SPCAX", "SPCD", "SPCFLD",
    "SPCOFF", "SPCOFF1", "SPCR", "SPCS", "SPCS1", "SPCSD", "SPHERE", "SPLINE1", "SPLINE2", "SPLINE3", "SPLINE4",
    "SPLINE5", "SPLINE6", "SPLINE7", "SPLINEX", "SPOINT", "SPRELAX", "STOCHAS", "STREAML1", "STREAML2", "SUPAX",
    "SUPORT", "SUPORT1", "SWLDPRM", "TABDMP1", "TABL3D", "TABLE3D", "TABLED1", "TABLED2", "TABLED3", "TABLED4",
    "TABLED5", "TABLEH1", "TABLEHT", "TABLEM1", "TABLEM2", "TABLEM3", "TABLEM4", "TABLES1", "TABLEST", "TABRND1",
    "TABRNDG", "TEMP", "TEMPAX", "TEMPB3", "TEMPBC", "TEMPD", "TEMPF", "TEMPN1", "TEMPP1", "TEMPP2", "TEMPP3",
    "TEMPRB", "TF", "TIC", "TIC3", "TICD", "TICEL", "TICREF", "TICS", "TIM", "TLOAD1", "TLOAD2", "TMCPARA", "TOPVAR",
    "TRANS", "TRIM", "TRIM2", "TSTEP", "TSTEP1", "TSTEPNL", "TTEMP", "UNBALNC", "USET", "USET1", "UXVEC", "VCCT",
    "VIEW", "VIEW3D",
    // Held by decks MSC or Simcenter Nastran ran (see above).
    "ABSNMVS", "ABSTRCT", "ACPLNW", "AMLREG", "BCRPARA", "BCSURF", "CGEN", "DELETE", "DMNCON", "DMRLAW", "DVTREL1",
    "EGRID", "GRIDG", "GROUP", "LIST", "MATDMG", "NLCNTL2", "NLCNTLG", "PFASTT", "PINTS", "PLOADX", "PLOTE", "PLOTG",
    "PLOTOPT", "POINT", "RANDVAR", "SPCG", "TABLEM5",
    };
    std::sort(v.begin(), v.end());
    return v;
  }();
  return names;
}

bool is_bulk_entry_name(std::string_view name) {
  const auto& v = bulk_entry_names();
  return std::binary_search(v.begin(), v.end(), name);
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Optimal string alignment: the Levenshtein recurrence plus a transposition of
  // two adjacent characters (Damerau), three rows kept.
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::size_t> prev2(m + 1), prev(m + 1), cur(m + 1);
  std::iota(prev.begin(), prev.end(), std::size_t{0});
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

std::optional<std::string> nearest_bulk_entry_name(std::string_view name) {
  // One edit in a name of four characters or fewer already reaches many real
  // names (CROD, CBAR, GRID, SPC, MPC), so short names get one edit, longer two.
  const std::size_t limit = name.size() <= 4 ? 1 : 2;
  std::optional<std::string_view> best;
  std::size_t best_d = limit + 1;
  bool best_typed = false;
  for (std::string_view c : bulk_entry_names()) {  // sorted: the first of equals is the alphabetical first
    const std::size_t la = c.size(), lb = name.size();
    if ((la > lb ? la - lb : lb - la) > limit) continue;
    const std::size_t d = edit_distance(name, c);
    if (d == 0 || d > limit) continue;
    const bool typed = is_supported_card(std::string(c));
    if (d < best_d || (d == best_d && typed && !best_typed)) {
      best = c;
      best_d = d;
      best_typed = typed;
    }
  }
  if (!best) return std::nullopt;
  return std::string(*best);
}

}  // namespace ssid::formats
