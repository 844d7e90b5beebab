#!/usr/bin/env bash
# A farm bake on a real Slurm: starts a loopback cluster (scripts/slurm-local) in a fresh folder,
# bakes the demo scene with technique sh as a job array of 4 shards (scripts/farm/shard.sbatch
# running `prt-bake bake sh --shard {task}/4`) and merges them in a job that waits for them
# (scripts/farm/merge.sbatch running `prt-bake merge`, afterok). Task 2's first attempt is killed
# with SIGKILL in the middle of its bake. Passes when the merged blob is byte for byte the blob of
# the same bake run whole on this machine, task 2 ran twice (requeued by shard.sbatch) and every
# other task once, and `prt-bake merge` refuses a set with a shard missing or with a shard of
# another bake (another seed), saying so. Then `prt-bake scene --shard {task}/2` bakes the demo
# scene's objects into a shared cache as an array of 2, and a job after it writes the outputs,
# which must be the bytes of the same scene bake run here.
#   farm_bake.sh SOURCE_DIR PRT_BAKE      (ctest: pipeline.slurm.farm_bake, label "slurm")
# The cluster is stopped and its folder removed on any exit, and by a watchdog should the test be
# killed outright (SIGKILL, as ctest does at its timeout).
set -euo pipefail

root=$(cd "${1:-$(dirname "$0")/../../..}" && pwd)
prt_bake=$(realpath "${2:?give the prt-bake executable}")
slurm_local=$root/scripts/slurm-local
farm=$root/scripts/farm
wait_seconds=${PRT_SLURM_TEST_WAIT:-90}

fail() {
  echo "farm_bake: FAILED: $*" >&2
  exit 1
}

for tool in slurmctld slurmd munged sbatch scontrol; do
  command -v "$tool" >/dev/null 2>&1 || PATH=$PATH:/usr/sbin:/sbin command -v "$tool" >/dev/null ||
    fail "$tool is missing: run scripts/setup (it installs slurmctld slurmd slurm-client munge)"
done

# Nothing of a Slurm this test may itself run under (a job's SLURM_*, a user's SBATCH_* options)
# reaches the loopback cluster's commands.
for name in $(compgen -e); do
  case "$name" in SLURM_* | SBATCH_* | SALLOC_* | SRUN_*) unset "$name" ;; esac
done

