#!/usr/bin/env bash
# Software in the loop: the simulated world (colag_world) and the robots' unchanged firmware as
# separate processes — uav_fw (robot.hal: sim) and one ugv_fw per UGV (can.interface: sim) —
# talking only over Cyclone DDS.
#   scripts/sitl.sh [--ugvs N] [--scenario sparse|dense|pillars|rooms | --scenario-file F]
#                   [--seed S] [--max-time S]
#                   [--world ideal|field|FILE] [--json OUT] [--netns] [--loss PCT] [--domain D] [--build DIR]
#                   [--time-scale X] [--kill-ugv I@T [--restart-after S]]
#                   [--uav-stack sim|px4 [--px4-release R] [--px4-silent-at T | --px4-failsafe-at T |
#                    --px4-pilot-at T]] [--ugv-base colag|odrive|agilex_v2] [--ros2] [--mcap FILE]
# Waits for the mission to end, writes the metrics JSON (colag_sim's schema; default
# build/sitl/run-<pid>/metrics.json), stops every process by PID, prints a summary, and exits 0 when
# every UGV reached its goal with no collision (1 otherwise, 2 on a usage or set-up error, 77
# when --netns cannot work on this machine: not root, no iproute2/nftables, no namespaces).
#   --scenario-file F  a scenario file (colag_sim's, config/scenarios/README.md): the map, each
#               UGV's start and goal (each ugv.yaml gets its goal and start guess), the world;
#               --seed, --max-time and --world given as well override it; not with --ugvs.
#   --world W   the world's profile (colag_sim's --world; default ideal): field makes the wheels,
#               the UAV's odometry, LiDAR and camera what real ones are; uav.yaml gets the world's
#               LiDAR pattern and camera view (colag_world --print-uav-sensors). Each robot reads
#               this host's clock: the profile's clock offsets are colag_sim's alone.
#   --netns     every robot in its own network namespace (the world in a hub namespace with a
#               bridge), joined by veth pairs; all created here and removed on exit. Needs root.
#               Prints each robot's DDS traffic (bytes/s in and out, robot-to-robot domain only).
#   --loss PCT  (with --netns) every robot namespace drops PCT % of the incoming robot-to-robot
#               DDS packets (nftables; the simulator's own link is not degraded).
#   --time-scale X  X simulated seconds per wall-clock second for every process (default 1:
#               real time); they all scale CLOCK_MONOTONIC alike, so they agree on the time.
#   --domain D  the robots' DDS domain (the sim link uses D + 1); default: a free one. Every run
#               holds its domain (a lock per domain), so runs at the same time never share one.
#   --kill-ugv I@T  kills UGV I's ugv_fw (SIGKILL: a crash) at mission time T s; the world keeps
#               its body where it stopped. --restart-after S starts it again S s later, with the
#               same configuration: it resumes from the pose it kept (robot.state_file).
#   --uav-stack px4  uav_fw flies with robot.hal px4 through its real drivers: colag_world plays
#               PX4's uXRCE-DDS agent (px4_msgs, release --px4-release, default 1.16), FAST-LIO's
#               /Odometry and the Livox driver's /livox/lidar on the sim link's domain (D + 1);
#               the UAV takes off from the ground through the offboard protocol. Faults:
#               --px4-silent-at T (the agent falls silent), --px4-failsafe-at T (PX4 fails
#               safe), --px4-pilot-at T (a pilot switches to position mode): every UGV must
#               stop within a second and uav.log say why.
#   --ugv-base B  the UGVs' bases speak B on their CAN buses (colag_world emulates two ODrive
#               axes or an AgileX base; each ugv.yaml gets can.protocol B). Default colag.
#   --ros2      every robot's ROS 2 telemetry on (`ros2: {enabled: true}`): ugv<i>/odom, status,
#               plan, prediction, map; uav/odom, status, map, support_plan; /tf; on domain D.
#               Goals on ugv<i>/goal_pose.
#   --mcap FILE record the mission as MCAP (colag_record on domain D; implies --ros2).
# Logs and configurations: build/sitl/run-<pid>/.
set -euo pipefail
caller=$PWD
cd "$(dirname "$0")/.."

