#!/usr/bin/env bash
# Output regression for refactors that must not change results: run every
# scene of geo/*.toml, the quick scripts/bench3d scenes and the variants of
# scripts/regress/cases.txt (interface kind, cuts, bonded, rule) with one
# binary, and diff contact.csv and summary.json (timings removed) against a
# reference directory made the same way by another binary.
#
#   scripts/regress/compare.sh ref  OLD_BINARY DIR [NAME_REGEX]  # write the reference
#   scripts/regress/compare.sh diff NEW_BINARY DIR [NAME_REGEX]  # run again, diff
#
# A case whose run fails keeps its stderr as `error.txt` (compared too), so a
# refusal is pinned as well as an answer; an unconverged run also keeps the
# files it wrote. NAME_REGEX picks cases by name. Exit status 1 when
# anything differs.
set -u
mode=${1:?ref|diff}; bin=$(realpath "${2:?binary}"); dir=${3:?directory}; pick=${4:-.}
here=$(cd "$(dirname "$0")" && pwd); root=$(cd "$here/../.." && pwd)
side=$dir/$mode; mkdir -p "$side"
status=0
while read -r name scene args; do
  [[ -z "$name" || "$name" == \#* ]] && continue
  [[ "$name" =~ $pick ]] || continue
  out=$side/$name; rm -rf "$out"; mkdir -p "$out"
  start=$(date +%s)
  # shellcheck disable=SC2086
  (cd "$root" && "$bin" solve "$scene" --quiet --out "$out/run" $args) >/dev/null 2>"$out/error.txt"
  sed -i "s|$out|OUT|g" "$out/error.txt"
  if [[ -e "$out/run/summary.json" ]]; then
    cp "$out/run/contact.csv" "$out/contact.csv" 2>/dev/null || : >"$out/contact.csv"
    python3 - "$out/run/summary.json" "$out/summary.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
# (wall times: the stages', the safety search's cost and its trials' seconds)
def timing(k):
    return k.startswith("timings") or k.endswith("_s") or k == "seconds"
def strip(v):
    if isinstance(v, dict):
        return {k: strip(x) for k, x in v.items() if not timing(k)
                and k not in ("peak_memory_bytes", "file")}
    if isinstance(v, list):
        return [strip(x) for x in v]
    return v
json.dump(strip(s), open(sys.argv[2], "w"), indent=1, sort_keys=True)
PY
  fi
  rm -rf "$out/run"
  took=$(( $(date +%s) - start ))
  if [[ "$mode" == diff ]]; then
    ref=$dir/ref/$name; verdict=same
    for f in contact.csv summary.json error.txt; do
      if [[ -e "$ref/$f" || -e "$out/$f" ]] && ! cmp -s "$ref/$f" "$out/$f"; then
        verdict="DIFFERS ($f)"; status=1
      fi
    done
    printf '%-28s %4ss  %s\n' "$name" "$took" "$verdict"
  else
    printf '%-28s %4ss  %s\n' "$name" "$took" "$( [[ -s $out/error.txt ]] && echo refused || echo ok)"
  fi
done <"$here/cases.txt"
exit $status
