#!/usr/bin/env bash
# End-to-end checks of the command line on generated phantoms and, where DATA_DIR
# holds them, on the real datasets. Usage: tests/end-to-end.sh bin/tortuosity
# Prints one line per check and "e2e: N passed, N failed" last.
set -u -o pipefail
T=${1:?usage: end-to-end.sh path/to/tortuosity}
DATA_DIR=${DATA_DIR:-../shared/data}
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"

column() {  # column NAME FILE: prints that column of a TSV (header row dropped)
  awk -F'\t' -v name="$1" 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == name) c = i; next } { print $c }' "$2"
}

near() {    # near A B RELTOL
  awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t * (b < 0 ? -b : b)) }'
}

# ---------------------------------------------------------------- the build
# 'make' in a fresh clone builds the program, two jobs at a time as the README's reproduce runs
# (REPO: the repository, given by 'make check').
if [ -n "${REPO:-}" ] && [ -d "$REPO/.git" ]; then
  make_builds_program() {
    git clone -q "$REPO" "$work/clone" || return 1
    cp "$REPO/paper.nw" "$REPO/Makefile" "$work/clone/"        # the working copy, committed or not
    make -s -j2 -C "$work/clone" >"$work/make.log" 2>&1 || { tail -5 "$work/make.log"; return 1; }
    "$work/clone/bin/tortuosity" --help >/dev/null
  }
  check "'make -j2' in a fresh clone builds bin/tortuosity" make_builds_program

  # make install puts the report where the manual page says, once it is built.
  if [ -f "$REPO/build/paper.pdf" ]; then
    install_puts_report() {
      make -s -C "$REPO" install PREFIX="$work/prefix" >"$work/install.log" 2>&1 || { tail -3 "$work/install.log"; return 1; }
      cmp -s "$REPO/build/paper.pdf" "$work/prefix/share/doc/tortuosity/paper.pdf" \
        && grep -q 'share/doc/tortuosity/paper.pdf' "$work/prefix/share/man/man1/tortuosity.1"
    }
    check "make install puts the report in share/doc/tortuosity, where the manual page says" install_puts_report
  fi

  # make lint must catch a program whose package a stage does not list: the report stage
  # without poppler-utils (pdftoppm makes the figures' PNGs, pdffonts checks the PDF's fonts),
  # judged on the table of uses that the lint before it saved.
  # The lint installs every stage's packages first, which only root may do.
  if [ "$(id -u)" = 0 ] || ls "$REPO"/build/.tools-{build,report,test,fuzz,bench,parallel} >/dev/null 2>&1; then
    lint_catches_missing_package() {
      local report
      report=$(make -s -C "$REPO" -f Makefile -pn 2>/dev/null | sed -n 's/^PACKAGES_report := //p')
      [ -n "$report" ] && [[ " $report " == *" poppler-utils "* ]] || { echo "no poppler-utils in PACKAGES_report"; return 1; }
      make -s -C "$REPO" lint >"$work/lint.log" 2>&1 || { tail -5 "$work/lint.log"; return 1; }
      ! make -s -C "$REPO" lint LINT_JUDGE=build/lint-uses.tsv PACKAGES_report="${report/poppler-utils/}" \
          >"$work/lint-bad.log" 2>&1 \
        && grep -q 'pdftoppm (program, from package poppler-utils) is used by the report stage' "$work/lint-bad.log" \
        && grep -q 'pdffonts .* is used by the report stage' "$work/lint-bad.log" \
        || { echo "make lint without poppler-utils:"; tail -5 "$work/lint-bad.log"; return 1; }
    }
    check "make lint passes, and fails naming pdftoppm and the report stage without poppler-utils" \
      lint_catches_missing_package
  fi

  # The shape check of make lint names a loop of calls between two files, a file over 1,000
  # lines and a chunk over 120 lines; the package itself passes it (make lint, above).
  structure_finds_what_is_wrong() {
    local d=$work/structure
    mkdir -p "$d/build/src" && cd "$d" || return 1
    printf 'int b(int);\nint a(int x) { return x ? b(x - 1) : 0; }\n' >build/src/a.c
    { printf 'int a(int);\nint b(int x) { return a(x);\n'; for i in $(seq 1000); do echo; done; echo '}'; } >build/src/b.c
    cc -c -o a.o build/src/a.c && cc -c -o b.o build/src/b.c || { cd - >/dev/null; return 1; }
    { echo '<<long>>='; seq 121; echo '<<next>>='; seq 2; echo '@'; echo '<<short>>='; seq 120; echo '@'; } >doc.nw
    ! bash "$REPO/build/scripts/structure.sh" doc.nw a.o b.o >out.txt 2>&1
    local failed=$?
    cd - >/dev/null
    [ $failed = 0 ] && grep -q 'go round in a loop' "$d/out.txt" && grep -q 'build/src/b.c: 1003 lines' "$d/out.txt" \
      && grep -q 'doc.nw:1: <<long>>= is 121 lines' "$d/out.txt" && ! grep -q '<<short>>' "$d/out.txt" \
      || { cat "$d/out.txt"; return 1; }
  }
  check "make lint's shape check names a loop of calls, a C file over 1,000 lines and a chunk over 120" \
    structure_finds_what_is_wrong
  # ... and a header that includes one from above it (d.h includes c.h, while c.c calls d.c), and a
  # file of the method (METHOD) over 500 lines.
  structure_finds_upward_include() {
    local d=$work/structure-up
    mkdir -p "$d/build/src" && cd "$d" || return 1
    { printf 'int d(int);\nint c(int x) { return d(x);\n'; for i in $(seq 500); do echo; done; echo '}'; } >build/src/c.c
    printf 'int d(int x) { return x; }\n' >build/src/d.c
    printf '#include "c.h"\n' >build/src/d.h; : >build/src/c.h
    cc -c -o c.o build/src/c.c && cc -c -o d.o build/src/d.c || { cd - >/dev/null; return 1; }
    echo '@' >doc.nw
    ! METHOD='c' bash "$REPO/build/scripts/structure.sh" doc.nw c.o d.o >out.txt 2>&1
    local failed=$?
    cd - >/dev/null
    [ $failed = 0 ] && grep -q 'build/src/d.h includes c.h, a module above it' "$d/out.txt" \
      && grep -q 'build/src/c.c: 503 lines, more than 500' "$d/out.txt" || { cat "$d/out.txt"; return 1; }
  }
  check "make lint's shape check names a header that includes one from above it and a method file over 500 lines" \
    structure_finds_upward_include

  # make install into a temporary prefix (and staged under DESTDIR); the manual page renders;
  # a C program built with pkg-config reads a file and measures a circle through the library.
  install_and_link() {
    local prefix=$work/prefix
    make -s -C "$REPO" install PREFIX="$prefix" >"$work/install.log" 2>&1 || { tail -5 "$work/install.log"; return 1; }
    make -s -C "$REPO" install PREFIX=/opt/tort DESTDIR="$work/stage" >>"$work/install.log" 2>&1 || return 1
    [ -x "$work/stage/opt/tort/bin/tortuosity" ] && grep -q '^prefix=/opt/tort$' "$work/stage/opt/tort/lib/pkgconfig/tortuosity.pc" \
      || { echo "DESTDIR staging"; return 1; }
    "$prefix/bin/tortuosity" --version | grep -qE '^tortuosity [0-9]+\.[0-9]+\.[0-9]+ \(commit [^)]+\)$' \
      || { echo "--version"; return 1; }
    MANWIDTH=80 man -l "$prefix/share/man/man1/tortuosity.1" 2>/dev/null >"$work/man.txt" || { echo "man -l"; return 1; }
    for section in EXAMPLES METRICS 'EXIT STATUS' 'SEE ALSO' CITING; do
      grep -q "^$section" "$work/man.txt" || { echo "man page: no $section section"; return 1; }
    done
    grep -q -- '--split-gap' "$work/man.txt" && grep -q 'vmtkcenterlinegeometry' "$work/man.txt" \
      && grep -q 'TCCT_L' "$work/man.txt" || { echo "man page text"; return 1; }
    cat >"$work/use-library.c" <<'PROGRAM'
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <tortuosity.h>
int main(int argc, char **argv)
{
    char msg[256];
    tort_vessels *vs;
    if (argc != 2 || tort_read_file(argv[1], NULL, &vs, msg, sizeof msg) != 0) { fprintf(stderr, "%s\n", msg); return 1; }
    const double *xyz, *r;
    size_t n = tort_vessel_points(vs, 0, &xyz, &r);
    tort_options opt;
    tort_options_default(&opt);
    tort_result res;
    if (tort_measure(xyz, r, n, "10", &opt, &res, msg, sizeof msg) != 0) { fprintf(stderr, "%s\n", msg); return 1; }
    int ac = tort_metric_index("AC");
    printf("%s %zu %s %.6f\n", tort_vessel_label(vs, 0), n, res.status, res.metric[ac]);
    tort_vessels_free(vs);
    return 0;
}
PROGRAM
    export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
    cc -o "$work/use-library" "$work/use-library.c" $(pkg-config --cflags --libs tortuosity) 2>"$work/cc.log" \
      || { cat "$work/cc.log"; return 1; }
    awk 'BEGIN { for (i = 0; i < 60; i++) { t = atan2(0, -1) * i / 59; print 5 * cos(t), 5 * sin(t), 0 } }' >"$work/circle.txt"
    local got; got=$("$work/use-library" "$work/circle.txt") || return 1
    [ "$(cut -d' ' -f1-3 <<<"$got")" = "1 60 ok" ] && near "$(cut -d' ' -f4 <<<"$got")" 0.2 1e-3 \
      || { echo "library on a circle of radius 5 mm: $got (want AC 0.2/mm)"; return 1; }
    ! nm -g --defined-only "$prefix/lib/libtortuosity.a" | awk 'NF == 3 && $3 !~ /^tort_/' | grep -q . \
      || { echo "names other than tort_ are global in the library"; return 1; }
    ! nm -D --defined-only "$prefix/lib/libtortuosity.so.1" | awk 'NF == 3 && $3 !~ /^(tort_|TORTUOSITY_)/' \
      | grep -q . || { echo "names other than tort_ are exported by the shared library"; return 1; }
    objdump -p "$prefix/lib/libtortuosity.so" | grep -q 'SONAME *libtortuosity\.so\.1$' || { echo "soname"; return 1; }
    ! grep -q '^#line' "$prefix/include/tortuosity.h" || { echo "#line in the installed header"; return 1; }
    got=$(cd / && env -i PATH=/usr/bin:/bin PYTHONPATH="$prefix/lib/python3/dist-packages" /usr/bin/python3 -c \
      'import tortuosity, numpy; t = numpy.linspace(0, 3, 40); m = tortuosity.measure(numpy.column_stack([5 * numpy.cos(t), 5 * numpy.sin(t), 0 * t])); print(m["status"], round(m["AC"], 4))') \
      && [ "$got" = "ok 0.2" ] || { echo "Python from the prefix: $got"; return 1; }
  }
  check "make install: program, man -l, a C program linked with pkg-config and Python from the prefix measure a circle; only tort_ names exported" install_and_link

  # A data file that is not the one the manifest names stops make before any result, with a message.
  if [ -f "$DATA_DIR/vmtk-aorta/aorta-centerline.vtp" ]; then
    data_digest_checked() {
      mkdir -p "$work/data/vmtk-aorta"
      { cat "$DATA_DIR/vmtk-aorta/aorta-centerline.vtp"; echo; } >"$work/data/vmtk-aorta/aorta-centerline.vtp"
      ! make -s -C "$REPO" build/data/aorta-ct.sha256 DATA_DIR="$work/data" >"$work/digest.log" 2>&1 \
        && grep -q "aorta-centerline.vtp: these are not the files the results were made from" "$work/digest.log" \
        || { cat "$work/digest.log"; return 1; }
    }
    check "make stops at a data file whose sha256 differs from the manifest's, naming it" data_digest_checked
  fi

  # A locale whose collation puts "centerlines.npy" before "ORCA_centerlines.npy" (German, built by
  # make check) changes neither a dataset's digest nor the order of its files.
  if [ -d "$DATA_DIR/fdenz-coronary" ] && [ -d "$REPO/build/locale/de_DE.UTF-8" ]; then
    files_in_byte_order() {
      LOCPATH="$REPO/build/locale" LC_ALL=de_DE.UTF-8 make -s -C "$REPO" build/data/coronary-ct.sha256 \
        DATA_DIR="$(cd "$DATA_DIR" && pwd)" >"$work/locale.log" 2>&1 || { cat "$work/locale.log"; return 1; }
      local shown
      shown=$(cd "$DATA_DIR" && LOCPATH="$REPO/build/locale" LC_ALL=de_DE.UTF-8 bash -c \
        'shopt -s nullglob; f=(fdenz-coronary/*centerlines.npy); echo "${f[0]}"')
      [ "$shown" = fdenz-coronary/centerlines.npy ] || { echo "the German locale is not in effect: $shown"; return 1; }
    }
    check "a German locale's collation changes neither a dataset's digest nor the order of its files" files_in_byte_order
  fi
