#!/usr/bin/env bash
# pip install of the package from the source tree, offline, into a fresh virtual environment that
# sees Debian's setuptools and numpy: import tortuosity, its __version__ the program's, and a
# measurement equal to the command line's. Usage: pip-install.sh path/to/tortuosity REPO
set -uo pipefail
T=$(realpath "${1:?usage: pip-install.sh path/to/tortuosity REPO}")
REPO=${2:?usage: pip-install.sh path/to/tortuosity REPO}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0 failed=0
check() {
  local name=$1; shift
  if out=$("$@" 2>&1); then echo "ok   $name"; passed=$((passed + 1))
  else echo "FAIL $name"; echo "$out" | tail -8 | sed 's/^/     /'; failed=$((failed + 1)); fi
}
pip_install() {
  local before
  before=$(cd "$REPO" && git status --porcelain --untracked-files=all -- . ':!build')
  /usr/bin/python3 -m venv --system-site-packages "$work/venv" || return 1
  (cd "$REPO" && "$work/venv/bin/pip" install -q --no-index --no-build-isolation .) || return 1
  cd "$work" || return 1
  local version program
  version=$("$work/venv/bin/python" -c 'import tortuosity; print(tortuosity.__version__)') || return 1
  program=$("$T" --version | awk 'NR == 1 { print $2 }')
  [ "$version" = "$program" ] || { echo "__version__ $version, the program $program"; return 1; }
  "$work/venv/bin/python" -c 'import tortuosity, os; print(os.path.dirname(tortuosity.__file__))' \
    | grep -q "^$work/venv/" || { echo "the module imported is not the installed one"; return 1; }
  "$T" phantom --shape helix >"$work/helix.txt" || return 1
  local cli py
  cli=$("$T" metrics -q -r 10 "$work/helix.txt" | awk -F'\t' 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i }
        NR == 2 { print $c["AC"], $c["TT"], $c["D"] }')
  py=$("$work/venv/bin/python" - "$work/helix.txt" <<'PY'
import sys, tortuosity
(_, points), = tortuosity.read(sys.argv[1])
m = tortuosity.measure(points, rate=10)
print("%.9g %.9g %.9g" % (m["AC"], m["TT"], m["D"]))
PY
) || return 1
  [ "$cli" = "$py" ] || { echo "command line: $cli; pip-installed module: $py"; return 1; }
  [ "$before" = "$(cd "$REPO" && git status --porcelain --untracked-files=all -- . ':!build')" ] \
    || { echo "pip install left files in the source tree:"; (cd "$REPO" && git status --short); return 1; }
}
check "pip install --no-build-isolation . in a fresh venv: import, __version__ the program's, its numbers" pip_install
echo "pip: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
