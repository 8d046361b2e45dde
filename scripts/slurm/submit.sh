#!/usr/bin/env bash
# Submits a study to Slurm (docs/cluster.md, "Slurm"): the one command for a study that needs a
# cluster. From the repository root:
#   scripts/slurm/submit.sh --srun STUDY.json OUT [SBATCH_OPTION...]
#       one job, MPI ranks launched by srun (scripts/slurm/study.sbatch): e.g. --nodes=16
#   scripts/slurm/submit.sh --array N STUDY.json OUT [SBATCH_OPTION...]
#       a job array of N shards (scripts/slurm/study-array.sbatch), then a collect job that writes
#       the tables once every shard has ended
#   scripts/slurm/submit.sh --array N --tasks K[,K...] STUDY.json OUT [SBATCH_OPTION...]
#       shards K... of N again (one that was cancelled, failed or ran out of time: its finished
#       cases are kept), then the collect job
# SBATCH_OPTIONs (--partition, --nodes, --cpus-per-task, --time, ...) go to every sbatch and
# override the scripts' #SBATCH lines. The request is checked first (sbatch --test-only): a
# partition, node or size the job cannot get is refused with one line, exit 2, nothing submitted
# and nothing written. Then OUT/slurm/ gets the jobs' logs. Prints the job ids on stdout.
# OUT must be on a file system every node sees; ASPERITY (default build/bin/asperity) is the
# program the jobs run.
set -euo pipefail

fail() {  # one line, exit 2: bad input, nothing submitted or written
  echo "submit.sh: $*" >&2
  exit 2
}

mode="" shards="" tasks=""
while [[ $# -gt 0 ]]; do
  case $1 in
    --srun) mode=srun; shift ;;
    --array) mode=array; shards=${2:-}; shift 2 || fail "--array: give the number of shards N" ;;
    --tasks) tasks=${2:-}; shift 2 || fail "--tasks: give K[,K...]" ;;
    *) break ;;
  esac
done
[[ -n $mode && $# -ge 2 ]] ||
  fail "usage: submit.sh --srun|--array N [--tasks K,...] STUDY.json OUT [SBATCH_OPTION...]"
study=$1 out=$2
shift 2
sbatch_options=("$@")
for option in "${sbatch_options[@]}"; do
  [[ $option == -* ]] || fail "\"$option\": expected an sbatch option (--name=value) after OUT"
  case $option in
    --array*|--output*|--error*|--dependency*|--parsable|--wait|--test-only)
      fail "$option: set by submit.sh itself" ;;
  esac
done
if [[ $mode == array ]]; then
  [[ $shards =~ ^[1-9][0-9]*$ ]] || fail "--array: the number of shards must be a whole number >= 1 (got \"$shards\")"
  tasks=${tasks:-1-$shards}
  [[ $tasks =~ ^[0-9]+(-[0-9]+)?(,[0-9]+(-[0-9]+)?)*$ ]] ||
    fail "--tasks: expected K[,K...] or K-L (got \"$tasks\")"
  for k in ${tasks//[,-]/ }; do
    ((k >= 1 && k <= shards)) || fail "--tasks: shard $k is not one of 1-$shards"
  done
elif [[ -n $tasks ]]; then
  fail "--tasks: only with --array"
fi
[[ -f $study && -r $study ]] || fail "$study: no such study file"
command -v sbatch >/dev/null || fail "sbatch is not installed (a Slurm client: slurm-client)"
here=$(cd "$(dirname "$0")" && pwd)
asperity=${ASPERITY:-build/bin/asperity}
[[ -x $asperity ]] || fail "$asperity: no asperity program there (build it, or set ASPERITY)"
# Absolute paths: the jobs start in the submission folder on another node.
ASPERITY=$(realpath "$asperity")
export ASPERITY
study=$(realpath "$study")
out=$(realpath -m "$out")

# One line and exit 2 from sbatch's REPLY to a request it refused: its first error line.
refused() {
  local why
  why=$(grep -m1 -E 'error|failure' <<<"$1" | sed -E 's/^(sbatch: error|allocation failure): //')
  fail "sbatch refused the job (${sbatch_options[*]:-no options}): ${why:-$1}"
}

# sbatch ARGS...: the job id, or one line and exit 2 when Slurm refuses the request.
submit() {
  local reply
  reply=$(sbatch --parsable "${sbatch_options[@]}" "$@" 2>&1) || refused "$reply"
  echo "${reply%%;*}"
}

if [[ $mode == srun ]]; then
  job=(--job-name=asperity-study "$here/study.sbatch" "$study" "$out")
else
  job=(--job-name=asperity-shard "--array=$tasks" "$here/study-array.sbatch" "$study" "$out" "$shards")
fi
collect=(--job-name=asperity-collect --nodes=1 --ntasks=1 --cpus-per-task=1 --wrap
  "$(printf '%q ' "$ASPERITY" study "$study" --out "$out" --collect --allow-failed)")
# Ask first, submit nothing: a partition, node, size or time the cluster cannot give is refused
# here, before OUT exists.
reply=$(sbatch --test-only "${sbatch_options[@]}" "${job[@]}" 2>&1) || refused "$reply"

mkdir -p "$out/slurm"
if [[ $mode == srun ]]; then
  id=$(submit --output="$out/slurm/%x-%j.out" "${job[@]}")
  echo "submit.sh: job $id runs $study into $out (log in $out/slurm/)" >&2
  echo "$id"
else
  id=$(submit --output="$out/slurm/%x-%A_%a.out" "${job[@]}")
  cid=$(submit --dependency="afterany:$id" --output="$out/slurm/%x-%j.out" "${collect[@]}")
  echo "submit.sh: array job $id (shards $tasks of $shards) then collect job $cid into $out (logs in $out/slurm/)" >&2
  echo "$id $cid"
fi
