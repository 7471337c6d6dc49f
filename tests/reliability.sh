#!/usr/bin/env bash
# Reliability checks of the command line: -o onto links, FIFOs and devices, write
# errors, temporary files, interrupted runs, silent merges and splits of vessels,
# resource limits and escaping of odd bytes. Usage: tests/reliability.sh bin/tortuosity
# Prints one line per check and "reliability: N passed, N failed" last; exits 0.
# Runs as root in CI: no check ever names a real device as -o (links in $work only).
set -u -o pipefail
T=${1:?usage: reliability.sh path/to/tortuosity}
case $T in /*) ;; */*) T=$PWD/$T ;; esac   # absolute: some checks run in subdirectories
. "$(dirname "${BASH_SOURCE[0]}")/harness.sh"

skip() {    # skip NAME REASON: an ok line for a check that cannot run here
  passed=$((passed + 1)); echo "ok   $1 (skipped: $2)"
}

run() {     # run COMMAND...: stdout in $work/stdout, stderr in $work/stderr, exit status in $rc
  "$@" >"$work/stdout" 2>"$work/stderr"; rc=$?
}

in_dir() {  # in_dir DIR COMMAND...: runs the command in DIR
  (cd "$1" && shift && exec "$@")
}

expect_rc() {   # expect_rc WANT: the last run exited with WANT
  [ "$rc" = "$1" ] && return 0
  echo "exit $rc, expected $1"; head -5 "$work/stderr"; return 1
}

has_message() { # the last run wrote a message on standard error
  [ -s "$work/stderr" ] || { echo "no message on standard error"; return 1; }
}

refused() {     # refused WANT COMMAND...: exit WANT, a message, nothing on standard output
  local want=$1; shift
  run "$@"
  expect_rc "$want" && has_message || return 1
  [ ! -s "$work/stdout" ] || { echo "output despite the error:"; head -3 "$work/stdout"; return 1; }
}

