#!/usr/bin/env bash
# A farm bake on a real Slurm: starts a loopback cluster (scripts/slurm-local) in a fresh folder,
# submits scripts/farm/shard.sbatch as an array of 4 tasks and scripts/farm/merge.sbatch after
# them (afterok), with dummy commands: each task writes its part, task 2 kills itself with SIGKILL
# on its first attempt, and the merge concatenates the parts. Passes when the merge wrote the 4
# parts in order, task 2 ran twice (requeued by shard.sbatch) and every other task once.
#   farm_bake.sh [SOURCE_DIR]      (ctest: pipeline.slurm.farm_bake, label "slurm")
# The cluster is stopped and its folder removed on any exit, and by a watchdog should the test be
# killed outright (SIGKILL, as ctest does at its timeout).
set -euo pipefail

root=$(cd "${1:-$(dirname "$0")/../../..}" && pwd)
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

# Each task notes its attempt (SLURM_RESTART_COUNT), task 2 dies on its first, then the task
# writes its part. shard.sbatch puts the task's index for {task}.
# shellcheck disable=SC2016 # expanded by the task's sh
shard_command='echo "${SLURM_RESTART_COUNT:-0}" >>attempts.{task}
if [ {task} = 2 ] && [ ! -e killed.2 ]; then
  : >killed.2
  kill -KILL $$
fi
echo "part {task}" >part.{task}'
array=$(sbatch --parsable --array=0-3 --output="$work/shard-%A_%a.out" \
  "$farm/shard.sbatch" sh -c "$shard_command") || report "sbatch of the shards failed"
array=${array%%;*}
merge=$(sbatch --parsable --dependency="afterok:$array" --kill-on-invalid-dep=yes \
  --output="$work/merge-%j.out" "$farm/merge.sbatch" \
  sh -c 'cat part.0 part.1 part.2 part.3 >merged') || report "sbatch of the merge failed"
merge=${merge%%;*}
echo "farm_bake: shards are job array $array, the merge job $merge"

# The merge's state until it ends (no accounting database: scontrol keeps ended jobs MinJobAge).
deadline=$((SECONDS + wait_seconds))
state=
while :; do
  state=$(scontrol show job -o "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p')
  case "$state" in
    COMPLETED) break ;;
    FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | PREEMPTED | BOOT_FAIL | DEADLINE)
      report "the merge job $merge ended $state" ;;
  esac
  [ "$SECONDS" -lt "$deadline" ] ||
    report "the merge job $merge is still ${state:-unknown} after $wait_seconds s"
  sleep 0.5
done
echo "farm_bake: merge done $((SECONDS - started)) s after the start"

expected=$'part 0\npart 1\npart 2\npart 3'
[ -f merged ] || report "the merge wrote no file"
[ "$(cat merged)" = "$expected" ] ||
  report "merged holds '$(tr '\n' '|' <merged)', not the 4 parts in order"
for task in 0 1 3; do
  [ "$(cat "attempts.$task" 2>/dev/null)" = 0 ] ||
    report "task $task ran with restart counts '$(tr '\n' ' ' <"attempts.$task")', not once"
done
[ "$(cat attempts.2 2>/dev/null)" = $'0\n1' ] ||
  report "task 2 ran with restart counts '$(tr '\n' ' ' <attempts.2)', not 0 then 1"
grep -q 'requeuing' "shard-${array}_2.out" ||
  report "shard-${array}_2.out does not say that shard.sbatch requeued task 2"
echo "farm_bake: passed in $((SECONDS - started)) s: 4 parts merged, task 2 retried once"
