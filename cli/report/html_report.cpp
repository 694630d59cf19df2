/// \file html_report.cpp
/// The report page: one function per section, each reading its keys of the
/// JSON and drawing through svg.hpp. Nothing here computes a result; the only
/// arithmetic is drawing (scales, projections, the shapes' display amplitude)
/// and the parameters' change expressed in prior σ.
#include "cli/report/html_report.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <set>

#include "cli/report/frf_chart.hpp"
#include "cli/report/pretest_picture.hpp"
#include "cli/report/projection.hpp"
#include "cli/report/report_data.hpp"
#include "cli/report/svg.hpp"
#include "estimator/reporting/number_text.hpp"

namespace ssid::cli::report {

namespace {

using json = nlohmann::json;
using estimator::fixed;
using estimator::significant;

/// Ten distinguishable colours (Tableau 10) for series.
const char* series_colour(std::size_t i) {
  static const char* c[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                            "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
  return c[i % 10];
}

double num_or(const json& j, const char* key, double fallback = NAN) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

std::string figure(const std::string& id, const std::string& svg, const std::string& caption) {
  return fmt::format("<figure id=\"{}\">\n{}<figcaption>{}</figcaption>\n</figure>\n", esc(id), svg, caption);
}

std::string legend_item(const std::string& swatch_style, const std::string& text) {
  return fmt::format("<span class=\"key\"><span class=\"swatch\" style=\"{}\"></span>{}</span>", swatch_style, esc(text));
}

// ---------------------------------------------------------------- the page

const char* kStyle = R"(
body{font:14px/1.45 system-ui,-apple-system,"Segoe UI",Roboto,Helvetica,Arial,sans-serif;color:#222;max-width:1180px;margin:0 auto;padding:12px 20px}
h1{font-size:22px;margin:8px 0}h2{font-size:18px;border-bottom:1px solid #ccc;padding-bottom:3px;margin-top:28px}
table{border-collapse:collapse;margin:6px 0}td,th{border:1px solid #ddd;padding:2px 7px;text-align:left;vertical-align:top}
th{background:#f3f3f3}td.n{text-align:right;font-variant-numeric:tabular-nums}
code,.mono{font-family:ui-monospace,Menlo,Consolas,monospace;font-size:12px}
figure{display:inline-block;margin:8px 14px 14px 0;vertical-align:top;break-inside:avoid}
figcaption{font-size:12px;color:#444;max-width:760px}
svg.chart text{font-size:11px;fill:#222}svg .label{font-size:12px}
svg .grid{stroke:#e4e4e4}svg .frame{fill:none;stroke:#666}
svg .pair{fill:none;stroke:#e15759;stroke-width:2.5}svg .cellv{font-size:9px}
svg .undeformed{fill:none;stroke:#c8c8c8;stroke-width:1}svg .deformed{fill:none;stroke-width:1.6}
svg .fe{stroke:#1f5fa8}svg .test{stroke:#c0392b}svg .error{stroke:#7b3294}svg .wire0{fill:none;stroke:#e6b0aa;stroke-width:1;stroke-dasharray:3 2}
svg .cause{fill:#e15759;stroke:#7a1f1f}svg .misfit{fill:#f28e2b;fill-opacity:.75}
.key{display:inline-block;margin-right:14px;font-size:12px}.swatch{display:inline-block;width:14px;height:10px;margin-right:4px;vertical-align:middle}
.controls{margin:6px 0;padding:6px;background:#f6f6f6;border:1px solid #e0e0e0}
.partial{background:#fdecea;border:1px solid #e15759;padding:6px}
.note{color:#555;font-size:12px}
@media print{.controls{display:none}figure[data-pair],figure[data-frf]{display:inline-block!important}body{max-width:none}h2{break-after:avoid}}
)";

std::string page_head(const std::string& title) {
  // The error hook comes first so that an error anywhere in the page is recorded
  // (the headless-browser test reads data-script-errors).
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" "
      "content=\"width=device-width\">\n<title>{}</title>\n<style>{}</style>\n<script>\n"
      "window.ssidErrors=[];function ssidError(m){{window.ssidErrors.push(String(m));"
      "document.documentElement.setAttribute('data-script-errors',window.ssidErrors.join(' | '));}}\n"
      "window.addEventListener('error',function(e){{ssidError(e.message||e);}});\n"
      "</script>\n</head>\n<body>\n",
      esc(title), kStyle);
}

const char* kScript = R"(<script>
(function(){
  // View direction of the mode shapes.
  var sel=document.getElementById('view');
  function show(v){document.querySelectorAll('g.view').forEach(function(g){g.style.display=g.getAttribute('data-view')===v?'':'none';});}
  if(sel){sel.addEventListener('change',function(){show(sel.value);});show(sel.value);}
  // The pair shown (all by default; print shows all).
  var pair=document.getElementById('pair');
  function showPair(k){document.querySelectorAll('figure[data-pair]').forEach(function(f){f.style.display=k==='all'||f.getAttribute('data-pair')===k?'':'none';});}
  if(pair){pair.addEventListener('change',function(){showPair(pair.value);});
    window.addEventListener('hashchange',function(){var m=/^#(shape|mems)-([0-9]+)$/.exec(location.hash);if(m){pair.value=m[2];showPair(m[2]);}});}
  // The FRF shown (all by default; print shows all).
  var frf=document.getElementById('frf');
  if(frf){frf.addEventListener('change',function(){var k=frf.value;document.querySelectorAll('figure[data-frf]').forEach(function(f){f.style.display=k==='all'||f.getAttribute('data-frf')===k?'':'none';});});}
  // Animation: each visible deformed drawing swings between +1 and -1 times its
  // deflection about its undeformed base (path data-base); print shows the static +1.
  var anim=document.getElementById('animate'),cache=new Map(),t0=performance.now();
  function nums(d){return (d.match(/-?[0-9.]+/g)||[]).map(Number);}
  function frame(now){
    if(!anim||!anim.checked)return;
    var c=Math.cos((now-t0)/1600*2*Math.PI);
    document.querySelectorAll('g.view path.deformed').forEach(function(p){
      if(p.parentNode.parentNode.style.display==='none')return;
      var e=cache.get(p);
      if(!e){var b=document.getElementById(p.getAttribute('data-base'));e={d:p.getAttribute('d'),p:nums(p.getAttribute('d')),u:nums(b?b.getAttribute('d'):'')};cache.set(p,e);}
      if(e.u.length!==e.p.length)return;
      var s='';for(var i=0;i<e.p.length;i+=4){s+='M'+(e.u[i]+c*(e.p[i]-e.u[i])).toFixed(1)+' '+(e.u[i+1]+c*(e.p[i+1]-e.u[i+1])).toFixed(1)+'L'+(e.u[i+2]+c*(e.p[i+2]-e.u[i+2])).toFixed(1)+' '+(e.u[i+3]+c*(e.p[i+3]-e.u[i+3])).toFixed(1);}
      p.setAttribute('d',s);});
    requestAnimationFrame(frame);
  }
  function still(){cache.forEach(function(e,p){p.setAttribute('d',e.d);});}
  if(anim){anim.addEventListener('change',function(){if(anim.checked)requestAnimationFrame(frame);else still();});requestAnimationFrame(frame);}
  window.addEventListener('beforeprint',function(){if(anim)anim.checked=false;still();});
  // What the headless-browser test reads: figures drawn with a non-empty extent.
  var figs=document.querySelectorAll('figure svg'),empty=[];
  figs.forEach(function(s){var m=s.querySelector('.marks *, .cell, .deformed');var b=null;try{b=m&&m.getBBox();}catch(e){}
    var r=s.getBoundingClientRect();if(!b||!(b.width>0||b.height>0)||!(r.width>0&&r.height>0))empty.push(s.id);});
  var h=document.documentElement;h.setAttribute('data-figures',figs.length);h.setAttribute('data-empty-figures',empty.join(' '));
  h.setAttribute('data-page-height',Math.round(h.scrollHeight));h.setAttribute('data-rendered','1');
})();
</script>
)";

std::string run_section(const json& j) {
  std::string s = "<section id=\"run\">\n<table class=\"run\">\n";
  if (!j.contains("run")) return s + "</table>\n</section>\n";
  const json& r = j["run"];
  s += fmt::format("<tr><th>command</th><td class=\"mono\">{}</td></tr>\n", esc(r.value("command", "")));
  s += "<tr><th>inputs</th><td><table>\n<tr><th>file</th><th>bytes</th><th>SHA-256</th></tr>\n";
  for (const auto& f : r["inputs"])
    s += fmt::format("<tr class=\"input\"><td class=\"mono\">{}</td><td class=\"n\">{}</td><td class=\"mono\">{}</td></tr>\n",
                     esc(f.value("path", "")), f.value("bytes", 0), esc(f.value("sha256", "")));
  s += "</table></td></tr>\n";
  s += fmt::format("<tr><th>ssid</th><td>{}</td></tr>\n<tr><th>date</th><td>{}</td></tr>\n", esc(r.value("version", "")),
                   esc(r.value("date", "")));
  s += "</table>\n";
  if (j.value("partial", false))
    s += fmt::format("<p class=\"partial\">PARTIAL RESULT: {} — the values shown are not an answer to trust.</p>\n",
                     esc(j.value("partial_reason", "")));
  return s + "</section>\n";
}

// ---------------------------------------------------------------- correlation

/// Any matrix of the JSON (rows × columns) as a heat map with its labels, the
/// cells of `marked` (row, column) outlined; colour scale 0 … 1.
std::string matrix_figure(const json& rows, const std::vector<std::string>& row_labels, const std::vector<std::string>& col_labels,
                          const std::string& row_title, const std::string& col_title, const std::string& value_label,
                          const std::set<std::pair<std::size_t, std::size_t>>& marked, const std::string& id,
                          const std::string& caption) {
  HeatMap h;
  for (const auto& r : rows) h.values.push_back(r.get<std::vector<double>>());
  h.row_labels = row_labels, h.col_labels = col_labels;
  h.row_title = row_title, h.col_title = col_title, h.value_label = value_label;
  h.marked = marked;
  return figure(id, heat_map_svg(h, id + "-svg", value_label), caption);
}

/// The MAC matrix as a heat map. `rows_are_fe`: rows analysis modes (correlate)
/// or test modes (estimate).
std::string mac_figure(const json& mac, const std::vector<int>& row_modes, const std::vector<int>& col_modes,
                       bool rows_are_fe, const json& pairs, const std::string& id, const std::string& caption,
                       const std::string& form) {
  std::vector<std::string> rows, cols;
  for (int m : row_modes) rows.push_back(std::to_string(m));
  for (int m : col_modes) cols.push_back(std::to_string(m));
  auto index = [](const std::vector<int>& v, int m) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), m) - v.begin());
  };
  std::set<std::pair<std::size_t, std::size_t>> marked;
  for (const auto& p : pairs) {
    const int fe = p["fe_mode"], test = p["test_mode"];
    const std::size_t i = index(row_modes, rows_are_fe ? fe : test), k = index(col_modes, rows_are_fe ? test : fe);
    if (i < row_modes.size() && k < col_modes.size()) marked.insert({i, k});
  }
  return matrix_figure(mac, rows, cols, rows_are_fe ? "analysis mode" : "test mode", rows_are_fe ? "test mode" : "analysis mode",
                       "MAC" + form, marked, id, caption);
}

/// The cross-orthogonality heat map (|X|; rows the analysis modes, or with `rows_are_test`
/// the test modes, as the MAC beside it), the pairs outlined, and the pairs' acceptance
/// (diagonal > min_diagonal, off-diagonal < max_off_diagonal).
std::string xor_figure(const json& x, bool rows_are_test, const std::string& id = "fig-xor") {
  if (x.contains("unavailable"))
    return fmt::format("<p class=\"note\" id=\"{}\">Cross-orthogonality: not available ({}).</p>\n",
                       id == "fig-xor" ? std::string("xor-unavailable") : id + "-unavailable",
                       esc(x["unavailable"].get<std::string>()));
  HeatMap h;
  for (const auto& row : x["matrix"]) h.values.push_back(row.get<std::vector<double>>());
  const auto rows = x["fe_modes"].get<std::vector<int>>(), cols = x["test_modes"].get<std::vector<int>>();
  for (int m : rows) h.row_labels.push_back(std::to_string(m));
  for (int m : cols) h.col_labels.push_back(std::to_string(m));
  h.row_title = "analysis mode";
  h.col_title = "test mode";
  if (rows_are_test) {
    std::vector<std::vector<double>> t(cols.size(), std::vector<double>(rows.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t k = 0; k < cols.size(); ++k) t[k][i] = h.values[i][k];
    h.values = t;
    std::swap(h.row_labels, h.col_labels);
    std::swap(h.row_title, h.col_title);
  }
  h.value_label = "|cross-orthogonality|";
  const double dmin = x["min_diagonal"], omax = x["max_off_diagonal"];
  std::string table = "<table class=\"xor-pairs\">\n<tr><th>analysis</th><th>test</th><th>|X| of the pair</th><th>largest "
                      "off-diagonal</th><th>accepted</th></tr>\n";
  for (const auto& p : x["pairs"]) {
    const int fe = p["fe_mode"], test = p["test_mode"];
    const auto i = static_cast<std::size_t>(std::find(rows.begin(), rows.end(), fe) - rows.begin());
    const auto k = static_cast<std::size_t>(std::find(cols.begin(), cols.end(), test) - cols.begin());
    if (i < rows.size() && k < cols.size()) h.marked.insert(rows_are_test ? std::make_pair(k, i) : std::make_pair(i, k));
    table += fmt::format("<tr class=\"xor-pair\" data-fe-mode=\"{}\" data-test-mode=\"{}\" data-v=\"{}\" data-off=\"{}\"><td "
                         "class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td></tr>\n",
                         fe, test, exact(p["xor"]), exact(p["largest_off_diagonal"]), fe, test, fixed(p["xor"], 3),
                         fixed(p["largest_off_diagonal"], 3), p["accepted"].get<bool>() ? "yes" : "<b>no</b>");
  }
  table += "</table>\n";
  return figure(id, heat_map_svg(h, id + "-svg", "cross-orthogonality matrix"),
                fmt::format("Cross-orthogonality |φ_aᵀ M_r φ_e| (cell values as in the JSON's matrix, here {}) of {} with every test mode, each mode at unit generalised "
                            "mass under M_r; M_r: {}. Outlined: the pairs. The usual acceptance: the pair's value above {} and "
                            "every other value in its row and column below {}.",
                            rows_are_test ? "rows the test modes" : "rows the analysis modes", esc(x.value("basis", "")),
                            esc(x.value("reduction", "")), significant(dmin, 3),
                            significant(omax, 3))) +
         table;
}

// ---------------------------------------------------------------- frequencies

/// Test vs analysis frequency on logarithmic axes, the diagonal with ±1 % and
/// ±`band` % bands; `before` (hollow) and `after` (filled) pairs.
std::string frequency_figure(const json& after, const json* before, double band, const std::string& after_name) {
  std::vector<double> all;
  for (const json* set : {&after, before})
    if (set)
      for (const auto& p : *set) all.push_back(p["test_hz"]), all.push_back(p["fe_hz"]);
  const Axis a = log_axis_around(all, "test frequency [Hz]");
  Axis b = a;
  b.label = "analysis frequency [Hz]";
  Chart c(460, 380, a, b);
  // Bands as polygons between (1 − e) f and (1 + e) f; the axes are logarithmic, so the bands are straight.
  for (double e : {band / 100.0, 0.01}) {
    c.add(fmt::format("<polygon class=\"band\" data-pct=\"{}\" points=\"{},{} {},{} {},{} {},{}\" fill=\"{}\"/>\n",
                      exact(e * 100), px(c.x(a.lo)), px(c.y(a.lo * (1 - e))), px(c.x(a.hi)), px(c.y(a.hi * (1 - e))),
                      px(c.x(a.hi)), px(c.y(a.hi * (1 + e))), px(c.x(a.lo)), px(c.y(a.lo * (1 + e))),
                      e == 0.01 ? "#cfe3cf" : "#eef5ee"));
  }
  c.add(fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#555\" stroke-dasharray=\"4 3\"/>\n", px(c.x(a.lo)),
                    px(c.y(a.lo)), px(c.x(a.hi)), px(c.y(a.hi))));
  auto points = [&](const json& set, const std::string& cls, const std::string& style, const std::string& name) {
    for (const auto& p : set) {
      const double t = p["test_hz"], f = p["fe_hz"];
      c.add(fmt::format("<circle class=\"{}\" data-fe-mode=\"{}\" data-test-mode=\"{}\" data-x=\"{}\" data-y=\"{}\" cx=\"{}\" "
                        "cy=\"{}\" r=\"3.6\" {}><title>{}: test mode {} {} Hz, analysis mode {} {} Hz, error {} %</title></circle>\n",
                        cls, p["fe_mode"].get<int>(), p["test_mode"].get<int>(), exact(t), exact(f), px(c.x(t)), px(c.y(f)), style,
                        name, p["test_mode"].get<int>(), significant(t, 6), p["fe_mode"].get<int>(), significant(f, 6),
                        fixed(p["error_pct"].get<double>(), 3)));
    }
  };
  if (before) points(*before, "freq-before", "fill=\"none\" stroke=\"#777\" stroke-width=\"1.3\"", "before the update");
  points(after, "freq-after", "fill=\"#1f5fa8\"", after_name);
  std::string keys = legend_item("background:#1f5fa8", after_name);
  if (before) keys += legend_item("border:1.3px solid #777;background:#fff", "before the update");
  keys += legend_item("background:#cfe3cf", "±1 %") + legend_item("background:#eef5ee", "±" + significant(band, 3) + " %");
  return figure("fig-frequencies", c.svg("frequencies-svg", "test against analysis frequency"),
                "Test against analysis frequency of each pair (logarithmic axes), the diagonal and error bands. " + keys);
}

/// Frequency error per pair: bars, before and after side by side.
std::string error_figure(const json& after, const json* before, const std::string& after_name) {
  std::vector<double> errs{0.0};
  for (const auto& p : after) errs.push_back(p["error_pct"]);
  std::map<int, double> before_by_test;
  if (before)
    for (const auto& p : *before) {
      before_by_test[p["test_mode"].get<int>()] = p["error_pct"].get<double>();
      errs.push_back(p["error_pct"]);
    }
  const double n = static_cast<double>(after.size());
  Chart c(std::max(460.0, 90 + 22 * n), 300, {-0.5, n - 0.5, "pair (test mode)"},
          axis_around(errs, "frequency error (analysis − test) / test [%]", 0.08, true));
  std::vector<std::pair<double, std::string>> cats;
  const double w = (c.x(1) - c.x(0)) * (before ? 0.38 : 0.7);
  c.add(fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#444\"/>\n", px(c.left()), px(c.right()), px(c.y(0))));
  for (std::size_t k = 0; k < after.size(); ++k) {
    const auto& p = after[k];
    const int tm = p["test_mode"];
    cats.push_back({static_cast<double>(k), std::to_string(tm)});
    auto bar = [&](double e, double x0, const std::string& cls, const char* fill, const std::string& name) {
      const double y0 = c.y(std::max(e, 0.0)), y1 = c.y(std::min(e, 0.0));
      c.add(fmt::format("<rect class=\"{}\" data-test-mode=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                        "fill=\"{}\"><title>test mode {}, {}: {} %</title></rect>\n",
                        cls, tm, exact(e), px(x0), px(y0), px(w), px(std::max(y1 - y0, 0.5)), fill, tm, name, fixed(e, 3)));
    };
    const double xc = c.x(static_cast<double>(k));
    if (before && before_by_test.count(tm)) bar(before_by_test[tm], xc - w, "err-before", "#aaaaaa", "before the update");
    bar(p["error_pct"], before ? xc : xc - w / 2, "err-after", "#1f5fa8", after_name);
  }
  if (after.size() > 30)  // label every other pair when crowded
    for (std::size_t k = 1; k < cats.size(); k += 2) cats[k].second.clear();
  c.set_x_categories(cats);
  std::string keys = legend_item("background:#1f5fa8", after_name);
  if (before) keys += legend_item("background:#aaa", "before the update");
  return figure("fig-errors", c.svg("errors-svg", "frequency error per pair"), "Frequency error of each pair. " + keys);
}

std::string pair_table(const json& pairs, const json* before) {
  std::map<int, const json*> b;
  if (before)
    for (const auto& p : *before) b[p["test_mode"].get<int>()] = &p;
  std::string s = "<table class=\"pairs\">\n<tr><th>test mode</th><th>test [Hz]</th><th>analysis mode</th><th>analysis [Hz]</th>"
                  "<th>error [%]</th><th>MAC</th>";
  if (before) s += "<th>before: analysis [Hz]</th><th>error [%]</th><th>MAC</th>";
  s += "</tr>\n";
  for (const auto& p : pairs) {
    s += fmt::format("<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                     "<td class=\"n\">{}</td><td class=\"n\">{}</td>",
                     p["test_mode"].get<int>(), significant(p["test_hz"], 7), p["fe_mode"].get<int>(), significant(p["fe_hz"], 7),
                     fixed(p["error_pct"], 3), fixed(p["mac"], 4));
    if (before) {
      auto it = b.find(p["test_mode"].get<int>());
      if (it != b.end())
        s += fmt::format("<td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>", significant((*it->second)["fe_hz"], 7),
                         fixed((*it->second)["error_pct"], 3), fixed((*it->second)["mac"], 4));
      else
        s += "<td colspan=\"3\">(not paired)</td>";
    }
    s += "</tr>\n";
  }
  return s + "</table>\n";
}

// ---------------------------------------------------------------- parameters

std::string parameter_figures(const json& j) {
  const json& ps = j["parameters"];
  std::string s = "<section id=\"parameters\">\n<h2>Parameters</h2>\n";
  // Prior (0 ± 1) and posterior ((estimate − initial)/σ₀ ± σ/σ₀) in prior σ.
  std::vector<double> ys{-1.2, 1.2};
  for (const auto& p : ps) {
    const double s0 = p["prior_std"];
    const double z = (num_or(p, "estimate") - num_or(p, "initial")) / s0, zs = num_or(p, "posterior_std") / s0;
    ys.push_back(z - zs), ys.push_back(z + zs);
  }
  const double n = static_cast<double>(ps.size());
  Chart c(std::max(460.0, 120 + 70 * n), 320, {-0.5, n - 0.5, "parameter"},
          axis_around(ys, "change [prior σ]", 0.06, true));
  std::vector<std::pair<double, std::string>> cats;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const auto& p = ps[k];
    const std::string name = p["name"];
    cats.push_back({static_cast<double>(k), name});
    const double s0 = p["prior_std"], r0 = p["initial"], r = p["estimate"], sd = p["posterior_std"];
    const double xc = c.x(static_cast<double>(k));
    auto bar = [&](double x, double z, double zs, const std::string& cls, const char* col, const std::string& attrs,
                   const std::string& title) {
      c.add(fmt::format("<g class=\"{}\" data-name=\"{}\" {}><line x1=\"{}\" x2=\"{}\" y1=\"{}\" y2=\"{}\" stroke=\"{}\" "
                        "stroke-width=\"2\"/><line x1=\"{}\" x2=\"{}\" y1=\"{}\" y2=\"{}\" stroke=\"{}\"/><line x1=\"{}\" x2=\"{}\" "
                        "y1=\"{}\" y2=\"{}\" stroke=\"{}\"/><circle cx=\"{}\" cy=\"{}\" r=\"4\" fill=\"{}\"/><title>{}</title></g>\n",
                        cls, esc(name), attrs, px(x), px(x), px(c.y(z - zs)), px(c.y(z + zs)), col, px(x - 6), px(x + 6),
                        px(c.y(z - zs)), px(c.y(z - zs)), col, px(x - 6), px(x + 6), px(c.y(z + zs)), px(c.y(z + zs)), col, px(x),
                        px(c.y(z)), col, esc(title)));
    };
    const std::string unit = p.value("unit", "");
    bar(xc - 10, 0, 1, "prior", "#999999", fmt::format("data-v=\"{}\" data-s=\"{}\"", exact(r0), exact(s0)),
        fmt::format("{} prior: {} ± {} {}", name, significant(r0, 6), significant(s0, 4), unit));
    bar(xc + 10, (r - r0) / s0, sd / s0, "posterior", "#1f5fa8", fmt::format("data-v=\"{}\" data-s=\"{}\"", exact(r), exact(sd)),
        fmt::format("{} posterior: {} ± {} {} ({} prior σ; σ {} of the prior's)", name, significant(r, 8), significant(sd, 4),
                    unit, fixed((r - r0) / s0, 2), fixed(sd / s0, 3)));
  }
  c.set_x_categories(cats);
  s += figure("fig-parameters", c.svg("parameters-svg", "prior and posterior of each parameter"),
              "Prior mean ± σ (grey, at 0 ± 1) and posterior mean ± σ (blue) of each parameter, as the change from the prior "
              "mean in units of the prior σ: a short blue bar is a parameter the test informed; one as long as the grey "
              "bar is one it did not. " +
                  legend_item("background:#999", "prior") + legend_item("background:#1f5fa8", "posterior"));
  // The values, with units.
  s += "<table class=\"params\">\n<tr><th>parameter</th><th>initial</th><th>estimate</th><th>prior σ</th><th>posterior σ</th>"
       "<th>change [%]</th><th>σ ratio</th><th>unit</th><th>designs</th></tr>\n";
  for (const auto& p : ps)
    s += fmt::format("<tr><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                     "<td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td><td>{}</td></tr>\n",
                     esc(p["name"].get<std::string>()), significant(p["initial"], 6), significant(num_or(p, "estimate"), 8),
                     significant(p["prior_std"], 4), significant(num_or(p, "posterior_std"), 4), fixed(num_or(p, "change_pct"), 2),
                     fixed(num_or(p, "std_ratio"), 3), esc(p.value("unit", "")), esc(p.value("designs", "")));
  s += "</table>\n";
  // Posterior correlation.
  if (j.contains("identifiability") && j["identifiability"].contains("posterior_correlation")) {
    HeatMap h;
    for (const auto& row : j["identifiability"]["posterior_correlation"]) h.values.push_back(row.get<std::vector<double>>());
    for (const auto& p : ps) h.row_labels.push_back(p["name"]), h.col_labels.push_back(p["name"]);
    h.row_title = h.col_title = "parameter";
    h.value_label = "posterior correlation ρ";
    h.lo = -1, h.hi = 1;
    const json& id = j["identifiability"];
    std::string cap = fmt::format("Posterior correlation of the parameters. Rank {} of {}, condition {}.", id.value("rank", 0),
                                  id.value("parameters", 0), id["condition"].is_number() ? significant(id["condition"], 4) : "∞");
    if (!id["uninformed"].empty()) {
      cap += " Not informed by the data:";
      for (const auto& u : id["uninformed"]) cap += " " + esc(u.get<std::string>());
      cap += ".";
    }
    s += figure("fig-correlation", heat_map_svg(h, "correlation-svg", "posterior correlation"), cap);
  }
  return s + "</section>\n";
}

std::string convergence_figures(const json& j) {
  const json& its = j["iterations"];
  if (its.empty()) return "";
  const json& ps = j["parameters"];
  std::string s = "<section id=\"convergence\">\n<h2>Convergence</h2>\n";
  std::vector<double> cycles, ys{0.0};
  for (std::size_t i = 0; i < its.size(); ++i) cycles.push_back(static_cast<double>(i));
  for (const auto& it : its)
    for (const auto& p : ps)
      ys.push_back((it["parameters"][p["name"].get<std::string>()].get<double>() - p["initial"].get<double>()) /
                   p["prior_std"].get<double>());
  const Axis xa = {-0.3, static_cast<double>(its.size()) - 0.7, "cycle"};
  Chart c(520, 320, xa, axis_around(ys, "change [prior σ]", 0.06, true));
  std::vector<std::pair<double, std::string>> cats;
  for (std::size_t i = 0; i < its.size(); ++i) cats.push_back({double(i), std::to_string(its[i]["cycle"].get<int>())});
  if (its.size() > 15)
    for (std::size_t k = 1; k < cats.size(); k += 2) cats[k].second.clear();
  c.set_x_categories(cats);
  std::string keys;
  for (std::size_t k = 0; k < ps.size(); ++k) {
    const std::string name = ps[k]["name"];
    const double r0 = ps[k]["initial"], s0 = ps[k]["prior_std"];
    std::string line, dots;
    for (std::size_t i = 0; i < its.size(); ++i) {
      const double r = its[i]["parameters"][name];
      const double x = c.x(double(i)), y = c.y((r - r0) / s0);
      line += (i ? " " : "") + px(x) + "," + px(y);
      dots += fmt::format("<circle class=\"conv\" data-name=\"{}\" data-cycle=\"{}\" data-v=\"{}\" cx=\"{}\" cy=\"{}\" r=\"2.6\" "
                          "fill=\"{}\"><title>{} cycle {}: {}</title></circle>\n",
                          esc(name), its[i]["cycle"].get<int>(), exact(r), px(x), px(y), series_colour(k), esc(name),
                          its[i]["cycle"].get<int>(), significant(r, 8));
    }
    c.add(fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\"/>\n", line, series_colour(k)) + dots);
    keys += legend_item(std::string("background:") + series_colour(k), name);
  }
  s += figure("fig-convergence", c.svg("convergence-svg", "parameters per cycle"),
              "Each parameter per cycle, as its change from the prior mean in prior σ. " + keys);
  // The objective and the frequency error per cycle.
  auto per_cycle = [&](const char* key, const std::string& label, const std::string& id, const char* colour) {
    std::vector<double> v;
    for (const auto& it : its) v.push_back(it[key]);
    const bool log = key == std::string("objective") && *std::min_element(v.begin(), v.end()) > 0;
    Chart k(360, 260, xa, log ? log_axis_around(v, label) : axis_around(v, label, 0.08, true));
    k.set_x_categories(cats);
    std::string pl;
    for (std::size_t i = 0; i < its.size(); ++i) {
      pl += (i ? " " : "") + px(k.x(double(i))) + "," + px(k.y(v[i]));
      k.add(fmt::format("<circle class=\"{}\" data-cycle=\"{}\" data-v=\"{}\" cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"{}\"><title>cycle {}: "
                        "{}</title></circle>\n",
                        id, its[i]["cycle"].get<int>(), exact(v[i]), px(k.x(double(i))), px(k.y(v[i])), colour,
                        its[i]["cycle"].get<int>(), significant(v[i], 6)));
    }
    k.add(fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"{}\"/>\n", pl, colour));
    return k.svg(id + "-svg", label);
  };
  s += figure("fig-objective", per_cycle("objective", "objective J", "objective", "#59a14f"),
              "The objective J (data misfit + prior term) per cycle.");
  s += figure("fig-rms", per_cycle("frequency_rms_pct", "frequency error, RMS [%]", "rms", "#e15759"),
              "The RMS frequency error of the pairs per cycle.");
  return s + "</section>\n";
}

// ---------------------------------------------------------------- mode shapes

double largest(const Points& s) {
  double m = 0;
  for (const auto& [id, v] : s) m = std::max(m, v.norm());
  return m;
}

/// One shape drawn alone, a panel per view (the page's view menu shows one): the frame,
/// the defs of `behind` drawn first (pairs of a defs prefix, "<prefix>-<view>", and the
/// class it is drawn with), the shape at its largest deflection as a path of class
/// "deformed `cls`" that the animation swings about "wire-<view>", and `title`.
std::string single_shape_svg(const std::string& id, const std::string& label, double w, double h,
                             const std::vector<View>& vs, const std::vector<Placement>& pl,
                             const std::vector<std::pair<std::string, std::string>>& behind, const std::string& cls,
                             const Lines& lines, const Points& grids, const Points& shape, double amp,
                             const std::string& title, const std::string& pre = "") {
  std::string svg = fmt::format("<svg id=\"{}\" class=\"shapes\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" "
                                "width=\"{}\" height=\"{}\" role=\"img\" aria-label=\"{}\">\n",
                                id, px(w), px(h), px(w), px(h), esc(label));
  for (std::size_t v = 0; v < vs.size(); ++v) {
    svg += fmt::format("<g class=\"view\" data-view=\"{}\"{}>\n<g transform=\"translate(0 0)\"><rect x=\"0.5\" y=\"0.5\" "
                       "width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#ddd\"/>",
                       vs[v].name, v ? " style=\"display:none\"" : "", px(w - 1), px(h - 1));
    for (const auto& [prefix, c] : behind)
      svg += fmt::format("<use href=\"#{}{}-{}\" class=\"{}\"/>\n", pre, prefix, vs[v].name, c);
    svg += fmt::format("<path class=\"deformed {}\" data-base=\"{}wire-{}\" d=\"{}\"/>\n<text x=\"8\" y=\"16\" "
                       "font-size=\"12\">{}</text></g>\n</g>\n",
                       cls, pre, vs[v].name, lines_d(lines, grids, &shape, amp, pl[v]), esc(title));
  }
  return svg + "</svg>\n";
}

/// The seed's Figure 4 for one pair: the error mode ê of MEMS (Eqs. 2–3) drawn on the
/// test's wire frame at the analysis shape's amplitude `amp` (so its size reads against
/// the analysis panel's), beside the MEMS coefficients α of every test mode.
std::string mems_figure(const json& sh, std::size_t k, const Points& grids,
                        const std::vector<std::pair<std::int64_t, std::int64_t>>& test_lines, double amp,
                        const std::vector<View>& vs, const std::vector<Placement>& pl, double w, double h,
                        const std::string& pre = "") {
  const json& m = sh["mems"];
  const Points err = read_points(m["error"]);
  const int fm = sh["fe_mode"], tm = sh["test_mode"];
  const std::string svg =
      single_shape_svg(fmt::format("{}mems-{}-svg", pre, k), fmt::format("error mode of analysis mode {}", fm), w, h, vs, pl,
                       {{"undeformed", "undeformed"}, {"wire", "wire0"}}, "error", test_lines, grids, err, amp,
                       fmt::format("error mode ê, e² = {}", significant(m["error_squared"], 4)), pre);
  // The coefficients α_i of the unit-norm test shapes.
  std::vector<double> a{0.0};
  for (const auto& r : m["alpha"]) a.push_back(r[1]);
  const double n = static_cast<double>(m["alpha"].size());
  Chart c(std::max(300.0, 80 + 17 * n), h, {-0.5, n - 0.5, "test mode"}, axis_around(a, "MEMS coefficient α", 0.08, true));
  std::vector<std::pair<double, std::string>> cats;
  const double bw = (c.x(1) - c.x(0)) * 0.7;
  c.add(fmt::format("<line x1=\"{0}\" x2=\"{1}\" y1=\"{2}\" y2=\"{2}\" stroke=\"#444\"/>\n", px(c.left()), px(c.right()), px(c.y(0))));
  for (std::size_t i = 0; i < m["alpha"].size(); ++i) {
    const int t = m["alpha"][i][0];
    const double al = m["alpha"][i][1];
    const double y0 = c.y(std::max(al, 0.0)), y1 = c.y(std::min(al, 0.0));
    cats.push_back({static_cast<double>(i), std::to_string(t)});
    c.add(fmt::format("<rect class=\"alpha\" data-test-mode=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                      "fill=\"{}\"><title>test mode {}: α = {}</title></rect>\n",
                      t, exact(al), px(c.x(static_cast<double>(i)) - bw / 2), px(y0), px(bw), px(std::max(y1 - y0, 0.5)),
                      t == tm ? "#c0392b" : "#7f7f7f", t, significant(al, 4)));
  }
  if (cats.size() > 30)
    for (std::size_t i = 1; i < cats.size(); i += 2) cats[i].second.clear();
  c.set_x_categories(cats);
  // A later configuration's figures (`pre` not empty) stay out of the pair menu: always shown.
  return fmt::format(
      "<figure id=\"{12}mems-{0}\" class=\"mems\"{13} data-error-squared=\"{1}\" data-mac-superposition=\"{2}\" "
      "data-pair-error-squared=\"{3}\">\n{4}{5}<figcaption>Pair {6}, MEMS (the seed's Eqs. 2–3 and Figure 4): analysis mode {7} "
      "fitted by every test mode (each scaled to unit norm) in the least-squares sense. Left: the error mode ê = φ_a − Σ α_i φ_e_i "
      "on the test's wire frame, at the analysis panel's amplitude; right: the coefficients α_i (red: test mode {8}, the pair's). "
      "e² = {9}, MAC of the superposition {10}; with the pair's test shape alone e² = {11}.</figcaption>\n</figure>\n",
      k, exact(m["error_squared"]), exact(m["mac_superposition"]), exact(m["pair_error_squared"]), svg,
      c.svg(fmt::format("{}mems-{}-alpha-svg", pre, k), "MEMS coefficients"), k + 1, fm, tm,
      significant(m["error_squared"], 4), fixed(m["mac_superposition"], 4), significant(m["pair_error_squared"], 4), pre,
      pre.empty() ? fmt::format(" data-pair=\"{}\"", k) : std::string());
}

/// The diagonal of the grids' bounding box: the structure's size, against which the
/// shapes' largest displacement is drawn (0 for fewer than two distinct grids).
double extent(const Points& grids) {
  if (grids.empty()) return 0;
  Eigen::Vector3d lo = grids.begin()->second, hi = lo;
  for (const auto& [id, p] : grids) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return (hi - lo).norm();
}

/// Each view's placement of `grids` in a `w` × `h` panel.
std::vector<Placement> placements(const std::vector<View>& vs, const Points& grids, double w, double h) {
  std::vector<Placement> pl;
  for (const auto& v : vs) pl.push_back(place(v, grids, w, h));
  return pl;
}

/// The view menu the page's script reads (select#view), with the animation switch
/// (input#animate) when the drawings below it move.
std::string view_menu(const std::vector<View>& vs, bool animate) {
  std::string s = "<div class=\"controls\">view <select id=\"view\">";
  for (const auto& v : vs) s += fmt::format("<option value=\"{}\">{}</option>", v.name, esc(v.label));
  s += "</select>";
  if (animate) s += " <label><input type=\"checkbox\" id=\"animate\" checked> animate</label>";
  return s + "</div>\n";
}

/// `pre` prefixes every id (a later configuration's section: "c2-"); only the first
/// section (pre empty) has the view and pair menus, which the page's script finds by id.
std::string shapes_section(const json& j, const std::string& pre = "", const std::string& title = "Mode shapes") {
  if (!j.contains("geometry") || !j.contains("shapes") || j["shapes"].empty()) return "";
  const json& g = j["geometry"];
  const Points grids = read_points(g["grids"]);
  if (grids.empty()) return "";
  const auto lines = read_lines(g["lines"]), test_lines = read_lines(g["test_lines"]);
  const double size = extent(grids);
  const double w = 360, h = 270;
  const auto vs = views();
  const std::vector<Placement> pl = placements(vs, grids, w, h);

  std::string s = "<section id=\"" + pre + "shapes\">\n<h2>" + esc(title) + "</h2>\n" + (pre.empty() ? view_menu(vs, true) : "");
  s += "<p class=\"note\">Analysis (blue, left) on the deck's elements; test (red, right) on the test's wire frame "
       "(test grids joined where the deck's elements join them), scaled onto the analysis shape by the least-squares "
       "factor; grey: the undeformed structure (dashed red: the test's undeformed wire frame). The largest displacement "
       "is drawn at 8 % of the structure's size. The animation swings each shape through its undeformed position; print "
       "(or animate off) shows it at its largest deflection.</p>\n";
  // The undeformed drawings, once per view, used by every pair.
  s += "<svg width=\"0\" height=\"0\" style=\"position:absolute\" aria-hidden=\"true\"><defs>\n";
  for (std::size_t v = 0; v < vs.size(); ++v)
    s += fmt::format("<path id=\"{3}undeformed-{0}\" d=\"{1}\"/>\n<path id=\"{3}wire-{0}\" d=\"{2}\"/>\n", vs[v].name,
                     lines_d(lines, grids, nullptr, 0, pl[v]), lines_d(test_lines, grids, nullptr, 0, pl[v]), pre);
  s += "</defs></svg>\n";
  // The pair shown: every pair by default and in print; one through the selector or an anchor.
  if (pre.empty()) {
    s += "<div class=\"controls\">pair <select id=\"pair\"><option value=\"all\">all</option>";
    for (std::size_t k = 0; k < j["shapes"].size(); ++k)
      s += fmt::format("<option value=\"{}\">{}: analysis {} / test {}</option>", k, k + 1,
                       j["shapes"][k]["fe_mode"].get<int>(), j["shapes"][k]["test_mode"].get<int>());
    s += "</select> <span class=\"note\">go to:";
    for (std::size_t k = 0; k < j["shapes"].size(); ++k)
      s += fmt::format(" <a href=\"#shape-{0}\">pair {1}</a> (<a href=\"#mems-{0}\">MEMS</a>)", k, k + 1);
    s += "</span></div>\n";
  }
  std::size_t k = 0;
  for (const auto& sh : j["shapes"]) {
    const Points fe = read_points(sh["fe"]), test = read_points(sh["test"]);
    const double amp = 0.08 * size / std::max(largest(fe), 1e-300);
    const int fm = sh["fe_mode"], tm = sh["test_mode"];
    const double fhz = sh["fe_hz"], thz = sh["test_hz"], mac = sh["mac"];
    std::string svg = fmt::format(
        "<svg id=\"{}shape-{}-svg\" class=\"shapes\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {} {}\" width=\"{}\" "
        "height=\"{}\" role=\"img\" aria-label=\"analysis mode {} and test mode {}\">\n",
        pre, k, px(2 * w), px(h), px(2 * w), px(h), fm, tm);
    for (std::size_t v = 0; v < vs.size(); ++v) {
      svg += fmt::format("<g class=\"view\" data-view=\"{}\"{}>\n", vs[v].name, v ? " style=\"display:none\"" : "");
      auto panel = [&](double x0, const Points& shape, const std::vector<std::pair<std::int64_t, std::int64_t>>& ls,
                       const std::string& cls, const std::string& title) {
        // The shape at its largest deflection; the page's script swings it through the
        // undeformed drawing (base) to the opposite deflection: the projection is linear.
        const std::string base = pre + (cls == "test" ? "wire-" : "undeformed-") + std::string(vs[v].name);
        std::string p = fmt::format("<g transform=\"translate({} 0)\"><rect x=\"0.5\" y=\"0.5\" width=\"{}\" height=\"{}\" "
                                    "fill=\"none\" stroke=\"#ddd\"/><use href=\"#{}undeformed-{}\" class=\"undeformed\"/>\n",
                                    px(x0), px(w - 1), px(h - 1), pre, vs[v].name);
        if (cls == "test") p += fmt::format("<use href=\"#{}wire-{}\" class=\"wire0\"/>\n", pre, vs[v].name);
        p += fmt::format("<path class=\"deformed {}\" data-base=\"{}\" d=\"{}\"/>\n<text x=\"8\" y=\"16\" "
                         "font-size=\"12\">{}</text></g>\n",
                         cls, base, lines_d(ls, grids, &shape, amp, pl[v]), esc(title));
        return p;
      };
      svg += panel(0, fe, lines, "fe", fmt::format("analysis mode {}: {} Hz", fm, significant(fhz, 5)));
      svg += panel(w, test, test_lines, "test", fmt::format("test mode {}: {} Hz", tm, significant(thz, 5)));
      svg += "</g>\n";
    }
    svg += "</svg>\n";
    s += fmt::format("<figure id=\"{}shape-{}\" class=\"shape\"{} data-fe-mode=\"{}\" data-test-mode=\"{}\" data-fe-hz=\"{}\" "
                     "data-test-hz=\"{}\" data-mac=\"{}\">\n{}<figcaption>Pair {}: analysis mode {} ({} Hz) and test mode {} ({} "
                     "Hz), MAC {}, error {} %.</figcaption>\n</figure>\n",
                     pre, k, pre.empty() ? fmt::format(" data-pair=\"{}\"", k) : std::string(), fm, tm, exact(fhz), exact(thz),
                     exact(mac), svg, k + 1, fm, significant(fhz, 6), tm, significant(thz, 6), fixed(mac, 4),
                     fixed((fhz - thz) / thz * 100, 3));
    if (sh.contains("mems")) s += mems_figure(sh, k, grids, test_lines, amp, vs, pl, w, h, pre);
    ++k;
  }
  return s + "</section>\n";
}

// ---------------------------------------------------------------- diagnosis

std::string diagnosis_sections(const json& j) {
  std::string s;
  const json& e = j["evidence"];
  s += "<section id=\"residuals\">\n<h2>1. What the updated model gets wrong</h2>\n<ul>\n";
  for (const auto& f : e["findings"]) s += "<li>" + esc(f.get<std::string>()) + "</li>\n";
  s += "</ul>\n";
  // Residuals by mode: frequency error and MEMS error per test mode.
  const json& modes = e["modes"];
  if (!modes.empty()) {
    const double n = static_cast<double>(modes.size());
    auto by_mode = [&](const char* key, const std::string& label, const std::string& id, const char* fill, bool zero) {
      std::vector<double> v{0.0};
      for (const auto& m : modes)
        if (m[key].is_number()) v.push_back(m[key]);
      Chart c(std::max(420.0, 90 + 22 * n), 280, {-0.5, n - 0.5, "test mode"}, axis_around(v, label, 0.08, zero));
      std::vector<std::pair<double, std::string>> cats;
      const double w = (c.x(1) - c.x(0)) * 0.7;
      for (std::size_t k = 0; k < modes.size(); ++k) {
        const auto& m = modes[k];
        cats.push_back({double(k), std::to_string(m["test_mode"].get<int>())});
        if (!m[key].is_number() || (m["fe_mode"].is_number() && m["fe_mode"].get<int>() == 0 && key != std::string("mems_error")))
          continue;  // no partner: no frequency error
        const double x = m[key];
        const double y0 = c.y(std::max(x, 0.0)), y1 = c.y(std::min(x, 0.0));
        c.add(fmt::format("<rect class=\"{}\" data-test-mode=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                          "fill=\"{}\"><title>test mode {}: {}</title></rect>\n",
                          id, m["test_mode"].get<int>(), exact(x), px(c.x(double(k)) - w / 2), px(y0), px(w),
                          px(std::max(y1 - y0, 0.5)), fill, m["test_mode"].get<int>(), significant(x, 4)));
      }
      c.set_x_categories(cats);
      return c.svg(id + "-svg", label);
    };
    s += figure("fig-mode-error", by_mode("error_pct", "frequency error [%]", "mode-error", "#1f5fa8", true),
                "Frequency error of each test mode against its partner after the ordinary update (no bar: no partner).");
    s += figure("fig-mems", by_mode("mems_error", "MEMS error e²", "mems", "#b07aa1", true),
                "The MEMS error of each test mode (the seed's Fig. 4 measure): the share of the test shape the analysis "
                "modes cannot represent.");
  }
  const json& gm = e["grid_misfit"];
  if (!gm.empty()) {
    const double n = static_cast<double>(gm.size());
    std::vector<double> v{0.0};
    for (const auto& m : gm) v.push_back(m["share"]);
    Chart c(std::max(420.0, 90 + 30 * n), 280, {-0.5, n - 0.5, "grid"}, axis_around(v, "share of the shape misfit", 0.08, true));
    std::vector<std::pair<double, std::string>> cats;
    const double w = (c.x(1) - c.x(0)) * 0.7;
    for (std::size_t k = 0; k < gm.size(); ++k) {
      const double x = gm[k]["share"];
      const auto grid = gm[k]["grid"].get<std::int64_t>();
      cats.push_back({double(k), std::to_string(grid)});
      c.add(fmt::format("<rect class=\"grid-misfit\" data-grid=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" "
                        "fill=\"#f28e2b\"><title>grid {}: {}</title></rect>\n",
                        grid, exact(x), px(c.x(double(k)) - w / 2), px(c.y(x)), px(w), px(c.y(0) - c.y(x)), grid, fixed(x, 4)));
    }
    c.set_x_categories(cats);
    s += figure("fig-grid-misfit", c.svg("grid-misfit-svg", "shape misfit by grid"),
                "The grids where the measured shapes differ most from the updated model's (share of the total misfit).");
  }
  s += "</section>\n";

  // Ranking of causes.
  const json& rk = j["ranking"];
  s += "<section id=\"ranking\">\n<h2>2–3. Hypotheses tested, ranked by evidence</h2>\n";
  if (!rk.empty()) {
    const std::size_t shown = std::min<std::size_t>(rk.size(), 12);
    std::vector<double> v;
    const double nominal = j.contains("nominal") ? num_or(j["nominal"], "log_evidence") : NAN;
    if (std::isfinite(nominal)) v.push_back(nominal);
    for (std::size_t k = 0; k < shown; ++k) v.push_back(rk[k]["log_evidence"]);
    Chart c(std::max(460.0, 100 + 40 * double(shown)), 300, {-0.5, double(shown) - 0.5, "rank"},
            axis_around(v, "score [nats]", 0.08, false));
    std::vector<std::pair<double, std::string>> cats;
    const double w = (c.x(1) - c.x(0)) * 0.7, base = c.bottom();
    for (std::size_t k = 0; k < shown; ++k) {
      const double x = rk[k]["log_evidence"];
      cats.push_back({double(k), std::to_string(k + 1)});
      c.add(fmt::format("<rect class=\"rank\" data-rank=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\">"
                        "<title>{}. {} at {}: {} nats</title></rect>\n",
                        k + 1, exact(x), px(c.x(double(k)) - w / 2), px(c.y(x)), px(w), px(std::max(base - c.y(x), 0.5)),
                        k == 0 ? "#e15759" : "#4e79a7", k + 1, esc(rk[k]["kind"].get<std::string>()),
                        esc(rk[k]["location"]["text"].get<std::string>()), fixed(x, 1)));
    }
    if (std::isfinite(nominal))
      c.add(fmt::format("<line class=\"nominal\" data-v=\"{0}\" x1=\"{1}\" x2=\"{2}\" y1=\"{3}\" y2=\"{3}\" stroke=\"#222\" "
                        "stroke-dasharray=\"5 3\"><title>deck as given: {4} nats</title></line>\n",
                        exact(nominal), px(c.left()), px(c.right()), px(c.y(nominal)), fixed(nominal, 1)));
    c.set_x_categories(cats);
    s += figure("fig-ranking", c.svg("ranking-svg", "hypotheses by score"),
                "Score (Laplace log-evidence + unpaired-mode penalty − log of the locations searched) of the best "
                "hypotheses; dashed: the deck as given. Higher is better supported by the test.");
    s += "<table class=\"ranking\">\n<tr><th>rank</th><th>kind</th><th>location</th><th>score [nats]</th><th>freq RMS [%]</th>"
         "<th>mean MAC</th><th>paired</th><th>added parameters</th></tr>\n";
    for (std::size_t k = 0; k < shown; ++k) {
      const auto& r = rk[k];
      std::string added;
      for (const auto& p : r["parameters"])
        added += esc(p["name"].get<std::string>()) + " = " + significant(p["estimate"], 5) + " ± " + significant(p["std"], 3) + "<br>";
      s += fmt::format("<tr><td class=\"n\">{}</td><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                       "<td class=\"n\">{}</td><td class=\"n\">{}</td><td>{}</td></tr>\n",
                       k + 1, esc(r["kind"].get<std::string>()), esc(r["location"]["text"].get<std::string>()),
                       fixed(r["log_evidence"], 1), fixed(r["freq_rms_pct"], 3), fixed(r["mean_mac"], 4), r["paired"].get<int>(),
                       added);
    }
    s += "</table>\n";
  }
  s += "</section>\n";

  // The cause, where it sits, and the gain.
  const json& cause = j["cause"];
  s += "<section id=\"cause\">\n<h2>4. The cause</h2>\n";
  if (cause.is_object()) {
    s += fmt::format("<p><b>{}</b> — {}</p>\n", esc(cause.value("kind", "")), esc(cause.value("summary", "")));
    if (j.contains("geometry") && cause.contains("location")) {
      const json& g = j["geometry"];
      const Points grids = read_points(g["grids"]);
      const auto lines = read_lines(g["lines"]);
      std::set<std::int64_t> at;
      for (const auto& id : cause["location"]["grids"]) at.insert(id.get<std::int64_t>());
      std::map<std::int64_t, double> misfit;
      for (const auto& m : e["grid_misfit"]) misfit[m["grid"].get<std::int64_t>()] = m["share"].get<double>();
      if (!grids.empty()) {
        const double w = 560, h = 400;
        const View v = views().front();
        const Placement p = place(v, grids, w, h);
        std::string svg = fmt::format(
            "<svg id=\"cause-svg\" class=\"chart\" xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {0} {1}\" width=\"{0}\" "
            "height=\"{1}\" role=\"img\" aria-label=\"where the cause sits\">\n<g class=\"marks\">\n<path class=\"undeformed\" "
            "d=\"{2}\" stroke=\"#888\"/>\n",
            px(w), px(h), lines_d(lines, grids, nullptr, 0, p));
        double most = 0;
        for (const auto& [id, sh] : misfit) most = std::max(most, sh);
        for (const auto& [id, sh] : misfit) {
          if (!grids.count(id)) continue;
          const auto q = p(grids.at(id));
          svg += fmt::format("<circle class=\"misfit\" data-grid=\"{}\" data-v=\"{}\" cx=\"{}\" cy=\"{}\" r=\"{}\"><title>grid {}: "
                             "{} of the shape misfit</title></circle>\n",
                             id, exact(sh), px(q.x()), px(q.y()), px(4 + 10 * std::sqrt(sh / std::max(most, 1e-300))), id,
                             fixed(sh, 3));
        }
        for (auto id : at) {
          if (!grids.count(id)) continue;
          const auto q = p(grids.at(id));
          svg += fmt::format("<circle class=\"cause\" data-grid=\"{}\" cx=\"{}\" cy=\"{}\" r=\"5\"><title>{} at grid {}</title></circle>\n",
                             id, px(q.x()), px(q.y()), esc(cause.value("kind", "")), id);
        }
        svg += "</g>\n</svg>\n";
        s += figure("fig-cause", svg,
                    "Where the named cause sits (red) on the structure (isometric view), and the grids of the largest shape "
                    "misfit (orange, area ∝ share). " +
                        legend_item("background:#e15759", "cause: " + cause["location"].value("text", "")) +
                        legend_item("background:#f28e2b", "shape misfit"));
      }
    }
    if (cause.contains("parameters")) {
      s += "<table>\n<tr><th>added parameter</th><th>meaning</th><th>estimate</th><th>σ</th></tr>\n";
      for (const auto& p : cause["parameters"])
        s += fmt::format("<tr><td>{}</td><td>{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                         esc(p.value("name", "")), esc(p.value("meaning", "")), significant(p["estimate"], 6),
                         significant(p["std"], 4));
      s += "</table>\n";
    }
  }
  s += "</section>\n";
  if (j.contains("gain")) {
    const json& b = j["gain"]["before"];
    const json& a = j["gain"]["after"];
    s += "<section id=\"gain\">\n<h2>5. The gain</h2>\n";
    // Two small bar pairs: RMS frequency error and mean MAC, before and after.
    auto pair_chart = [&](const char* key, const std::string& label, const std::string& id, bool unit_range) {
      const double vb = b[key], va = a[key];
      Chart c(260, 240, {-0.5, 1.5, ""}, unit_range ? Axis{0, 1, label} : axis_around({0.0, vb, va}, label, 0.1, true));
      c.set_x_categories({{0, "before"}, {1, "after"}});
      const double w = (c.x(1) - c.x(0)) * 0.55;
      int k = 0;
      for (const auto& [name, v] : {std::pair<const char*, double>{"before", vb}, {"after", va}}) {
        c.add(fmt::format("<rect class=\"gain\" data-when=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\">"
                          "<title>{}: {}</title></rect>\n",
                          name, exact(v), px(c.x(k) - w / 2), px(c.y(v)), px(w), px(std::max(c.y(0) - c.y(v), 0.5)),
                          k ? "#59a14f" : "#aaaaaa", name, significant(v, 5)));
        ++k;
      }
      return c.svg(id, label);
    };
    s += figure("fig-gain-rms", pair_chart("freq_rms_pct", "frequency error, RMS [%]", "gain-rms-svg", false),
                fmt::format("RMS frequency error before ({} %) and after ({} %) the cause is added and estimated.",
                            fixed(b["freq_rms_pct"], 3), fixed(a["freq_rms_pct"], 3)));
    s += figure("fig-gain-mac", pair_chart("mean_mac", "mean MAC", "gain-mac-svg", true),
                fmt::format("Mean MAC of the pairs before ({}) and after ({}); paired modes {} and {} of {}.", fixed(b["mean_mac"], 4),
                            fixed(a["mean_mac"], 4), b.value("paired", 0), a.value("paired", 0), a.value("measured", 0)));
    s += "</section>\n";
  }
  return s;
}

// ---------------------------------------------------------------- pretest

/// One bar per method of j["methods"] for `key` (log10 of the value when `log10`),
/// the run's method in red.
std::string method_bars(const json& j, const char* key, bool log10, const std::string& label, const std::string& id) {
  const json& ms = j["methods"];
  const double n = static_cast<double>(ms.size());
  std::vector<double> v{0.0};
  auto drawn = [&](const json& m) -> double {  // the bar's height, NaN where there is none (no set, singular, det F = 0)
    if (!m.contains(key) || !m[key].is_number()) return NAN;
    const double x = log10 ? std::log10(m[key].get<double>()) : m[key].get<double>();
    return std::isfinite(x) ? x : NAN;
  };
  for (const auto& m : ms)
    if (std::isfinite(drawn(m))) v.push_back(drawn(m));
  if (v.size() == 1) return "";  // no method has a value to draw
  Chart c(std::max(360.0, 110 + 60 * n), 280, {-0.5, n - 0.5, "method"}, axis_around(v, label, 0.08, true));
  std::vector<std::pair<double, std::string>> cats;
  const double w = (c.x(1) - c.x(0)) * 0.6;
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const std::string name = ms[k]["method"];
    cats.push_back({double(k), name});
    const double x = drawn(ms[k]);
    if (!std::isfinite(x)) continue;
    const double raw = ms[k][key];
    const double y0 = c.y(std::max(x, 0.0)), y1 = c.y(std::min(x, 0.0));
    c.add(fmt::format("<rect class=\"{}\" data-method=\"{}\" data-v=\"{}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\">"
                      "<title>{}: {}</title></rect>\n",
                      id, esc(name), exact(raw), px(c.x(double(k)) - w / 2), px(y0), px(w), px(std::max(y1 - y0, 0.5)),
                      name == j.value("method", "") ? "#e15759" : "#4e79a7", esc(name), significant(raw, 5)));
  }
  c.set_x_categories(cats);
  return c.svg(id + "-svg", label);
}

std::string exciter_table(const json& ex) {
  std::string s = "<table class=\"exciters\">\n<tr><th>exciter</th><th>grid</th><th>direction cosines (grid's frame)</th></tr>\n";
  for (std::size_t k = 0; k < ex.size(); ++k) {
    const auto& d = ex[k]["direction"];
    s += fmt::format("<tr><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">({}, {}, {})</td></tr>\n", k + 1,
                     ex[k]["grid"].get<std::int64_t>(), fixed(d[0], 4), fixed(d[1], 4), fixed(d[2], 4));
  }
  return s + "</table>\n";
}

/// The simulated test's table (and its cross-orthogonality) of an "evaluation" object.
std::string evaluation_part(const json& e, const std::string& id, const std::string& title) {
  std::string s = fmt::format("<h3>{}</h3>\n<p>Identified {} of {} target mode(s); max frequency error {} %, ", esc(title),
                              e.value("identified", 0), e["targets"].size(),
                              e["max_frequency_error_pct"].is_number() ? fixed(e["max_frequency_error_pct"], 3) : "—");
  s += fmt::format("cross-orthogonality (SEREP mass): min diagonal {}, max off-diagonal {}.</p>\n",
                   e["min_diagonal_xor"].is_number() ? fixed(e["min_diagonal_xor"], 3) : "—",
                   e["max_offdiagonal_xor"].is_number() ? fixed(e["max_offdiagonal_xor"], 3) : "—");
  s += fmt::format("<table class=\"evaluation\" id=\"{}-table\">\n<tr><th>mode</th><th>FE [Hz]</th><th>identified [Hz]</th>"
                   "<th>error [%]</th><th>damping ratio</th><th>MAC</th></tr>\n",
                   esc(id));
  for (const auto& t : e["targets"]) {
    s += fmt::format("<tr class=\"target\" data-mode=\"{}\"><td class=\"n\">{}</td><td class=\"n\">{}</td>", t["mode"].get<int>(),
                     t["mode"].get<int>(), significant(t["fe_hz"], 6));
    if (t.value("identified", false))
      s += fmt::format("<td class=\"n\" data-v=\"{}\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                       exact(t["hz"]), significant(t["hz"], 6), fixed(t["frequency_error_pct"], 3), fixed(t["damping_ratio"], 4),
                       fixed(t["mac"], 3));
    else
      s += "<td colspan=\"4\">not identified</td></tr>\n";
  }
  s += "</table>\n";
  if (e.contains("xor")) {
    std::vector<std::string> rows, cols;
    for (const auto& r : e["xor_rows"]) rows.push_back(std::to_string(r.get<int>()));
    for (std::size_t k = 0; k < e["xor"][0].size(); ++k) cols.push_back(std::to_string(k + 1));
    s += matrix_figure(e["xor"], rows, cols, "FE target mode", "identified mode", "cross-orthogonality", {}, "fig-" + id + "-xor",
                       "Cross-orthogonality of the identified modes (columns, in the order matched) with the FE target modes "
                       "(rows), SEREP mass on the sensors.");
  }
  return s;
}

std::string pretest_sections(const json& j) {
  std::string s;
  const bool triax = j.value("triax", false);
  const json& sensors = j["sensors"];
  std::vector<std::string> targets;
  for (const auto& t : j["target_modes"]) targets.push_back(std::to_string(t["mode"].get<int>()));

  // 1. The picture, in four views.
  s += "<section id=\"placement\">\n<h2>Sensors and exciters</h2>\n";
  s += fmt::format("<p>{} target mode(s), {} {} by {} from {} candidate DOF(s) of a {}-DOF model.</p>\n", targets.size(),
                   triax ? sensors.size() / 3 : sensors.size(), triax ? "triaxes" : "sensor DOF(s)", esc(j.value("method", "")),
                   j.value("candidates", 0), j.value("dof", 0));
  if (j.contains("geometry") && !j["geometry"]["grids"].empty()) {
    const auto vs = views();
    s += view_menu(vs, false);
    s += figure("fig-placement", pretest_picture_svg(j, vs, "placement-svg"),
                "The structure (grey) with each sensor as an arrow along its measured direction (triaxes: squares), the "
                "exciters as red arrows along their force directions (given exciters orange), and the sensors' wire frame "
                "(dashed; the trace lines of the UFF output).");
  }
  s += "<table class=\"sensors\">\n<tr><th>#</th><th>grid</th><th>measures</th><th>score</th><th>direction (basic)</th></tr>\n";
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    const auto& x = sensors[k];
    const auto& d = x["direction_basic"];
    s += fmt::format("<tr class=\"sensor\" data-grid=\"{}\" data-component=\"{}\"><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                     "<td>{}</td><td class=\"n\">{}</td><td class=\"n\">({}, {}, {})</td></tr>\n",
                     x["grid"].get<std::int64_t>(), sensor_component(x), k + 1, x["grid"].get<std::int64_t>(),
                     esc(sensor_label(x)), significant(x["score"], 4), fixed(d[0], 3), fixed(d[1], 3), fixed(d[2], 3));
  }
  s += "</table>\n</section>\n";

  // 2. Fisher information per method.
  s += "<section id=\"fisher\">\n<h2>Fisher information</h2>\n";
  s += "<table class=\"fisher\">\n<tr><th>method</th><th>det F</th><th>log10 det F</th><th>condition number</th><th>rank</th></tr>\n";
  const json rows = j.contains("methods") ? j["methods"] : json::array({j});
  auto opt = [](const json& v, int d) { return v.is_number() ? significant(v, d) : std::string("—"); };
  for (const auto& m : rows) {
    if (m.contains("error")) {
      s += fmt::format("<tr class=\"method\" data-method=\"{0}\"><td>{0}</td><td colspan=\"4\">no set: {1}</td></tr>\n",
                       esc(m.value("method", "")), esc(m.value("error", "")));
      continue;
    }
    s += fmt::format("<tr class=\"method\" data-method=\"{}\"><td>{}</td><td class=\"n\" data-v=\"{}\">{}</td><td class=\"n\">{}</td>"
                     "<td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                     esc(m.value("method", "")), esc(m.value("method", "")) + (m.value("method", "") == j.value("method", "") ? " (this run)" : ""),
                     exact(m["fisher_determinant"]), significant(m["fisher_determinant"], 5), opt(m["log10_fisher_determinant"], 5),
                     opt(m["condition_number"], 5), m.value("fisher_rank", 0));
  }
  s += "</table>\n";
  if (j.contains("methods")) {
    const std::string det = method_bars(j, "fisher_determinant", true, "log10 det F", "fisher-det");
    const std::string cond = method_bars(j, "condition_number", true, "log10 condition number", "fisher-cond");
    if (!det.empty())
      s += figure("fig-fisher-det", det,
                "The determinant of the Fisher information Φ_sᵀΦ_s of the target modes on each method's sensor set "
                "(mass-normalised modes, unit noise; log scale); red: this run's method. Larger is better.");
    if (!cond.empty())
      s += figure("fig-fisher-cond", cond,
                "The condition number of the Fisher information for each method's set; red: this run's. Smaller is better: "
                "the target modes are told apart.");
  }
  s += "</section>\n";

  // 3. Test-analysis models: cross-orthogonality of the targets.
  s += "<section id=\"tam\">\n<h2>Test-analysis models on the sensors</h2>\n";
  const json& acc = j["acceptance"];
  s += fmt::format("<p>Cross-orthogonality Φᵀ M_TAM Φ of the target modes on the sensor set; accepted: diagonal &gt; {}, "
                   "off-diagonal &lt; {} (primary modes &lt; {}).</p>\n",
                   significant(acc["min_diagonal"], 3), significant(acc["max_offdiagonal"], 3),
                   significant(acc["max_offdiagonal_primary"], 3));
  for (const char* name : {"guyan", "irs", "serep"}) {
    if (!j["tam"].contains(name)) continue;
    const json& t = j["tam"][name];
    if (t.value("status", "") != "ok") {
      s += fmt::format("<p class=\"partial\">{}: failed: {}</p>\n", name, esc(t.value("message", "")));
      continue;
    }
    const std::string verdict =
        t.value("accepted_primary", false) ? "accepted (primary)" : t.value("accepted", false) ? "accepted (secondary)" : "NOT accepted";
    std::set<std::pair<std::size_t, std::size_t>> diagonal;
    for (std::size_t i = 0; i < targets.size(); ++i) diagonal.insert({i, i});
    s += matrix_figure(t["xor"], targets, targets, "target mode", "target mode", "cross-orthogonality", diagonal,
                       std::string("fig-tam-") + name,
                       fmt::format("{} TAM: min diagonal {}, max off-diagonal {}, max frequency error {} %: {}.", name,
                                   fixed(t["min_diagonal_xor"], 4), fixed(t["max_offdiagonal_xor"], 4),
                                   fixed(t["max_frequency_error_pct"], 3), verdict));
  }
  s += "</section>\n";

  // 4. Exciters.
  if (!j["exciters"].empty() || j.contains("given_exciters")) {
    s += "<section id=\"exciters\">\n<h2>Exciters</h2>\n";
    auto dropoff = [&](const json& ex, const json& D, double objective, const std::string& id, const std::string& who) {
      std::string t = fmt::format("<h3>{}: objective {}</h3>\n", esc(who), significant(objective, 6)) + exciter_table(ex);
      std::vector<std::string> cols;
      for (std::size_t k = 0; k < ex.size(); ++k) cols.push_back(std::to_string(k + 1) + " (grid " + std::to_string(ex[k]["grid"].get<std::int64_t>()) + ")");
      t += matrix_figure(D, targets, cols, "target mode", "exciter", "MIF drop-off", {}, id,
                         "The multivariate MIF's drop-off at each target mode for each exciter (smaller is better; the objective "
                         "takes each mode's best exciter, no penalty at or below 0.1).");
      return t;
    };
    if (!j["exciters"].empty()) {
      s += dropoff(j["exciters"], j["mif_dropoff"], j["exciter_objective"], "fig-mif", "placed by the genetic algorithm");
      const auto best = j["ga"]["best_per_generation"].get<std::vector<double>>();
      if (!best.empty()) {
        std::vector<double> gen;
        for (std::size_t g = 0; g < best.size(); ++g) gen.push_back(double(g));
        Chart c(520, 280, axis_around(gen, "generation", 0.03), axis_around(best, "objective (best member)", 0.08));
        std::string pl;
        for (std::size_t g = 0; g < best.size(); ++g) {
          pl += (g ? " " : "") + px(c.x(double(g))) + "," + px(c.y(best[g]));
          c.add(fmt::format("<circle class=\"ga\" data-generation=\"{}\" data-v=\"{}\" cx=\"{}\" cy=\"{}\" r=\"2.4\" fill=\"#59a14f\">"
                            "<title>generation {}: {}</title></circle>\n",
                            g, exact(best[g]), px(c.x(double(g))), px(c.y(best[g])), g, significant(best[g], 6)));
        }
        c.add(fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#59a14f\"/>\n", pl));
        const json& ga = j["ga"];
        s += figure("fig-ga", c.svg("ga-svg", "GA objective per generation"),
                    fmt::format("The best member's objective per generation (population {}, {} generations, seed {}, {} "
                                "evaluations).",
                                ga.value("population", 0), ga.value("generations", 0), ga["seed"].dump(), ga.value("evaluations", 0)));
      }
    }
    if (j.contains("given_exciters")) {
      const json& g = j["given_exciters"];
      s += dropoff(g["exciters"], g["mif_dropoff"], g["objective"], "fig-mif-given", "given (--exciter-at)");
    }
    s += "</section>\n";
  }

  // 5. The simulated test.
  if (j.contains("evaluation") || (j.contains("given_exciters") && j["given_exciters"].contains("evaluation"))) {
    s += "<section id=\"evaluation\">\n<h2>Simulated test (--evaluate)</h2>\n";
    if (j.contains("evaluation"))
      s += evaluation_part(j["evaluation"], "evaluation", j["exciters"].empty() ? "with the given exciters" : "with the GA's exciters");
    if (j.contains("given_exciters") && j["given_exciters"].contains("evaluation"))
      s += evaluation_part(j["given_exciters"]["evaluation"], "evaluation-given", "with the given exciters");
    s += "</section>\n";
  }

  // 6. Model error.
  if (j.contains("model_error")) {
    const json& m = j["model_error"];
    s += "<section id=\"model-error\">\n<h2>Model error</h2>\n";
    auto list = [&](const json& l) {
      std::string t;
      for (const auto& x : l)
        t += " " + std::to_string(x["grid"].get<std::int64_t>()) + (x.contains("component") ? " " + esc(sensor_label(x)) : "");
      return t.empty() ? std::string(" —") : t;
    };
    s += fmt::format("<p>Seed {}: of {} strut(s), {} area(s) −20 % and {} +20 %. {} of {} {} changed; dropped:{}; added:{}.</p>\n",
                     m["seed"].dump(), m.value("struts", 0), m.value("areas_decreased", 0), m.value("areas_increased", 0),
                     m.value("changed", 0), m.value("of", 0), esc(m.value("unit", "")), list(m["removed"]), list(m["added"]));
    s += "</section>\n";
  }
  return s;
}

std::string notes_section(const json& j) {
  if (!j.contains("notes") || j["notes"].empty()) return "";
  std::string s = "<section id=\"notes\">\n<h2>Notes</h2>\n<ul>\n";
  for (const auto& n : j["notes"]) s += "<li>" + esc(n.get<std::string>()) + "</li>\n";
  return s + "</ul>\n</section>\n";
}

std::string command_of(const json& j) {
  if (!j.contains("run")) return "";
  const std::string c = j["run"].value("command", "");
  const auto a = c.find(' ');
  if (a == std::string::npos) return "";
  const auto b = c.find(' ', a + 1);
  return c.substr(a + 1, b == std::string::npos ? std::string::npos : b - a - 1);
}

std::vector<int> mode_numbers(const json& modes) {
  std::vector<int> v;
  for (const auto& m : modes) v.push_back(m.is_object() ? m["mode"].get<int>() : m.get<int>());
  return v;
}

/// "a:b" of a [node, direction] pair.
std::string dof_pair(const json& d) { return fmt::format("{}:{}", d[0].get<long>(), d[1].get<int>()); }

/// An FRF's {"re": [...], "im": [...]} as complex values.
std::vector<std::complex<double>> complex_values(const json& p) {
  const auto re = p["re"].get<std::vector<double>>(), im = p["im"].get<std::vector<double>>();
  std::vector<std::complex<double>> v(re.size());
  for (std::size_t k = 0; k < re.size(); ++k) v[k] = {re[k], im[k]};
  return v;
}

/// The menu that shows one FRF figure (figures with data-frf = the record's index) or all.
std::string frf_menu(const json& records) {
  std::string s = "<div class=\"controls\">FRF <select id=\"frf\"><option value=\"all\">all</option>";
  std::size_t k = 0;
  for (const auto& r : records)
    s += fmt::format("<option value=\"{}\">response {} / reference {}</option>", k++, dof_pair(r["response"]),
                     dof_pair(r["reference"]));
  return s + "</select></div>\n";
}

/// The measured FRFs against those of the identified modal model (the seed's Figure 4:
/// the synthesized FRFs laid over the measured ones), one figure per FRF with its FRAC,
/// a menu to show one.
std::string frf_fit_section(const json& fit) {
  const std::vector<double> hz = fit["hz"].get<std::vector<double>>();
  const std::string unit = fit.value("unit", "");
  std::string s = "<section id=\"frf-fit\">\n<h2>FRFs: measured and of the identified modes</h2>\n";
  s += fmt::format("<p>Each measured FRF against the FRF of the identified modes ({}, {}…{} Hz; {} of the FRFs "
                   "unexplained, relative Frobenius norm). FRAC = |Σ H<sub>x</sub> Ĥ*|² / (Σ|H<sub>x</sub>|² Σ|Ĥ|²) over "
                   "the lines: 1 when the two have the same shape.</p>\n",
                   esc(fit["model"].get<std::string>()), significant(fit["band_hz"][0], 4), significant(fit["band_hz"][1], 4),
                   significant(fit["fit_error"], 3));
  s += frf_menu(fit["records"]);
  std::size_t k = 0;
  for (const auto& r : fit["records"]) {
    const std::string title = "response " + dof_pair(r["response"]) + " / reference " + dof_pair(r["reference"]);
    const std::vector<FrfCurve> curves{{"measured", "#c0392b", "measured", hz, complex_values(r["measured"]), ""},
                                       {"synthesized", "#1f5fa8", "identified modes", hz, complex_values(r["synthesized"]), "6 4"}};
    const std::string frac = r["frac"].is_null() ? std::string("—") : fixed(r["frac"].get<double>(), 4);
    s += fmt::format("<figure id=\"fig-frf-{0}\" class=\"frf\" data-frf=\"{0}\" data-frac=\"{1}\">\n{2}<figcaption>{3}: "
                     "FRAC {4}.</figcaption>\n</figure>\n",
                     k, r["frac"].is_null() ? std::string() : exact(r["frac"].get<double>()),
                     frf_overlay_svg(curves, title, unit.empty() ? "the file's unit" : unit, fmt::format("frf-{}", k)),
                     esc(title), frac);
    ++k;
  }
  return s + "</section>\n";
}

/// The measured FRFs against the analysis model's (`frf_comparison`, frf_comparison.hpp):
/// the seed's Figures 6–9, with the model before and after the update where the JSON holds
/// both. One figure per FRF (measured solid, each analysis dashed) with its FRAC per
/// analysis (attributes data-frac: the last analysis's, data-frac-before: the first's when
/// there are more: the model before the update, grey), a menu to show one, and the damping each analysis mode was given.
std::string frf_comparison_section(const json& c, const std::string& title) {
  static const char* colours[] = {"#1f5fa8", "#2e8b57", "#8e44ad"};
  const auto& analyses = c["analyses"];
  const bool before = analyses.size() > 1;  // the first is the model before the update
  std::string s = "<section id=\"frf-comparison\">\n<h2>" + esc(title) + "</h2>\n";
  s += fmt::format("<p>Each measured FRF of {} ({} drawn, drive points first) against the FRF of the deck's modes by "
                   "modal superposition (the seed's Eq. 2), observed along the same signed test directions; each "
                   "analysis mode is damped as the test mode it stands for (table below). FRAC = |Σ H<sub>x</sub> "
                   "Ĥ*|² / (Σ|H<sub>x</sub>|² Σ|Ĥ|²) over the lines: 1 when the two have the same shape.</p>\n",
                   esc(c["file"].get<std::string>()), c["frfs"].size());
  if (!c["left_out"].empty())
    s += fmt::format("<p class=\"note\">{} FRF(s) not drawn, e.g. {}.</p>\n", c["left_out"].size(),
                     esc(c["left_out"][0].get<std::string>()));
  s += frf_menu(c["frfs"]);
  std::size_t k = 0;
  for (const auto& r : c["frfs"]) {
    const std::vector<double> hz = r["hz"].get<std::vector<double>>();
    std::vector<FrfCurve> curves{{"measured", "#c0392b", "measured", hz, complex_values(r["measured"]), ""}};
    std::string fracs, data;
    for (std::size_t a = 0; a < r["analyses"].size(); ++a) {
      const json& x = r["analyses"][a];
      const std::string label = x["label"].get<std::string>();
      // Before the update grey and dotted, as the frequency figures draw it.
      curves.push_back({fmt::format("analysis-{}", a), before && a == 0 ? "#777777" : colours[a % 3], label, hz,
                        complex_values(x), before && a == 0 ? "2 3" : "6 4"});
      fracs += fmt::format("{}FRAC {} {}", a ? ", " : "", esc(label),
                           x["frac"].is_null() ? std::string("—") : fixed(x["frac"].get<double>(), 4));
      // The last analysis's FRAC (the estimate's), and the first's when there are two (before the update).
      if (a + 1 == r["analyses"].size() || (before && a == 0))
        data += fmt::format(" data-frac{}=\"{}\"", a + 1 == r["analyses"].size() ? "" : "-before",
                            x["frac"].is_null() ? std::string() : exact(x["frac"].get<double>()));
    }
    const std::string title = "response " + dof_pair(r["response"]) + " / reference " + dof_pair(r["reference"]);
    s += fmt::format("<figure id=\"fig-frfc-{0}\" class=\"frf\" data-frf=\"{0}\"{1}>\n{2}<figcaption>{3} (grids {4} / "
                     "{5}; {6}): {7}.</figcaption>\n</figure>\n",
                     k, data, frf_overlay_svg(curves, title, r["unit"].get<std::string>(), fmt::format("frfc-{}", k)),
                     esc(title), r["response_grid"].get<long>(), r["reference_grid"].get<long>(),
                     esc(r["at"].get<std::string>()), fracs);
    ++k;
  }
  s += "<table class=\"pairs\"><caption>Modal damping of the analysis FRFs</caption>\n<tr><th>analysis</th><th>mode</th>"
       "<th>frequency (Hz)</th><th>ζ (%)</th><th>from</th></tr>\n";
  for (const auto& a : analyses)
    for (const auto& m : a["modes"])
      s += fmt::format("<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n", esc(a["label"].get<std::string>()),
                       m["mode"].get<int>(), fixed(m["hz"].get<double>(), 3), fixed(100 * m["zeta"].get<double>(), 3),
                       esc(m["zeta_from"].get<std::string>()));
  return s + "</table>\n</section>\n";
}

/// The identified modes drawn on the test's geometry (its nodes and trace lines): one
/// figure per mode, the undeformed wire frame grey, the shape red at 8 % of the
/// structure's size, the views and the animation as the analysis shapes'.
std::string identified_shapes_section(const json& j) {
  std::string s = "<section id=\"identified-shapes\">\n<h2>Identified mode shapes</h2>\n";
  if (!j.contains("geometry") || !j.contains("identified_shapes")) {
    if (j.contains("geometry_note")) s += "<p class=\"note\">" + esc(j["geometry_note"].get<std::string>()) + "</p>\n";
    return j.contains("geometry_note") ? s + "</section>\n" : "";
  }
  const Points grids = read_points(j["geometry"]["grids"]);
  const Lines wire = read_lines(j["geometry"]["test_lines"]);
  // A structure without extent (one node) still gets a scale for its arrows.
  const double size = std::max(extent(grids), 1e-300);
  const double w = 360, h = 270;
  const auto vs = views();
  const std::vector<Placement> pl = placements(vs, grids, w, h);
  s += view_menu(vs, true);
  s += "<p class=\"note\">Each identified mode (the real part of its unit shape, each measured direction in its node's "
       "displacement system turned to global) on the test's trace lines; grey: the undeformed wire frame. The largest "
       "displacement is drawn at 8 % of the structure's size. Nodes without a measured direction do not move.</p>\n";
  s += "<svg width=\"0\" height=\"0\" style=\"position:absolute\" aria-hidden=\"true\"><defs>\n";
  for (std::size_t v = 0; v < vs.size(); ++v)
    s += fmt::format("<path id=\"wire-{}\" d=\"{}\"/>\n", vs[v].name, lines_d(wire, grids, nullptr, 0, pl[v]));
  s += "</defs></svg>\n";
  for (const auto& m : j["identified_shapes"]) {
    const Points shape = read_points(m["points"]);
    const int mode = m["mode"];
    const double hz = m["hz"];
    const double amp = 0.08 * size / std::max(largest(shape), 1e-300);
    const std::string svg = single_shape_svg(fmt::format("identified-{}-svg", mode), fmt::format("identified mode {}", mode),
                                             w, h, vs, pl, {{"wire", "undeformed"}}, "test", wire, grids, shape, amp,
                                             fmt::format("mode {}: {} Hz", mode, significant(hz, 6)));
    s += fmt::format("<figure id=\"identified-{0}\" class=\"identified-shape\" data-mode=\"{0}\" data-hz=\"{1}\">\n{2}"
                     "<figcaption>Identified mode {0}: {3} Hz.</figcaption>\n</figure>\n",
                     mode, exact(hz), svg, significant(hz, 6));
  }
  return s + "</section>\n";
}

/// The identified modes' table: frequency, damping, their σ, MPC, MPD.
std::string identification_sections(const json& j) {
  std::string s = "<section id=\"stabilisation\">\n<h2>Stabilisation diagram</h2>\n";
  if (j.contains("stabilisation")) {
    const json& st = j["stabilisation"];
    const json& c = st["criteria"];
    s += figure("fig-stabilisation", stabilisation_svg(j, false),
                fmt::format("{} poles at model orders {}…{}, classed against the previous order: stable in frequency within "
                            "{} %, in damping within {} %, in shape at complex MAC ≥ {}; screened out (×): damping ≤ 0 or > {}, "
                            "MPC < {}, MPD > {}°. A cluster of stable poles recurring at {} % of the orders or more is a mode "
                            "(red lines). Grey curve: {} (log scale, fitted to the order range).",
                            j.value("method", "era") == "plscf" ? "pLSCF" : "ERA",
                            st["orders"].empty() ? 0 : st["orders"].front().get<long>(),
                            st["orders"].empty() ? 0 : st["orders"].back().get<long>(),
                            significant(100 * c["freq_tol"].get<double>(), 3),
                            significant(100 * c["damping_tol"].get<double>(), 3), significant(c["mac_min"], 3),
                            significant(c["zeta_max"], 3), significant(c["mpc_min"], 3), significant(c["mpd_max_deg"], 3),
                            significant(100 * c["min_fraction"].get<double>(), 3),
                            st["frf_sum"].value("of", "FRFs") == "free-decay spectra"
                                ? "Σ|Y(f)| over the free decays' spectra"
                                : "Σ|H| over every FRF"));
  } else {
    s += "<p class=\"note\">No diagram: ARMAX's modes come from runs over response subsets, not from model orders.</p>\n";
  }
  s += "</section>\n<section id=\"modes\">\n<h2>Identified modes</h2>\n<table class=\"modes\">\n<tr><th>mode</th><th>frequency "
       "[Hz]</th><th>σ [Hz]</th><th>damping [%]</th><th>σ [%]</th><th>MPC</th><th>MPD [°]</th></tr>\n";
  std::size_t k = 0;
  for (const auto& m : j["modes"]) {
    ++k;
    const double hz = m["hz"], hs = m["hz_std"], z = m["zeta"], zs = m["zeta_std"], mpc = num_or(m, "mpc"),
                 mpd = num_or(m, "mpd_deg");
    s += fmt::format("<tr class=\"mode\" data-hz=\"{}\" data-hz-std=\"{}\" data-zeta=\"{}\" data-zeta-std=\"{}\" data-mpc=\"{}\" "
                     "data-mpd=\"{}\"><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td>"
                     "<td class=\"n\">{}</td><td class=\"n\">{}</td><td class=\"n\">{}</td></tr>\n",
                     exact(hz), exact(hs), exact(z), exact(zs), exact(mpc), exact(mpd), k, fixed(hz, 6), significant(hs, 4),
                     fixed(100 * z, 4), significant(100 * zs, 4), fixed(mpc, 4), fixed(mpd, 2));
  }
  s += "</table>\n";
  if (j.contains("rejected") && !j["rejected"].empty()) {
    s += "<p class=\"note\">Poles not kept:";
    for (const auto& [reason, n] : j["rejected"].items()) s += fmt::format(" {} {};", esc(reason), n.get<int>());
    s += "</p>\n";
  }
  s += "</section>\n";
  if (j.contains("frf_fit") && j["frf_fit"].contains("hz")) s += frf_fit_section(j["frf_fit"]);
  return s;
}

}  // namespace

std::string stabilisation_svg(const json& j, bool standalone) {
  const json& st = j["stabilisation"];
  std::vector<double> hz, ord{0.0};
  for (const auto& p : st["poles"]) hz.push_back(p["hz"]), ord.push_back(p["order"]);
  for (const auto& m : j["modes"]) hz.push_back(m["hz"]);
  const json& fs = st["frf_sum"];
  const auto fhz = fs["hz"].get<std::vector<double>>(), fmag = fs["magnitude"].get<std::vector<double>>();
  double hz_hi = fhz.empty() ? 0 : fhz.back();
  for (double f : hz) hz_hi = std::max(hz_hi, f);
  for (const auto& o : st["orders"]) ord.push_back(o);  // orders without poles (beyond ERA's rank) too
  const double order_hi = *std::max_element(ord.begin(), ord.end()) + 2;
  Chart c(900, 460, {0, hz_hi > 0 ? hz_hi : 1, "frequency [Hz]"}, {0, order_hi, "model order"});
  // Σ|H| on a log scale mapped onto [0, order_hi]: a backdrop telling where the peaks are.
  double lo = INFINITY, hi = -INFINITY;
  for (double m : fmag)
    if (m > 0) lo = std::min(lo, std::log10(m)), hi = std::max(hi, std::log10(m));
  if (hi > lo) {
    std::string pts;
    for (std::size_t k = 0; k < fhz.size() && k < fmag.size(); ++k)
      if (fmag[k] > 0) pts += px(c.x(fhz[k])) + "," + px(c.y((std::log10(fmag[k]) - lo) / (hi - lo) * order_hi)) + " ";
    c.add("<polyline class=\"frf-sum\" fill=\"none\" stroke=\"#b8b8b8\" stroke-width=\"1\" points=\"" + pts + "\"/>\n");
  }
  int mode = 0;
  for (const auto& m : j["modes"]) {
    ++mode;
    const double f = m["hz"];
    c.add(fmt::format("<line class=\"chosen\" data-mode=\"{0}\" data-x=\"{1}\" x1=\"{2}\" x2=\"{2}\" y1=\"{3}\" y2=\"{4}\" "
                      "stroke=\"#e15759\" stroke-width=\"1.2\" stroke-dasharray=\"5 3\"><title>mode {0}: {5} Hz</title></line>\n"
                      "<text x=\"{6}\" y=\"{7}\" font-size=\"11\" fill=\"#e15759\">{0}</text>\n",
                      mode, exact(f), px(c.x(f)), px(c.top()), px(c.bottom()), significant(f, 6), px(c.x(f) + 3), px(c.top() + 12)));
  }
  // One symbol per class (pole_class_symbol): s stable, v frequency and shape, d frequency and
  // damping, f frequency only, o new, x screened out.
  auto symbol = [](const std::string& cls, double x, double y) -> std::string {
    if (cls == "s") return fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"3.5\" fill=\"#2ca02c\"", px(x), px(y));
    if (cls == "v")
      return fmt::format("<path d=\"M{} {}l4 4l-4 4l-4 -4z\" fill=\"none\" stroke=\"#9467bd\" stroke-width=\"1.3\"", px(x), px(y - 4));
    if (cls == "d")
      return fmt::format("<rect x=\"{}\" y=\"{}\" width=\"7\" height=\"7\" fill=\"none\" stroke=\"#ff7f0e\" stroke-width=\"1.3\"",
                         px(x - 3.5), px(y - 3.5));
    if (cls == "f")
      return fmt::format("<path d=\"M{} {}h8M{} {}v8\" stroke=\"#1f77b4\" stroke-width=\"1.5\"", px(x - 4), px(y), px(x), px(y - 4));
    if (cls == "o")
      return fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"none\" stroke=\"#666\" stroke-width=\"1\"", px(x), px(y));
    return fmt::format("<path d=\"M{} {}l5 5m0 -5l-5 5\" stroke=\"#c9c9c9\" stroke-width=\"1\"", px(x - 2.5), px(y - 2.5));
  };
  for (const auto& p : st["poles"]) {
    const double f = p["hz"], o = p["order"].get<double>();
    const std::string cls = p["class"];
    const std::string reason = p["reason"];
    c.add(symbol(cls, c.x(f), c.y(o)) +
          fmt::format(" class=\"pole\" data-x=\"{}\" data-y=\"{}\" data-cls=\"{}\"><title>order {}: {} Hz, ζ {} %{}{}</title></{}>\n",
                      exact(f), exact(o), esc(cls), p["order"].get<long>(), significant(f, 6),
                      significant(100 * p["zeta"].get<double>(), 3), reason.empty() ? "" : ", ", esc(reason),
                      cls == "s" || cls == "o" ? "circle" : cls == "d" ? "rect" : "path"));
  }
  // The legend, inside the plot's top right corner (an SVG file carries no caption).
  const std::vector<std::pair<std::string, std::string>> keys = {
      {"s", "stable (frequency, damping, shape)"}, {"v", "frequency and shape"}, {"d", "frequency and damping"},
      {"f", "frequency only"}, {"o", "new"}, {"x", "screened out"}};
  const double lx = c.right() - 250, ly = c.top() + 8;
  std::string legend = fmt::format("<rect class=\"legend\" x=\"{}\" y=\"{}\" width=\"242\" height=\"{}\" fill=\"#fff\" "
                                   "fill-opacity=\"0.9\" stroke=\"#ccc\"/>\n",
                                   px(lx), px(ly), px(14.0 * (keys.size() + 1) + 6));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const double y = ly + 12 + 14.0 * static_cast<double>(k);
    legend += symbol(keys[k].first, lx + 10, y) + "/>" +
              fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"11\">{}</text>\n", px(lx + 22), px(y + 4), esc(keys[k].second));
  }
  legend += fmt::format("<path d=\"M{} {}h14\" stroke=\"#e15759\" stroke-dasharray=\"5 3\"/><text x=\"{}\" y=\"{}\" "
                        "font-size=\"11\">chosen mode</text>\n",
                        px(lx + 3), px(ly + 12 + 14.0 * keys.size()), px(lx + 22), px(ly + 16 + 14.0 * keys.size()));
  c.add(legend);
  std::string svg = c.svg("stabilisation-svg", "stabilisation diagram");
  if (standalone) {
    const auto at = svg.find('>') + 1;
    svg.insert(at, "\n<style>text{font:11px sans-serif;fill:#222}.grid{stroke:#e4e4e4}.frame{fill:none;stroke:#666}"
                   ".label{font-size:12px}</style>");
    svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + svg;
  }
  return svg;
}

std::string html_report(const json& j) {
  const std::string cmd = command_of(j);
  std::string title = "ssid " + cmd + " report";
  if (j.contains("title") && j["title"].is_string()) title += ": " + j["title"].get<std::string>();
  std::string s = page_head(title);
  s += "<h1>" + esc(title) + "</h1>\n" + run_section(j);

  if (cmd == "correlate") {
    const std::string form = j.value("mac_form", "squared") == "squared" ? "" : " (non-squared)";
    s += "<section id=\"correlation\">\n<h2>Correlation</h2>\n";
    s += fmt::format("<p>{} analysis and {} test modes compared at {} common DOFs. Accepted pairs: MAC ≥ {} and |error| ≤ {} %.</p>\n",
                     j["fe_modes"].size(), j["test_modes"].size(), j.value("dofs", 0), significant(j["min_mac"], 3),
                     significant(j["max_frequency_error_pct"], 3));
    json accepted = json::array();
    for (const auto& p : j["pairs"])
      if (p.value("accepted", false)) accepted.push_back(p);
    s += mac_figure(j["mac"], mode_numbers(j["fe_modes"]), mode_numbers(j["test_modes"]), true, accepted, "fig-mac",
                    "MAC of every analysis mode with every test mode; outlined: the accepted pairs.", form);
    if (j.contains("cross_orthogonality")) s += xor_figure(j["cross_orthogonality"], false);
    if (j.contains("cross_orthogonality_tam"))
      for (const auto& [tam, x] : j["cross_orthogonality_tam"].items()) s += xor_figure(x, false, "fig-xor-" + tam);
    s += "</section>\n<section id=\"frequencies\">\n<h2>Frequencies</h2>\n";
    s += frequency_figure(accepted, nullptr, j.value("max_frequency_error_pct", 10.0), "accepted pairs");
    s += error_figure(accepted, nullptr, "accepted pairs");
    s += pair_table(j["pairs"], nullptr) + "</section>\n";
    if (j.contains("frf_comparison")) s += frf_comparison_section(j["frf_comparison"], "FRFs: measured and of the analysis");
  } else if (cmd == "estimate") {
    const json& c0 = j["configurations"].empty() ? json::object() : j["configurations"][0];
    s += "<section id=\"correlation\">\n<h2>Correlation at the estimate</h2>\n";
    std::vector<int> fe_modes;
    for (std::size_t k = 0; k < c0.value("fe_hz", std::vector<double>{}).size(); ++k) fe_modes.push_back(static_cast<int>(k) + 1);
    json pairs0 = json::array();
    for (const auto& p : c0["pairs"]) pairs0.push_back(p);
    s += mac_figure(c0["correlation"], c0["test_modes"].get<std::vector<int>>(), fe_modes, false, pairs0, "fig-mac",
                    "MAC of every test mode with every analysis mode at the estimate" +
                        std::string(j["configurations"].size() > 1 ? " (first configuration)" : "") +
                        "; outlined: the pairs of the update.",
                    "");
    if (j.contains("cross_orthogonality")) s += xor_figure(j["cross_orthogonality"], true);
    if (j.contains("cross_orthogonality_tam"))
      for (const auto& [tam, x] : j["cross_orthogonality_tam"].items()) s += xor_figure(x, true, "fig-xor-" + tam);
    s += "</section>\n<section id=\"frequencies\">\n<h2>Frequencies before and after the update</h2>\n";
    const json* before = j.contains("initial_pairs") ? &j["initial_pairs"] : nullptr;
    s += frequency_figure(j["pairs"], before, 5.0, "at the estimate");
    s += error_figure(j["pairs"], before, "at the estimate");
    s += pair_table(j["pairs"], before) + "</section>\n";
    if (j.contains("frf_comparison")) s += frf_comparison_section(j["frf_comparison"], "FRFs before and after the update");
    s += parameter_figures(j) + convergence_figures(j);
  } else if (cmd == "identify") {
    s += identification_sections(j) + identified_shapes_section(j);
  } else if (cmd == "diagnose") {
    s += diagnosis_sections(j);
    if (j.contains("frf_comparison"))
      s += frf_comparison_section(j["frf_comparison"], "FRFs of the deck, of the ordinary update and of the named cause");
  } else if (cmd == "pretest") {
    s += pretest_sections(j);
  }
  s += shapes_section(j);
  if (j.contains("configuration_shapes"))  // estimate's second and later configurations
    for (std::size_t k = 0; k < j["configuration_shapes"].size(); ++k) {
      const json& c = j["configuration_shapes"][k];
      s += shapes_section(c, fmt::format("c{}-", k + 2),
                          "Mode shapes: configuration " + std::to_string(k + 2) +
                              (c.value("configuration", "").empty() ? "" : " (" + c["configuration"].get<std::string>() + ")"));
    }
  s += notes_section(j);
  s += "<p class=\"note\">Every number in this report is in the JSON result of the same run (";
  s += esc(j.contains("run") ? j["run"].value("command", "") : "") + "); the report draws it.</p>\n";
  s += kScript;
  s += "</body>\n</html>\n";
  return s;
}

}  // namespace ssid::cli::report