fi

# ---------------------------------------------------------------- command line
check "tortuosity --help exits 0" "$T" --help
for cmd in metrics profile sufficient phantom phantom-study; do
  check "$cmd --help exits 0" "$T" "$cmd" --help
done
metrics_help_lists_options() {
  local help; help=$("$T" metrics --help) || return 1
  for opt in --rates --trim --filter --integrator --planar --lambda --segments --ic-tol \
             --format --voxel --jobs --output --quiet --help; do
    grep -q -- "$opt" <<<"$help" || { echo "metrics --help does not document $opt"; return 1; }
  done
}
check "metrics --help documents every option" metrics_help_lists_options

exit_status_and_one_line() {   # expected-status COMMAND...
  local want=$1; shift
  "$@" >"$work/stdout" 2>"$work/stderr"; local got=$?
  [ "$got" = "$want" ] || { echo "exit $got, expected $want"; cat "$work/stderr"; return 1; }
  [ "$(wc -l <"$work/stderr")" -ge 1 ] || { echo "no message"; return 1; }
  [ ! -s "$work/stdout" ] || { echo "output despite the error"; return 1; }
}
check "metrics no-such-file exits 2" exit_status_and_one_line 2 "$T" metrics no-such-file
check "no-such-file message is one line" bash -c "'$T' metrics no-such-file 2>&1 >/dev/null | wc -l | grep -qx 1"
check "unknown option exits 2" exit_status_and_one_line 2 "$T" metrics --no-such-option x
check "bad --rates exits 2" exit_status_and_one_line 2 "$T" metrics --rates 1,zero x
check "unknown command exits 2" exit_status_and_one_line 2 "$T" frobnicate

printf '0 0 0\n1 0 0\n2 1 x\n' >"$work/bad.txt"
check "malformed text exits 2" exit_status_and_one_line 2 "$T" metrics "$work/bad.txt"
check "malformed text names file:line" bash -c "'$T' metrics '$work/bad.txt' 2>&1 | grep -q 'bad.txt:3: '"
printf '1 0 0 0 0 1 -1\n2 0 1 0 0 1 9\n' >"$work/bad.swc"
check "SWC with a missing parent names file:line" bash -c "'$T' metrics '$work/bad.swc' 2>&1 | grep -q 'bad.swc:2: parent 9'"

# ---------------------------------------------------------------- phantoms through the whole program
"$T" phantom --shape salkowski >"$work/salk.txt"
"$T" phantom --shape salkowski --truth >"$work/salk-truth.tsv"
"$T" metrics -q --rates 100 "$work/salk.txt" >"$work/salk.tsv"
for m in TC TT TCCT TC_L TT_L TCCT_L; do
  check "Salkowski $m at 100X within 1% of quadrature" \
    near "$(column $m "$work/salk.tsv")" "$(column $m "$work/salk-truth.tsv")" 0.01
done
header_has_columns() {
  local header; header=$(head -1 "$1")
  for c in file vessel rate n L D D1 IC_kappa IC_N SOA AC AT ACCT TC TT TCCT TC_L TT_L TCCT_L \
           TC_sum TT_sum TCCT_sum r_min r_mean recon_err recon_err_rel status; do
    grep -qw "$c" <<<"$(tr '\t' '\n' <<<"$header")" || { echo "missing column $c"; return 1; }
  done
}
check "metrics header names every required column" header_has_columns "$work/salk.tsv"
check "standard input as -" bash -c "'$T' phantom --shape helix | '$T' metrics -q --rates raw,1 - | grep -c '^-' | grep -qx 2"

"$T" phantom --shape helix --count 40 --sigma 0.05 --seed 3 >"$work/helices.txt"
"$T" metrics -q --jobs 1 "$work/helices.txt" >"$work/h1.tsv"
"$T" metrics -q --jobs 2 -o "$work/h2.tsv" "$work/helices.txt"
check "1 and 2 threads give identical output (-o file)" cmp "$work/h1.tsv" "$work/h2.tsv"
check "-o leaves no temporary file" bash -c "! ls '$work' | grep -q '\\.tmp\\.'"
check "same seed gives the same phantoms" bash -c "'$T' phantom --count 3 --sigma 0.1 --seed 9 | cmp - <('$T' phantom --count 3 --sigma 0.1 --seed 9)"
check "profile has samples and reconstruction" bash -c "'$T' profile --rate 10 '$work/salk.txt' | awk -F'\t' 'NR>1 && \$18==1 {n++} END {exit !(n > 300)}'"
# --vessel all: every row names its vessel in the last column (the ordinals 1..3; 46 points at 2X: 92 rows).
profile_all_labelled() {
  "$T" phantom --shape helix --count 3 --seed 4 | "$T" profile -q --rate 2 --vessel all - >"$work/all.tsv" || return 1
  awk -F'\t' 'NR == 1 { ok = $NF == "vessel"; next } NF { n[$NF]++ }
    END { exit !(ok && length(n) == 3 && n[1] == n[2] && n[2] == n[3] && n[1] == 92) }' "$work/all.tsv"
}
check "profile --vessel all: the vessel's label on every row" profile_all_labelled

profile_says_undersampled() {   # a helix at five points a turn: profiled, and standard error says its status
  awk 'BEGIN { c = sqrt(17); h = 2 * 3.141592653589793 * c / 5
               for (i = 0; i < 41; i++) { t = i * h / c; printf "%.6f %.6f %.6f\n", 4 * cos(t), 4 * sin(t), t } }' \
    >"$work/helix5.txt"
  "$T" profile --rate 10 "$work/helix5.txt" 2>"$work/helix5.err" | awk 'END { exit NR < 100 }' || return 1
  grep -q 'undersampled at rate 10$' "$work/helix5.err"
}
check "profile of an undersampled vessel: its samples, and its status on standard error" profile_says_undersampled

# Densities: 2 points per mm of a 44.72 mm helix is round(89.44) + 1 = 90 samples, 89 steps of 0.5025 mm.
per_mm_density() {
  "$T" phantom --shape helix | "$T" metrics -q --rates 2/mm,1 - >"$work/per-mm.tsv" || return 1
  awk -F'\t' 'NR == 2 && $3 == "2/mm" && $5 == 90 && $4 == 46 {ok++} NR == 3 && $3 == "1" && $5 == 46 {ok++}
               END {exit ok != 2}' "$work/per-mm.tsv" || { cat "$work/per-mm.tsv"; return 1; }
}
check "metrics --rates 2/mm samples a helix at 2 points per mm of fitted length" per_mm_density
check "phantom --density caption: 19 Salkowski points" bash -c "'$T' phantom --shape salkowski --density caption | wc -l | grep -qx 19"
check "phantom --density 16 and --points together: exit 2" bash -c "'$T' phantom --density 16 --points 9; [ \$? -eq 2 ]"
check "phantom-study --reading cm: exit 2 with a message" bash -c \
  "'$T' phantom-study --reading cm 2>&1 | grep -q \"reading takes sd or variance\"; [ \${PIPESTATUS[0]} -eq 2 ]"
# --uncertainty: a column M_se after every metric, filled wherever the metric is (the sums of
# curvature and torsion from the noise, every metric from its change at half the basis); the
# same metrics as without it; refused for a .vtp output.
uncertainty_columns() {
  "$T" phantom --shape helix --sigma 0.05 --count 2 >"$work/noisy-helix.txt" || return 1
  "$T" metrics -q --rates 10 "$work/noisy-helix.txt" >"$work/plain.tsv" || return 1
  "$T" metrics -q --rates 10 --uncertainty "$work/noisy-helix.txt" >"$work/se.tsv" || return 1
  awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { for (i = 6; i < c["r_min"]; i += 2) if ($i != "" && $(i + 1) == "") bad = 1
      if (!($c["AC_se"] > 0) || !($c["TT_se"] > 0) || !($c["L_se"] > 0) || !($c["D_se"] > 0)) bad = 1 }
    END { exit bad || NR != 3 }' "$work/se.tsv" || { head -2 "$work/se.tsv"; return 1; }
  cmp <(cut -f"$(head -1 "$work/se.tsv" | tr '\t' '\n' | grep -vn '_se$' | cut -d: -f1 | paste -sd,)" "$work/se.tsv") \
      "$work/plain.tsv"
}
check "metrics --uncertainty: M_se beside each metric, filled where defined, the metrics unchanged" uncertainty_columns
# The fidelity benchmark in small (make fidelity runs it whole): the sweep's self-test against
# closed forms and finite differences, then 300 of its curves of another seed at 10X. Where the
# data sample the curve, D, TC and AC are within 10% of the truth in at least 93%, and over all ok
# rows within 10% or three M_se in at least 93% (the whole sweep: 96-100% and 95-96%).
sweep=${REPO:-.}/build/fidelity-sweep
fidelity_in_small() {
  "$sweep" --selftest >"$work/selftest.log" || { cat "$work/selftest.log"; return 1; }
  "$sweep" --seed 7 --scale 0.1 --curves "$work/fid-curves.txt" --truth "$work/fid-truth.tsv" || return 1
  "$T" metrics -q --uncertainty --rates 10 "$work/fid-curves.txt" >"$work/fid-measured.tsv" || return 1
  awk -v summary=1 -f "${REPO:-.}/build/scripts/fidelity.awk" "$work/fid-truth.tsv" "$work/fid-measured.tsv" \
    >"$work/fid-summary.txt" || return 1
  awk '/^10 / { gsub(/\|/, " | "); $0 = $0; rows++
                for (i = 1; i <= NF; i++) if ($i == "|") bar[++k] = i
                for (m = 1; m <= 4; m++) if ($(bar[m] + 2) + 0 < 93) bad = 1 }
       /^  n [0-9]+ +notok/ { if (!well++ && ($8 + 0 < 93 || $10 + 0 < 93 || $12 + 0 < 93)) bad = 1 }
       END { exit bad || !well || rows != 1 }' "$work/fid-summary.txt" || { cat "$work/fid-summary.txt"; return 1; }
}
[ -x "$sweep" ] && check "fidelity in small: the sweep's truths hold, and 300 curves of known curvature are measured right" \
  fidelity_in_small
