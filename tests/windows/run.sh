#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Windows build (scripts/build-windows.sh) run under wine, against the Linux build:
#   run.sh CHECK LINUX_BUILD WINDOWS_BUILD SOURCE CORPUS
# CHECK is one of: prefix, corpus, over-existing, in-place-unicode, crlf, stdin-stdout,
# interrupt, diff, c-example, zip, recipes. Each prints what it compared and exits 0 when
# the two agree, 1 when not. WINEPREFIX is the build's own (LINUX_BUILD/wineprefix).
set -euo pipefail
check=$1 linux=$2 windows=$3 source=$4 corpus=$5
export WINEPREFIX="$linux/wineprefix" WINEDEBUG=-all WINEDLLOVERRIDES="mscoree,mshtml="
exe="$windows/arcpress.exe"
for f in "$exe" "$windows/arcpress.dll" "$windows/compress_c.exe"; do
  [ -f "$f" ] || { echo "no $f: build it with scripts/build-windows.sh (the README's test command does)"; exit 1; }
done
command -v wine >/dev/null || { echo "no wine: scripts/install-deps.sh --test installs it"; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sample="$source/samples/contour.nc"
fail() { echo "FAIL: $*"; exit 1; }
# The Windows path of a file here (wine maps the root of the Linux file system to Z:).
winpath() { printf 'Z:%s' "$(realpath "$1" | tr / '\\')"; }
# Both builds write the commit they were built from into the output's header: they must be
# built from the same one for their bytes to be compared.
if [ "$check" != prefix ]; then
  lv=$("$linux/arcpress" --version | head -1) wv=$(wine "$exe" --version | head -1)
  [ "$lv" = "$wv" ] || fail "the builds differ ('$lv' on Linux, '$wv' on Windows): build both again (scripts/build.sh --test)"
fi
# (Not `ls | grep -q`: under pipefail, grep leaving early can fail the pipe.)
has_temporary() { [ -n "$(find "$1" -maxdepth 1 -name '*.arcpress-*')" ]; }
no_temporaries() { ! has_temporary "$1" || fail "a temporary file was left in $1: $(ls -a "$1")"; }

case $check in
  prefix)  # made once, before the others (a ctest fixture)
    wineboot -i >/dev/null 2>&1 || true
    wine "$exe" --version
    ;;
  corpus)  # every corpus file: the same bytes and the same exit status as the Linux build
    n=0
    for f in "$corpus"/*/* "$sample"; do
      case $f in *.md) continue ;; esac
      [ -f "$f" ] || continue  # (no corpus here: the sample alone)
      rl=0; rw=0
      "$linux/arcpress" "$f" -o "$work/linux.out" 2>"$work/linux.err" || rl=$?
      wine "$exe" "$f" -o "$work/windows.out" 2>"$work/windows.err" || rw=$?
      [ "$rl" = "$rw" ] || fail "$(basename "$f"): exit $rl on Linux, $rw on Windows"
      cmp "$work/linux.out" "$work/windows.out" || fail "$(basename "$f"): the outputs differ"
      n=$((n + 1))
    done
    echo "$n programs: the same output and exit status"
    ;;
  over-existing)  # -o over an existing file replaces it whole, and leaves nothing beside it
    mkdir "$work/out"
    echo "an older program" > "$work/out/part.nc"
    wine "$exe" "$sample" -o "$work/out/part.nc"
    "$linux/arcpress" "$sample" -o "$work/expected.nc"
    cmp "$work/expected.nc" "$work/out/part.nc" || fail "-o over an existing file"
    # twice: the file the first run wrote is replaced too
    wine "$exe" "$sample" --tolerance 0.02 -o "$work/out/part.nc"
    "$linux/arcpress" "$sample" --tolerance 0.02 -o "$work/expected.nc"
    cmp "$work/expected.nc" "$work/out/part.nc" || fail "-o over the file it wrote"
    no_temporaries "$work/out"
    # A read-only file is not replaced (Windows replaces none), and says so.
    chmod a-w "$work/out/part.nc"
    rc=0; wine "$exe" "$sample" -o "$work/out/part.nc" 2>"$work/err" || rc=$?
    [ "$rc" = 3 ] && grep -q 'read-only' "$work/err" || fail "a read-only destination: exit $rc, $(cat "$work/err")"
    cmp "$work/expected.nc" "$work/out/part.nc" || fail "the read-only destination changed"
    no_temporaries "$work/out"
    echo "-o replaced an existing file twice, and refused a read-only one (exit 3)"
    ;;
  in-place-unicode)  # --in-place on a file whose name is not ASCII, given as a Windows path
    mkdir "$work/Ø pièces"
    name="$work/Ø pièces/Ø-pièce 部品.nc"
    cp "$sample" "$name"
    chmod u+w "$name"
    wine "$exe" --in-place "$(winpath "$name")"
    "$linux/arcpress" "$sample" -o "$work/expected.nc"
    cmp "$work/expected.nc" "$name" || fail "--in-place on $name"
    no_temporaries "$work/Ø pièces"
    [ "$(ls "$work/Ø pièces")" = "Ø-pièce 部品.nc" ] || fail "the folder holds $(ls "$work/Ø pièces")"
    echo "--in-place rewrote $(basename "$name")"
    ;;
  crlf)  # a program with CRLF line ends comes out with CRLF line ends, as on Linux
    sed 's/$/\r/' "$sample" > "$work/crlf.nc"
    wine "$exe" "$work/crlf.nc" -o "$work/windows.nc"
    "$linux/arcpress" "$work/crlf.nc" -o "$work/linux.nc"
    cmp "$work/linux.nc" "$work/windows.nc" || fail "CRLF output differs from Linux's"
    lines=$(wc -l < "$work/windows.nc")
    [ "$(grep -c $'\r$' "$work/windows.nc")" = "$lines" ] || fail "not every line ends in CRLF"
    echo "$lines lines, each ending in CRLF"
    ;;
  stdin-stdout)  # standard input to standard output, byte for byte: CR kept, none added, Ctrl-Z read on
    { sed 's/$/\r/' "$sample"; printf '(a comment with Ctrl-Z \032 in it)\r\nG1 X1 Y1\nM2\n'; } > "$work/in.nc"
    wine "$exe" < "$work/in.nc" > "$work/windows.nc"
    "$linux/arcpress" < "$work/in.nc" > "$work/linux.nc"
    cmp "$work/linux.nc" "$work/windows.nc" || fail "standard output differs from Linux's"
    grep -q 'M2' "$work/windows.nc" || fail "the program was cut at Ctrl-Z"
    wine "$exe" --passthrough < "$work/in.nc" > "$work/same.nc"
    cmp "$work/in.nc" "$work/same.nc" || fail "--passthrough changed bytes"
    # From a pipe, read to its end into a temporary file first (and streamed with --stream):
    # the subprogram after M30 is read, so the quarter circle after its call is one arc.
    { printf 'G90 G17 G21\nG0 X0 Y0\nG1 F500\nM98 P2000\n'
      for i in $(seq 0 30); do
        awk -v i="$i" 'BEGIN { a = 3.14159265358979 * i / 60; printf "G1 X%.4f Y%.4f\n", 20 * cos(a) - 20, 20 * sin(a) }'
      done
      printf 'G90 G0 Z5\nM30\nO2000\nG91 G1 X1.\nG90\nM99\n'; } > "$work/sub.nc"
    cat "$work/sub.nc" | wine "$exe" --dialect fanuc > "$work/windows-sub.nc"
    "$linux/arcpress" "$work/sub.nc" --dialect fanuc > "$work/linux-sub.nc"
    cmp "$work/linux-sub.nc" "$work/windows-sub.nc" || fail "a piped program comes out otherwise than the file on Linux"
    grep -q '^G3 ' "$work/windows-sub.nc" || fail "the piped program's subprogram was not read"
    cat "$work/sub.nc" | wine "$exe" --dialect fanuc --stream > "$work/windows-streamed.nc"
    ! grep -q '^G3 ' "$work/windows-streamed.nc" || fail "--stream read the subprogram after the end"
    # A reader that closes the pipe early: exit 3, and how much it took.
    for _ in $(seq 800); do cat "$sample"; done > "$work/big.nc"
    { rc=0; wine "$exe" "$work/big.nc" 2>"$work/err" || rc=$?; echo "$rc" > "$work/rc"; } | head -c 1000 > /dev/null
    [ "$(cat "$work/rc")" = 3 ] || fail "a closed pipe: exit $(cat "$work/rc")"
    grep -q 'standard output closed after' "$work/err" || fail "a closed pipe: $(cat "$work/err")"
    echo "standard input to standard output is binary-safe, a pipe reads as the file; a closed pipe is exit 3, '$(cat "$work/err")'"
    ;;
  interrupt)  # Ctrl-C (wine turns SIGINT into the console's Ctrl-C) while the output is being written
    mkdir "$work/out"
    echo "the program as it was" > "$work/out/dest.nc"
    mkfifo "$work/fifo"
    # Three MB, then the input stalls with the temporary file open and half written.
    big="$corpus/printer/ps271_benchy.gcode"
    [ -f "$big" ] || { for _ in $(seq 500); do cat "$sample"; done > "$work/big.nc"; big="$work/big.nc"; }
    { head -c 3000000 "$big"; exec sleep 30; } > "$work/fifo" 2>/dev/null &
    feeder=$!
    wine "$exe" - -o "$work/out/dest.nc" --stream < "$work/fifo" 2>"$work/err" &  # (written as it comes)
    runner=$!
    for _ in $(seq 100); do has_temporary "$work/out" && break; sleep 0.2; done
    has_temporary "$work/out" || fail "no temporary file appeared"
    sleep 1
    kill -0 "$runner" 2>/dev/null || fail "arcpress.exe is not running: $(cat "$work/err")"
    kill -INT "$runner"  # (wine runs the program in the process it started as)
    rc=0; wait "$runner" || rc=$?
    kill "$feeder" 2>/dev/null || true
    [ "$rc" != 0 ] || fail "exit 0 after an interrupt"
    [ "$(cat "$work/out/dest.nc")" = "the program as it was" ] || fail "the destination changed"
    no_temporaries "$work/out"
    echo "interrupted (exit $rc): the destination and its folder are as they were"
    ;;
  diff)  # arcpress.exe diff gives the verdicts the Linux build gives
    "$linux/arcpress" "$sample" -o "$work/a.nc"
    sed 's/X\([0-9]*\)\.\([0-9]\)/X\1.9/' "$work/a.nc" > "$work/moved.nc"
    for pair in "$sample $work/a.nc" "$sample $work/moved.nc" "$sample $sample"; do
      set -- $pair
      rl=0; rw=0
      "$linux/arcpress" diff "$1" "$2" --tolerance 0.01 > "$work/l.txt" || rl=$?
      wine "$exe" diff "$1" "$2" --tolerance 0.01 > "$work/w.txt" || rw=$?
      cmp "$work/l.txt" "$work/w.txt" || fail "the diff reports differ"
      lv=$(grep -E '^(SAME|DIFFERENT|INCOMPLETE)' "$work/l.txt") wv=$(grep -E '^(SAME|DIFFERENT|INCOMPLETE)' "$work/w.txt")
      [ "$rl" = "$rw" ] || fail "diff $(basename "$1") $(basename "$2"): exit $rl on Linux, $rw on Windows"
      [ "$lv" = "$wv" ] || fail "diff verdicts differ: '$lv' / '$wv'"
      echo "diff $(basename "$1") $(basename "$2"): exit $rw, $wv"
    done
    ;;
  c-example)  # the C example, linked against arcpress.dll, writes what the command writes
    wine "$windows/compress_c.exe" "$sample" "$work/c.nc" fanuc
    wine "$exe" "$sample" --dialect fanuc -o "$work/cli.nc"
    cmp "$work/c.nc" "$work/cli.nc" || fail "compress_c.exe and arcpress.exe differ"
    echo "compress_c.exe (arcpress.dll) writes what arcpress.exe writes"
    ;;
  zip)  # the zip, unpacked into a folder with a space, runs from there with its own dialects
    cpack -G ZIP --config "$windows/CPackConfig.cmake" -B "$work/pkg" >/dev/null
    zip=$(ls "$work/pkg"/arcpress-*-win64.zip)
    mkdir "$work/Program Files"
    (cd "$work/Program Files" && unzip -q "$zip")
    dir=$(ls -d "$work/Program Files"/arcpress-*-win64)
    for f in arcpress.exe arcpress.dll lib/libarcpress.dll.a include/arcpress/arcpress.h include/arcpress/arcpress.hpp \
             dialects/marlin.toml README.md LICENSE; do
      [ -f "$dir/$f" ] || fail "the zip has no $f"
    done
    wine "$dir/arcpress.exe" dialects > "$work/dialects.txt"
    grep -q '^marlin' "$work/dialects.txt" || fail "the unpacked program finds no dialects"
    wine "$dir/arcpress.exe" "$sample" --dialect fanuc -o "$work/zip.nc"
    "$linux/arcpress" "$sample" --dialect fanuc -o "$work/linux.nc"
    cmp "$work/zip.nc" "$work/linux.nc" || fail "the unpacked program writes other bytes"
    # More dialect folders in ARCPRESS_DIALECT_PATH, separated by ';' as on Windows.
    mkdir -p "$work/my dialects/one" "$work/my dialects/two"
    sed 's/^name = "fanuc"/name = "mine"/' "$dir/dialects/fanuc.toml" > "$work/my dialects/two/mine.toml"
    ARCPRESS_DIALECT_PATH="$(winpath "$work/my dialects/one");$(winpath "$work/my dialects/two")" \
      wine "$dir/arcpress.exe" dialects > "$work/dialects.txt"
    grep -q '^mine' "$work/dialects.txt" || fail "ARCPRESS_DIALECT_PATH split at ';' finds no 'mine'"
    # The progress line (for inputs over 4 MB), asked for where standard error is no console.
    big="$corpus/printer/prusaslicer-2.5_bunny_marlin.gcode"
    [ -f "$big" ] || { for _ in $(seq 800); do cat "$sample"; done > "$work/big.nc"; big="$work/big.nc"; }
    wine "$dir/arcpress.exe" "$big" --progress -o "$work/p.nc" 2>"$work/progress.txt"
    grep -q 'MB/s' "$work/progress.txt" || fail "no progress line: $(cat "$work/progress.txt")"
    echo "$(basename "$zip"): $(unzip -l "$zip" | tail -1 | awk '{print $2}') files; runs unpacked"
    ;;
  recipes)  # postproc/README.md's Windows recipes, as the slicer and a CAM system run them
    cpack -G ZIP --config "$windows/CPackConfig.cmake" -B "$work/pkg" >/dev/null
    mkdir -p "$work/Program Files" "$work/my prints"
    (cd "$work/Program Files" && unzip -q "$work"/pkg/arcpress-*-win64.zip && mv arcpress-*-win64 arcpress)
    app=$(winpath "$work/Program Files/arcpress/arcpress.exe")
    prints="$work/my prints"
    f="$corpus/printer/ps_benchy_snippet_m83.gcode"; [ -f "$f" ] || f="$sample"
    # PrusaSlicer, OrcaSlicer, SuperSlicer: the post-processing line, the G-code file's path
    # appended as the last argument (a Windows path, spaces and all).
    cp "$f" "$prints/part 1.gcode"
    chmod u+w "$prints/part 1.gcode"  # (Windows replaces no read-only file)
    wine "$app" --tolerance 0.01 --in-place "$(winpath "$prints/part 1.gcode")"
    "$linux/arcpress" "$f" --tolerance 0.01 -o "$work/expected.gcode"
    cmp "$work/expected.gcode" "$prints/part 1.gcode" || fail "the slicer recipe"
    # A CAM system that runs a program after posting: the batch file of postproc/README.md.
    cp "$f" "$prints/part 2.nc"
    chmod u+w "$prints/part 2.nc"
    sed -n '/^```bat$/,/^```$/p' "$source/postproc/README.md" | sed '1d;$d' \
      | sed "s|C:\\\\Program Files\\\\arcpress\\\\arcpress.exe|$(winpath "$work/Program Files/arcpress/arcpress.exe" | sed 's/\\/\\\\/g')|" \
      | sed 's/$/\r/' > "$work/arcpress-post.bat"
    grep -q 'arcpress.exe' "$work/arcpress-post.bat" || fail "postproc/README.md has no batch recipe"
    wine cmd /c "$(winpath "$work/arcpress-post.bat")" "$(winpath "$prints/part 2.nc")" || fail "the batch recipe failed"
    "$linux/arcpress" "$f" --dialect fanuc --tolerance 0.01 -o "$work/expected.nc"
    cmp "$work/expected.nc" "$prints/part 2.nc" || fail "the batch recipe wrote other bytes"
    no_temporaries "$prints"
    echo "the slicer's post-processing line and the CAM batch file rewrote 'part 1.gcode' and 'part 2.nc'"
    ;;
  *) echo "run.sh: no check '$check'" >&2; exit 2 ;;
esac