alive() {   # alive PID: the child is running (not exited, not a zombie)
  local stat
  { read -r stat <"/proc/$1/stat"; } 2>/dev/null || return 1
  stat=${stat##*) }
  [ "${stat%% *}" != Z ]
}

reap() {    # reap PID SECONDS: waits for a child, its status; TERM, then KILL, and late=1 when it takes longer
  local pid=$1 n=$(($2 * 10))
  late=0
  while [ "$n" -gt 0 ] && alive "$pid"; do sleep 0.1; n=$((n - 1)); done
  if alive "$pid"; then
    late=1
    echo "process $pid still running after $2 s: terminated"
    kill -TERM "$pid" 2>/dev/null; sleep 0.5; kill -KILL "$pid" 2>/dev/null
  fi
  wait "$pid"
}

elapsed_below() {   # elapsed_below T0 T1 SECONDS
  awk -v a="$1" -v b="$2" -v s="$3" 'BEGIN { exit !(b - a < s) }'
}

same_bytes() {  # same_bytes EXPECTED GOT: GOT holds exactly the reference result
  [ -s "$1" ] || { echo "reference output $1 is empty"; return 1; }
  [ -f "$2" ] || { echo "$2 is missing or not a regular file"; return 1; }
  cmp "$1" "$2" || { echo "$2 differs from the standard-output result"; head -3 "$2"; return 1; }
}

# ---------------------------------------------------------------- inputs
"$T" phantom --shape helix --count 3 >"$work/h3.txt"
"$T" metrics -q --rates 1 "$work/h3.txt" >"$work/h3.tsv"          # the reference result
"$T" phantom --shape helix >"$work/h45.txt"
"$T" phantom --shape helix --points 8 >"$work/pts8.txt"           # 8 points, for the CSV files
"$T" phantom --shape helix --count 50 >"$work/h50.txt"
"$T" phantom --shape helix | awk 'NF { print $0, 0.5; next } { print }' >"$work/radii.txt"
# Slow input: about 10 s at --rates 1000 on one thread (25 s under AddressSanitizer), so a run
# is still computing at 0.5 s; reading it takes 0.1 s (0.3 s under AddressSanitizer).
"$T" phantom --shape helix --count 400 --points 300 >"$work/slow.txt"
slow=(metrics -q --jobs 1 --rates 1000)
printf '0 0 0\n1 x 0\n' >"$work/bad.txt"
reference_has_rows() { [ "$(wc -l <"$work/h3.tsv")" = 4 ] || { echo "metrics of 3 helices: $(wc -l <"$work/h3.tsv") lines"; return 1; }; }
check "reference: metrics of 3 helices to standard output has a header and 3 rows" reference_has_rows

# ---------------------------------------------------------------- 1. -o onto special files
o_symlink_to_file() {   # o_symlink_to_file TARGET-SPELLING: -o LINK writes through to F, LINK stays
  local dir=$work/s-$2 target=$1
  mkdir "$dir"; echo old >"$dir/F"; ln -s "$target" "$dir/LINK"
  run "$T" metrics -q --rates 1 -o "$dir/LINK" "$work/h3.txt"
  expect_rc 0 || return 1
  [ -L "$dir/LINK" ] && [ "$(readlink "$dir/LINK")" = "$target" ] \
    || { echo "LINK is no longer a symlink to F:"; ls -l "$dir"; return 1; }
  same_bytes "$work/h3.tsv" "$dir/F"
}
check "-o LINK (absolute symlink to a regular file): exit 0, F has the result, LINK still -> F" \
  o_symlink_to_file "$work/s-abs/F" abs
check "-o LINK (relative symlink to a regular file): exit 0, F has the result, LINK still -> F" \
  o_symlink_to_file F rel

o_fifo() {
  mkfifo "$work/fifo"
  timeout 20 cat "$work/fifo" >"$work/fifo-got" &
  local reader=$!
  run timeout 20 "$T" metrics -q --rates 1 -o "$work/fifo" "$work/h3.txt"
  reap "$reader" 2 >/dev/null
  expect_rc 0 || return 1
  [ -p "$work/fifo" ] || { echo "the FIFO was replaced:"; ls -l "$work/fifo"; return 1; }
  same_bytes "$work/h3.tsv" "$work/fifo-got"
}
check "-o FIFO: exit 0, the reader gets the result, FIFO still a FIFO" o_fifo

o_link_to_dev_null() {
  ln -s /dev/null "$work/null-link"
  run "$T" metrics -q --rates 1 -o "$work/null-link" "$work/h3.txt"
  [ -c /dev/null ] || { echo "/dev/null IS NO LONGER A CHARACTER DEVICE"; ls -l /dev/null; return 1; }
  expect_rc 0 || return 1
  [ -L "$work/null-link" ] && [ "$(readlink "$work/null-link")" = /dev/null ] \
    || { echo "the link was replaced:"; ls -l "$work/null-link"; return 1; }
}
check "-o LINK -> /dev/null: exit 0, /dev/null still a device, LINK still a symlink" o_link_to_dev_null

variant_onto_provenance() {   # a variant's table named as the main table's provenance file, or the reverse
  mkdir -p "$work/vp"
  refused 2 "$T" metrics -q --rates 1 -o "$work/vp/t" --variant "--planar -o $work/vp/t.provenance.tsv" \
    "$work/h3.txt" || return 1
  refused 2 "$T" metrics -q --rates 1 -o "$work/vp/t.provenance.tsv" --variant "--planar -o $work/vp/t" \
    "$work/h3.txt" || return 1
  [ -z "$(ls "$work/vp")" ] || { echo "files were written:"; ls "$work/vp"; return 1; }
}
check "--variant -o onto the main table's provenance file (or the reverse): exit 2, nothing written" \
  variant_onto_provenance

# ---------------------------------------------------------------- 2. write errors
write_error() {     # write_error COMMAND...: standard output on /dev/full; exit 1 with a message
  "$@" >/dev/full 2>"$work/stderr"; rc=$?
  expect_rc 1 && has_message
}
one_line_message() {
  write_error "$@" || return 1
  [ "$(wc -l <"$work/stderr")" = 1 ] || { echo "message of $(wc -l <"$work/stderr") lines:"; head -5 "$work/stderr"; return 1; }
}
o_dev_full() {      # -o through a link: a buggy rename then replaces the link, never /dev/full itself
  ln -s /dev/full "$work/full-link"
  run "$T" phantom --points 1000 -o "$work/full-link"
  [ -c /dev/full ] || { echo "/dev/full IS NO LONGER A CHARACTER DEVICE"; ls -l /dev/full; return 1; }
  expect_rc 1 && has_message
}
if [ -c /dev/full ]; then
  check "phantom --points 1000 >/dev/full: exit 1, one-line message" one_line_message "$T" phantom --points 1000
  check "phantom --truth >/dev/full (small output): exit 1, message" write_error "$T" phantom --truth
  check "phantom --points 1000 -o LINK -> /dev/full: exit 1, message, /dev/full still a device" o_dev_full
  check "metrics of 50 helices >/dev/full: exit 1, message" write_error "$T" metrics -q "$work/h50.txt"
  check "profile >/dev/full: exit 1, message" write_error "$T" profile -q "$work/h50.txt"
  check "sufficient >/dev/full (small output): exit 1, message" write_error "$T" sufficient -q "$work/radii.txt"
  printf '0 0 0\n1 1 0\n' >"$work/two-points.txt"    # a warning: no curvature at any rate
  stderr_full() {
    "$T" metrics "$work/two-points.txt" >/dev/null 2>/dev/full; rc=$?
    expect_rc 1
  }
  check "metrics with a warning, standard error on /dev/full: exit 1" stderr_full
  check "the same with -q (nothing to say): exit 0" sh -c '"$1" metrics -q "$2" >/dev/null 2>/dev/full' sh "$T" \
    "$work/two-points.txt"
else
  for name in "phantom --points 1000 >/dev/full" "phantom --truth >/dev/full" "phantom -o LINK -> /dev/full" \
              "metrics >/dev/full" "profile >/dev/full" "sufficient >/dev/full" "2>/dev/full" "-q 2>/dev/full"; do
    skip "$name" "no /dev/full"
  done
fi

# ---------------------------------------------------------------- 3. temporary files
o_long_name() {
  local name; printf -v name '%*s' 254 ''; name=${name// /o}
  run "$T" metrics -q --rates 1 -o "$work/$name" "$work/h3.txt"
  expect_rc 0 && same_bytes "$work/h3.tsv" "$work/$name" || return 1
  grep -q "name is too long for a provenance file beside it" "$work/stderr" || { cat "$work/stderr"; return 1; }
}
check "-o with a 254-character file name: exit 0, the file has the result, a note that it has no provenance" o_long_name

o_leaves_only_result() {
  mkdir "$work/d"
  run "$T" metrics -q --rates 1 -o "$work/d/out.tsv" "$work/h3.txt"
  expect_rc 0 || return 1
  [ "$(ls -A "$work/d" | tr '\n' ' ')" = "out.tsv out.tsv.provenance.tsv " ] \
    || { echo "directory holds:"; ls -A "$work/d"; return 1; }
  same_bytes "$work/h3.tsv" "$work/d/out.tsv"
}
check "-o DIR/out.tsv: afterwards DIR holds only out.tsv and its provenance" o_leaves_only_result

provenance_place_refused() {   # KIND: a directory or a FIFO where FILE.provenance.tsv goes
  rm -rf "$work/pv" && mkdir "$work/pv"
  if [ "$1" = directory ]; then mkdir "$work/pv/out.tsv.provenance.tsv"; else mkfifo "$work/pv/out.tsv.provenance.tsv"; fi
  run timeout 20 "$T" metrics -q --rates 1 -o "$work/pv/out.tsv" "$work/h3.txt"
  expect_rc 2 && has_message || return 1
  grep -q "its provenance file .*out.tsv.provenance.tsv is" "$work/stderr" || { cat "$work/stderr"; return 1; }
  [ "$(ls -A "$work/pv")" = out.tsv.provenance.tsv ] || { echo "directory holds:"; ls -A "$work/pv"; return 1; }
}
check "-o FILE with a directory at FILE.provenance.tsv: exit 2 at once, nothing written" \
  provenance_place_refused directory
check "-o FILE with a FIFO at FILE.provenance.tsv: exit 2 at once (no wait for a reader), nothing written" \
  provenance_place_refused fifo


killed_run_leaves_nothing() {   # killed_run_leaves_nothing SIGNAL
  local sig=$1 dir=$work/k-$1 pid status
  mkdir "$dir"
  set -m    # a job of its own: a non-interactive shell starts background jobs with SIGINT ignored,
  # and env restores every signal's default where this script was started with some ignored (nohup)
  env --default-signal "$T" "${slow[@]}" -o "$dir/out.tsv" "$work/slow.txt" 2>"$work/stderr" &
  pid=$!
  set +m
  sleep 0.5
  alive "$pid" || { wait "$pid"; echo "finished (exit $?) within 0.5 s: nothing was interrupted"; return 1; }
  kill "-$sig" "$pid"
  reap "$pid" 5; status=$?
  [ "$late" = 0 ] || { echo "still running 5 s after SIG$sig"; return 1; }
  [ "$status" != 0 ] || { echo "exit 0 after SIG$sig"; return 1; }
  [ -z "$(ls -A "$dir")" ] || { echo "exit $status; left behind:"; ls -A "$dir"; return 1; }
}
check "SIGTERM while computing: non-zero exit, nothing left in the output directory" killed_run_leaves_nothing TERM
check "SIGINT while computing: non-zero exit, nothing left in the output directory" killed_run_leaves_nothing INT
for sig in HUP QUIT ALRM USR1 USR2 PIPE XCPU VTALRM PROF IO PWR STKFLT SYS TRAP ABRT BUS SEGV FPE ILL \
           RTMIN RTMIN+7 RTMAX; do   # every catchable signal that ends a process (real-time ones by sample)
  check "SIG$sig while computing: non-zero exit, nothing left in the output directory" killed_run_leaves_nothing $sig
done

# Standard output is spooled where TMPDIR says (a small /tmp is no limit), and written directly where
# no spool can be made there; a spool that fails names its directory.
spool_in_tmpdir() {
  local dir=$work/spool pid found=0
  mkdir -p "$dir"
  TMPDIR=$dir "$T" "${slow[@]}" "$work/slow.txt" >"$work/spooled.tsv" 2>/dev/null &
  pid=$!
  sleep 0.5
  ls -l "/proc/$pid/fd" 2>/dev/null | grep -q "$dir/.tortuosity-spool-" && found=1
  kill "$pid"; wait "$pid" 2>/dev/null
  [ "$found" = 1 ] || { echo "no spool in TMPDIR"; return 1; }
  "$T" phantom --count 3 >"$work/spool-helices.txt" || return 1
  "$T" metrics -q "$work/spool-helices.txt" >"$work/direct.tsv" || return 1
  TMPDIR=$work/no-such-dir "$T" metrics -q "$work/spool-helices.txt" >"$work/nodir.tsv" || return 1
  cmp -s "$work/direct.tsv" "$work/nodir.tsv" || { echo "TMPDIR missing: other output"; return 1; }
  (ulimit -f 1; TMPDIR=$dir exec "$T" metrics -q "$work/spool-helices.txt" >"$work/limited.tsv" \
     2>"$work/stderr"); [ $? -ne 0 ] && grep -qF "spooled in $dir" "$work/stderr" \
     || { echo "a failed spool: exit $?"; cat "$work/stderr"; return 1; }
}
check "standard output is spooled in TMPDIR, written directly where TMPDIR has no room for one, a failed spool named" \
  spool_in_tmpdir

# A path under /proc that reaches a regular file is a file, not a descriptor: however it is
# spelled (through the process's cwd or root, by its PID or self, through a symlink), a run that
# fails leaves the old result as it was and nothing beside it, and one that succeeds replaces it
# whole, with its provenance.
proc_paths_replace_atomically() {
  local dir=$work/proc-paths spelling
  mkdir -p "$dir"
  "$T" phantom >"$dir/good.txt" && printf '1 2 3\nx y z\n' >"$dir/bad.txt" || return 1
  ln -sfn /proc/self/cwd/old.tsv "$dir/link.tsv"
  for spelling in /proc/self/cwd/old.tsv "/proc/self/root$dir/old.tsv" link.tsv "/proc/PID/cwd/old.tsv"; do
    echo OLD >"$dir/old.tsv"; rm -f "$dir/old.tsv.provenance.tsv"
    (cd "$dir" && exec "$T" metrics -q -o "${spelling/PID/$BASHPID}" good.txt bad.txt) 2>/dev/null
    [ $? = 2 ] && [ "$(cat "$dir/old.tsv")" = OLD ] && [ "$(ls -A "$dir" | wc -l)" = 4 ] \
      || { echo "$spelling, a failed run: $(head -c 60 "$dir/old.tsv")"; ls -A "$dir"; return 1; }
    (cd "$dir" && exec "$T" metrics -q -o "${spelling/PID/$BASHPID}" good.txt) || return 1
    [ "$(wc -l <"$dir/old.tsv")" -gt 1 ] && grep -q OLD "$dir/old.tsv" && return 1
    [ -s "$dir/old.tsv.provenance.tsv" ] || { echo "$spelling: no provenance"; return 1; }
  done
}
check "-o through /proc (cwd, root, PID, a symlink): a failed run leaves the old result whole, a good one replaces it" \
  proc_paths_replace_atomically

refused_before_computing() {    # refused_before_computing OUTPUT: exit 2 within 1 s, message names OUTPUT's directory
  local out=$1 t0 t1
  t0=$(date +%s.%N)
  run timeout 3 "$T" "${slow[@]}" -o "$out" "$work/slow.txt"
  t1=$(date +%s.%N)
  expect_rc 2 && has_message || return 1
  grep -qF "${out%/*}" "$work/stderr" || { echo "message does not name $out:"; head -3 "$work/stderr"; return 1; }
  elapsed_below "$t0" "$t1" 1 || { echo "took $(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') s: computed first"; return 1; }
}
check "-o MISSING-DIR/out.tsv: exit 2 in under 1 s (before computing), message names the path" \
  refused_before_computing "$work/missing-dir/out.tsv"
output_path_before_input() {
  run "$T" metrics -q -o "$work/missing-dir/out.tsv" "$work/bad.txt"
  expect_rc 2 && has_message || return 1
  grep -qF "$work/missing-dir" "$work/stderr" || { echo "message is not about the output path:"; head -3 "$work/stderr"; return 1; }
  ! grep -qF bad.txt "$work/stderr" || { echo "message is about the input:"; head -3 "$work/stderr"; return 1; }
}
check "-o MISSING-DIR/out.tsv with a malformed input: the message is about the output path" output_path_before_input

if [ "$(id -u)" = 0 ]; then
  skip "-o into a read-only (555) directory: exit 2 before computing" root
else
  read_only_dir() {
    mkdir "$work/ro"; chmod 555 "$work/ro"
    refused_before_computing "$work/ro/out.tsv"; local s=$?
    chmod 755 "$work/ro"
    [ -z "$(ls -A "$work/ro")" ] || { echo "left behind:"; ls -A "$work/ro"; return 1; }
    return $s
  }
  check "-o into a read-only (555) directory: exit 2 in under 1 s (before computing), message names it" read_only_dir
fi

o_is_input() {  # o_is_input SETUP OUTPUT: in $work/g, -o OUTPUT with input in.txt is refused, in.txt unchanged
  rm -rf "$work/g"; mkdir -p "$work/g/sub"; cp "$work/h3.txt" "$work/g/in.txt"
  (cd "$work/g" && eval "$1") || { echo "setup failed: $1"; return 1; }
  run in_dir "$work/g" "$T" metrics -q --rates 1 -o "$2" in.txt
  cmp -s "$work/h3.txt" "$work/g/in.txt" || { echo "the input was changed (exit $rc):"; head -2 "$work/g/in.txt"; return 1; }
  expect_rc 2 && has_message
}
check "-o naming the input, same spelling: exit 2, input unchanged" o_is_input : in.txt
check "-o naming the input as ./in.txt: exit 2, input unchanged" o_is_input : ./in.txt
check "-o naming the input by its absolute path: exit 2, input unchanged" o_is_input : "$work/g/in.txt"
check "-o naming the input as sub/../in.txt: exit 2, input unchanged" o_is_input : sub/../in.txt
check "-o naming a hard link to the input: exit 2, input unchanged" o_is_input "ln in.txt hard.txt" hard.txt
check "-o naming a symlink to the input: exit 2, input unchanged" o_is_input "ln -s in.txt sym.txt" sym.txt

# ---------------------------------------------------------------- 4. silent merges and splits
vessels_are() {     # vessels_are WANT FILE: metrics --rates 1 exits 0 with rows "vessel:n_data ..." = WANT
  run "$T" metrics -q --rates 1 "$2"
  expect_rc 0 || return 1
  local got; got=$(awk -F'\t' 'NR > 1 { printf "%s%s:%s", sep, $2, $4; sep = " " }' "$work/stdout")
  [ "$got" = "$1" ] || { echo "vessel:n_data '$got', expected '$1'"; return 1; }
}
csv_rows() {        # csv_rows GROUP [FIRST LAST]: points FIRST..LAST of pts8.txt as GROUP,x,y,z
  awk -v g="$1" -v a="${2:-1}" -v b="${3:-8}" 'NF && ++n >= a && n <= b { print g "," $1 "," $2 "," $3 }' "$work/pts8.txt"
}

{ printf '\xef\xbb\xbf'; echo vessel,x,y,z; csv_rows a; csv_rows b; } >"$work/bom.csv"
check "CSV with a UTF-8 BOM before the group column: vessels a and b of 8 points" vessels_are "a:8 b:8" "$work/bom.csv"

long60a=$(printf 'v%.0s' {1..59})a long60b=$(printf 'v%.0s' {1..59})b
long100a=$(printf 'w%.0s' {1..99})a long100b=$(printf 'w%.0s' {1..99})b
{ echo vessel,x,y,z; csv_rows "$long60a"; csv_rows "$long60b"; } >"$work/long60.csv"
{ echo vessel,x,y,z; csv_rows "$long100a"; csv_rows "$long100b"; } >"$work/long100.csv"
check "CSV group values of 60 characters differing at the end: 2 vessels, full labels" \
  vessels_are "$long60a:8 $long60b:8" "$work/long60.csv"
check "CSV group values of 100 characters differing at the end: 2 vessels, full labels" \
  vessels_are "$long100a:8 $long100b:8" "$work/long100.csv"

{ echo vessel,x,y,z; csv_rows A 1 4; csv_rows B 1 4; csv_rows A 5 6; } >"$work/resume.csv"
group_resumes() {
  refused 2 "$T" metrics -q --rates 1 "$work/resume.csv" || return 1
  grep -qF "$work/resume.csv:10:" "$work/stderr" || { echo "message does not name line 10:"; head -3 "$work/stderr"; return 1; }
}
check "CSV group A A A A B B B B A A: exit 2, message names line 10 where A resumes" group_resumes

{ echo line_id,point_index,x,y,z; awk 'NF { print "0," n++ "," $1 "," $2 "," $3 }' "$work/pts8.txt" | tac; } \
  >"$work/reversed-index.csv"
index_out_of_order() {
  refused 2 "$T" metrics -q --rates 1 "$work/reversed-index.csv" || return 1
  grep -qF "$work/reversed-index.csv:3: point 6 after point 7" "$work/stderr" \
    || { echo "message does not name line 3:"; head -3 "$work/stderr"; return 1; }
}
check "CSV rows in reverse point_index order: exit 2 at line 3, not joined in the rows' order" index_out_of_order

tube() {     # tube NAME: a MetaIO tube of pts8.txt's points, in ITK 4's columns
  printf 'ObjectType = Tube\nNDims = 3\nName = %s\nPointDim = x y z r\nNPoints = 8\nPoints = \n' "$1"
  awk 'NF { print $1, $2, $3, 0.5 }' "$work/pts8.txt"
}
{ printf 'ObjectType = Scene\nNDims = 3\nNObjects = 2\n'; tube a; tube b | head -5; } >"$work/cut-tube.tre"
tube_cut_short() {
  refused 2 "$T" metrics -q --rates 1 "$work/cut-tube.tre" || return 1
  grep -qF "$work/cut-tube.tre:18: a tube (NPoints 8) without its Points block" "$work/stderr" \
    || { echo "message does not name line 18:"; head -3 "$work/stderr"; return 1; }
}
check ".tre whose last tube ends in its header: exit 2 naming that tube, not its first tube alone" tube_cut_short
# A Scene counts its objects (ITK reads that many): cut short between two tubes, the file has fewer;
# with a tube appended by hand, more, which ITK would leave unread. Both are refused at the count.
{ printf 'ObjectType = Scene\nNDims = 3\nNObjects = 3\n'; tube a; tube b; } >"$work/scene-fewer.tre"
{ printf 'ObjectType = Scene\nNDims = 3\nNObjects = 1\n'; tube a; tube b; } >"$work/scene-more.tre"
scene_count() {     # scene_count FILE MESSAGE
  refused 2 "$T" metrics -q --rates 1 "$1" || return 1
  grep -qF "$1:3: $2" "$work/stderr" || { echo "message does not name line 3:"; head -3 "$work/stderr"; return 1; }
}
check ".tre whose Scene counts 3 objects and holds 2 tubes (cut between them): exit 2 at the count" \
  scene_count "$work/scene-fewer.tre" "NObjects 3, but the file holds 2 objects after its Scene: it is cut short"
check ".tre whose Scene counts 1 object and holds 2 tubes: exit 2 at the count, not a vessel ITK would not read" \
  scene_count "$work/scene-more.tre" "NObjects 1, but the file holds 2 objects after its Scene"

{ echo vessel,x,y,z; csv_rows a 1 4; echo; csv_rows a 5 8; } >"$work/group-blank.csv"
{ echo vessel,x,y,z; csv_rows a 1 4; echo '# a comment'; csv_rows a 5 8; } >"$work/group-comment.csv"
check "a blank line inside a CSV group does not split the vessel" vessels_are "a:8" "$work/group-blank.csv"
check "a # comment line inside a CSV group does not split the vessel" vessels_are "a:8" "$work/group-comment.csv"

{ sed -n 1,4p "$work/pts8.txt"; echo '# a comment'; sed -n 5,8p "$work/pts8.txt"; } >"$work/text-comment.txt"
{ sed -n 1,4p "$work/pts8.txt"; echo; sed -n 5,8p "$work/pts8.txt"; } >"$work/text-blank.txt"
check "a # comment line inside a plain-text vessel does not split it" vessels_are "1:8" "$work/text-comment.txt"
check "a blank line in plain text still separates vessels" vessels_are "1:4 2:4" "$work/text-blank.txt"

printf '0,5 0 0\n1,5 0,1 0\n2,5 0,4 0\n3,5 0,9 0\n4,5 1,6 0\n5,5 2,5 0\n' >"$work/decimal-comma.txt"
decimal_comma() {
  refused 2 "$T" metrics -q --rates 1 "$work/decimal-comma.txt" || return 1
  grep -qF "$work/decimal-comma.txt:1:" "$work/stderr" || { echo "message does not name line 1:"; head -3 "$work/stderr"; return 1; }
}
check "plain text with decimal commas (0,5 0 0): exit 2, message names line 1" decimal_comma
awk 'NF { print $1 ", " $2 ", " $3 }' "$work/pts8.txt" >"$work/comma-space.txt"
check "plain text '1, 2, 3' (comma and space) is still read" vessels_are "1:8" "$work/comma-space.txt"

two_x_columns() {   # two_x_columns NAME HEADER
  { echo "$2"; awk 'NF { print $1 "," $1 * 1000 "," $2 "," $3 }' "$work/pts8.txt"; } >"$work/$1.csv"
  refused 2 "$T" metrics -q --rates 1 "$work/$1.csv" || return 1
  grep -qF "$work/$1.csv:1:" "$work/stderr" || { echo "message does not name line 1:"; head -3 "$work/stderr"; return 1; }
}
check "CSV header x_mm,x_um,y,z (two x columns): exit 2, message names line 1" two_x_columns x-mm-um x_mm,x_um,y,z
check "CSV header x_mm,x_mm,y,z (x twice): exit 2, message names line 1" two_x_columns x-mm-mm x_mm,x_mm,y,z

{ for i in $(seq 1 48); do printf 'c%d,' "$i"; done; printf 'x,y,z'; for i in $(seq 49 97); do printf ',c%d' "$i"; done; echo
  awk 'NF { for (i = 1; i <= 48; i++) printf "%d,", i; printf "%s,%s,%s", $1, $2, $3
            for (i = 49; i <= 97; i++) printf ",%d", i; print "" }' "$work/pts8.txt"; } >"$work/wide.csv"
wide_csv() {
  [ "$(head -1 "$work/wide.csv" | awk -F, '{ print NF }')" = 100 ] || { echo "fixture: header is not 100 columns"; return 1; }
  vessels_are "1:8" "$work/wide.csv"
}
check "CSV with 100 columns (x, y, z in the middle): read, 8 points" wide_csv

# ---------------------------------------------------------------- 5. resource limits
segments_bound() {
  refused 2 timeout 5 "$T" metrics -q --segments 5000 "$work/h45.txt" || return 1
  grep -qw 1000 "$work/stderr" || { echo "message does not give the bound 1000:"; head -3 "$work/stderr"; return 1; }
}
check "--segments 5000: exit 2, message gives the bound 1000" segments_bound

printf '0 0 0\n2e8 1e7 0\n4e8 0 3e7\n6e8 -1e7 0\n8e8 0 0\n' >"$work/far5.txt"
density_bound() {   # five points 2e8 mm apart at 3/mm would be 2.4e9 samples: more than 1e5 a point
  run timeout 10 "$T" metrics -q --rates 3/mm,10 "$work/far5.txt"
  expect_rc 0 || return 1
  local got; got=$(awk -F'\t' 'NR > 1 { printf "%s%s:%s", sep, $3, $NF; sep = " " }' "$work/stdout")
  [ "$got" = "3/mm:too-many-samples 10:ok" ] || { echo "rate:status '$got'"; return 1; }
}
check "3/mm on five points 2e8 mm apart: too-many-samples at once (more than 1e5 a point), 10X still ok" density_bound

"$T" phantom --shape helix --points 1500 >"$work/p1500.txt"
segments_in_little_memory() {
  (ulimit -v 400000; exec timeout 120 "$T" metrics -q --jobs 1 --segments 1000 "$work/p1500.txt") \
    >"$work/stdout" 2>"$work/stderr"; rc=$?
  case $rc in
    0) [ "$(wc -l <"$work/stdout")" = 5 ] || { echo "exit 0 but $(wc -l <"$work/stdout") lines, expected 5"; return 1; } ;;
    1) has_message ;;
    *) echo "exit $rc (timeout or signal), expected 0, or 1 with a message"; head -5 "$work/stderr"; return 1 ;;
  esac
}
if grep -q __asan_init "$T" 2>/dev/null; then
  skip "--segments 1000 on 1500 points under ulimit -v 400000: exit 0, or 1 with a message" "AddressSanitizer build"
