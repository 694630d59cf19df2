#!/bin/sh
# Makes the screenshots of docs/report.md from the samples' reports:
#   sh docs/report/screenshots.sh BUILD_DIR
# Each shot is the page with the sections before it hidden (a <style> added to a
# copy of the report), 1000 px wide, taken by headless Chromium.
set -e
build=${1:-build}
src=$(cd "$(dirname "$0")/../.." && pwd)
out="$src/docs/report"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$src"
"$build/ssid" estimate -q samples/mpi_rod.bdf samples/estimate/measured.unv \
  --study samples/estimate/study.json --json "$tmp/estimate.json" --report "$tmp/estimate.html" >/dev/null
"$build/ssid" diagnose -q samples/mpi_rod.bdf samples/mpi_rod_hidden_mass.unv \
  --json "$tmp/diagnosis.json" --report "$tmp/diagnosis.html" >/dev/null
"$build/ssid" pretest samples/mpi_rod.bdf --target-modes 12 --min-hz 1 --sensors 18 --method ei --exciters 2 \
  --exciter-at 41:0,1,0 --exciter-at 79:0,0,1 --evaluate --json "$tmp/pretest.json" --report "$tmp/pretest.html" >/dev/null
"$build/ssid" correlate samples/mpi_rod.bdf samples/estimate/measured.unv \
  --json "$tmp/correlate.json" --report "$tmp/correlate.html" >/dev/null 2>&1
# The diagnosis with FRFs: stand-in "measured" FRFs of a deck with the sample's hidden
# mass and STRUTA error (docs/report.md, "FRFs of the model over the measured ones").
echo '{"parameters": [{"name": "STRUTA", "estimate": 2.11575e-4}]}' >"$tmp/struta.json"
"$build/ssid" update-deck samples/mpi_rod.bdf "$tmp/struta.json" -o "$tmp/struta.bdf" >/dev/null
sed 's/^ENDDATA/CONM2   9001    29              2.0\nENDDATA/' "$tmp/struta.bdf" >"$tmp/hidden.bdf"
"$build/ssid" frf "$tmp/hidden.bdf" --drive 29,2 --response 29,2 41,3 --damping 0.01 --band 2:60 --lines 1161 \
  --uff "$tmp/hidden_frf.unv" >/dev/null 2>&1
"$build/ssid" diagnose -q samples/mpi_rod.bdf samples/mpi_rod_hidden_mass.unv --frf "$tmp/hidden_frf.unv" \
  --frf-damping 0.01 --json "$tmp/diagnosis_frf.json" --report "$tmp/diagnosis_frf.html" >/dev/null
python3 samples/identify/chain_frf.py "$tmp/chain_frf.unv"
"$build/ssid" identify modes "$tmp/chain_frf.unv" --json "$tmp/identify.json" --report "$tmp/identify.html" >/dev/null 2>&1
# shot REPORT NAME HEIGHT HIDDEN-SECTIONS
shot() {
  sed "s|</head>|<style>$4{display:none}</style></head>|" "$tmp/$1.html" >"$tmp/shot-$2.html"
  timeout 120 chromium --headless=new --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run \
    --user-data-dir="$tmp/profile" --virtual-time-budget=3000 --hide-scrollbars --window-size=1000,"$3" \
    --screenshot="$out/$2.png" "file://$tmp/shot-$2.html" >/dev/null 2>&1
}
shot estimate estimate_correlation 1250 "#fig-xor,table.xor-pairs"
shot estimate estimate_parameters 1300 "#run,#correlation,#frequencies,h1"
shot estimate estimate_shapes 900 "#run,#correlation,#frequencies,#parameters,#convergence,h1,#shape-0,#shape-1,#shape-2,#shape-3,#shape-4,#shape-5,.mems"
shot correlate correlate_xor 1050 "#run,#fig-mac,h1,#frequencies,#shapes,table.xor-pairs"
shot correlate correlate_mems 950 "#run,#correlation,#frequencies,h1,#shape-0,#shape-1,#mems-0,#mems-1,.shape:not(#shape-2),.mems:not(#mems-2)"
shot identify identify 900 ".none"
shot identify identify_frf 1050 "#run,#stabilisation,#modes,h1,#fig-frf-1,#fig-frf-2"
shot diagnosis diagnosis 1400 ".none"
shot diagnosis diagnosis_cause 1000 "#run,#residuals,#ranking,h1"
shot diagnosis_frf diagnosis_frf 1050 "#run,#residuals,#ranking,#cause,#gain,h1,#fig-frfc-1,table.pairs"
shot pretest pretest 1250 "#run,h1,table.sensors"
shot pretest pretest_tam 1000 "#run,#placement,#fisher,h1,#fig-tam-irs,#fig-tam-serep"
ls -l "$out"/*.png
