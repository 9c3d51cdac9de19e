#!/usr/bin/env bash
# expect.sh CODE PATTERN COMMAND...
# Passes (exit 0) when COMMAND exits with CODE and what it prints (stdout and stderr) matches the
# extended regular expression PATTERN: CTest's PASS_REGULAR_EXPRESSION alone ignores exit codes.
set -u
code=$1
pattern=$2
shift 2
out=$("$@" 2>&1)
rc=$?
printf '%s\n' "$out"
if [ "$rc" -ne "$code" ]; then
  echo "expect.sh: exit code $rc, expected $code" >&2
  exit 1
fi
# The whole output as one text: `.` also matches a line break, as in CTest's expressions.
if ! [[ "$out" =~ $pattern ]]; then
  echo "expect.sh: the output does not match: $pattern" >&2
  exit 1
fi
echo "expect.sh: PASS"
