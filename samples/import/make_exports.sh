#!/bin/sh
# Operators "from another FE code": exports K and M of a deck (default
# samples/frame.bdf) as OP4 at the nominal design and at +-0.01 % of each DESVAR
# (ssid plays the other code here), writes spec.json and imports it with finite
# differences.
# Usage: samples/import/make_exports.sh [path/to/ssid [DECK]]   (default: ssid on PATH)
# Output: samples/import/work/, or $SSID_IMPORT_WORK (exports, spec.json, imported/ and exact/ operators).
set -eu
SSID=${1:-ssid}
# A path given relative to the caller's folder (build/ssid) must survive the cd below;
# a bare name is looked up on PATH.
case "$SSID" in
  */*) SSID=$(cd "$(dirname "$SSID")" && pwd)/$(basename "$SSID") ;;
esac
HERE=$(cd "$(dirname "$0")" && pwd)
DECK=$(cd "$(dirname "${2:-$HERE/../frame.bdf}")" && pwd)/$(basename "${2:-$HERE/../frame.bdf}")
W="${SSID_IMPORT_WORK:-$HERE/work}"
rm -rf "$W"
mkdir -p "$W"
cd "$W"

# Nominal export (K and M only, as another code would give them) and its DOF map.
"$SSID" assemble "$DECK" -o nominal --no-derivatives >/dev/null

# label, id and value of the deck's DESVARs, from the manifest.
params=$(python3 -c 'import json; [print(p["label"], p["id"], repr(p["value"])) for p in json.load(open("nominal/manifest.json"))["parameters"]]')

{
  printf '{\n "dofs": "nominal/manifest.json",\n "K": "nominal/K.op4",\n "M": "nominal/M.op4",\n "parameters": [\n'
  first=1
  echo "$params" | while read -r label id value; do
    plus=$(python3 -c "print(repr($value * (1 + 1e-4)))")
    minus=$(python3 -c "print(repr($value * (1 - 1e-4)))")
    "$SSID" assemble "$DECK" -o "${label}_plus" --no-derivatives --set "$label=$plus" >/dev/null 2>&1
    "$SSID" assemble "$DECK" -o "${label}_minus" --no-derivatives --set "$label=$minus" >/dev/null 2>&1
    [ $first -eq 1 ] || printf ',\n'
    first=0
    printf '  {"label": "%s", "id": %s, "value": %s,\n' "$label" "$id" "$value"
    printf '   "plus":  {"value": %s, "K": "%s_plus/K.op4",  "M": "%s_plus/M.op4"},\n' "$plus" "$label" "$label"
    printf '   "minus": {"value": %s, "K": "%s_minus/K.op4", "M": "%s_minus/M.op4"}}' "$minus" "$label" "$label"
  done
  printf '\n ]\n}\n'
} > spec.json

"$SSID" assemble --import spec.json -o imported
# The exact operators, for comparison.
"$SSID" assemble "$DECK" -o exact >/dev/null 2>&1
echo "compare imported/ with exact/ (e.g. translators::read_operator_set on both manifests)"