check "metrics --uncertainty -o x.vtp: exit 2" bash -c \
  "'$T' metrics -q --uncertainty -o '$work/se.vtp' '$work/noisy-helix.txt' 2>/dev/null; [ \$? -eq 2 ]"
# A long vessel: 11,000 points of the helix at 100X are 1.1 million samples, more than are measured
# whole (2^20), so they are measured in pieces: ok, the helix's curvature 0.2 and torsion 0.1 per mm,
# and the same bytes from one thread and from two (with a short vessel beside it).
long_vessel_in_pieces() {
  { "$T" phantom --shape helix --points 11000; echo; "$T" phantom --shape helix; } >"$work/long.txt" || return 1
  "$T" metrics -q --rates 100 --jobs 1 "$work/long.txt" >"$work/long-1.tsv" || return 1
  "$T" metrics -q --rates 100 --jobs 2 "$work/long.txt" >"$work/long-2.tsv" || return 1
  cmp "$work/long-1.tsv" "$work/long-2.tsv" || return 1
  awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next } NR == 2 {
      d1 = $c["AC"] - 0.2; d2 = $c["AT"] - 0.1
      ok = $c["status"] == "ok" && $c["n"] == 1100000 && d1 * d1 < 1e-12 && d2 * d2 < 1e-12 }
    END { exit !(ok && NR == 3) }' "$work/long-1.tsv" || { cut -f5,12,13,37 "$work/long-1.tsv"; return 1; }
}
check "metrics: a vessel of 1.1 million samples is measured in pieces, ok, with the helix's curvature and torsion" \
  long_vessel_in_pieces
study_threads() {   # the summary of a cell does not depend on the number of threads
  "$T" phantom-study --shape salkowski --sigma 0.01 --count 60 --jobs 1 -o "$work/study-1.tsv" || return 1
  "$T" phantom-study --shape salkowski --sigma 0.01 --count 60 --jobs 3 -o "$work/study-3.tsv" || return 1
  cmp "$work/study-1.tsv" "$work/study-3.tsv" || return 1
  awk -F'\t' 'NR > 1 && $6 != 60 {bad++} END {exit bad > 0 || NR != 46}' "$work/study-1.tsv"
}
check "phantom-study: 60 realisations in every row, the same with 1 and 3 threads" study_threads

# The paper's 16 tables and figures, each with a committed counterpart or a reason.
concordance_complete() {
  local root; root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  awk -F'\t' -v root="$root" 'NR == 1 { next } { items[$1] = 1; n++
      if ($3 !~ /^(reproduced|differs|stand-in|not-reproducible)$/) { print "bad status: " $0; bad = 1 }
      if ($3 == "not-reproducible" && $6 == "") { print "no reason: " $1; bad = 1 }
      if ($3 != "not-reproducible" && system("test -f \"" root "/" $4 "\"")) { print "no file: " $4; bad = 1 }
      if ($3 != "not-reproducible" && $5 !~ /^(fig|tab):/) { print "no counterpart in the report: " $1; bad = 1 } }
    END { for (k = 1; k <= 7; k++) if (!(("Figure " k) in items)) { print "missing Figure " k; bad = 1 }
          for (k = 1; k <= 2; k++) if (!(("Table " k) in items)) { print "missing Table " k; bad = 1 }
          for (k = 1; k <= 3; k++) if (!(("Figure S" k) in items)) { print "missing Figure S" k; bad = 1 }
          for (k = 1; k <= 4; k++) if (!(("Table S" k) in items)) { print "missing Table S" k; bad = 1 }
          exit bad || n != 16 }' "$root/results/concordance.tsv"
}
check "results/concordance.tsv: the paper's 16 items, each with a committed file or a reason" concordance_complete

"$T" phantom --shape helix --points 1000000 >"$work/long.txt"
check "a vessel of 10^6 points is measured (raw and 1X) with exact ACCT" bash -c \
  "'$T' metrics -q --rates raw,1 '$work/long.txt' | awk -F'\t' 'NR>1 && \$NF==\"ok\" && \$14>0.2235 && \$14<0.2237 {n++} END {exit n!=2}'"
printf '0 0 0\n0 0 0\n0 0 0\n\n0 0 0\n1 0 0\n\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 0\n5 0 0\n' >"$work/degenerate.txt"
check "degenerate vessels get a status, not NaN" bash -c \
  "'$T' metrics -q --rates 1,10 '$work/degenerate.txt' | cut -f4- | grep -qiE 'nan|inf' && exit 1; \
   '$T' metrics -q --rates 1,10 '$work/degenerate.txt' | awk -F'\t' 'NR>1 {print \$NF}' | tr '\n' ' ' \
   | grep -qx 'too-few-points too-few-points no-curvature no-curvature ok ok '"
check "a two-point vessel has L, D and D1 but no curvature" bash -c \
  "'$T' metrics -q --rates 1 '$work/degenerate.txt' | awk -F'\t' 'NR==3 && \$6==0.8 && \$7==1 && \$8==0 && \$9==\"\" {ok=1} END {exit !ok}'"
profile_ends_defined() {   # every sample has a speed; tau, N, B are empty exactly where the frame is undefined
  "$T" profile --rate 1 "$work/degenerate.txt" --vessel 3 >"$work/straight-profile.tsv" 2>/dev/null
  "$T" profile --rate 1 "$work/salk.txt" >"$work/salk-profile.tsv" || return 1
  awk -F'\t' 'NR > 1 && ($8 == "" || $8 == 0 || $7 == "" || $12 == "") { bad++ } END { exit bad > 0 }' "$work/salk-profile.tsv" \
    || { echo "Salkowski profile at 1X has an undefined or zero value"; return 1; }
  awk -F'\t' 'NR > 1 && ($6 != 0 || $7 != "" || $12 != "" || $8 == "") { bad++ } END { exit bad > 0 }' "$work/straight-profile.tsv" \
    || { echo "straight profile: tau, N or B written where undefined"; return 1; }
}
check "profile: derivatives at every sample, undefined values empty" profile_ends_defined

# ---------------------------------------------------------------- sharded runs
"$T" phantom --shape helix --count 30 --sigma 0.05 --seed 7 >"$work/shard-a.txt"
"$T" phantom --shape salkowski --count 6 --points 150 --sigma 0.01 --seed 8 >"$work/shard-b.txt"
shard_files=("$work/shard-a.txt" "$work/shard-b.txt")
"$T" metrics -q "${shard_files[@]}" >"$work/unsharded.tsv"
shards_join_to_whole() {   # shards_join_to_whole N: N shards, joined with the header once
  local k parts=()
  for k in $(seq "$1"); do
    "$T" metrics -q --shard "$k/$1" -o "$work/shard-$k-of-$1.tsv" "${shard_files[@]}" || return 1
    parts+=("$work/shard-$k-of-$1.tsv")
  done
  awk 'FNR > 1 || NR == 1' "${parts[@]}" | cmp - "$work/unsharded.tsv"
}
check "--shard: shards 1..4 joined are the unsharded output, byte for byte" shards_join_to_whole 4
check "--shard: shards 1..7 joined (more shards than helices per file) likewise" shards_join_to_whole 7
shard_stops_early() {   # shard 1 of 4 stops reading after its vessels: both files still in its provenance
  local inputs
  inputs=$(awk -F'\t' '$1 == "input" { print $2, $3, $4 }' "$work/shard-4-of-4.tsv.provenance.tsv")
  [ "$(printf '%s\n' "$inputs" | wc -l)" = 2 ] || return 1
  [ "$inputs" = "$(awk -F'\t' '$1 == "input" { print $2, $3, $4 }' "$work/shard-1-of-4.tsv.provenance.tsv")" ] \
    || return 1
  # a later file whose third vessel is malformed: shard 1 never reaches it, the whole run and shard 4 do
  { printf '0 0 0\n1 0 0\n2 1 0\n\n0 0 1\n1 0 1\n2 1 1\n\n0 0 2\n1 x 2\n'; } >"$work/shard-bad.txt"
  "$T" metrics -q --shard 1/4 -o "$work/shard-early.tsv" "$work/shard-a.txt" "$work/shard-bad.txt" || return 1
  awk -F'\t' '$1 == "input"' "$work/shard-early.tsv.provenance.tsv" | grep -q shard-bad.txt || return 1
  "$T" metrics -q --shard 4/4 "$work/shard-a.txt" "$work/shard-bad.txt" >/dev/null 2>&1; [ $? = 2 ] || return 1
  "$T" metrics -q "$work/shard-a.txt" "$work/shard-bad.txt" >/dev/null 2>&1; [ $? = 2 ]
}
check "--shard: shard 1 of 4 reads no further than its vessels (a later file's error is the later shards'); its provenance names every input, as shard 4's" \
  shard_stops_early
sufficient_shards() {
  "$T" phantom --shape helix --count 12 --seed 9 --sigma 0.02 | awk 'NF { print $0, 0.3; next } { print }' \
    >"$work/radii12.txt"
  "$T" sufficient -q "$work/radii12.txt" >"$work/suff-all.tsv" || return 1
  local k; for k in 1 2 3; do "$T" sufficient -q --shard $k/3 "$work/radii12.txt" >"$work/suff-$k.tsv" || return 1; done
  awk 'FNR > 1 || NR == 1' "$work"/suff-{1,2,3}.tsv | cmp - "$work/suff-all.tsv"
}
check "sufficient --shard: shards 1..3 joined are the unsharded output" sufficient_shards
# The smallest sufficient rate whatever the ladder's order: shuffled and reversed ladders, with the
# rates a vessel needs among them, give the ascending ladder's table byte for byte.
sufficient_any_order() {
  local up=1,2,5,10,20,50,100 ladder
  "$T" sufficient -q --ladder "$up" "$work/radii12.txt" >"$work/suff-up.tsv" || return 1
  awk -F'\t' 'NR > 1 && $6 != "none" { n++ } END { exit n < 6 }' "$work/suff-up.tsv" || return 1
  for ladder in 100,50,20,10,5,2,1 20,1,100,5,50,2,10 100,10,1; do
    "$T" sufficient -q --ladder "$ladder" "$work/radii12.txt" >"$work/suff-order.tsv" || return 1
    if [ "$ladder" = 100,10,1 ]; then
      "$T" sufficient -q --ladder 1,10,100 "$work/radii12.txt" | cmp -s - "$work/suff-order.tsv" || return 1
    else
      cmp -s "$work/suff-up.tsv" "$work/suff-order.tsv" || { echo "ladder $ladder"; return 1; }
    fi
  done
}
check "sufficient --ladder: the smallest sufficient rate, whatever the ladder's order" sufficient_any_order

# ---------------------------------------------------------------- several readings of one fit
# metrics --variant: each table is the bytes of a run of its own with those options, on one thread
# and two: noisy helices and Salkowski curves, vessels of 1 to 6 points (statuses before the
# reconstruction), a helix of 1,100 points (measured in pieces at 1000X) and readings that share
# the samples (the integrators) or not (the filter, the significant reading).
"$T" phantom --shape helix --points 1100 --sigma 0.01 --seed 3 >"$work/long-helix.txt"
variant_words=("--integrator rotation" "--integrator bishop" "--integrator bishop --planar" "--filter"
               "--filter --integrator bishop" "--torsion significant" "--torsion significant --integrator rotation")
