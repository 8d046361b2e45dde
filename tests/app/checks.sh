# The check helpers of the shell tests that run the program as a user would (cli_contract.sh,
# peers_contract.sh, hostile.sh). Sourced by a test called as `TEST.sh ASPERITY_BINARY
# SOURCE_DIR`: sets $bin and $src from those, $work to a scratch folder removed at exit; `check
# NAME CONDITION...` counts CONDITION's outcome (a failure prints NAME); `report_checks` prints the
# counts and returns non-zero when any check failed (the test's exit status).
bin=$(realpath "$1")
src=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
passed=0
failed=0
check() {  # check NAME CONDITION...
  local name=$1; shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL: $name"; fi
}
report_checks() {
  echo "$passed passed, $failed failed"
  test "$failed" -eq 0
}