else
  check "--segments 1000 on 1500 points under ulimit -v 400000: exit 0, or 1 with a message" segments_in_little_memory
fi

# Memory running out part-way: every limit gives either the whole table or nothing and a message.
# The limits start where the program (and the libraries it loads) can start at all on this machine.
no_partial_table() {
  local v rc hit=0 base=10000
  until (ulimit -v $base; exec "$T" --version) >/dev/null 2>&1; do
    base=$((base + 5000)); [ $base -le 400000 ] || { echo "the program does not start under 400 MB"; return 1; }
  done
  for v in $base $((base + 10000)) $((base + 20000)) $((base + 40000)); do
    (ulimit -v $v; exec timeout 120 "$T" metrics -q --jobs 1 --segments 1000 "$work/p1500.txt") \
      >"$work/stdout" 2>"$work/stderr"; rc=$?
    case $rc in
      0) [ "$(wc -l <"$work/stdout")" = 5 ] || { echo "limit $v KB: exit 0 with a partial table"; return 1; } ;;
      1) [ ! -s "$work/stdout" ] || { echo "limit $v KB: exit 1 after writing rows"; return 1; }
         grep -q 'out of memory' "$work/stderr" || { echo "limit $v KB: no message"; return 1; }; hit=1 ;;
      *) echo "limit $v KB: exit $rc"; head -3 "$work/stderr"; return 1 ;;
    esac
  done
  [ $hit = 1 ] || echo "(no limit ran out of memory on this machine)"
}
if grep -q __asan_init "$T" 2>/dev/null; then
  skip "memory running out: the whole table, or nothing and a message" "AddressSanitizer build"