variants_match_own_runs() {   # variants_match_own_runs JOBS OPTIONS... FILES
  local jobs=$1 k args=(); shift
  for k in "${!variant_words[@]}"; do args+=(--variant "${variant_words[$k]} -o $work/variant-$k.tsv"); done
  "$T" metrics -q --jobs "$jobs" "${args[@]}" -o "$work/variant-main.tsv" "$@" || return 1
  "$T" metrics -q --jobs "$jobs" "$@" | cmp - "$work/variant-main.tsv" || return 1
  for k in "${!variant_words[@]}"; do
    "$T" metrics -q --jobs "$jobs" ${variant_words[$k]} "$@" | cmp - "$work/variant-$k.tsv" \
      || { echo "--variant '${variant_words[$k]}' differs from its own run"; return 1; }
    [ -s "$work/variant-$k.tsv.provenance.tsv" ] || { echo "no provenance for variant $k"; return 1; }
  done
}
check "metrics --variant: every table the bytes of its own run (phantoms, degenerate vessels), one thread" \
  variants_match_own_runs 1 "${shard_files[@]}" "$work/degenerate.txt"
check "metrics --variant: likewise on a vessel measured in pieces (a helix of 1.1 million samples at 1000X)" \
  variants_match_own_runs 2 --rates 1000 "$work/long-helix.txt"
check "metrics --variant: likewise on two threads, with a null twin and a precision" \
  variants_match_own_runs 2 --null planar --precision 0.05 "${shard_files[@]}" "$work/degenerate.txt"
