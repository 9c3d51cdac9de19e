#!/usr/bin/env bash
# Two SITL runs started together must not share a DDS domain (they used to pick 10 + PID % 100 * 2,
# and two PIDs equal mod 100 flew into each other): claim_domain hands each its own, and refuses an
# explicit domain another run holds.
set -u
. "$(dirname "$0")/../../scripts/lib/claim-domain.sh"
export COLAG_DOMAIN_LOCKS=$(mktemp -d)
out=$(mktemp -d)
for k in 1 2 3; do
  (claim_domain && echo "$domain" >"$out/$k" && sleep 2) &
done
sleep 1
a=$(cat "$out/1") b=$(cat "$out/2") c=$(cat "$out/3")
echo "claimed: $a $b $c"
if [ "$a" = "$b" ] || [ "$a" = "$c" ] || [ "$b" = "$c" ]; then echo "FAIL: a domain claimed twice"; exit 1; fi
if (claim_domain "$a"); then echo "FAIL: domain $a claimed while held"; exit 1; fi
wait
if ! (claim_domain "$a"); then echo "FAIL: domain $a still held after its run ended"; exit 1; fi
rm -rf "$out" "$COLAG_DOMAIN_LOCKS"
echo "claim_domain: PASS"