else
  check "memory running out: the whole table, or nothing and a message" no_partial_table
fi

"$T" phantom --shape helix --count 20 --sigma 0.05 --seed 5 >"$work/h20.txt"
many_threads() {
  "$T" metrics -q --jobs 1 "$work/h20.txt" >"$work/h20-1.tsv" || { echo "--jobs 1 failed"; return 1; }
  OMP_NUM_THREADS=100000 run timeout 60 "$T" metrics -q "$work/h20.txt"
  expect_rc 0 && same_bytes "$work/h20-1.tsv" "$work/stdout"
}
check "OMP_NUM_THREADS=100000: exit 0, output identical to --jobs 1" many_threads

# ---------------------------------------------------------------- 6. output hygiene
mkdir "$work/n"
cp "$work/h45.txt" "$work/n/a"$'\t'"b.txt"; cp "$work/h45.txt" "$work/n/a"$'\n'"b.txt"
odd_names() {   # sets $work/stdout to metrics --rates 1 of the two odd names, run in $work/n
  run in_dir "$work/n" "$T" metrics -q --rates 1 "a"$'\t'"b.txt" "a"$'\n'"b.txt"
  expect_rc 0
}
fields_per_row() {
  odd_names || return 1
  [ "$(wc -l <"$work/stdout")" = 3 ] || { echo "$(wc -l <"$work/stdout") lines, expected a header and 2 rows:"; cat -A "$work/stdout" | cut -c1-60; return 1; }
  local columns; columns=$("$T" metrics --help | tr -d '\n' | sed 's/.*Columns://; s/\..*//' | wc -w)
  awk -F'\t' -v n="$columns" 'NF != n { print "line " NR ": " NF " fields, --help lists " n; bad = 1 } END { exit bad }' "$work/stdout"
}
check "file names with TAB and newline: 3 lines, every one with the fields --help lists" fields_per_row
file_column_escaped() {
  odd_names || return 1
  local got; got=$(awk -F'\t' 'NR > 1 { printf "%s%s", sep, $1; sep = " " }' "$work/stdout")
  [ "$got" = 'a\tb.txt a\nb.txt' ] || { echo "file column '$got', expected 'a\\tb.txt a\\nb.txt'"; return 1; }
}
check "file names with TAB and newline: file column reads a\\tb.txt and a\\nb.txt" file_column_escaped

{ echo vessel,x,y,z; csv_rows $'\x1b[31mred'; } >"$work/esc.csv"
esc_label() {
  run "$T" metrics -q --rates 1 "$work/esc.csv"
  expect_rc 0 || return 1
  ! grep -q $'\x1b' "$work/stdout" || { echo "a raw ESC byte in the output"; return 1; }
  local got; got=$(awk -F'\t' 'NR == 2 { print $2 }' "$work/stdout")
  [ "$got" = '\x1b[31mred' ] || { echo "label '$got', expected '\\x1b[31mred'"; return 1; }
}
check "CSV group value with an ESC byte: no ESC in the output, label reads \\x1b[31mred" esc_label

esc_name=$work/bad$'\x1b'"[2J.txt"
cp "$work/bad.txt" "$esc_name"
esc_message() {
  refused 2 "$T" metrics -q "$esc_name" || return 1
  ! grep -q $'\x1b' "$work/stderr" || { echo "a raw ESC byte in the message:"; cat -A "$work/stderr" | head -3; return 1; }
}
check "malformed file named with an ESC byte: no raw ESC in the message" esc_message
esc_message_names_file() {
  refused 2 "$T" metrics -q "$esc_name" || return 1
  grep -qF "$work/bad\\x1b[2J.txt:2:" "$work/stderr" || { echo "message does not read $work/bad\\x1b[2J.txt:2:"; cat -A "$work/stderr" | head -3; return 1; }
}
check "malformed file named with an ESC byte: message names it as bad\\x1b[2J.txt:2:" esc_message_names_file

close_rates() {
  run "$T" metrics -q --rates 1,1.000001 "$work/h45.txt"
  expect_rc 0 || return 1
  local got; got=$(awk -F'\t' 'NR > 1 { printf "%s%s", sep, $3; sep = " " }' "$work/stdout")
  [ "$got" = "1 1.000001" ] || { echo "rate labels '$got', expected '1 1.000001'"; return 1; }
}
check "--rates 1,1.000001: two rows with rate labels 1 and 1.000001" close_rates
check "--rates 1,1 (a rate twice): exit 2" refused 2 "$T" metrics -q --rates 1,1 "$work/h45.txt"

printf '10 10 10\n11 10 10\n12 11 10\n13 13 11\n14 16 13\n' >"$work/voxels.dat"
check "--voxel 1x1x1junk: exit 2" refused 2 "$T" metrics -q --voxel 1x1x1junk "$work/voxels.dat"
check "--voxel 1x1: exit 2" refused 2 "$T" metrics -q --voxel 1x1 "$work/voxels.dat"

# ---------------------------------------------------------------- 7. a second adversarial pass
{ echo 'x,y,z,vessel'; csv_rows 'v#1' 1 4 | awk -F, '{ print $2 "," $3 "," $4 "," $1 }'
  csv_rows 'v#2' 5 8 | awk -F, '{ print $2 "," $3 "," $4 "," $1 }'; } >"$work/hash.csv"
check "a # inside a CSV value is part of the value: vessels v#1 and v#2" vessels_are "v#1:4 v#2:4" "$work/hash.csv"
{ echo '"vessel",x,y,z'; csv_rows a 1 4; csv_rows b 5 8; } >"$work/quoted.csv"
check "a quoted header name (\"vessel\") is read: vessels a and b" vessels_are "a:4 b:4" "$work/quoted.csv"
awk 'NF { gsub(/ /, " , "); print }' "$work/pts8.txt" >"$work/spaced-commas.txt"
check "plain text '1 , 2 , 3' (spaces around commas) is read" vessels_are "1:8" "$work/spaced-commas.txt"

"$T" phantom --shape helix --count 60 --points 300 >"$work/medium.txt"
hup_ignored() {     # started with HUP ignored (nohup): a HUP does not stop the run
  mkdir -p "$work/hup"
  ( trap '' HUP; exec "$T" metrics -q --jobs 1 --rates 1000 -o "$work/hup/out.tsv" "$work/medium.txt" ) &
  local pid=$!
  sleep 0.3; kill -HUP "$pid" 2>/dev/null
  reap "$pid" 120; local status=$?
  [ "$status" = 0 ] || { echo "exit $status after HUP"; return 1; }
  [ "$(wc -l <"$work/hup/out.tsv")" = 61 ] || { echo "out.tsv incomplete"; return 1; }
}
check "a run started under nohup (HUP ignored) survives a HUP and writes its result" hup_ignored

to_stdout_link() {
  "$T" metrics -q --rates 1 -o /dev/stdout "$work/h3.txt" | cat >"$work/piped.tsv" || return 1
  same_bytes "$work/h3.tsv" "$work/piped.tsv" || return 1
  printf 'precious\n' >"$work/log"
  { "$T" metrics -q --rates 1 -o /dev/stdout "$work/h3.txt"; } >>"$work/log" || return 1
  [ "$(head -1 "$work/log")" = precious ] || { echo "the file behind >> was replaced"; return 1; }
  [ "$(wc -l <"$work/log")" = 5 ] || { echo "log has $(wc -l <"$work/log") lines, expected 5"; return 1; }
}
check "-o /dev/stdout into a pipe, and appended with >>: written through, nothing replaced" to_stdout_link

symlink_loop() {
  mkdir -p "$work/loop" && ln -sfn B "$work/loop/A" && ln -sfn A "$work/loop/B"
  refused 2 "$T" metrics -q --rates 1 -o "$work/loop/A" "$work/h3.txt" || return 1
  [ -L "$work/loop/A" ] && [ -L "$work/loop/B" ] || { echo "a link of the loop was replaced"; return 1; }
}
check "-o a symlink loop: exit 2, the links untouched" symlink_loop

