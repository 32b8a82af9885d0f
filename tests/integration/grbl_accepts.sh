#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Grbl's own G-code parser as a judge of what arcpress writes for the grbl dialect: each
# program is compressed at four bands and the output read by Grbl 1.1's parser
# (gc_execute_line(), its radius check `error:33` and its 79-character lines included), as
# grbl-sim's validator runs it. The programs: each corpus file Grbl reads but for 20 lines at
# most (those are passed through, so the output may have them and no other refused line),
# and test programs that sample circles and helices of 0.06 mm (in inches 0.5 mm) to 500 mm
# radius in the three planes, in millimetres and in inches, at the origin and a metre from
# it, summed a row per unit and plane. Prints the blocks and arcs written and the lines
# refused (scripts/docs_figures.sh grbl puts the table in docs/verification.md); exit 1
# where Grbl refuses a line of an output that it reads in the input.
# With GTRACE, the validator linked with grbl_trace.c, the path Grbl plans for the output
# (its arcs cut by its own mc_arc()) must also lie within the band of the one it plans for
# the input (`arcpress diff`), and the table has the largest distance between them.
#   grbl_accepts.sh ARCPRESS GVALIDATE CORPUS_DIR [GTRACE]
# GVALIDATE is grbl-sim's validator built against Grbl 1.1, in a folder of your own:
#   git clone https://github.com/gnea/grbl && cd grbl/grbl
#   git clone https://github.com/grbl/grbl-sim && cd grbl-sim
#   make gvalidate FLAGS='-O2 -fcommon'        # -> gvalidate.exe
#   o="validator.o overridden_report.o avr/interrupt.o avr/pgmspace.o avr/io.o avr/eeprom.o"
#   o="$o grbl_eeprom_extensions.o system_declares.o"
#   for m in protocol planner settings print nuts_bolts stepper gcode spindle_control \
#     motion_control limits coolant_control probe system jog; do o="$o ../$m.o"; done
#   cc -O2 -fcommon -DF_CPU=16000000 -include config.h -I. -DPLAT_LINUX -o gtrace.exe \
#     ARCPRESS_SOURCE/tests/integration/grbl_trace.c $o -lm -lrt -pthread -Wl,--wrap=plan_buffer_line
set -euo pipefail
arcpress=$1 validator=$(realpath "$2") corpus=$3 tracer=${4:+$(realpath "$4")}
[ -x "$validator" ] || { echo "grbl_accepts: no validator at '$validator'" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# refused FILE: the lines Grbl refuses, 21 at most, as "error:N: text". The validator stops
# at the first refusal; that line is blanked and the rest read again. A run of more than
# 10 s counts as a refusal of the line it stopped at and ends the reading.
refused() {
  tr -d '\r' < "$1" > "$work/judged.nc"
  local out n err
  for _ in $(seq 21); do
    out=$(cd "$work" && timeout 10 "$validator" judged.nc 2>&1) && return 0
    [ $? = 124 ] && err=timeout || err=$(grep -m1 -o '^error:[0-9]*' <<< "$out" || echo "exit")
    n=$(grep -c -E '^(ok|error:)' <<< "$out" || true)
    [ "$err" = timeout ] && n=$((n + 1))
    echo "$err: $(sed -n "${n}p" "$work/judged.nc")"
    [ "$err" = timeout ] && return 0
    sed -i "${n}s/.*//" "$work/judged.nc"
  done
}

# planned OUT: the path Grbl plans for the program refused() read last, its refused lines
# blanked, as G-code (grbl_trace.c).
planned() {
  { echo "G21 G90"; (cd "$work" && timeout 60 "$tracer" judged.nc 2>&1 > /dev/null) || true; } > "$1"
}

# Test programs: circles and a helix sampled into moves 0.001 mm off the circle at most,
# printed as Grbl reads them (3 decimals in mm, 4 in inches).
python3 - "$work" <<'PY'
import math, sys
out = sys.argv[1]
planes = {"G17": (0, 1, 2), "G18": (2, 0, 1), "G19": (1, 2, 0)}  # (first, second, normal) of X Y Z
def program(name, plane, unit, radius_mm, origin_mm, turns, climb_mm):
    scale = 25.4 if unit == "G20" else 1.0
    digits = 4 if unit == "G20" else 3
    first, second, normal = planes[plane]
    # Angle per move: the chord 0.001 mm inside the circle at most, 2 degrees at most.
    step = min(2 * math.acos(max(-1.0, 1 - 0.001 / radius_mm)), math.radians(2))
    n = max(8, int(math.ceil(2 * math.pi * turns / step)))
    lines = [f"({name})", f"{unit} G90 G94 {plane}", "F500"]
    def point(t):
        p = [origin_mm] * 3
        a = 2 * math.pi * turns * t
        p[first] += radius_mm * math.cos(a)
        p[second] += radius_mm * math.sin(a)
        p[normal] -= climb_mm * t
        return " ".join(f"{'XYZ'[k]}{p[k] / scale:.{digits}f}" for k in range(3))
    lines.append("G0 " + point(0))
    lines += ["G1 " + point(i / n) for i in range(1, n + 1)]
    lines.append("M2")
    open(f"{out}/{name}.nc", "w").write("\n".join(lines) + "\n")
for unit in ("G21", "G20"):
    for plane in planes:
        # (0.06 mm is 2.4 of an inch program's last digits: no circle left to fit)
        for r in (0.5, 5, 50, 500) if unit == "G20" else (0.06, 0.5, 5, 50, 500):
            for origin in (0, 1000):
                program(f"{unit}-{plane}-r{r:g}-at{origin}", plane, unit, r, origin, 1, 0)
        program(f"{unit}-{plane}-helix-r3", plane, unit, 3, 0, 3, 2)
PY

status=0
declare -A sums=()
order=()
printf '%-44s %6s %7s %6s %14s %15s %12s\n' program band "blocks" arcs "refused, input" "refused, output" "planned mm"
for f in "$corpus"/*/* "$work"/G2*.nc; do
  case $f in *.md) continue ;; esac
  name=$(basename "$f")
  # Lines Grbl refuses in the input are passed through as they are, and refused again; a
  # program Grbl refuses more than 20 lines of (or stops reading) is for another controller.
  refused "$f" > "$work/input-refused.txt"
  [ "$(wc -l < "$work/input-refused.txt")" -gt 20 ] && continue
  grep -q '^timeout' "$work/input-refused.txt" && continue
  [ -z "$tracer" ] || planned "$work/input-planned.nc"
  for band in 0.05 0.01 0.005 0.001; do
    "$arcpress" "$f" -o "$work/out.nc" --dialect grbl --tolerance "$band" --stats 2> "$work/stats.txt" ||
      { echo "FAIL: $name at $band: arcpress exit $?: $(tail -2 "$work/stats.txt")"; status=1; continue; }
    written=$(sed -n 's/^  written *\([0-9]*\) G1 + \([0-9]*\) G2\/G3.*/\1 \2/p' "$work/stats.txt")
    refused "$work/out.nc" > "$work/output-refused.txt"
    # Refusals of the output that the input does not have, line for line.
    new=$(sort "$work/output-refused.txt" | comm -23 - <(sort "$work/input-refused.txt"))
    planned_mm=-
    if [ -n "$tracer" ]; then
      planned "$work/output-planned.nc"
      if ! "$arcpress" diff "$work/input-planned.nc" "$work/output-planned.nc" --tolerance "$band" --dialect grbl \
        > "$work/diff.txt" 2>&1; then
        echo "  planned paths: $(grep -E '^(DIFFERENT|INCOMPLETE)' "$work/diff.txt" || tail -1 "$work/diff.txt")"
        status=1
      fi
      planned_mm=$(sed -n 's/^max deviation \([0-9.]*\) mm.*/\1/p' "$work/diff.txt")
    fi
    row=("$band" "$(awk '{print $1 + $2}' <<< "$written")" "$(awk '{print $2}' <<< "$written")"
      "$(wc -l < "$work/input-refused.txt")" "$(grep -c . <<< "$new" || true)" "$planned_mm")
    if [[ $f == "$work"/* ]]; then  # a test program: summed over its unit and plane
      key="test circles ${name:0:7} $band"
      read -r b a i o x <<< "${sums[$key]:-0 0 0 0 -}"
      x=$(awk -v x="$x" -v y="${row[5]}" 'BEGIN { print (x == "-" || y + 0 > x + 0) ? y : x }')  # the largest
      sums[$key]="$((b + row[1])) $((a + row[2])) $((i + row[3])) $((o + row[4])) $x"
      [[ " ${order[*]-} " == *" $key "* ]] || order+=("$key")
    else
      printf '%-44s %6s %7s %6s %14s %15s %12s\n' "$name" "${row[@]}"
    fi
    if [ -n "$new" ]; then
      sed 's/^/  refused: /' <<< "$new" | head -5
      status=1
    fi
  done
done
for key in "${order[@]}"; do
  printf '%-44s %6s %7s %6s %14s %15s %12s\n' "${key% *}" "${key##* }" ${sums[$key]}
done
exit $status
