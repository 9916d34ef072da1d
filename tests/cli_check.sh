#!/usr/bin/env bash
# Runs one command-line test and checks its exit status and its output together (CTest's
# PASS_REGULAR_EXPRESSION alone ignores the exit status, WILL_FAIL alone ignores the message).
# Usage: cli_check.sh [--status N] [--expect REGEX]... [--reject REGEX]... [--needs PATH]
#                     [--clean PATH]... -- COMMAND [ARG...]
#   --status N     the exit status the command must return (default 0)
#   --expect RE    an extended regular expression the output (stdout and stderr) must match;
#                  '.' matches across lines
#   --reject RE    one it must not match
#   --needs PATH   exit 77 (CTest's SKIP_RETURN_CODE) when PATH, input data, is not there
#   --clean PATH   removed before the command runs, so that a stale output cannot pass
set -uo pipefail
status=0
expects=()
rejects=()
while [[ $# -gt 0 && "$1" != "--" ]]; do
  case "$1" in
    --status) status="$2"; shift 2 ;;
    --expect) expects+=("$2"); shift 2 ;;
    --reject) rejects+=("$2"); shift 2 ;;
    --needs)
      if [[ ! -e "$2" ]]; then
        echo "cli_check: skipped, $2 is not there"
        exit 77
      fi
      shift 2 ;;
    --clean) rm -rf -- "$2"; shift 2 ;;
    *) echo "cli_check: unknown option '$1'" >&2; exit 2 ;;
  esac
done
if [[ $# -lt 2 ]]; then
  echo "cli_check: no command after --" >&2
  exit 2
fi
shift
out="$(mktemp)"
trap 'rm -f "$out"' EXIT
"$@" >"$out" 2>&1
got=$?
cat "$out"
failed=0
if [[ "$got" != "$status" ]]; then
  echo "cli_check: exit status $got, expected $status" >&2
  failed=1
fi
for re in "${expects[@]+"${expects[@]}"}"; do
  if ! grep -Ezq -- "$re" "$out"; then
    echo "cli_check: output does not match '$re'" >&2
    failed=1
  fi
done
for re in "${rejects[@]+"${rejects[@]}"}"; do
  if grep -Ezq -- "$re" "$out"; then
    echo "cli_check: output matches '$re', which it must not" >&2
    failed=1
  fi
done
exit "$failed"