if compgen -G "$DATA_DIR/fdenz-coronary/*centerlines.npy" >/dev/null; then
  check "metrics --variant: every table the bytes of its own run on the coronary data" \
    variants_match_own_runs 2 --units mm --split-gap 1 "$DATA_DIR"/fdenz-coronary/*centerlines.npy
fi
sufficient_variants_match() {   # the sufficient rate of every integrator (and filtered) in one run
  local words=("--integrator rotation" "--integrator bishop" "--filter" "--filter --integrator rotation") k args=()
  for k in "${!words[@]}"; do args+=(--variant "${words[$k]} -o $work/suff-variant-$k.tsv"); done
  "$T" sufficient -q "${args[@]}" -o "$work/suff-variant.tsv" "$work/radii12.txt" || return 1
  cmp "$work/suff-variant.tsv" "$work/suff-all.tsv" || return 1
  for k in "${!words[@]}"; do
    "$T" sufficient -q ${words[$k]} "$work/radii12.txt" | cmp - "$work/suff-variant-$k.tsv" \
      || { echo "sufficient --variant '${words[$k]}' differs from its own run"; return 1; }
  done
  awk -F'\t' 'NR > 1 && $6 != "none" { n++ } END { exit n < 6 }' "$work/suff-variant-0.tsv"
}
check "sufficient --variant: every integrator's table the bytes of its own run" sufficient_variants_match
variant_refusals() (   # each refused with exit 2 and its message, nothing written, no temporary file left
  # (a subshell: its cd stays here)
  local args msg program
  program=$(cd "$(dirname "$T")" && pwd)/$(basename "$T")
  "$program" phantom >"$work/variant-helix.txt" || return 1
  mkdir -p "$work/refused" && cd "$work/refused" || return 1
  while IFS='|' read -r args msg; do
    eval "'$program' metrics -q $args '$work/variant-helix.txt'" >/dev/null 2>"$work/variant.err"
    [ $? -eq 2 ] || { echo "$args: not exit 2"; return 1; }
    grep -q -- "$msg" "$work/variant.err" || { echo "$args:"; cat "$work/variant.err"; return 1; }
    [ -z "$(ls -A)" ] || { echo "$args left:"; ls -A; return 1; }
  done <<'EOF'
--variant '--integrator rotation'|needs -o FILE
--variant '--integrator foo -o b.tsv'|unknown integrator 'foo'
--variant '--segments 40 -o b.tsv'|not '--segments'
--variant '--integrator rotation -o ./a.tsv' -o a.tsv|two tables would go to one file
--variant '--filter -o b.tsv' --variant '--integrator bishop -o ../refused/b.tsv' -o a.tsv|two tables would go to one file
--variant '--filter -o b.tsv' --uncertainty -o a.tsv|not with --uncertainty
--variant '--filter -o b.vtp' -o a.tsv|not .vtp files
EOF
)
check "metrics --variant: a reading without a file of its own, an unknown word or value, two tables to one file, --uncertainty and .vtp refused (exit 2, nothing written)" \
  variant_refusals
# Options a command has no use for are refused with exit 2 and a message naming the option, never
# ignored: --null and --uncertainty outside metrics; metrics takes them. --precision, the data's,
# every command that fits takes.
unused_options_refused() {
  local cmd opts
  "$T" phantom >"$work/one-helix.txt" || return 1
  for cmd in profile sufficient; do
    for opts in "--null planar" "--null straight --precision 0.1" "--uncertainty"; do
      "$T" $cmd $opts "$work/one-helix.txt" >/dev/null 2>"$work/unused.err"; [ $? -eq 2 ] || return 1
      grep -q -- "${opts%% *}" "$work/unused.err" || { echo "$cmd $opts"; cat "$work/unused.err"; return 1; }
    done
    "$T" $cmd -q --precision 0.31,digits:4 "$work/one-helix.txt" >/dev/null || return 1
  done
  "$T" metrics -q --null planar --precision 0.1 --uncertainty "$work/one-helix.txt" >/dev/null
}
check "options that do not apply (--null, --uncertainty outside metrics) are refused, not ignored" \
  unused_options_refused
# A SlicerVMTK curve whose control point was deleted after its radii were measured: one Radius value
# too many. Slicer loads it without radii; so does the reader, with a warning, and the curve is measured.
slicer_radius_mismatch() {
  awk 'BEGIN {
    printf "{\"markups\": [{\"type\": \"Curve\", \"coordinateSystem\": \"LPS\", \"coordinateUnits\": \"mm\", "
    printf "\"controlPoints\": ["
    for (i = 0; i < 13; i++)
      printf "%s{\"id\": \"%d\", \"position\": [%.6f, %.6f, %.6f], \"positionStatus\": \"defined\"}",
             i ? ", " : "", i + 1, 10 * cos(i / 4), 10 * sin(i / 4), i
    printf "], \"measurements\": [{\"name\": \"Radius\", \"controlPointValues\": ["
    for (i = 0; i < 14; i++) printf "%s1.5", i ? ", " : ""
    print "]}]}]}" }' >"$work/deleted.mrk.json"
  "$T" metrics -r 1 "$work/deleted.mrk.json" >"$work/deleted.tsv" 2>"$work/deleted.err" || { cat "$work/deleted.err"; return 1; }
  grep -q 'Radius measurement has 14 values for 13 control points; read without radii' "$work/deleted.err" || return 1
  awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i } NR == 2 { exit !($c["status"] == "ok" && $c["r_mean"] == "") }' \
    "$work/deleted.tsv"
}
check "a Slicer curve with one Radius value too many: read without radii, with a warning (as Slicer)" slicer_radius_mismatch
# Coordinates in the wrong unit: an aorta centerline in micrometres read as millimetres (78 m long), and
# a vessel in millimetres read as micrometres (steps of nanometres), each warned of.
units_warned() {
  awk 'BEGIN { for (i = 0; i < 200; i++) printf "%.1f %.1f %.1f\n", 20000 * cos(i / 50), 20000 * sin(i / 50), 400 * i }' \
    >"$work/aorta-um.txt"
  "$T" metrics -r 1 "$work/aorta-um.txt" 2>&1 >/dev/null | grep -q "mm long in steps of .* read in mm: are the units right" || return 1
  awk 'BEGIN { for (i = 0; i < 50; i++) printf "%.4f %.4f %.4f\n", 5 * cos(i / 100), 5 * sin(i / 100), 0.01 * i }' \
    >"$work/mm.txt"
  "$T" metrics -r 1 --units um "$work/mm.txt" 2>&1 >/dev/null | grep -q "read in um: are the units right" || return 1
  "$T" metrics -r 1 "$work/mm.txt" 2>&1 >/dev/null | grep -q "units" && return 1
  return 0
}
check "coordinates in the wrong unit (a vessel longer than a body, or steps of nanometres) are warned of" units_warned
# TubeTK's tortuosity tests (VesselView's TortuosityLogicTests): a sine tube, y = sin x over one
# period in 1,000 points. The package's polyline (--rates raw --trim 0) gives TubeTK's distance metric
# (1.21581) and inflection count metric (2 x 1.21581) to its 4 decimals, and TubeTK's filter's sum of
# angles on the same points, 0.4117 (the test's own expectation, 0.4112, is older than the filter).
tubetk_sine() {
  awk 'BEGIN { for (i = 0; i < 1000; i++) { x = 8 * atan2(1, 1) * i / 1000; printf "%.17g %.17g 0\n", x, sin(x) } }' \
    >"$work/sine-tube.txt"
  "$T" metrics -q --rates raw --trim 0 "$work/sine-tube.txt" \
    | awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i }
                  NR == 2 { printf "  sine tube: D %.5f, IC_N %.5f, SOA %.5f\n", $c["D"], $c["IC_N"], $c["SOA"]
                            exit !(sprintf("%.4f %.4f %.4f", $c["D"], $c["IC_N"], $c["SOA"]) == "1.2158 2.4316 0.4117") }'
}
check "TubeTK's sine tube at the raw rate: its distance and inflection count metrics, its filter's sum of angles" tubetk_sine
# The authors' R code on one phantom (make peers runs it on all): the helix at 10 points/mm, with its
# own calls; its curvature is 5/3 n/(n-1) of the truth (its first-derivative stencil, a step L/n).
PEER_DIR=${DATA_DIR:+$DATA_DIR/../peers/tortuosity_R/code_and_sample_data}
if [ -n "${REPO:-}" ] && [ -n "$PEER_DIR" ] && [ -d "$PEER_DIR" ]; then
  peer_on_helix() {
    make -s -C "$REPO" build/scripts/peers.R >/dev/null || return 1
    "$T" phantom --shape helix >"$work/peer-helix.txt" || return 1
    Rscript "$REPO/build/scripts/peers.R" "$PEER_DIR" "$work/peer-helix.txt" 10 "$work/peer-helix.tsv" 2>/dev/null \
      || return 1
    awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i }
                NR == 2 { want = 5 / 3 * $c["n"] / ($c["n"] - 1)
                          printf "  the peer on the helix: AC %.4f, %.4f times the truth 0.2 (5/3 n/(n-1) = %.4f)\n",
                                 $c["AC"], $c["AC"] / 0.2, want
                          exit !($c["status"] == "ok" && ($c["AC"] / 0.2) / want > 0.99 && ($c["AC"] / 0.2) / want < 1.01) }' \
      "$work/peer-helix.tsv"
  }
  check "the authors' R code on the helix phantom: its curvature 5/3 n/(n-1) of the truth, as the report says" peer_on_helix
fi
# A voxel path: two turns of a helix (radius 3.296 mm, pitch 0.3 of it; curvature 0.2783 /mm)
# traced through voxels of 0.824 x 0.824 x 1 mm, each point a voxel's centre. Given the voxels
# (--precision), the fit does not climb their staircase: AC within 5% at 10X; without them GCV's
# fit climbs it (AC more than twice the truth), as the P-spline section says.
voxel_path_precision() {
  awk 'BEGIN { R = 3.296; b = 0.3 * R; q = 0.824; pi = atan2(0, -1); n = 8000
    for (i = 0; i < n; i++) { t = 4 * pi * i / (n - 1)
      x = q * int((R * cos(t) + 0.3) / q + 100.5) - 100 * q; y = q * int((R * sin(t) + 0.5) / q + 100.5) - 100 * q
      z = int(b * t + 0.2 + 100.5) - 100; p = x " " y " " z; if (p != last) print p; last = p } }' >"$work/voxels.txt"
  local with without
  with=$("$T" metrics -q -r 10 --precision 0.824x0.824x1 "$work/voxels.txt" | awk -F'\t' 'NR == 2 { print $12 }')
  without=$("$T" metrics -q -r 10 "$work/voxels.txt" | awk -F'\t' 'NR == 2 { print $12 }')
  echo "  voxel path: AC $with with the voxels, $without without (truth 0.2783)"
  awk -v a="$with" -v b="$without" 'BEGIN { exit !(a > 0.95 * 0.2783 && a < 1.05 * 0.2783 && b > 2 * 0.2783) }'
}
check "a voxel path given its voxels (--precision): the fit does not climb the staircase" voxel_path_precision
# A profile with nothing to profile (every vessel without samples at the rate) exits 1 and says so;
# one vessel with samples among them is a profile. The status warning says what a row has.
nothing_to_profile() {
  printf '0 0 0\n1 0 0\n' >"$work/two-points.txt"
  "$T" profile --rate 10 "$work/two-points.txt" >/dev/null 2>"$work/stderr"; [ $? = 1 ] || return 1
  grep -q "no vessel had samples to profile" "$work/stderr" || return 1
  { cat "$work/two-points.txt"; echo; "$T" phantom; } >"$work/two-and-helix.txt"
  "$T" profile -q --rate 10 --vessel all "$work/two-and-helix.txt" >/dev/null || return 1
  printf '0 0 0\n1 0.1 0\n2 0.3 0\n3 0.6 0.1\n' >"$work/four-points.txt"
  "$T" metrics --rates 10 "$work/four-points.txt" 2>&1 >/dev/null | grep -q "no-torsion (L, D, D1 and the metrics of curvature alone)"
}
check "profile with nothing to profile: exit 1 and a message; a no-torsion warning names the curvature metrics" \
  nothing_to_profile
# A slip in a command's or an option's name: exit 2, and the one meant named; a word near none is
# only unknown.
did_you_mean() {
  local typed want
  while IFS='|' read -r typed want; do
    "$T" $typed >/dev/null 2>"$work/stderr"; [ $? = 2 ] || { echo "$typed: not exit 2"; return 1; }
    if [ "$want" = - ]; then grep -q "did you mean" "$work/stderr" && { echo "$typed: a suggestion"; return 1; }
    else grep -qF "did you mean '$want'" "$work/stderr" || { echo "$typed:"; cat "$work/stderr"; return 1; }; fi
  done <<'WORDS'
metrix|metrics
profiel|profile
sufficent|sufficient
phantom-studdy|phantom-study
xyz|-
metrics --segmnts=5|--segments
metrics --uncertainy|--uncertainty
profile --vesel 1|--vessel
sufficient --laddr 1,2|--ladder
phantom --cuont 2|--count
phantom-study --sigmaa 1|--sigma
metrics --qqqqqqq|-
WORDS
  return 0
}
check "a command or an option misspelt: exit 2 and 'did you mean' the one meant, none for a word near nothing" did_you_mean
# File names with double quotes (first, inside, last, doubled) and a tab: the table and its
# provenance read back whole by R's read.delim and Python's csv module (pandas reads as they do).
quoted_names_read_back() {
  local dir=$work/quoted name
  mkdir -p "$dir"
  for name in '"first.txt' 'in"side.txt' 'last".txt' 'two""quotes.txt' "$(printf 'tab\there.txt')"; do
    "$T" phantom --count 2 >"$dir/$name" || return 1
  done
  "$T" metrics -q --rates 1,2 -o "$dir/out.tsv" "$dir"/*.txt || return 1
  /usr/bin/python3 - "$dir" <<'PY' || return 1
import csv, os, sys
d = sys.argv[1]
with open(os.path.join(d, "out.tsv"), newline="") as f:
    rows = list(csv.DictReader(f, delimiter="\t"))
names = sorted({os.path.basename(r["file"]) for r in rows})
want = sorted(n.replace("\t", "\\t") for n in os.listdir(d) if n.endswith(".txt"))
with open(os.path.join(d, "out.tsv.provenance.tsv"), newline="") as f:
    inputs = [os.path.basename(r["value"]) for r in csv.DictReader(f, delimiter="\t") if r["item"] == "input"]
sys.exit(not (len(rows) == 20 and names == want and sorted(inputs) == want))
PY
  if command -v Rscript >/dev/null; then
    Rscript --vanilla -e 'd <- read.delim(file.path(commandArgs(TRUE)[1], "out.tsv"))
      p <- read.delim(file.path(commandArgs(TRUE)[1], "out.tsv.provenance.tsv"))
      quit(status = !(nrow(d) == 20 && length(unique(d$file)) == 5 && sum(p$item == "input") == 5 &&
                      "\"first.txt" %in% basename(d$file)))' "$dir" || return 1
  fi
}
check "file names with double quotes and tabs: the table and its provenance read back whole (R, Python's csv)" \
  quoted_names_read_back
# A .tre file of 40,000 tubes, children of 40 parents, written with the parents first and with the
# parents last: the same vessels, and the second no slower than three times the first (each parent
# is found by a bisection over the sorted IDs; a scan for it took 8 times as long).
tre_parents_any_order() {
  local order t0 t1 t2
  for order in first last; do
    awk -v order="$order" 'BEGIN { n = 40000; p = 40; print "ObjectType = Scene\nNDims = 3\nNObjects = " n
      for (k = 0; k < n; k++) {
        i = order == "first" ? k : (k + p) % n              # tubes 0..p-1 are the parents
        printf "ObjectType = Tube\nNDims = 3\nID = %d\nParentID = %d\n", i, i < p ? -1 : i % p
        printf "Offset = %d 0 0\nNPoints = 3\nPointDim = x y z r\nPoints =\n", i < p ? i : 0
        for (j = 0; j < 3; j++) print j, i % 5, 0, 1 } }' >"$work/parents-$order.tre"
  done
  t0=$(date +%s.%N)
  "$T" metrics -q --rates raw "$work/parents-first.tre" | sort >"$work/parents-first.tsv" || return 1
  t1=$(date +%s.%N)
  "$T" metrics -q --rates raw "$work/parents-last.tre" | sort >"$work/parents-last.tsv" || return 1
  t2=$(date +%s.%N)
  cut -f2- "$work/parents-first.tsv" | cmp -s - <(cut -f2- "$work/parents-last.tsv") || { echo "other vessels"; return 1; }
  awk -v a="$t0" -v b="$t1" -v c="$t2" 'BEGIN { exit !(c - b <= 3 * (b - a) + 0.2) }' \
    || { echo "parents last $(awk -v b="$t1" -v c="$t2" 'BEGIN { print c - b }') s, first $(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') s"; return 1; }
}
check ".tre: 40,000 tubes read as the same vessels with their 40 parents first or last, in about the same time" \
  tre_parents_any_order
# SWC trees are counted from their ids and parents alone, and a shard leaves unread the files
# that hold none of its vessels: mixed with plain text and CSV (counted by reading), the shards
# still join to the whole, and their provenance names every input as the whole run's does.
swc_tree() {   # swc_tree SEED TRUNK BRANCHES: a trunk, side branches of 15 nodes, and a lone root
  awk -v seed="$1" -v n="$2" -v b="$3" 'BEGIN { srand(seed); id = 1; print "# generated tree"
    printf "%d 1 0 0 0 2 -1\n", id
    for (i = 1; i < n; i++) { id++; printf "%d 1 %.3f %.3f %.3f 2 %d\n", id, 10 * cos(0.2 * i) + rand(),
                                     10 * sin(0.2 * i) + rand(), 2 * i, id - 1 }
    for (k = 0; k < b; k++) { p = 1 + int(rand() * (n - 1)); x = 10 * cos(0.2 * p); y = 10 * sin(0.2 * p)
      for (j = 1; j <= 15; j++) { id++; printf "%d 3 %.3f %.3f %.3f 1 %d\n", id, x + 0.8 * j * cos(k + 0.1 * j),
                                          y + 0.8 * j * sin(k), 2 * p + 0.3 * j * rand(), p; p = id } }
    printf "%d 1 50 50 50 1 -1\n", id + 1 }'
}
for s in 1 2 3 4; do swc_tree "$s" $((30 + 20 * s)) $((2 + s)) >"$work/tree-$s.swc"; done
awk 'BEGIN { print "vessel,x,y,z"; for (v = 1; v <= 5; v++) for (i = 0; i < 40; i++)
             printf "%d,%.3f,%.3f,%.3f\n", v, 3 * cos(0.15 * i + v), 3 * sin(0.15 * i), 0.4 * i }' >"$work/mixed.csv"
swc_files=("$work/tree-1.swc" "$work/shard-b.txt" "$work/tree-2.swc" "$work/mixed.csv" "$work/tree-3.swc" "$work/tree-4.swc")
"$T" metrics -q --units mm -o "$work/swc-whole.tsv" "${swc_files[@]}"
swc_shards_join() {   # swc_shards_join N
  local k parts=()
  for k in $(seq "$1"); do
    "$T" metrics -q --units mm --shard "$k/$1" -o "$work/swc-$k-of-$1.tsv" "${swc_files[@]}" || return 1
    parts+=("$work/swc-$k-of-$1.tsv")
    cmp -s <(grep '^input' "$work/swc-whole.tsv.provenance.tsv") <(grep '^input' "$work/swc-$k-of-$1.tsv.provenance.tsv") \
      || { echo "shard $k of $1: its provenance's inputs differ from the whole run's"; return 1; }
  done
  awk 'FNR > 1 || NR == 1' "${parts[@]}" | cmp - "$work/swc-whole.tsv"
}
swc_shards_join_all() { swc_shards_join 3 && swc_shards_join 5 && swc_shards_join 8; }
check "--shard on SWC trees, plain text and CSV: shards 1..3, 1..5 and 1..8 join to the whole run; every shard's provenance names every input" \
  swc_shards_join_all
swc_shard_skips_files() {   # an earlier tree with a bad coordinate: counted, but only the shards that hold it read it
  sed '5s/^\([0-9]*\) \([0-9]*\) [^ ]*/\1 \2 x/' "$work/tree-1.swc" >"$work/tree-bad.swc"
  grep -q '^[0-9]* [0-9]* x ' "$work/tree-bad.swc" || return 1
  "$T" metrics -q --units mm --shard 4/4 -o "$work/skip.tsv" "$work/tree-bad.swc" "$work/tree-4.swc" "$work/tree-4.swc" \
    || { echo "shard 4 of 4 read the bad tree"; return 1; }
  [ "$(awk -F'\t' '$1 == "input" && NR < 7 { print $3 }' "$work/skip.tsv.provenance.tsv")" \
    = "$(sha256sum <"$work/tree-bad.swc" | cut -d' ' -f1)" ] || { echo "the unread tree's digest is not its sha256sum"; return 1; }
  "$T" metrics -q --units mm --shard 1/4 "$work/tree-bad.swc" "$work/tree-4.swc" "$work/tree-4.swc" >/dev/null \
    2>"$work/skip.err"; [ $? = 2 ] && grep -q 'tree-bad.swc:5:' "$work/skip.err" || { echo "shard 1 of 4 did not fail"; return 1; }
  "$T" metrics -q --units mm "$work/tree-bad.swc" "$work/tree-4.swc" >/dev/null 2>&1; [ $? = 2 ]
}
check "--shard: a shard leaves unread an SWC file without vessels of its own (its digest still in the provenance); the shard that holds it, and the whole run, report its bad line" \
  swc_shard_skips_files
