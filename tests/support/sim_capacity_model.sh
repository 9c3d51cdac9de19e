#!/bin/sh
# A stand-in for colag_sim in the test of `colag_bench tables --table 4`: it writes the JSON of a
# mission whose numbers follow a known model of N UGVs and K UAVs (self-perception reaches in
# 70 s; ColAG in 70 (1 + 0.08 N / K) s, waiting N / K s), so that the table's ratios and its
# "fewest UAVs" lines can be checked: 3 UGVs need 2 UAVs, 7 need 4, 12 and 16 none of 1-4.
n=1; k=1; sp=0; json=""
while [ $# -gt 0 ]; do
  case "$1" in
    --ugvs) n=$2; shift ;;
    --uavs) k=$2; shift ;;
    --json) json=$2; shift ;;
    --self-perception) sp=1 ;;
  esac
  shift
done
awk -v n="$n" -v k="$k" -v sp="$sp" 'BEGIN {
  reach = sp ? 70 : 70 * (1 + 0.08 * n / k); wait = sp ? 0 : n / k;
  printf "{\"summary\": {\"reach_time_s\": %.4f, \"waiting_time_s\": %.4f, ", reach, wait;
  printf "\"max_waiting_time_s\": %.4f, \"ugv_traj_length_m\": 33, \"uav_traj_length_m\": 100, ", wait;
  printf "\"collisions\": 0, \"all_reached\": true}, \"realtime_factor\": 50, \"sim_time_s\": 100}\n";
}' > "$json"