"$T" phantom --shape helix --count 200 >"$work/h200.txt"
file_size_limit() {
  mkdir -p "$work/fs"
  (ulimit -f 1; exec "$T" metrics -q --rates 1,2 -o "$work/fs/out.tsv" "$work/h200.txt") 2>"$work/stderr"
  local status=$?
  [ "$status" = 1 ] || { echo "exit $status, expected 1"; return 1; }
  has_message || return 1
  [ -z "$(ls -A "$work/fs")" ] || { echo "left in the directory: $(ls -A "$work/fs")"; return 1; }
}
check "ulimit -f 1: exit 1 with a message, no file left" file_size_limit

stderr_closed() {
  awk '{ print } NR == 5 { print }' "$work/h3.txt" >"$work/rep.txt"
  "$T" metrics --rates 1 -o "$work/closed.tsv" "$work/rep.txt" 2>&- || return 1
  [ "$(head -c 4 "$work/closed.tsv")" = file ] || { echo "the result starts with: $(head -1 "$work/closed.tsv")"; return 1; }
}
check "standard error closed: messages do not land in the result" stderr_closed

empty_name_first() {
  local t0 t1; t0=$(date +%s.%N)
  refused 2 "$T" "${slow[@]}" -o '' "$work/slow.txt" || return 1
  t1=$(date +%s.%N); elapsed_below "$t0" "$t1" 1 || { echo "took more than 1 s: computed first"; return 1; }
}
check "-o '' (empty name): exit 2 before computing" empty_name_first
too_long_first() {
  local t0 t1; t0=$(date +%s.%N)
  refused 2 "$T" "${slow[@]}" -o "$work/$(printf 'n%.0s' $(seq 256))" "$work/slow.txt" || return 1
  t1=$(date +%s.%N); elapsed_below "$t0" "$t1" 1 || { echo "took more than 1 s: computed first"; return 1; }
}
check "-o with a 256-byte name: exit 2 before computing" too_long_first

esc_in_option() {
  run "$T" metrics --trim $'\e[2J' "$work/h3.txt"
  expect_rc 2 || return 1
  ! grep -q $'\e' "$work/stderr" || { echo "raw ESC in the message"; return 1; }
}
check "an option value with ESC: exit 2, the message escapes it" esc_in_option
esc_in_unknown() {
  run "$T" metrics $'--\e[2J' "$work/h3.txt"
  expect_rc 2 || return 1
  ! grep -q $'\e' "$work/stderr" || { echo "raw ESC in the message"; return 1; }
}
check "an unknown option with ESC: exit 2, the message escapes it" esc_in_unknown
check "--voxel 1x1x0x1 (hexadecimal): exit 2" refused 2 "$T" metrics -q --voxel 1x1x0x1 "$work/voxels.dat"
check "--voxel 0x2x3x4 (hexadecimal): exit 2" refused 2 "$T" metrics -q --voxel 0x2x3x4 "$work/voxels.dat"
check "--rates 1,,2 (an empty rate): exit 2" refused 2 "$T" metrics -q --rates 1,,2 "$work/h3.txt"
check "--rate ' 10' (leading space): exit 2" refused 2 "$T" profile -q --rate ' 10' "$work/h3.txt"

stdin_is_output() {
  mkdir -p "$work/si" && cp "$work/h3.txt" "$work/si/in.txt" && cp "$work/h3.txt" "$work/si/copy.txt"
  refused 2 "$T" metrics -q --rates 1 -o "$work/si/in.txt" - <"$work/si/in.txt" || return 1
  cmp -s "$work/si/in.txt" "$work/si/copy.txt" || { echo "the input was changed"; return 1; }
}
check "- as input with -o naming the file on standard input: exit 2, input unchanged" stdin_is_output

# ---------------------------------------------------------------- 8. the third adversarial pass
# Each check below failed on the program before its fix (issue: "Nothing lost, nothing misread").
PYTHON=${PYTHON:-/usr/bin/python3}     # Debian's, with numpy and h5py (the test stage's packages)

sidecar_is_input() {    # sidecar_is_input: FILE.provenance.tsv is an input, as a copy or through a link
  local dir=$work/sc; mkdir -p "$dir"
  cp "$work/h3.txt" "$dir/out.tsv.provenance.tsv"; cp "$work/h3.txt" "$dir/copy.txt"
  refused 2 "$T" metrics -q -o "$dir/out.tsv" "$dir/out.tsv.provenance.tsv" --format text || return 1
  cmp -s "$dir/out.tsv.provenance.tsv" "$dir/copy.txt" || { echo "the input was overwritten"; return 1; }
  [ ! -e "$dir/out.tsv" ] || { echo "out.tsv written"; return 1; }
  cp "$work/h3.txt" "$dir/data.txt"; ln -s data.txt "$dir/r.tsv.provenance.tsv"
  refused 2 "$T" metrics -q -o "$dir/r.tsv" "$dir/data.txt" || return 1
  cmp -s "$dir/data.txt" "$dir/copy.txt" || { echo "the input behind the link was overwritten"; return 1; }
  [ -z "$(ls -A "$dir" | grep tortuosity)" ] || { echo "temporary files left"; ls -A "$dir"; return 1; }
}
check "a provenance file that is an input (a copy, or a link to one): exit 2, the input intact" sidecar_is_input

failed_sidecar_keeps_result() {   # the sidecar cannot be written (ulimit -f): the old result and sidecar stay
  local dir=$work/fs long; mkdir -p "$dir/in"; long=$(printf 'n%.0s' {1..150})
  for i in $(seq 30); do cp "$work/h3.txt" "$dir/in/$long$i.txt"; done
  "$T" metrics -q --rates 1 -o "$dir/r.tsv" "$work/h3.txt" || return 1
  cp "$dir/r.tsv" "$dir/r.old"; cp "$dir/r.tsv.provenance.tsv" "$dir/p.old"
  (ulimit -f 1; exec "$T" metrics -q --rates 1 --shard 1/1000000 -o "$dir/r.tsv" "$dir"/in/*.txt) \
    >"$work/stdout" 2>"$work/stderr"; rc=$?
  expect_rc 1 && has_message || return 1
  cmp -s "$dir/r.tsv" "$dir/r.old" || { echo "the result was replaced"; return 1; }
  cmp -s "$dir/r.tsv.provenance.tsv" "$dir/p.old" || { echo "the provenance was replaced"; return 1; }
  [ -z "$(ls -A "$dir" | grep tortuosity)" ] || { echo "temporary files left"; ls -A "$dir"; return 1; }
}
check "the provenance cannot be written (ulimit -f 1, 30 long names): exit 1, old result and provenance kept" \
  failed_sidecar_keeps_result

sidecar_into_read_only() {    # as an unprivileged user: the sidecar links into a directory it cannot write
  local dir ro; dir=$(mktemp -d /tmp/tortuosity-ro.XXXXXX); ro=$dir/ro
  mkdir "$ro"; chmod 755 "$dir"; cp "$work/h3.txt" "$dir/h3.txt"; ln -s ro/p.tsv "$dir/r.tsv.provenance.tsv"
  chmod 555 "$ro"
  local as=(); [ "$(id -u)" = 0 ] && { chown -R nobody "$dir"; chown root "$ro"; as=(setpriv --reuid=nobody --regid=nogroup --clear-groups); }
  "${as[@]}" "$T" metrics -q --rates 1 -o "$dir/r.tsv" "$dir/h3.txt" >"$work/stdout" 2>"$work/stderr"; rc=$?
  local left; left=$(ls -A "$dir")
  chmod -R u+w "$dir"; rm -rf "$dir"
  expect_rc 2 && has_message || return 1
  [ "$left" = "$(printf 'h3.txt\nr.tsv.provenance.tsv\nro')" ] || { echo "left behind: $left"; return 1; }
}
if [ "$(id -u)" != 0 ] || command -v setpriv >/dev/null; then
  check "a provenance link into a read-only directory (unprivileged): exit 2 before computing, nothing written" \
    sidecar_into_read_only
else
  skip "a provenance link into a read-only directory" "root without setpriv"
fi

concurrent_runs() {     # two runs write one -o at once: result and provenance always from the same run
  local dir=$work/cc i bad=0; mkdir -p "$dir"
  for i in $(seq 20); do
    "$T" metrics -q --rates 1,2 -o "$dir/c.tsv" "$work/h3.txt" & "$T" metrics -q --rates 1,2 -o "$dir/c.tsv" "$work/h50.txt" &
    wait
    local rows input; rows=$(wc -l <"$dir/c.tsv"); input=$(awk -F'\t' '$1 == "input" { print $2 }' "$dir/c.tsv.provenance.tsv")
    case "$rows:$input" in 7:*/h3.txt|101:*/h50.txt) ;; *) bad=$((bad + 1)) ;; esac
  done
  [ $bad = 0 ] || { echo "$bad of 20 trials: the result of one run, the provenance of the other"; return 1; }
}
check "two runs writing one -o at once, 20 trials: result and provenance of the same run" concurrent_runs

tmp_files_exclusive() {   # every file made beside -o is created with O_EXCL (a planted link is never followed)
  command -v strace >/dev/null || { echo "strace is not installed (test stage)"; return 1; }
  local dir=$work/ex; mkdir -p "$dir"
  ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0 \
    strace -f -qq -e trace=openat -o "$work/trace" "$T" metrics -q --rates 1 -o "$dir/out.tsv" "$work/h3.txt" || return 1
  local made; made=$(grep -c '\.tortuosity-' "$work/trace")
  [ "$made" -ge 2 ] || { echo "$made temporary files seen, expected the result's and its provenance's"; return 1; }
  ! grep '\.tortuosity-' "$work/trace" | grep -v 'O_EXCL' | grep -q . \
    || { echo "a temporary file opened without O_EXCL:"; grep '\.tortuosity-' "$work/trace" | grep -v O_EXCL; return 1; }
}
check "the temporary files beside -o (result and provenance) are created with O_CREAT|O_EXCL" tmp_files_exclusive

{ echo vessel,x,y,z; csv_rows 1 1 4; awk 'NF && ++n >= 5 { print "1," $1 + 50 "," $2 "," $3 }' "$work/pts8.txt"
  csv_rows 2 1 4; awk 'NF && ++n >= 5 { print "2," $1 + 50 "," $2 "," $3 }' "$work/pts8.txt"; } >"$work/ids12.csv"