ugvs=3 scenario=dense seed=1 max_time=400 json="" netns=0 loss=0 scale=1
build=build/host domain="" kill_ugv="" restart_after="" world_name=ideal
scenario_file="" given=()  # given: --ugvs/--seed/--max-time/--world as typed (with a scenario file)
uav_stack=sim px4_release=1.16 px4_fault=() ugv_base=colag ros2=0 mcap=""
usage() { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 2; }
while (($#)); do
  case "$1" in
    --ugvs) ugvs=$2; given+=(--ugvs "$2"); shift 2 ;;
    --scenario) scenario=$2; shift 2 ;;
    --scenario-file) scenario_file=$2; [[ $2 == /* ]] || scenario_file=$caller/$2; shift 2 ;;
    --seed) seed=$2; given+=(--seed "$2"); shift 2 ;;
    --world) world_name=$2; [[ $2 == ideal || $2 == field || $2 == /* ]] || world_name=$caller/$2
             given+=(--world "$world_name"); shift 2 ;;
    --max-time) max_time=$2; given+=(--max-time "$2"); shift 2 ;;
    --json) json=$2; shift 2 ;;
    --netns) netns=1; shift ;;
    --loss) loss=$2; shift 2 ;;
    --domain) domain=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --time-scale) scale=$2; shift 2 ;;
    --kill-ugv) kill_ugv=$2; shift 2 ;;
    --restart-after) restart_after=$2; shift 2 ;;
    --uav-stack) uav_stack=$2; shift 2 ;;
    --ugv-base) ugv_base=$2; shift 2 ;;
    --ros2) ros2=1; shift ;;
    --mcap) mcap=$2; [[ $2 == /* ]] || mcap=$caller/$2; ros2=1; shift 2 ;;
    --px4-release) px4_release=$2; shift 2 ;;
    --px4-silent-at|--px4-failsafe-at|--px4-pilot-at) px4_fault=("$1" "$2"); shift 2 ;;
    *) usage ;;
  esac
done
[[ $ugvs =~ ^[0-9]+$ ]] && ((ugvs >= 1 && ugvs <= 32)) || { echo "sitl: --ugvs must be 1..32" >&2; exit 2; }
[[ $uav_stack == sim || $uav_stack == px4 ]] || { echo "sitl: --uav-stack must be sim or px4" >&2; exit 2; }
[[ $ugv_base =~ ^(colag|odrive|agilex_v2)$ ]] || { echo "sitl: --ugv-base must be colag, odrive or agilex_v2" >&2; exit 2; }
[[ $uav_stack == px4 || ${#px4_fault[@]} -eq 0 ]] || { echo "sitl: PX4 faults need --uav-stack px4" >&2; exit 2; }
[[ $loss =~ ^[0-9]+$ ]] && ((loss <= 100)) || { echo "sitl: --loss must be 0..100" >&2; exit 2; }
((loss == 0 || netns)) || { echo "sitl: --loss needs --netns (loss is injected per namespace)" >&2; exit 2; }
for p in colag_world uav_fw ugv_fw; do
  [ -x "$build/bin/$p" ] || { echo "sitl: $build/bin/$p missing: build the host preset first" >&2; exit 2; }
done
# The mission as colag_world reads it, and each UGV's start and goal from it (one line each:
# id x y yaw goal_x goal_y): the world and the UGVs' configurations cannot disagree.
if [ -n "$scenario_file" ]; then
  mission_args=(--scenario-file "$scenario_file" "${given[@]}")
  scenario=$(basename "$scenario_file")
else
  mission_args=(--scenario "$scenario" --ugvs "$ugvs" --seed "$seed" --max-time "$max_time"
                --world "$world_name")
fi
placements=$("$build/bin/colag_world" "${mission_args[@]}" --print-placements) ||
  { echo "sitl: the mission: see above" >&2; exit 2; }
ugvs=$(wc -l <<<"$placements")
number='^[0-9]+([.][0-9]+)?$'
if [ -n "$kill_ugv" ]; then
  [[ $kill_ugv =~ ^([0-9]+)@([0-9]+([.][0-9]+)?)$ ]] && ((BASH_REMATCH[1] < ugvs)) ||
    { echo "sitl: --kill-ugv wants I@T with I < --ugvs and T seconds, e.g. 1@40" >&2; exit 2; }
  kill_id=${BASH_REMATCH[1]} kill_at=${BASH_REMATCH[2]}
fi
[ -z "$restart_after" ] || { [[ $restart_after =~ $number ]] && [ -n "$kill_ugv" ]; } ||
  { echo "sitl: --restart-after wants seconds, with --kill-ugv" >&2; exit 2; }
if ((netns)); then
  [ "$(id -u)" -eq 0 ] || { echo "sitl: --netns needs root (network namespaces)" >&2; exit 77; }
  command -v ip >/dev/null && command -v nft >/dev/null ||
    { echo "sitl: --netns needs ip (iproute2) and nft (nftables)" >&2; exit 77; }
  # `ip netns` bind-mounts under /run/netns and needs / to be a mount point: not so in a chroot,
  # where it would fail half-way and leave a mount behind. Probe without it first.
  mountpoint -q / ||
    { echo "sitl: / is not a mount point here (a chroot?): ip netns cannot work" >&2; exit 77; }
  unshare --net true 2>/dev/null ||
    { echo "sitl: cannot create network namespaces here (no CAP_SYS_ADMIN?)" >&2; exit 77; }
  if ! ip netns add "colag-probe-$$" 2>/dev/null || ! ip netns exec "colag-probe-$$" true 2>/dev/null; then
    ip netns delete "colag-probe-$$" 2>/dev/null || true
    echo "sitl: ip netns does not work here" >&2
    exit 77
  fi
  ip netns delete "colag-probe-$$"
fi

. "$(dirname "$0")/lib/claim-domain.sh"
[[ -z $domain || ($domain =~ ^[0-9]+$ && domain -le 231) ]] ||
  { echo "sitl: --domain must be 0..231 (the sim link uses the next one)" >&2; exit 2; }
if ! claim_domain "$domain"; then
  if [ -n "$domain" ]; then
    echo "sitl: domain $domain is in use by another SITL run on this machine" >&2
  else
    echo "sitl: every domain is in use by other SITL runs on this machine" >&2
  fi
  exit 2
fi
run=build/sitl/run-$$
[ -n "$json" ] || json=$run/metrics.json  # each run its own: two runs never share an output
mkdir -p "$run" "$(dirname "$json")"
run=$(cd "$run" && pwd)
rm -f "$json"

# Cyclone: participant indices give each domain a fixed port range (7400 + 250 * domain ...),
# which the loss rules rely on; on loopback, stay on lo.
if ((netns)); then
  export CYCLONEDDS_URI='<Discovery><ParticipantIndex>auto</ParticipantIndex><MaxAutoParticipantIndex>20</MaxAutoParticipantIndex></Discovery>'
else
  export CYCLONEDDS_URI='<General><Interfaces><NetworkInterface name="lo"/></Interfaces></General>'
fi

cat >"$run/uav.yaml" <<YAML
robot: {id: 0, hal: $uav_stack}
dds: {domain: $domain}
realtime: {fifo_priority: 0, lock_memory: false}
YAML
if ((ros2)); then echo "ros2: {enabled: true}" >>"$run/uav.yaml"; fi
# The UAV's sensors (and, on PX4, its flight stack's topics) as the world simulates them,
# described as on a board.
stack_args=(--uav-stack "$uav_stack" --ugv-base "$ugv_base")
[[ $uav_stack == sim ]] || stack_args+=(--px4-release "$px4_release" "${px4_fault[@]}")
"$build/bin/colag_world" "${mission_args[@]}" --domain "$domain" "${stack_args[@]}" \
  --print-uav-sensors >>"$run/uav.yaml" ||
  { echo "sitl: --world $world_name: see above" >&2; exit 2; }
while read -r i x y yaw gx gy route; do
  via=""  # x y pairs before the goal -> [[x, y], ...]
  read -ra r <<<"$route"
  for ((k = 0; k + 1 < ${#r[@]}; k += 2)); do via+="${via:+, }[${r[k]}, ${r[k + 1]}]"; done
  cat >"$run/ugv$i.yaml" <<YAML
robot: {id: $i, goal: [$gx, $gy], via: [$via], start_guess: [$x, $y, $yaw], state_file: $run/ugv$i.state}
dds: {domain: $domain}
realtime: {fifo_priority: 0, lock_memory: false}
can: {interface: sim, protocol: $ugv_base}
YAML
  if ((ros2)); then echo "ros2: {enabled: true}" >>"$run/ugv$i.yaml"; fi
done <<<"$placements"

pids=() namespaces=()
ns_of=()  # namespace of each robot (empty: none)
cleanup() {
  # The kill/restart job, and the program it started again.
  [ -z "${killer:-}" ] || kill "$killer" 2>/dev/null || true
  if [ -n "${run:-}" ] && [ -s "$run/restarted.pid" ]; then
    pids+=("$(cat "$run/restarted.pid")")
    rm -f "$run/restarted.pid"
  fi
  for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done
  for _ in $(seq 50); do
    alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || break
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -KILL "$pid" 2>/dev/null || true; done
  for ns in "${namespaces[@]}"; do ip netns delete "$ns" 2>/dev/null || true; done
}
trap cleanup EXIT
trap 'exit 130' INT TERM

robots=(uav)
for ((i = 0; i < ugvs; ++i)); do robots+=("ugv$i"); done
hub=""
if ((netns)); then
  hub=colag-$$-hub
  ip netns add "$hub"; namespaces+=("$hub")
  ip -n "$hub" link set lo up
  ip -n "$hub" link add br0 type bridge
  ip -n "$hub" addr add 10.77.0.1/24 dev br0
  ip -n "$hub" link set br0 up
  k=0
  port_lo=$((7400 + 250 * domain)) port_hi=$((7400 + 250 * domain + 249))
  for r in "${robots[@]}"; do
    ns=colag-$$-$r
    ip netns add "$ns"; namespaces+=("$ns")
    ip -n "$ns" link set lo up
    ip -n "$hub" link add "h$k" type veth peer name eth0 netns "$ns"
    ip -n "$hub" link set "h$k" master br0 up
    ip -n "$ns" addr add "10.77.0.$((10 + k))/24" dev eth0
    ip -n "$ns" link set eth0 up
    # Counters for the robot-to-robot domain (both directions), and the loss, on ingress.
    ip netns exec "$ns" nft -f - <<NFT
table inet colag {
  counter dds_in {}
  counter dds_out {}
  chain pre {
    type filter hook prerouting priority -300;
    iifname "eth0" udp dport $port_lo-$port_hi counter name dds_in
    iifname "eth0" udp dport $port_lo-$port_hi numgen random mod 100 < $loss drop
  }
  chain out {
    type filter hook output priority 0;
    oifname "eth0" udp dport $port_lo-$port_hi counter name dds_out
  }
}
NFT
    ns_of+=("$ns")
    k=$((k + 1))
  done
else
  for r in "${robots[@]}"; do ns_of+=(""); done
fi
# Run as `in_ns NS cmd... &`: exec makes the background job the program itself, so $! is its
# PID (`ip netns exec` execs the command in turn) and stopping it by PID reaches the program.
in_ns() {  # namespace command...
  if [ -n "$1" ]; then local ns=$1; shift; exec ip netns exec "$ns" "$@"; else shift; exec "$@"; fi
}

# A killed robot is silent until it is started again (and found by DDS discovery).
silence=5
[ -z "$kill_ugv" ] || silence=$(awk -v r="${restart_after:-1e6}" 'BEGIN {print r + 30}')
echo "sitl: $scenario, $ugvs UGVs, $([ -n "$scenario_file" ] && echo "seed and world from the file" || echo "seed $seed, $world_name world"), UAV on $uav_stack$([[ $uav_stack == px4 ]] && echo " $px4_release"), time x$scale, DDS domain $domain (sim link $((domain + 1)))$( ((netns)) && echo ", one network namespace per robot")$( ((loss)) && echo ", $loss % loss")"
echo "sitl: logs and configs in $run"
in_ns "$hub" "$build/bin/colag_world" "${mission_args[@]}" \
  --domain "$domain" --json "$json" --time-scale "$scale" \
  --max-silence "$silence" "${stack_args[@]}" >"$run/world.log" 2>&1 &
world=$!
pids+=("$world")
if [ -n "$mcap" ]; then
  in_ns "$hub" "$build/bin/colag_record" --domain "$domain" --out "$mcap" >"$run/record.log" 2>&1 &
  recorder=$!
  pids+=("$recorder")
fi
in_ns "${ns_of[0]}" "$build/bin/uav_fw" --config "$run/uav.yaml" --time-scale "$scale" >"$run/uav.log" 2>&1 &
uav=$!
pids+=("$uav")
if [[ $uav_stack == px4 ]]; then
  # On PX4 the mission ends with a landing: once the world says the mission is over (its PX4
  # stays up), uav_fw is stopped as an operator would stop it, and lands.
  (
    while kill -0 "$world" 2>/dev/null && ! grep -q "waiting for the UAV to land" "$run/world.log"; do
      sleep 0.2
    done
    kill -INT "$uav" 2>/dev/null || true
  ) &
  lander=$!
fi
for ((i = 0; i < ugvs; ++i)); do
  in_ns "${ns_of[$((i + 1))]}" "$build/bin/ugv_fw" --config "$run/ugv$i.yaml" --time-scale "$scale" >"$run/ugv$i.log" 2>&1 &
  pids+=($!)
done
start=$(date +%s)
if [ -n "$kill_ugv" ]; then
  # Mission time runs `scale` times the wall clock from the world's start.
  victim=${pids[$((kill_id + 2))]}
  (
    sleep "$(awk -v t="$kill_at" -v s="$scale" 'BEGIN {print t / s}')"
    kill -KILL "$victim" 2>/dev/null && echo "  sitl: killed UGV $kill_id's ugv_fw (pid $victim) at t ~ $kill_at s"
    [ -n "$restart_after" ] || exit 0
    sleep "$(awk -v t="$restart_after" -v s="$scale" 'BEGIN {print t / s}')"
    in_ns "${ns_of[$((kill_id + 1))]}" "$build/bin/ugv_fw" --config "$run/ugv$kill_id.yaml" \
      --time-scale "$scale" >"$run/ugv$kill_id.restart.log" 2>&1 &
    echo "$!" >"$run/restarted.pid"
    echo "  sitl: started UGV $kill_id's ugv_fw again (pid $!) at t ~ $(awk -v a="$kill_at" -v b="$restart_after" 'BEGIN {print a + b}') s"
  ) &
  killer=$!
fi
tail -f "$run/world.log" --pid "$world" 2>/dev/null | sed -u 's/^/  /' &
tailer=$!
set +e
wait "$world"
world_rc=$?
set -e
wait "$tailer" 2>/dev/null || true  # tail --pid ends within a second of the world
wall=$(($(date +%s) - start))
if [ -n "$mcap" ]; then
  kill -INT "$recorder" 2>/dev/null || true
  if wait "$recorder"; then
    echo "sitl: recording: $(tail -n 1 "$run/record.log" | sed 's/^colag_record: //')"
  else
    echo "sitl: colag_record failed; see $run/record.log" >&2
    exit 1
  fi
fi

if ((netns)); then
  echo "sitl: robot-to-robot DDS traffic per robot over $wall s (domain $domain only; the sim link excluded):"
  for ((k = 0; k < ${#robots[@]}; ++k)); do
    read -r in_b out_b < <(ip netns exec "${ns_of[$k]}" nft list counters table inet colag |
      awk '/counter dds_in/ {w="in"} /counter dds_out/ {w="out"} /bytes/ {for (i=1;i<=NF;i++) if ($i=="bytes") b[w]=$(i+1)} END {print b["in"]+0, b["out"]+0}')
    printf '  %-5s in %8d B/s   out %8d B/s\n' "${robots[$k]}" $((in_b / (wall > 0 ? wall : 1))) $((out_b / (wall > 0 ? wall : 1)))
  done
fi
cleanup
pids=() namespaces=()
# Nothing of this run may outlive it (a stray robot on the same domain would join the next run).
if pgrep -f -- "$run/" >/dev/null; then
  echo "sitl: processes of this run survived the stop:" >&2
  pgrep -af -- "$run/" >&2
  pkill -KILL -f -- "$run/" || true
  exit 1
fi
if ((world_rc != 0)) || [ ! -s "$json" ]; then
  echo "sitl: colag_world failed (exit $world_rc); see $run/*.log" >&2
  exit 1
fi
echo "sitl: metrics in $json"
if ((${#px4_fault[@]})); then
  # A PX4 fault: the mission cannot end; what counts is that every UGV stood still within a
  # second, with no collision, and the UAV said why.
  stood=$(sed -n 's/.*every UGV stood still \([0-9.]*\) s after.*/\1/p' "$run/world.log")
  why=$(grep -m1 'px4: no longer in control' "$run/uav.log" || true)
  echo "sitl: after PX4's fault: every UGV still after ${stood:-never} s; uav_fw: ${why:-no report}"
  if [ -n "$stood" ] && awk -v s="$stood" 'BEGIN {exit !(s <= 1.0)}' && [ -n "$why" ] &&
     grep -q '"collisions": 0' "$json"; then
    echo "sitl: PASS: every UGV stopped within 1 s of PX4's fault, no collision"
    exit 0
  fi
  echo "sitl: FAIL: the UGVs did not all stop within 1 s of PX4's fault, or a collision" >&2
  exit 1
fi
if [[ $uav_stack == px4 ]]; then
  landed=$(grep -m1 'uav_fw: landed and disarmed' "$run/uav.log" || true)
  echo "sitl: the UAV at the end: ${landed:-not landed (see $run/uav.log)}"
  [ -n "$landed" ] || { echo "sitl: FAIL: uav_fw did not land the UAV through PX4" >&2; exit 1; }
fi
if grep -q '"all_reached": true' "$json" && grep -q '"collisions": 0' "$json"; then
  echo "sitl: PASS: every UGV reached its goal, no collision"
else
  echo "sitl: FAIL: not every UGV reached its goal, or a collision" >&2
  # What each UGV that did not reach said last (CI keeps only this output, not the run folder).
  for ((i = 0; i < ugvs; ++i)); do
    awk -v id="$i" 'index($0, "\"id\": " id ",") {u = 1} u && /"reached": false/ {print "bad"; exit}
                    u && /"reached": true/ {exit}' "$json" | grep -q bad || continue
    echo "sitl: UGV $i did not reach; the end of its log ($run/ugv$i.log):" >&2
    tail -n 25 "$run/ugv$i.log" | sed 's/^/  | /' >&2
    [ ! -s "$run/ugv$i.restart.log" ] || tail -n 25 "$run/ugv$i.restart.log" | sed 's/^/  | (restarted) /' >&2
  done
  exit 1
fi