# In a point-per-line file a shard deals whole blocks of lines by their place among the file's
# point lines, and passes over those of earlier shards without reading a number.
awk 'BEGIN { srand(5) } { r = rand(); sub(/\r$/, "") }
     NF == 0 { print (r < 0.3 ? " , " : r < 0.5 ? "\t" : ""); next }
     { if (r < 0.05) print "# a note"; printf "%s%s\n", $0, r < 0.5 ? "\r" : "" }' "$work/shard-a.txt" >"$work/shard-crlf.txt"
text_shards_join() {   # text_shards_join N OPTIONS...: comments, CRLF and blank lines of commas, with SWC and CSV
  local n=$1 k parts=(); shift
  "$T" metrics -q "$@" -o "$work/text-whole.tsv" "$work/shard-crlf.txt" "$work/tree-2.swc" "$work/shard-b.txt" \
    "$work/mixed.csv" || return 1
  for k in $(seq "$n"); do
    "$T" metrics -q "$@" --shard "$k/$n" -o "$work/text-$k.tsv" "$work/shard-crlf.txt" "$work/tree-2.swc" \
      "$work/shard-b.txt" "$work/mixed.csv" || return 1
    parts+=("$work/text-$k.tsv")
  done
  awk 'FNR > 1 || NR == 1' "${parts[@]}" | cmp - "$work/text-whole.tsv"
}
text_shards_all() {
  text_shards_join 4 && text_shards_join 9 && text_shards_join 5 --split-gap 0.5 && text_shards_join 3 --keep-going
}
check "--shard on plain text with comments, CRLF and blank lines of commas (beside SWC and CSV): 4 and 9 shards join to the whole, and so do 5 with --split-gap and 3 with --keep-going" \
  text_shards_all
text_shard_passes_over() {   # a bad number in the first of many blocks: only the shards that hold it read it
  { printf '0 0 0\n1 x 0\n2 1 0\n\n'; cat "$work/shard-a.txt"; } >"$work/text-bad.txt"
  "$T" metrics -q --shard 4/4 "$work/text-bad.txt" >/dev/null || { echo "shard 4 of 4 read the bad block"; return 1; }
  "$T" metrics -q --shard 1/4 "$work/text-bad.txt" >/dev/null 2>"$work/pass.err"; [ $? = 2 ] \
    && grep -q 'text-bad.txt:2:' "$work/pass.err" || { echo "shard 1 of 4 did not fail"; return 1; }
  "$T" metrics -q "$work/text-bad.txt" >/dev/null 2>&1; [ $? = 2 ] || return 1
  # with --split-gap the pieces are numbered across the file, so every shard reads the blocks before its own
  "$T" metrics -q --split-gap 0.5 --shard 4/4 "$work/text-bad.txt" >/dev/null 2>&1; [ $? = 2 ]
}
check "--shard: a shard passes over a text file's blocks of earlier shards unread (a bad number there is the first shard's to report), except under --split-gap" \
  text_shard_passes_over
shard_empty_last() {   # a file without points after all the others: the last shard reads it and fails, as the whole run
  : >"$work/empty.txt"; printf '# only a comment\n' >"$work/comment.txt"
  local f n k failed
  for f in empty comment; do
    "$T" metrics -q "$work/shard-b.txt" "$work/$f.txt" >/dev/null 2>&1; [ $? = 2 ] || return 1
    for n in 1 2 3; do
      failed=0
      for k in $(seq $n); do "$T" metrics -q --shard $k/$n "$work/shard-b.txt" "$work/$f.txt" >/dev/null 2>&1 || failed=1; done
      [ $failed = 1 ] || { echo "$f.txt last: no shard of $n failed"; return 1; }
    done
  done
}
check "--shard: a file without points after every other file is read by the last shard, which fails as the whole run does" \
  shard_empty_last
shard_keep_going_directory() {   # --keep-going: a directory and /dev/null are reported and left out by the shards too
  mkdir -p "$work/a-directory"
  "$T" metrics -q --keep-going -o "$work/kgd.tsv" "$work/shard-b.txt" "$work/a-directory" /dev/null 2>/dev/null; [ $? = 1 ] || return 1
  local k; for k in 1 2 3; do
    "$T" metrics -q --keep-going --shard $k/3 -o "$work/kgd-$k.tsv" "$work/shard-b.txt" "$work/a-directory" /dev/null \
      2>"$work/kgd.err"; [ $? = 1 ] && grep -q 'a-directory: is a directory' "$work/kgd.err" || { echo "shard $k"; return 1; }
  done
  awk 'FNR > 1 || NR == 1' "$work"/kgd-{1,2,3}.tsv | cmp - "$work/kgd.tsv"
}
check "--shard --keep-going: a directory and /dev/null are reported and left out, and the shards join to the whole" \
  shard_keep_going_directory
for bad in 0/4 5/4 1/0 x 1/ 2/3x; do
  check "--shard $bad: exit 2" exit_status_and_one_line 2 "$T" metrics -q --shard "$bad" "$work/shard-a.txt"
done
check "--shard with standard input: exit 2 (the input is read twice)" \
  bash -c "'$T' metrics -q --shard 1/2 - <'$work/shard-a.txt' >/dev/null 2>&1; [ \$? = 2 ]"
check "--shard with a pipe (process substitution): exit 2, not an empty second reading" \
  bash -c "'$T' metrics -q --shard 1/2 <(cat '$work/shard-a.txt') >/dev/null 2>'$work/pipe.err'; [ \$? = 2 ] \
           && grep -q 'give files, not standard input or a pipe' '$work/pipe.err'"
# --split-gap cuts the vessels after the reader has counted them: 5000 two-point vessels in one
# block are 5000 vessels in windows of 1024, measured as if given apart.
awk 'BEGIN { for (i = 0; i < 5000; i++) printf "%d 0 0 0.1\n%d 1 0 0.1\n", 10 * i, 10 * i }' >"$work/gaps.txt"
awk 'BEGIN { for (i = 0; i < 5000; i++) printf "%d 0 0 0.1\n%d 1 0 0.1\n\n", 10 * i, 10 * i }' >"$work/apart.txt"
split_beyond_window() {   # COMMAND: the cut block and the separate vessels give the same rows
  "$T" "$1" -q --jobs 2 --split-gap 5 "$work/gaps.txt" >"$work/gaps.tsv" || return 1
  "$T" "$1" -q --jobs 2 "$work/apart.txt" | cut -f2- | cmp - <(cut -f2- "$work/gaps.tsv") \
    && [ "$(wc -l <"$work/gaps.tsv")" -gt 5000 ]
}
check "--split-gap: 5000 pieces of one block are measured as 5000 vessels apart" \
  split_beyond_window metrics
check "sufficient --split-gap: likewise" split_beyond_window sufficient

# The reading thread fills windows across the ends of files (64, 128, ... 1024 vessels): seven
# files of 150 vessels measured together are the files measured one at a time, row for row.
for k in 1 2 3 4 5 6 7; do
  "$T" phantom --shape helix --count 150 --points 30 --sigma 0.05 --seed $k >"$work/many-$k.txt"
done
windows_across_files() {   # JOBS
  local k; : >"$work/one-by-one.tsv"
  for k in 1 2 3 4 5 6 7; do
    "$T" metrics -q --jobs 1 "$work/many-$k.txt" | awk -v k=$k 'k == 1 || NR > 1' >>"$work/one-by-one.tsv" || return 1
  done
  "$T" metrics -q --jobs "$1" "$work"/many-[1-7].txt | cmp - "$work/one-by-one.tsv" \
    && [ "$(wc -l <"$work/one-by-one.tsv")" = $((1 + 7 * 150 * 4)) ]
}
check "windows across files: 7 files of 150 vessels together are the files one by one (1 thread)" \
  windows_across_files 1
check "windows across files: likewise on 3 threads" windows_across_files 3

slurm=${REPO:-.}/build/scripts/slurm-shards.sh
if [ -f "$slurm" ]; then
  slurm_task() {   # slurm_task K [COUNT] ARGS...: array task K of an array of COUNT tasks
    local k=$1 count=$2; shift 2
    SLURM_ARRAY_TASK_ID=$k SLURM_ARRAY_TASK_COUNT=$count SLURM_CPUS_PER_TASK=1 TORTUOSITY=$T bash "$slurm" "$@"
  }
  slurm_array_joins_to_whole() {
    local k
    for k in 1 2 3 4; do slurm_task $k 4 run "$work/slurm" 4 -q -- "${shard_files[@]}" || return 1; done
    bash "$slurm" join "$work/slurm" 4 | cmp - "$work/unsharded.tsv"
  }
  check "Slurm script (array tasks 1..4 run here, then joined) gives the unsharded output" slurm_array_joins_to_whole
  slurm_task_again() {   # task 3 submitted again alone (an array of one) still computes shard 3 of 4
    rm "$work/slurm/shard-3.tsv" && slurm_task 3 1 run "$work/slurm" 4 -q -- "${shard_files[@]}" \
      && bash "$slurm" join "$work/slurm" 4 | cmp - "$work/unsharded.tsv"
  }
  check "Slurm script: a task submitted again alone computes its own shard of N" slurm_task_again
  slurm_stale_shard() {  # a shard left from a run on other inputs is refused by the join
    cp -r "$work/slurm" "$work/slurm-stale" \
      && slurm_task 2 4 run "$work/slurm-stale" 4 -q -- "$work/shard-a.txt" || return 1
    bash "$slurm" join "$work/slurm-stale" 4 >/dev/null 2>"$work/stale.err"
    [ $? = 2 ] && grep -q 'shard-2.tsv: not from the run of shard-1.tsv' "$work/stale.err"
  }
  check "Slurm script: join refuses a shard from another run (exit 2)" slurm_stale_shard
  for bad in 0 abc -1; do
    check "Slurm script: join with N = '$bad': exit 2" \
      bash -c "bash '$slurm' join '$work/slurm' '$bad' </dev/null >/dev/null 2>&1; [ \$? = 2 ]"
  done
fi
if [ -n "${REPO:-}" ] && { command -v parallel >/dev/null || [ "$(id -u)" = 0 ]; }; then
  make_sharded_with_parallel() {
    make -s -C "$REPO" sharded FILES="${shard_files[*]}" SHARDS=4 JOBS=2 SHARD_DIR="$work/sharded" \
      >"$work/make-sharded.log" 2>&1 || { tail -5 "$work/make-sharded.log"; return 1; }
    cmp "$work/sharded/all.tsv" "$work/unsharded.tsv"
  }
  check "make sharded (GNU parallel, 2 jobs, 4 shards) gives the unsharded output" make_sharded_with_parallel
  sharded_odd_names() {   # names with a space, a quote and a ';' pass through parallel as they are
    local dir="$work/odd dir" out="$work/sharded out"
    mkdir -p "$dir" && cp "$work/shard-a.txt" "$dir/a b.txt" && cp "$work/shard-b.txt" "$dir/b;echo INJECTED >&2;'.txt"
    "$T" metrics -q "$dir/a b.txt" "$dir/b;echo INJECTED >&2;'.txt" >"$work/odd.tsv" || return 1
    make -s -C "$REPO" sharded FILES="'$dir'/*.txt" SHARDS=3 JOBS=2 SHARD_DIR="$out" \
      >"$work/make-odd.log" 2>&1 || { tail -5 "$work/make-odd.log"; return 1; }
    ! grep -q INJECTED "$work/make-odd.log" && cmp "$out/all.tsv" "$work/odd.tsv"
  }
  check "make sharded: file and folder names with spaces, quotes and ';' reach the program intact" sharded_odd_names
  check "make sharded SHARDS=0: exit 2, and no joined file" \
    bash -c "! make -s -C '$REPO' sharded FILES='$work/shard-a.txt' SHARDS=0 SHARD_DIR='$work/sharded0' >/dev/null 2>&1 \
             && [ ! -e '$work/sharded0/all.tsv' ]"
