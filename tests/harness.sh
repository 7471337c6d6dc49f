# The test scripts' common part, sourced by tests/end-to-end.sh and tests/reliability.sh:
# a scratch directory removed on exit, and check NAME COMMAND... counting passes and failures.
work=$(mktemp -d)
trap 'chmod -R u+rwx "$work" 2>/dev/null; rm -rf "$work"' EXIT
passed=0 failed=0

check() {   # check NAME COMMAND...: passes when the command succeeds
  local name=$1; shift
  if "$@" >"$work/out" 2>&1; then passed=$((passed + 1)); echo "ok   $name"
  else failed=$((failed + 1)); echo "FAIL $name"; sed 's/^/     /' "$work/out" | head -20; fi
}