# A short folder: slurm-local keeps Unix sockets in it.
dir=$(mktemp -d /tmp/prt-slurm.XXXXXX)
cleanup() {
  "$slurm_local" stop "$dir" || echo "farm_bake: stopping the cluster in $dir failed" >&2
  rm -rf "$dir"
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
# The watchdog: outside this process's tree, it stops the cluster once this shell is gone however
# it ended (after a normal exit the trap has already done it, and stop finds nothing).
# shellcheck disable=SC2016 # the watchdog's own arguments
(setsid sh -c 'while kill -0 "$1" 2>/dev/null; do sleep 1; done; "$2" stop "$3"; rm -rf "$3"' \
  watchdog $$ "$slurm_local" "$dir" </dev/null >/dev/null 2>&1 &)

started=$SECONDS
eval "$("$slurm_local" start "$dir")" || fail "the cluster did not start (above)"
echo "farm_bake: cluster up in $((SECONDS - started)) s: SLURM_CONF=$SLURM_CONF"

work=$dir/work
mkdir -p "$work"
cd "$work"

# Everything wrong ends here: what Slurm knows of the jobs, their logs, the daemons' logs.
report() {
  echo "farm_bake: FAILED: $*" >&2
  local job log
  for job in ${array:-} ${merge:-}; do
    echo "---- scontrol show job $job (in short) ----" >&2
    scontrol show job -o "$job" 2>&1 | grep -oE '^JobId=[^ ]*|(ArrayTaskId|JobState|Reason|Restarts|ExitCode|Dependency)=[^ ]*' |
      paste -sd ' ' | sed 's/ JobId=/\nJobId=/g' >&2 || true
  done
  for log in "$work"/*.out "$work"/attempts.*; do
    [ -f "$log" ] || continue
    echo "---- $log ----" >&2
    tail -n 20 "$log" >&2
  done
  for log in "$dir"/log/*.log; do
    echo "---- last lines of $log ----" >&2
    tail -n 30 "$log" >&2
  done
  exit 1
}

# The scene, and the same bake run whole here: what the farm's blob must equal.
"$prt_bake" --quiet demo-scene . --sky-width 16 || report "prt-bake demo-scene failed"
bake=(bake sh demo_scene.glb --order 4 --rays 64)
"$prt_bake" --quiet "${bake[@]}" -o whole.prtk || report "the whole bake failed"

# Each task notes its attempt (SLURM_RESTART_COUNT) and bakes its shard; task 2's first attempt
# is killed mid-bake, and fails as a killed task does (137) even when the bake was quicker than
# the kill. shard.sbatch puts the task's index for {task}.
# shellcheck disable=SC2016 # expanded by the task's sh
shard_command='echo "${SLURM_RESTART_COUNT:-0}" >>attempts.{task}
if [ {task} = 2 ] && [ ! -e killed.2 ]; then
  : >killed.2
  "$0" --quiet "$@" &
  sleep 0.1
  kill -KILL $! 2>/dev/null
  wait $!
  exit 137
fi
exec "$0" --quiet "$@"'
array=$(sbatch --parsable --array=0-3 --output="$work/shard-%A_%a.out" \
  "$farm/shard.sbatch" sh -c "$shard_command" "$prt_bake" "${bake[@]}" \
  --shard '{task}/4' -o 'part{task}.shard') || report "sbatch of the shards failed"
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$work/merge-%j.out" "$farm/merge.sbatch" \
  "$prt_bake" merge -o merged.prtk part0.shard part1.shard part2.shard part3.shard) ||
  report "sbatch of the merge failed"
merge=${merge%%;*}
echo "farm_bake: shards are job array $array, the merge job $merge"

# Waits for job $1 (named $2 in messages) to complete (no accounting database: scontrol keeps
# ended jobs MinJobAge).
wait_for_job() {
  local job=$1 what=$2 state= deadline=$((SECONDS + wait_seconds))
  while :; do
    state=$(scontrol show job -o "$job" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
    case "$state" in
      COMPLETED) break ;;
      FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | PREEMPTED | BOOT_FAIL | DEADLINE)
        report "the $what job $job ended $state" ;;
    esac
    [ "$SECONDS" -lt "$deadline" ] ||
      report "the $what job $job is still ${state:-unknown} after $wait_seconds s"
    sleep 0.5
  done
  echo "farm_bake: $what done $((SECONDS - started)) s after the start"
}
wait_for_job "$merge" merge

[ -f merged.prtk ] || report "the merge wrote no blob"
cmp -s merged.prtk whole.prtk ||
  report "the merged blob differs from the whole bake's ($(stat -c %s merged.prtk) and" \
    "$(stat -c %s whole.prtk) bytes)"
for task in 0 1 3; do
  [ "$(cat "attempts.$task" 2>/dev/null)" = 0 ] ||
    report "task $task ran with restart counts '$(tr '\n' ' ' <"attempts.$task")', not once"
done
[ "$(cat attempts.2 2>/dev/null)" = $'0\n1' ] ||
  report "task 2 ran with restart counts '$(tr '\n' ' ' <attempts.2)', not 0 then 1"
grep -q 'requeuing' "shard-${array}_2.out" ||
  report "shard-${array}_2.out does not say that shard.sbatch requeued task 2"
# A set with a part missing, or with a part of another bake, is refused with a clear message.
refused() {
  local says=$1
  shift
  if "$prt_bake" --quiet merge -o refused.prtk "$@" 2>refused.log; then
    report "prt-bake merge accepted $*"
  fi
  grep -q "$says" refused.log || report "prt-bake merge said '$(cat refused.log)', not '$says'"
  [ ! -e refused.prtk ] || report "a refused merge wrote refused.prtk"
}
refused "shard 2/4 is missing" part0.shard part1.shard part3.shard
"$prt_bake" --quiet "${bake[@]}" --seed 1 --shard 2/4 -o foreign.shard ||
  report "the foreign shard's bake failed"
refused "foreign.shard: belongs to another bake than part0.shard (other settings)" \
  part0.shard part1.shard foreign.shard part3.shard

# A whole scene on the farm: each task of an array bakes every other object into the cache they
# share (prt-bake scene --shard), and a job after them writes the outputs from it. They must be
# the bytes of the same scene bake run here, and the last job must have baked nothing anew.
scene=(scene demo_scene.glb --error-budget 10 --bounces 0 --ref-spp 64 --probe-vertices 32)
"$prt_bake" --quiet "${scene[@]}" -o scene-local || report "the local scene bake failed"
scene_array=$(sbatch --parsable --array=0-1 --output="$work/scene-%A_%a.out" \
  "$farm/shard.sbatch" "$prt_bake" --quiet "${scene[@]}" -o scene-farm --shard '{task}/2') ||
  report "sbatch of the scene shards failed"
array=${scene_array%%;*}
scene_final=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$work/scene-final-%j.out" "$farm/merge.sbatch" \
  "$prt_bake" --quiet "${scene[@]}" -o scene-farm) || report "sbatch of the scene's last job failed"
merge=${scene_final%%;*}
wait_for_job "$merge" "scene's last"
for file in scene-local/*.prtk scene-local/scene.json; do
  cmp -s "$file" "scene-farm/${file#scene-local/}" ||
    report "scene-farm/${file#scene-local/} differs from the local scene bake's"
done
python3 -c 'import json, sys
s = json.load(open(sys.argv[1]))["summary"]
sys.exit(0 if s["baked"] == s["from_cache"] == 4 else 1)' scene-farm/report.json ||
  report "the scene's last job baked objects anew: $(grep -A8 '"summary"' scene-farm/report.json)"
echo "farm_bake: passed in $((SECONDS - started)) s: 4 shards merged into the whole bake's" \
  "bytes, task 2 retried once, a missing and a foreign shard refused; a scene baked by 2" \
  "tasks into a shared cache gave the local scene bake's bytes"