fi

# ---------------------------------------------------------------- VTK output, read back by VTK
# VTK's own reader (python3-vtk9) must find every array of 'profile' and every row of 'metrics'.
PYTHON=${PYTHON:-/usr/bin/python3}
if "$PYTHON" -c 'import vtk' 2>/dev/null; then
  "$T" phantom --shape salkowski -o "$work/salk.txt"
  "$T" phantom --shape helix --count 2 -o "$work/helices.txt"
  vtp_roundtrip() {   # profile|metrics OPTIONS...: the .vtp and the table of the same command agree
    local mode=$1; shift
    "$T" "$mode" -q "$@" >"$work/rt.tsv" && "$T" "$mode" -q --vtk-names ours -o "$work/rt.vtp" "$@" \
      && "$PYTHON" "$(dirname "${BASH_SOURCE[0]}")/vtk-roundtrip.py" "$mode" "$work/rt.vtp" "$work/rt.tsv"
  }
  check "profile --vtk-names ours -o .vtp: vtkXMLPolyDataReader reads every point array as the table has it" \
    vtp_roundtrip profile --rate 10 "$work/salk.txt"
  check "metrics --vtk-names ours -o .vtp: every row is a cell with the row's values" \
    vtp_roundtrip metrics --rates 1,2/mm,10,raw "$work/helices.txt" "$work/salk.txt"
  # The first vessel without samples (two points: no-curvature; four: too-short at 1X), then others:
  # VTK reads every piece, every row a cell, with the same arrays.
  printf '0 0 0\n1 0 0\n\n0 0 0\n0.1 0.2 0\n0.2 0.3 0.1\n0.3 0.3 0.2\n\n' >"$work/short-first.txt"
  cat "$work/helices.txt" >>"$work/short-first.txt"
  check "metrics -o .vtp whose first vessels have no samples: VTK reads every row as a cell" \
    vtp_roundtrip metrics --rates 1,10,raw "$work/short-first.txt"
  "$T" phantom --shape helix --count 3 | awk 'NF { print $0, 0.5 + 0.001 * NR; next } { print }' >"$work/radii-helices.txt"
  vtp_vmtk() {
    "$T" metrics -q "$work/radii-helices.txt" >"$work/rt.tsv" \
      && "$T" metrics -q -o "$work/rt.vtp" "$work/radii-helices.txt" \
      && "$PYTHON" "$(dirname "${BASH_SOURCE[0]}")/vtk-roundtrip.py" vmtk "$work/rt.vtp" "$work/rt.tsv"
  }
  check "metrics -o .vtp: VMTK's array names by default, a Radius array, vtkThreshold keeps one rate" vtp_vmtk
  # The default colouring of a .vtp is the window's curvature at every rate, and a BraVa tree renders
  # (VTK offscreen, under xvfb-run: its window needs an X server).
  vtp_render() {
    local input=("$@")
    "$T" metrics -q "${input[@]}" >"$work/render.tsv" && "$T" metrics -q -o "$work/render.vtp" "${input[@]}" \
      && xvfb-run -a "$PYTHON" "$(dirname "${BASH_SOURCE[0]}")/vtk-render.py" "$work/render.vtp" "$work/render.tsv"
  }
  check "metrics -o .vtp: the active scalar is the window's curvature, its range the window's at every rate; it renders" \
    vtp_render "$work/short-first.txt"
  if [ -n "${DATA_DIR:-}" ] && [ -f "$DATA_DIR/brava-vessmorphovis/BG04.CNG.swc" ]; then
    check "a BraVa tree's .vtp renders offscreen in colour, coloured by the window's curvature" \
      vtp_render --units mm "$DATA_DIR/brava-vessmorphovis/BG04.CNG.swc"
  fi
  check "36 .vtp/.vtk files in every encoding VTK writes: read as VTK reads them" \
    bash -c "'$PYTHON' '$(dirname "${BASH_SOURCE[0]}")/vtk-fixtures.py' '$T' '$work/vtk-fixtures' >'$work/vtk-fixtures.log' \
             || { tail -3 '$work/vtk-fixtures.log'; exit 1; }"
  check "--vmtk-branches on VTK-written branch-extractor output (.vtp, .vtk, a vertex first): a vessel per group, blanked left out" \
    bash -c "'$PYTHON' '$(dirname "${BASH_SOURCE[0]}")/vmtk-branches.py' '$T' '$work/vmtk-branches' >'$work/vmtk-branches.log' \
             || { grep FAIL '$work/vmtk-branches.log'; exit 1; }"
fi

if "$PYTHON" -c 'import numpy' 2>/dev/null; then
  check "3D Slicer markups (LPS, RAS) and ITK/TubeTK tubes (ITK 5 and 4, transforms, parents, binary): the plain text's vessels; bad files refused" \
    bash -c "'$PYTHON' '$(dirname "${BASH_SOURCE[0]}")/slicer-itk-check.py' '$T' '$work/slicer-itk' >'$work/slicer-itk.log' \
             || { grep FAIL '$work/slicer-itk.log'; exit 1; }"
fi

if "$PYTHON" -c 'import h5py' 2>/dev/null; then
  check "HDF5 graph: chains joined, branches, merges and a cycle apart; a bad link refused" \
    bash -c "'$PYTHON' '$(dirname "${BASH_SOURCE[0]}")/hdf5-network.py' '$T' '$work/hdf5' >/dev/null"
fi

# ---------------------------------------------------------------- memory
# metrics streams its input: peak memory is set by a window of vessels and the file's bytes, not by
# the number of vessels (10^5 two-point vessels in 2.3 MB of text: well under 100 MB).
if ! grep -q __asan_init "$T" 2>/dev/null && [ -x /usr/bin/time ]; then
  streamed_memory() {
    awk 'BEGIN { for (i = 0; i < 100000; i++) printf "%d 0 0\n%d 1 0\n\n", i, i }' >"$work/many.txt"
    /usr/bin/time -f '%M' -o "$work/rss" "$T" metrics -q -o "$work/many.tsv" "$work/many.txt" || return 1
    [ "$(wc -l <"$work/many.tsv")" = 400001 ] && [ "$(cat "$work/rss")" -lt 102400 ] \
      || { echo "rows $(wc -l <"$work/many.tsv"), peak RSS $(cat "$work/rss") KB"; return 1; }
  }
  check "metrics on 10^5 two-point vessels: every row, peak RSS under 100 MB" streamed_memory
fi

# ---------------------------------------------------------------- provenance
provenance_loads() {
  "$T" metrics -q --rates 1 -o "$work/prov.tsv" "$work/helices.txt" || return 1
  local side=$work/prov.tsv.provenance.tsv sum
  sum=$(sha256sum "$work/helices.txt" | cut -c1-64)
  grep -qP "^input\t$work/helices.txt\t$sum\tmm$" "$side" || { cat "$side"; return 1; }
  grep -qP '^command\ttortuosity metrics -q --rates 1 -o ' "$side" || return 1
  Rscript -e "p <- read.delim('$side'); stopifnot(names(p) == c('item', 'value', 'sha256', 'units'), \
                 p\$sha256[p\$item == 'input'] == '$sum')" >/dev/null 2>&1 || { echo "read.delim"; return 1; }
  "$PYTHON" -c "import pandas as pd; p = pd.read_csv('$side', sep='\t'); \
                assert list(p.columns) == ['item', 'value', 'sha256', 'units']; \
                assert (p[p['item'] == 'input']['sha256'] == '$sum').all()" || { echo "pandas"; return 1; }
  head -1 "$work/prov.tsv" | grep -q '^file' || { echo "the result's own header changed"; return 1; }
}
check "-o FILE writes FILE.provenance.tsv: version, command, inputs with sha256; read.delim and pandas load it" \
  provenance_loads

# ---------------------------------------------------------------- real data (where present)
if [ -d "$DATA_DIR/brava-3darteryvis/allscans" ]; then
  brava=("$DATA_DIR"/brava-3darteryvis/allscans/*/*.swc)
  "$T" metrics -q --units mm "${brava[@]}" >"$work/brava.tsv"
  # REFERENCE: another build of the program (make check-sanitize gives bin/tortuosity, built with
  # the AVX2 clones of the hot loops, where this one is built for the x86-64 baseline alone).
  if [ -n "${REFERENCE:-}" ]; then
    same_bytes_as_reference() {
      "$REFERENCE" metrics -q --units mm "${brava[@]}" | cmp - "$work/brava.tsv" || return 1
      "$REFERENCE" metrics -q "$work/helices.txt" "$work"/many-[1-3].txt \
        | cmp - <("$T" metrics -q "$work/helices.txt" "$work"/many-[1-3].txt)
    }
    check "BraVa and noisy helices: the same bytes as another build ($REFERENCE)" same_bytes_as_reference
  fi
  check "BraVa allscans: 10,496 vessels" bash -c "[ \$(column vessel '$work/brava.tsv' 2>/dev/null | wc -l) -gt 0 ] || true; \
    awk -F'\t' 'NR>1 && \$3==\"1\"' '$work/brava.tsv' | wc -l | grep -qx 10496"
  check "BraVa at 1,2,10,100X: no NaN or inf anywhere" bash -c "! cut -f4- '$work/brava.tsv' | grep -qiE 'nan|inf'"
  check "BraVa: every row has a status" bash -c "awk -F'\t' 'NR>1 && \$NF==\"\" {bad++} END {exit bad>0}' '$work/brava.tsv'"
  check "BraVa: D >= 1 on every row that has D" bash -c "awk -F'\t' 'NR>1 && \$7!=\"\" && \$7<1 {bad++} END {exit bad>0}' '$work/brava.tsv'"
fi
dat=("$DATA_DIR"/brummer-tortuosity-R/*.dat)
if [ -f "${dat[0]}" ]; then
  check "Angicart .dat: 141 vessels" bash -c "'$T' metrics -q --rates 1 '${dat[0]}' | tail -n +2 | wc -l | grep -qx 141"
fi
# The upstream files against the CSVs derived from them (data/*/PROVENANCE.md): same vessels, same values.
same_rows() {   # same_rows A.tsv B.tsv RELTOL [ABSTOL]: same vessels, n_data, L and D1 (to the tolerances)
  paste <(cut -f2,4,6,8 "$1") <(cut -f2,4,6,8 "$2") | awk -F'\t' -v tol="$3" -v abstol="${4:-1e-12}" '
    function off(a, b) { d = a - b; if (d < 0) d = -d; return d > tol * (b < 0 ? -b : b) + abstol }
    NR > 1 && ($1 != $5 || $2 != $6 || off($3, $7) || off($4, $8)) { print "row " NR ": " $0; bad = 1 }
    END { exit bad || NR < 2 }'
}
vtp=$DATA_DIR/vmtk-aorta/aorta-centerline.vtp
if [ -f "$vtp" ]; then
  vtp_as_csv() {   # the CSV prints the Float32 coordinates with 7 digits, which do not give the floats back
    "$T" metrics -q --rates raw --trim 0 "$vtp" >"$work/aorta-vtp.tsv" \
      && "$T" metrics -q --rates raw --trim 0 "${vtp%.vtp}.lines.csv" >"$work/aorta-csv.tsv" \
      && same_rows "$work/aorta-vtp.tsv" "$work/aorta-csv.tsv" 1e-6 1e-6 \
      && [ "$(tail -n +2 "$work/aorta-vtp.tsv" | wc -l)" = 2 ]
  }
  check "aorta .vtp (VMTK: base64, zlib): the two vessels of its .lines.csv, L to 1e-6, D - 1 to 1e-6 mm/mm" vtp_as_csv
