# Sourced by scripts/sitl.sh (bash). claim_domain [D] sets `domain` to a robot domain D (the sim
# link uses D + 1) that no other SITL run on this machine holds, and holds it until the calling
# shell and every process it started have exited: an flock on a file per domain, which the
# programs inherit. With D given, that domain or nothing. Returns 1 when none is free.
claim_domain() {
  local wanted=${1:-} dir=${COLAG_DOMAIN_LOCKS:-/tmp/colag-sitl-domains} d fd k
  mkdir -p "$dir"
  local candidates=()
  if [ -n "$wanted" ]; then
    candidates=("$wanted")
  else
    # Even domains 10..208, starting at one drawn from the PID (fewer tries when runs start
    # together); the domain above each is its sim link.
    local first=$(($$ % 100))
    for ((k = 0; k < 100; ++k)); do candidates+=($((10 + ((first + k) % 100) * 2))); done
  fi
  for d in "${candidates[@]}"; do
    exec {fd}>"$dir/domain-$d.lock"
    if flock -n "$fd"; then
      domain=$d
      return 0
    fi
    exec {fd}>&-
  done
  return 1
}