sed 's/^2,/3,/' "$work/ids12.csv" >"$work/ids13.csv"
split_keeps_ids() {   # split_keeps_ids FILE WANT
  run "$T" metrics -q --rates 1 --split-gap 20 "$1"
  expect_rc 0 || return 1
  local got; got=$(awk -F'\t' 'NR > 1 { printf "%s%s", sep, $2; sep = " " }' "$work/stdout")
  [ "$got" = "$2" ] || { echo "labels '$got', expected '$2'"; return 1; }
}
check "--split-gap on a CSV with vessels 1 and 2: labels 1:1 1:2 2:1 2:2" split_keeps_ids "$work/ids12.csv" "1:1 1:2 2:1 2:2"
check "--split-gap on a CSV with vessels 1 and 3: labels 1:1 1:2 3:1 3:2" split_keeps_ids "$work/ids13.csv" "1:1 1:2 3:1 3:2"

long230=$(printf 'q%.0s' {1..240})
{ echo vessel,x,y,z; for g in "${long230}A" "${long230}B"; do
    csv_rows "$g" 1 4; awk -v g="$g" 'NF && ++n >= 5 { print g "," $1 + 50 "," $2 "," $3 }' "$work/pts8.txt"; done; } >"$work/long-ids.csv"
long_labels_distinct() {
  run "$T" metrics -q --rates 1 --split-gap 20 "$work/long-ids.csv"
  expect_rc 0 || return 1
  [ "$(awk -F'\t' 'NR > 1 { print $2 }' "$work/stdout" | sort -u | wc -l)" = 4 ] \
    || { echo "labels collide:"; awk -F'\t' 'NR > 1 { print substr($2, 230) }' "$work/stdout"; return 1; }
}
check "--split-gap on two 241-byte ids that differ at the end: four distinct labels" long_labels_distinct

first_r_min() {     # the r_min of the first row of the last run's table, found by its header
  awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) if ($i == "r_min") c = i } NR == 2 { print $c }' "$work/stdout"
}
{ echo x,y,z,vessel_diameter; awk 'NF { print $1 "," $2 "," $3 ",2" }' "$work/pts8.txt"; } >"$work/diam.csv"
diameter_advice() {   # the warning's advice, followed, gives radius 1 from diameter 2
  run "$T" metrics --rates 1 "$work/diam.csv"
  local advice; advice=$(grep -o -- '--columns [^ ]*' "$work/stderr")
  [ -n "$advice" ] || { echo "no advice in the warning:"; head -3 "$work/stderr"; return 1; }
  run "$T" metrics -q --rates 1 $advice "$work/diam.csv"
  expect_rc 0 || return 1
  [ "$(first_r_min)" = 1 ] || { echo "r_min $(first_r_min), expected 1 (half of 2)"; return 1; }
}
check "CSV column vessel_diameter: following the warning's advice gives r_min 1 for diameter 2" diameter_advice
vtp_with() {    # vtp_with ARRAY-NAME FILE: 8 points of pts8.txt, one line, one point array of value 2
  { printf '<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0"><PolyData>\n'
    printf '<Piece NumberOfPoints="8" NumberOfLines="1"><Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">\n'
    awk 'NF { print $1, $2, $3 }' "$work/pts8.txt"
    printf '</DataArray></Points><PointData><DataArray type="Float64" Name="%s" format="ascii">2 2 2 2 2 2 2 2</DataArray></PointData>\n' "$1"
    printf '<Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3 4 5 6 7</DataArray>\n'
    printf '<DataArray type="Int64" Name="offsets" format="ascii">8</DataArray></Lines></Piece></PolyData></VTKFile>\n'; } >"$2"
}
vtp_with Diameter "$work/diameter.vtp"; vtp_with vessel_diameter "$work/vdiam.vtp"
r_min_is() {    # r_min_is WANT FILE OPTIONS...
  local want=$1 file=$2; shift 2
  run "$T" metrics -q --rates 1 "$@" "$file"
  expect_rc 0 || return 1
  [ "$(first_r_min)" = "$want" ] || { echo "r_min '$(first_r_min)', expected $want"; return 1; }
}
check "VTK point array Diameter (2): read as radius 1" r_min_is 1 "$work/diameter.vtp"
vtk_diameter_advice() {
  run "$T" metrics --rates 1 "$work/vdiam.vtp"
  local advice; advice=$(grep -o -- '--radius-array [^ ]*' "$work/stderr")
  [ -n "$advice" ] || { echo "no advice in the warning:"; head -3 "$work/stderr"; return 1; }
  r_min_is 1 "$work/vdiam.vtp" $advice
}
check "VTK array vessel_diameter: following the warning's advice gives r_min 1 for diameter 2" vtk_diameter_advice

{ echo a,b,c; awk 'NF { print $1 "," $2 "," $3 }' "$work/pts8.txt"; } >"$work/abc.csv"
check "--columns a,a,c (one column for x and y): exit 2" refused 2 "$T" metrics -q --columns a,a,c "$work/abc.csv"
check "--columns a,b,c,a (x is also the radius): exit 2" refused 2 "$T" metrics -q --columns a,b,c,a "$work/abc.csv"

h5_fixture() {  # h5_fixture KIND FILE: a section morphology with one defect
  "$PYTHON" - "$1" "$2" <<'PY'
import sys, h5py, numpy as np
kind, path = sys.argv[1], sys.argv[2]
pts = np.array([[i, 0.1 * i * i, 0.01 * i ** 3, 1.0] for i in range(10)], dtype=np.float64)
v2 = kind.startswith("latest") or kind.endswith("-checksum")   # version 2 object headers, with checksums
with h5py.File(path, "w", libver="latest" if v2 else "earliest") as f:
    if kind == "partial":
        d = f.create_dataset("points", shape=(10, 4), dtype="f8", chunks=(2, 4))
        d[0:4] = pts[0:4]                          # rows 4-9 never written
    else:
        f.create_dataset("points", data=pts)
    f.create_dataset("structure", data=np.array([[0, -1]], dtype=np.int32))
    f.create_dataset("connectivity", data=np.zeros((0, 2), dtype=np.int32))
    addr = h5py.h5o.get_info(f["structure"].id).addr
    if kind in ("root-header-past-end", "root-checksum"):
        addr = h5py.h5o.get_info(f["/"].id).addr
    if kind == "points-checksum":
        addr = h5py.h5o.get_info(f["points"].id).addr
if kind.endswith("header-past-end"):               # the structure's (or the root group's) object header
    b = bytearray(open(path, "rb").read())         # (version 1) 1 MB long
    assert b[addr] == 1, "not a version 1 object header"
    b[addr + 8:addr + 12] = (1 << 20).to_bytes(4, "little")
    open(path, "wb").write(bytes(b))
if kind.endswith("-checksum"):                     # the first message's type byte changed: the checksum fails
    b = bytearray(open(path, "rb").read())
    assert b[addr:addr + 4] == b"OHDR", "not a version 2 object header"
    flags = b[addr + 5]
    b[addr + 6 + (16 if flags & 0x20 else 0) + (4 if flags & 0x10 else 0) + (1 << (flags & 3))] ^= 0x40
    open(path, "wb").write(bytes(b))
if kind == "precision0":                           # the structure's int32 type message, its precision set to 0
    b = bytearray(open(path, "rb").read())
    sig = bytes([0x10, 0x08, 0, 0, 4, 0, 0, 0, 0, 0, 32, 0])
    k = b.find(sig)
    assert k >= 0, "no int32 type message found"
    b[k + 10:k + 12] = b"\0\0"
    open(path, "wb").write(bytes(b))
PY
}
h5_refused() {  # h5_refused KIND WORDS: exit 2 and the message says WORDS
  h5_fixture "$1" "$work/$1.h5" || { echo "could not make the fixture"; return 1; }
  refused 2 "$T" metrics -q --rates 1 "$work/$1.h5" || return 1
  grep -q "$2" "$work/stderr" || { echo "message does not say '$2':"; head -3 "$work/stderr"; return 1; }
}
check "HDF5 /points chunked with only some chunks written: exit 2, 'written only in part'" h5_refused partial "written only in part"
check "HDF5 integer type of precision 0: exit 2 (no crash), 'bits'" h5_refused precision0 "bits"
h5_one_line() {  # h5_one_line KIND WORDS: refused before libhdf5 reads it: one line, nothing from libhdf5 at exit
  h5_refused "$1" "$2" || return 1
  [ "$(wc -l <"$work/stderr")" = 1 ] && ! grep -q "HDF5" "$work/stderr" || { echo "stderr:"; head -3 "$work/stderr"; return 1; }
}
check "HDF5 object header past the end of the data: exit 2, one line, nothing from libhdf5 at exit" \
  h5_one_line header-past-end "past the end"
check "HDF5 root group's object header past the end of the data: exit 2, one line, nothing at exit" \
  h5_one_line root-header-past-end "root group: its object header runs past the end"
check "HDF5 root group's version 2 object header failing its checksum: exit 2, one line, nothing at exit" \
  h5_one_line root-checksum "root group: its object header does not match its checksum"
check "HDF5 /points' version 2 object header failing its checksum: exit 2, one line, nothing at exit" \
  h5_one_line points-checksum "'/points': its object header does not match its checksum"
h5_latest_read() {  # a sound file of version 2 headers: every checksum agrees, and it is read
  h5_fixture latest "$work/latest.h5" || return 1
  run "$T" metrics -q --rates 1 "$work/latest.h5"
  expect_rc 0 && [ "$(wc -l <"$work/stdout")" = 2 ] && [ ! -s "$work/stderr" ]
}
check "HDF5 written with version 2 object headers (libver latest): read, no message" h5_latest_read

hdf5_little_memory() {  # every limit from 40 to 66 MB: exit 1 with a message (never a crash, never exit 2)
  h5_fixture plain "$work/plain.h5" || return 1
  local v
  for v in $(seq 40000 2000 66000); do
    (ulimit -v $v; exec "$T" metrics -q --rates 1 "$work/plain.h5") >"$work/stdout" 2>"$work/stderr"; rc=$?
    case $rc in
      0) ;;
      1) has_message || { echo "limit $v KB"; return 1; } ;;
      *) echo "limit $v KB: exit $rc"; head -2 "$work/stderr"; return 1 ;;
    esac
  done
}
if grep -q __asan_init "$T" 2>/dev/null; then
  skip "HDF5 under ulimit -v 40-66 MB: exit 0 or 1 with a message" "AddressSanitizer build"