fi
npy=("$DATA_DIR"/fdenz-coronary/*centerlines.npy)
if [ -f "${npy[0]}" ]; then
  npy_as_csv() {
    local f n
    for f in "${npy[@]}"; do
      "$T" metrics -q --rates raw --trim 0 --split-gap 1 "$f" >"$work/npy.tsv" \
        && "$T" metrics -q --rates raw --trim 0 "${f%.npy}.lines.csv" >"$work/npy-csv.tsv" || return 1
      # the CSV numbers its lines from 0, the program its pieces from 1: compare without labels
      awk -F'\t' 'BEGIN { OFS = "\t" } NR > 1 { $2 = $2 - 1 } 1' "$work/npy.tsv" >"$work/npy0.tsv"
      same_rows "$work/npy0.tsv" "$work/npy-csv.tsv" 1e-7 || return 1
      n+=" $(tail -n +2 "$work/npy.tsv" | wc -l)"
    done
    [ "$n" = " 18 7" ] || { echo "vessels:$n"; return 1; }
  }
  check "coronary .npy with --split-gap 1: 18 and 7 centerlines, as in the .lines.csv files" npy_as_csv
fi
h5=$DATA_DIR/bbp-weber-mouse-cortex/sample_3.h5
if [ -f "$h5" ]; then
  # 3,080 sections (the rows of sample_3.sections.csv) joined across 51 single-child links:
  # 3,029 vessels; 55,807 points less the 51 repeated junction points
  hdf5_counts() {
    "$T" metrics -q --rates raw --trim 0 "$h5" >"$work/h5.tsv" || return 1
    local sections; sections=$(tail -n +2 "${h5%.h5}.sections.csv" | cut -d, -f1 | uniq | wc -l)
    [ "$sections" = 3080 ] && [ "$(tail -n +2 "$work/h5.tsv" | wc -l)" = 3029 ] \
      && [ "$(awk -F'\t' 'NR > 1 { s += $4 } END { print s }' "$work/h5.tsv")" = 55756 ] \
      || { echo "sections $sections, vessels and points: $(tail -n +2 "$work/h5.tsv" | wc -l)"; return 1; }
  }
  check "mouse cortex .h5: 3,080 sections of the CSV joined into 3,029 vessels of 55,756 points" hdf5_counts
fi
# Fits that hold: on every dataset, no vessel 'ok' at 1X whose fit (the whole vessel, --trim 0) is
# longer than 1.2 times its polyline; fit_rms and fit_max_dev on every fitted 'ok' row;
# fewer than 2% of the vessels 'fit-departs' in a dataset of 100 vessels or more (no smoothing holds, or the
# residuals keep a pattern: about 1% of BraVa's).
fits_hold() {   # fits_hold NAME OPTIONS... FILES...
  local name=$1; shift
  "$T" metrics -q --rates raw,1 --trim 0 "$@" >"$work/hold-$name.tsv" || return 1
  awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
    { k = $1 FS $2 }
    $3 == "raw" { poly[k] = $c["L"]; next }
    { n++ }
    $c["status"] == "fit-departs" { departs++ }
    $c["status"] == "ok" {
      if ($c["fit_rms"] == "" || $c["fit_max_dev"] == "") { print "no fit_rms or fit_max_dev: " $2; bad = 1 }
      if ($c["L"] > 1.2 * poly[k]) { print "fit " $c["L"] " mm, polyline " poly[k] " mm: " $2; bad = 1 } }
    END { if (n >= 100 && departs >= 0.02 * n) { print departs " of " n " vessels fit-departs"; bad = 1 }
          exit bad || n == 0 }' \
    "$work/hold-$name.tsv"
}
if [ -d "$DATA_DIR/brava-3darteryvis/allscans" ]; then
  check "BraVa (3DArteryVis): every fit holds to its data (L <= 1.2 polyline), < 2% fit-departs" \
    fits_hold brava --units mm "${brava[@]}"
fi
if [ -d "$DATA_DIR/brava-vessmorphovis" ]; then
  check "BraVa (VessMorphoVis): every fit holds to its data, < 2% fit-departs" \
    fits_hold vmv --units mm "$DATA_DIR"/brava-vessmorphovis/*.swc
fi
# A tracing's gap, as the report states it: BraVa BH0016 693-708 (16 points, one step of 7.7 mm among
# steps of 1.5 to 2.5) is fitted on the centripetal parameter, within 0.25 mm RMS of its points and
# with TC 6.87 at 10X; on chord length the fit cut its U-bend (TC 4.35, 1.36 mm RMS). Its bend lies
# in the gap, which no point resolves: it is measured, and marked undersampled.
gap_takes_the_centripetal_parameter() {
  "$T" metrics -q --rates 10 --units mm "$DATA_DIR"/brava-3darteryvis/allscans/BH0016/BH0016records.swc |
    awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
      $2 == "693-708" { found = 1
                        ok = $c["status"] == "undersampled" && $c["fit_rms"] < 0.25 && $c["TC"] > 6.8 && $c["TC"] < 6.95 }
      END { exit !(found && ok) }'
}
[ -f "$DATA_DIR/brava-3darteryvis/allscans/BH0016/BH0016records.swc" ] &&
  check "BraVa BH0016 693-708: a gap in the tracing, fitted on the centripetal parameter (TC 6.87)" \
    gap_takes_the_centripetal_parameter
[ -f "$h5" ] && check "mouse cortex: every fit holds to its data, < 2% fit-departs" fits_hold cortex "$h5"
[ -f "${npy[0]}" ] && check "coronary CT: every fit holds to its data" fits_hold coronary --split-gap 1 "${npy[@]}"
# The basis follows the vessel: on the coronary centerlines (both files, many bends each), every 'ok'
# vessel's D, TC and AC at 10X with the default basis within 5% of a basis of 160 segments, which
# resolves them (on the paper's 20 segments, 19 of the 25 fits depart from their data).
basis_resolves_coronary() {
  "$T" metrics -q --rates 10 --split-gap 1 "${npy[@]}" >"$work/cor-default.tsv" || return 1
  "$T" metrics -q --rates 10 --split-gap 1 --segments 160 "${npy[@]}" >"$work/cor-160.tsv" || return 1
  paste "$work/cor-default.tsv" "$work/cor-160.tsv" | awk -F'\t' '
    NR == 1 { for (i = 1; i <= NF / 2; i++) c[$i] = i; half = NF / 2; next }
    $c["status"] == "ok" { n++
      split("D TC AC", m, " ")
      for (j = 1; j <= 3; j++) { a = $c[m[j]] + 0; b = $(c[m[j]] + half) + 0
        if (b == 0 || (a - b) / b > 0.05 || (b - a) / b > 0.05) {
          print $1 " vessel " $2 ": " m[j] " " a " against " b " on 160 segments"; bad = 1 } } }
    END { exit bad || n < 20 }'
}
[ -f "${npy[0]}" ] && check "coronary CT: every ok vessel's D, TC, AC at 10X within 5% of 160 segments" \
  basis_resolves_coronary
[ -f "${dat[0]}" ] && check "Angicart: every fit holds to its data" fits_hold angicart "${dat[@]}"
[ -f "$vtp" ] && check "aorta: every fit holds to its data" fits_hold aorta "$vtp"

# How much one vessel can move a pooled correlation, as the report states it: the twelve metrics of
# the correlation table at 100X over the human datasets (BraVa 3DArteryVis, coronary, aorta), each
# Pearson correlation recomputed with every vessel left out, here from the command line's output;
# the largest change and its vessel must be those of results/correlation-influence.tsv.
if [ -d "$DATA_DIR/brava-3darteryvis/allscans" ] && [ -f "${npy[0]}" ] && [ -f "$vtp" ] && command -v Rscript >/dev/null; then
  correlation_influence_as_stated() {
    { "$T" metrics -q --rates 100 --units mm "${brava[@]}"
      "$T" metrics -q --rates 100 --split-gap 1 "${npy[@]}" | tail -n +2
      "$T" metrics -q --rates 100 "$vtp" | tail -n +2; } >"$work/pool.tsv" || return 1
    Rscript --vanilla -e '
      d <- read.delim(commandArgs(TRUE)[1], na.strings = "", colClasses = c(status = "character"))
      d <- d[d$status == "ok", ]
      m <- c("TT", "AT", "TT_L", "AC", "TC_L", "TC", "IC_N", "TCCT_L", "ACCT", "SOA", "TCCT", "IC_kappa")
      X <- scale(as.matrix(d[, m]), scale = FALSE); n <- nrow(X) - 1; worst <- 0; who <- ""
      for (a in 1:11) for (b in (a + 1):12) {
        x <- X[, a]; y <- X[, b]; sx <- sum(x) - x; sy <- sum(y) - y
        loo <- (n * (sum(x * y) - x * y) - sx * sy) /
               sqrt((n * (sum(x * x) - x * x) - sx^2) * (n * (sum(y * y) - y * y) - sy^2))
        change <- abs(loo - cor(x, y))
        if (max(change) > worst) { worst <- max(change); who <- paste(basename(d$file), d$vessel)[which.max(change)] }
      }
      stated <- read.delim(commandArgs(TRUE)[2])[1, ]
      cat("largest change", worst, "leaving out", who, "; stated", stated$largest_change, stated$vessel, "\n")
      quit(status = !(abs(worst - stated$largest_change) <= 5e-3 * worst && endsWith(stated$vessel, who)))' \
      "$work/pool.tsv" "${REPO:-.}/results/correlation-influence.tsv" >"$work/loo.log" 2>&1 || { cat "$work/loo.log"; return 1; }
  }
  check "correlation table: the vessel that moves a pooled correlation most, and by how much, as the report says" \
    correlation_influence_as_stated
fi

aorta=$DATA_DIR/vmtk-aorta/aorta-centerline.lines.csv
if [ -f "$aorta" ]; then
  "$T" metrics -q --rates 1 "$aorta" >"$work/aorta.tsv"
  # 211 rows in line 0, one of them an exact repeat of its predecessor: 210 points are kept
  check "aorta .lines.csv: 2 vessels of 210 (211 less one repeat) and 198 points" \
    bash -c "[ \"\$(cut -f4 '$work/aorta.tsv' | tail -n +2 | tr '\n' ' ')\" = '210 198 ' ]"
  # VMTK's vtkvmtkCenterlineGeometry on aorta-centerline.vtp: Length and Tortuosity (= D - 1)
  whole_polyline_as_vmtk() {
    "$T" metrics -q --rates raw --trim 0 "$aorta" >"$work/aorta-raw.tsv" || return 1
    local L D1
    L=($(column L "$work/aorta-raw.tsv")); D1=($(column D1 "$work/aorta-raw.tsv"))
    near "${L[0]}" 77.81202643 1e-6 && near "${L[1]}" 76.15578820 1e-6 || { echo "L ${L[*]}"; return 1; }
    awk -v a="${D1[0]}" -v b="${D1[1]}" 'BEGIN { exit !(a - 0.025062208861 < 1e-6 && 0.025062208861 - a < 1e-6 &&
                                                     b - 0.022702864636 < 1e-6 && 0.022702864636 - b < 1e-6) }' \
      || { echo "D1 ${D1[*]}"; return 1; }
  }
  check "aorta raw --trim 0: L and D - 1 as VMTK publishes them (1e-6)" whole_polyline_as_vmtk
  check "sufficient (rotation) finds a rate for both aorta vessels" \
    bash -c "'$T' sufficient -q --integrator rotation '$aorta' | awk -F'\t' 'NR>1 && \$6!=\"none\" && \$8<\$5 {n++} END {exit n!=2}'"
fi

echo "e2e: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
