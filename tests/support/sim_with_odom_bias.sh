#!/bin/sh
# A "different build" of colag_sim for the A/B test of `colag_bench speed --baseline`: the same
# program with a 5 % wheel-encoder scale error, so that it flies a different mission.
exec "$COLAG_SIM" "$@" --odom-bias 5
