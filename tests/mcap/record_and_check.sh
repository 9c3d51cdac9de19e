#!/bin/sh
# Records a simulated mission as MCAP, then checks the file with the reference reader.
#   record_and_check.sh OUT.mcap "CHECK ARGS" COLAG_SIM [SIM ARGS...]
# Exit: the check's (0 good, 1 a check failed, 77 its packages missing: skipped); colag_sim's 2
# (bad input).
set -u
out=$1 checks=$2
shift 2
"$@" --quiet --mcap "$out"
rc=$?
if [ "$rc" -gt 1 ]; then
  echo "record_and_check: colag_sim exited $rc" >&2
  exit "$rc"
fi
# shellcheck disable=SC2086 # the check's arguments, split on purpose
exec node "$(dirname "$0")/check_mcap.mjs" "$out" $checks