else
  check "HDF5 under ulimit -v 40-66 MB: exit 0 or 1 with a message, never a crash" hdf5_little_memory
fi

urandom_at_once() {  # a device of binary bytes is refused from its first chunk, not read to the memory limit
  local t0 t1
  t0=$(date +%s.%N); refused 2 timeout 20 "$T" metrics -q /dev/urandom || return 1; t1=$(date +%s.%N)
  grep -q "NUL bytes" "$work/stderr" && elapsed_below "$t0" "$t1" 5 || { echo "after $t0 .. $t1:"; head -2 "$work/stderr"; return 1; }
}
check "metrics /dev/urandom: exit 2 at once, 'NUL bytes'" urandom_at_once
line_at_once() {   # line_at_once LINE PRODUCER...: a line that does not end, on a pipe: refused at once, by its number
  local line=$1 t0 t1; shift
  t0=$(date +%s.%N)
  ("$@" | head -c 200000000 | exec timeout 20 "$T" metrics -q -) >"$work/stdout" 2>"$work/stderr"; rc=$?
  t1=$(date +%s.%N)
  expect_rc 2 && grep -q "^-:$line: more than 1048576 bytes without a line break" "$work/stderr" \
    && elapsed_below "$t0" "$t1" 5 || { echo "after $t0 .. $t1:"; head -2 "$work/stderr"; return 1; }
}
endless_line() { yes xxxxxxxx | tr -d '\n'; }
points_then_endless_line() { awk 'NF && ++n <= 3' "$work/pts8.txt"; endless_line; }
check "a line that does not end, on a pipe: exit 2 at once, '-:1: more than 1048576 bytes'" line_at_once 1 endless_line
check "three points, then a line that does not end: exit 2 at once, '-:4:'" line_at_once 4 points_then_endless_line
long_comment_piped() {   # a comment of 1 MiB on a pipe (at the limit), then points: read
  { head -c 1048574 /dev/zero | tr '\0' x | sed 's/^/# /'; echo; cat "$work/pts8.txt"; } >"$work/long-comment.txt"
  run sh -c 'cat "$2" | exec "$1" metrics -q --rates 1 -' sh "$T" "$work/long-comment.txt"
  expect_rc 0
}
check "a comment line of 1 MiB, then points, on a pipe: exit 0" long_comment_piped
for p in 0.1x0.2 0.1,0.2 0.1x0.2x0.3x0.4 '' digits:4,digits:5; do
  check "--precision '$p': exit 2" refused 2 "$T" metrics -q --precision "$p" "$work/h3.txt"
done
help_lists_only_its_options() {  # profile and sufficient do not offer metrics' own options
  local c
  for c in profile sufficient metrics; do "$T" $c --help >"$work/help-$c.txt" || return 1; done
  for c in profile sufficient; do
    grep -qE -- '^ +--(null|uncertainty) ' "$work/help-$c.txt" && { echo "$c --help lists a metrics option"; return 1; }
  done
  grep -qE -- '^ +--uncertainty ' "$work/help-metrics.txt"
}
check "profile and sufficient --help list no option of metrics alone" help_lists_only_its_options
check "sufficient --vtk-names ours: exit 2 (it writes no VTK)" refused 2 "$T" sufficient -q --vtk-names ours "$work/h3.txt"
check "profile --vtk-names ours: accepted" "$T" profile -q --vtk-names ours "$work/h3.txt"

printf 'x;y;z\n0;0;0\n1,5;0;0\n2;1.234;0\n3;2;0\n4;3;1\n5;5;1\n' >"$work/marks.csv"
check "a semicolon CSV with 1,5 and 1.234: exit 2 (mixed decimal marks)" refused 2 "$T" metrics -q "$work/marks.csv"

closed_stdout() { "$T" metrics -q --rates 1 "$work/h3.txt" >&- 2>"$work/stderr"; rc=$?; [ $rc != 0 ] && has_message; }
check "metrics with standard output closed (>&-): not 0, a message" closed_stdout

"$T" phantom --shape helix --count 200 --points 200 >"$work/big.txt"
fsize_stdout() {    # fsize_stdout SINK: under ulimit -f 10, exit 0 into a pipe; into a file, 1 with a message
  local sink=$1
  case $sink in
    pipe) bash -c "ulimit -f 10; \"$T\" metrics -q --rates 1 \"$work/big.txt\" | wc -c" >"$work/stdout" 2>"$work/stderr"; rc=$?
          expect_rc 0 || return 1; [ "$(cat "$work/stdout")" -gt 20000 ] || { echo "only $(cat "$work/stdout") bytes"; return 1; } ;;
    null) bash -c "ulimit -f 10; exec \"$T\" metrics -q --rates 1 \"$work/big.txt\" >/dev/null" 2>"$work/stderr"; rc=$?
          expect_rc 0 ;;
    file) bash -c "ulimit -f 10; exec \"$T\" metrics -q --rates 1 \"$work/big.txt\" >\"$work/fs.out\"" 2>"$work/stderr"; rc=$?
          expect_rc 1 && has_message ;;
    phantom) bash -c "ulimit -f 10; exec \"$T\" phantom --points 100000 >\"$work/fs.out\"" 2>"$work/stderr"; rc=$?
          expect_rc 1 && has_message ;;
  esac
}
for sink in pipe null file phantom; do
  check "ulimit -f 10 with standard output a $sink: no SIGXFSZ (exit 0 where the sink has no limit, else 1)" fsize_stdout $sink
done

if [ -c /dev/full ]; then
  check "--list-metrics >/dev/full: exit 1, message" write_error "$T" metrics --list-metrics
  check "metrics --help >/dev/full: exit 1, message" write_error "$T" metrics --help
  check "--help >/dev/full: exit 1, message" write_error "$T" --help
fi

messages_say() {    # messages_say WORDS COMMAND...: exit 2 and the message has WORDS
  local words=$1; shift
  refused 2 "$@" || return 1
  grep -qF -- "$words" "$work/stderr" || { echo "message does not say '$words':"; head -3 "$work/stderr"; return 1; }
}
{ echo x,y,z; awk 'NF { print $1 "," $2 "," $3 }' "$work/pts8.txt"; } >"$work/plain.csv"
iconv -f UTF-8 -t UTF-16 "$work/plain.csv" >"$work/utf16.csv"
tr '\n' '\r' <"$work/plain.csv" >"$work/cr.csv"
check "a UTF-16 CSV: exit 2, 'UTF-16'" messages_say "UTF-16" "$T" metrics -q "$work/utf16.csv"
check "a CSV with CR-only line ends: exit 2, 'carriage return'" messages_say "carriage return" "$T" metrics -q "$work/cr.csv"
mkdir -p "$work/adir"
check "a directory as input: exit 2, 'is a directory'" messages_say "is a directory" "$T" metrics -q "$work/adir"
"$PYTHON" -c "
import sys; h = b\"{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }\x00\"; h += b' ' * (63 - len(h) % 64) + b'\n'
sys.stdout.buffer.write(b'\x93NUMPY\x01\x00' + len(h).to_bytes(2, 'little') + h + bytes(48))" >"$work/nul.npy"
npy_escape_once() {
  refused 2 "$T" metrics -q "$work/nul.npy" || return 1
  ! grep -qF '\\' "$work/stderr" || { echo "a doubled backslash:"; head -2 "$work/stderr"; return 1; }
}
check "an npy header with a NUL after '}': exit 2, the byte shown once (no doubled backslash)" npy_escape_once
{ printf '<?xml version="1.0"?>\n<VTKFile type="PolyData"><PolyData><Piece NumberOfPoints="2" NumberOfLines="1">\n'
  printf '<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 1 1</DataArray></Points>\n'
  printf '<Lines><DataArray type="UInt64" Name="connectivity" format="ascii">0 18446744073709551615</DataArray>\n'
  printf '<DataArray type="UInt64" Name="offsets" format="ascii">2</DataArray></Lines></Piece></PolyData></VTKFile>\n'; } >"$work/u64.vtp"
check "ASCII .vtp connectivity 18446744073709551615: exit 2, 'too large for an index'" \
  messages_say "too large for an index" "$T" metrics -q "$work/u64.vtp"
{ printf '# vtk DataFile Version 3.0\nx\nASCII\nDATASET POLYDATA\nPOINTS 3 double\n0 0 0 1 1 0 2 3 1\nLINES 1 4\n3 0 1 2\n'
  printf '\0\0\0\0\n'; } >"$work/nul.vtk"
check ".vtk with NUL bytes after the data: exit 2, the bytes shown (<00>)" messages_say "<00>" "$T" metrics -q "$work/nul.vtk"
printf '0 0 0\n0x10 1 0\n2 3 0\n3 4 1\n4 6 1\n' >"$work/hex.txt"
{ echo x,y,z; echo 0,0,0; echo 0x10,1,0; echo 2,3,0; echo 3,4,1; echo 4,6,1; } >"$work/hex.csv"
sed 's/1 1 1</0xAp0 1 1</' "$work/u64.vtp" | sed 's/18446744073709551615/1/; s/UInt64/Int64/g' >"$work/hex.vtp"
check "0x10 in a text coordinate: exit 2" refused 2 "$T" metrics -q "$work/hex.txt"
check "0x10 in a CSV coordinate: exit 2" refused 2 "$T" metrics -q "$work/hex.csv"
check "0xAp0 in an ASCII .vtp coordinate: exit 2" refused 2 "$T" metrics -q "$work/hex.vtp"
{ printf '# vtk DataFile Version 3.0\nnan\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n0 0 0\n1 0 0\n'
  printf 'nan 1 0\n3 1 0\nLINES 1 5\n4 0 1 2 3\n'; } >"$work/nan-point.vtk"
{ printf '<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0"><PolyData>\n'
  printf '<Piece NumberOfPoints="4" NumberOfLines="1"><Points>\n'
  printf '<DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 nan 1 0 3 1 0</DataArray>\n'
  printf '</Points><Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3</DataArray>\n'
  printf '<DataArray type="Int64" Name="offsets" format="ascii">4</DataArray></Lines></Piece></PolyData></VTKFile>\n'
} >"$work/nan-point.vtp"
bad_point_line() {   # bad_point_line FILE LINE: exit 2, the message names the point's line, not the cells'
  refused 2 "$T" metrics -q --rates 1 "$1" || return 1
  grep -qF "$1:$2: point 2:" "$work/stderr" || { echo "message does not name line $2:"; head -3 "$work/stderr"; return 1; }
}
check "legacy .vtk with a nan point used by LINES: exit 2 naming the point's line (8), not the LINES line" \
  bad_point_line "$work/nan-point.vtk" 8
check ".vtp with a nan point: exit 2 naming its Points DataArray's line (4), not <Lines>" \
  bad_point_line "$work/nan-point.vtp" 4

# Four points (0,0,0) (1,0,0) (2,1,0) (3,1,0) as raw appended Float64: a 4-byte count (96), then the data
z8='\x00\x00\x00\x00\x00\x00\x00\x00' one='\x00\x00\x00\x00\x00\x00\xf0\x3f'
two='\x00\x00\x00\x00\x00\x00\x00\x40' three='\x00\x00\x00\x00\x00\x00\x08\x40'
{ printf '<?xml version="1.0"?>\n<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt32">\n'
  printf '<PolyData><Piece NumberOfPoints="4" NumberOfLines="1"><Points>\n'
  printf '<DataArray type="Float64" NumberOfComponents="3" format="appended" offset="0"/></Points>\n'
  printf '<Lines><DataArray type="Int64" Name="connectivity" format="ascii">0 1 2 3</DataArray>\n'
  printf '<DataArray type="Int64" Name="offsets" format="ascii">4</DataArray></Lines></Piece></PolyData>\n'
  printf '<AppendedData encoding="raw">\n_\x60\x00\x00\x00'
  printf "$z8$z8$z8$one$z8$z8$two$one$z8$three$one$z8"
  printf '\n</AppendedData>\n</VTKFile>\n'; } >"$work/appended.vtp"
head -c -12 "$work/appended.vtp" >"$work/appended-cut.vtp"
appended_cut_short() {
  vessels_are "0:4" "$work/appended.vtp" || return 1
  messages_say "cut short" "$T" metrics -q --rates 1 "$work/appended-cut.vtp"
}
check ".vtp of raw appended data without its closing tags (cut short): exit 2, 'cut short'; whole, read" \
  appended_cut_short
not_applied() {     # not_applied WORDS OPTION... -- FILE: a warning names the option that does not apply
  local words=$1; shift
  run "$T" metrics --rates 1 "$@"
  expect_rc 0 || return 1
  grep -qF -- "$words" "$work/stderr" || { echo "no warning naming $words:"; head -3 "$work/stderr"; return 1; }
}
check "--columns on a text file: a warning" not_applied "--columns" --columns x,y,z "$work/h3.txt"
check "--radius-array on a CSV file: a warning" not_applied "--radius-array" --radius-array R "$work/plain.csv"
check "--voxel on a text file: a warning" not_applied "--voxel" --voxel 1x1x1 "$work/h3.txt"
check "sufficient -o s.vtp (writes a table): exit 2" refused 2 "$T" sufficient -q -o "$work/s.vtp" "$work/h3.txt"
check "phantom -o p.vtk (writes text): exit 2" refused 2 "$T" phantom -o "$work/p.vtk"
check "phantom --count 2000000: exit 2, the message gives the bound 1000000" \
  messages_say "1000000" "$T" phantom --count 2000000
"$PYTHON" -c "
import numpy as np, sys
a = np.array([[i * 0.25, 0, 0] for i in range(200)] + [[77 + 50 + i * 0.25, 1, 0] for i in range(200)])
np.save(sys.argv[1], a)" "$work/jump.npy"
jump_warned() {
  run "$T" metrics --rates 1 "$work/jump.npy"
  expect_rc 0 || return 1
  grep -qF -- "--split-gap" "$work/stderr" || { echo "no warning naming --split-gap:"; head -3 "$work/stderr"; return 1; }
}
check "an .npy with a 77 mm jump (300 times its steps) and no --split-gap: a warning naming --split-gap" jump_warned

{ cat "$work/h50.txt"; printf '\n0 0 0\n1 x 0\n'; } >"$work/late-bad.txt"
keep_going() {      # a mixed batch: the good files' vessels, as without the bad ones; each bad one named; exit 1
  "$T" metrics -q --rates 1,2 "$work/h3.txt" "$work/h50.txt" >"$work/good-only.tsv" || return 1
  run "$T" metrics -q --rates 1,2 --keep-going -o "$work/kg.tsv" "$work/h3.txt" "$work/bad.txt" \
    "$work/late-bad.txt" "$work/h50.txt"
  expect_rc 1 || return 1
  same_bytes "$work/good-only.tsv" "$work/kg.tsv" || return 1
  grep -qF "$work/bad.txt:2:" "$work/stderr" && grep -qF "$work/late-bad.txt:" "$work/stderr" \
    || { echo "a bad file is not named with its line:"; head -4 "$work/stderr"; return 1; }
  [ "$(awk -F'\t' '$1 == "input"' "$work/kg.tsv.provenance.tsv" | wc -l)" = 2 ] \
    || { echo "the provenance does not list the two good inputs"; return 1; }
}
check "--keep-going on good, bad and late-bad files: the good files' rows exactly, each bad file named, exit 1" keep_going
keep_going_shards() {   # the shards of a mixed batch join to the whole good result
  "$T" metrics -q --rates 1 "$work/h3.txt" "$work/h50.txt" >"$work/good1.tsv" || return 1
  local k
  for k in 1 2 3; do
    "$T" metrics -q --rates 1 --keep-going --shard $k/3 "$work/h3.txt" "$work/bad.txt" "$work/h50.txt" \
      >"$work/kgs-$k.tsv" 2>/dev/null; [ $? = 1 ] || { echo "shard $k: exit $?, expected 1"; return 1; }
  done
  { cat "$work/kgs-1.tsv"; tail -n +2 "$work/kgs-2.tsv"; tail -n +2 "$work/kgs-3.tsv"; } >"$work/kgs.tsv"
  same_bytes "$work/good1.tsv" "$work/kgs.tsv"
}
check "--keep-going --shard K/3 on a mixed batch: the three shards join to the good files' result" keep_going_shards
all_bad_kept_going() {   # --keep-going when every file is bad: exit 2, no table written
  run "$T" metrics -q --rates 1 --keep-going -o "$work/allbad.tsv" "$work/bad.txt" "$work/bad.txt"
  expect_rc 2 && has_message || return 1
  [ ! -e "$work/allbad.tsv" ] || { echo "a table was written:"; head -2 "$work/allbad.tsv"; return 1; }
}
check "--keep-going when every input file is bad: exit 2, no table" all_bad_kept_going
check "without --keep-going one bad file still stops the batch: exit 2, no rows" \
  refused 2 "$T" metrics -q --rates 1 "$work/h3.txt" "$work/bad.txt"

# ---------------------------------------------------------------- 9. inputs that never end, or too large to hold
# An input is read whole; what its first bytes already refuse is refused from them, and the rest stops
# at half the memory the run may use, each with exit 2 and a message naming the input.
endless_refused_at_once() {   # endless_refused_at_once FORMAT: /dev/zero refused from its first bytes
  local t0 t1
  t0=$(date +%s.%N)
  run timeout 20 "$T" metrics -q --format "$1" /dev/zero
  t1=$(date +%s.%N)
  expect_rc 2 && has_message || return 1
  grep -qF "/dev/zero" "$work/stderr" || { echo "message does not name /dev/zero:"; head -3 "$work/stderr"; return 1; }
  elapsed_below "$t0" "$t1" 2 || { echo "took $(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') s"; return 1; }
}
for fmt in text csv swc tre mrk angicart npy vtk vtp; do
  check "--format $fmt /dev/zero: exit 2 within 2 s, from its first bytes, message names it" endless_refused_at_once $fmt
done
check "/dev/zero as plain text: exit 2, 'NUL bytes'" messages_say "NUL bytes" "$T" metrics -q /dev/zero
too_large_file() {    # a sparse file of twice the machine's memory: refused before a byte is read
  local kb
  kb=$(awk '/^MemTotal:/ { print $2 }' /proc/meminfo)
  truncate -s $((2 * kb))K "$work/huge.txt" || { echo "cannot make a sparse file here"; return 1; }
  run timeout 5 "$T" metrics -q "$work/huge.txt"
  rm -f "$work/huge.txt"
  expect_rc 2 && grep -q "more than .* half the memory" "$work/stderr" \
    || { echo "exit $rc:"; head -3 "$work/stderr"; return 1; }
}
check "a file twice the machine's memory (sparse): exit 2 at once, 'more than ... half the memory'" too_large_file
endless_pipe() {      # text that never ends, under ulimit -v 1 GB: refused past 500 MB, not killed
  (ulimit -v 1000000; yes 'abc' | exec timeout 60 "$T" metrics -q -) >"$work/stdout" 2>"$work/stderr"; rc=$?
  expect_rc 2 && grep -q "standard input\|-: more than" "$work/stderr" \
    || { echo "exit $rc:"; head -3 "$work/stderr"; return 1; }
}
endless_hdf5() {      # HDF5 may have a user block before its signature: read up to the limit, then refused
  (ulimit -v 1000000; exec timeout 60 "$T" metrics -q --format hdf5 /dev/zero) >"$work/stdout" 2>"$work/stderr"; rc=$?
  expect_rc 2 && grep -q "more than" "$work/stderr" || { echo "exit $rc:"; head -3 "$work/stderr"; return 1; }
}
if grep -q __asan_init "$T" 2>/dev/null; then
  skip "yes abc | metrics - under ulimit -v 1 GB: exit 2, 'more than'" "AddressSanitizer build"
  skip "--format hdf5 /dev/zero under ulimit -v 1 GB: exit 2, 'more than'" "AddressSanitizer build"
else
  check "yes abc | metrics - under ulimit -v 1 GB: exit 2, 'more than'" endless_pipe
  check "--format hdf5 /dev/zero under ulimit -v 1 GB: exit 2, 'more than'" endless_hdf5
fi

echo "reliability: $passed passed, $failed failed"
exit 0
