#!/usr/bin/env bash
#SBATCH --job-name=gmg-batch
#SBATCH --cpus-per-task=2
# `gmg batch` on a Slurm cluster: a job array whose task K of N runs part K/N of the batch
# (gmg batch --shard K/N) into OUTDIR/part-K, and a job that joins the parts (gmg batch --merge)
# into OUTDIR once every part has ended: OUTDIR then holds every BVH (and report) with the merged
# summary, as one run of the whole batch would. The parts write exactly what one run would (see
# `gmg batch --help`).
#
#   scripts/slurm_batch.sh submit [--cpus C] N OUTDIR [gmg batch options...]
#       submits both: the array of N parts, each with C CPUs, and the merge (run this on a login node)
#   sbatch --array=1-N [--cpus-per-task=C] scripts/slurm_batch.sh OUTDIR [gmg batch options...]
#       only the parts; join them later with: gmg batch --merge OUTDIR/part-* -o OUTDIR
#
# The batch options are those of `gmg batch` (--pool/--graph, --tests, --seed, --reports, ...),
# with paths every node can read. Each part runs as many clips at once as its task has CPUs:
# --cpus C (2 by default; SBATCH_CPUS_PER_TASK=C works too, on every Slurm version, because the
# script passes it to sbatch as --cpus-per-task itself). GMG names the gmg binary (default: gmg
# on the PATH); the SBATCH_* environment variables sbatch reads pass further options (partition:
# SBATCH_PARTITION, time: SBATCH_TIMELIMIT, memory: SBATCH_MEM_PER_NODE; a part holds about one
# reference graph per CPU).
set -euo pipefail
gmg=${GMG:-gmg}

usage_submit() {
  echo "usage: $0 submit [--cpus C] N OUTDIR [gmg batch options...]" >&2
  exit 2
}

if [ "${1:-}" = submit ]; then
  shift
  cpus=${SBATCH_CPUS_PER_TASK:-}
  if [ "${1:-}" = --cpus ]; then
    [ $# -ge 2 ] || usage_submit
    cpus=$2
    shift 2
  fi
  [ $# -ge 2 ] || usage_submit
  if [ -n "$cpus" ] && ! [[ "$cpus" =~ ^[1-9][0-9]*$ ]]; then
    echo "$0: --cpus '$cpus' is not a whole number of CPUs (1 or more)" >&2
    exit 2
  fi
  n=$1 out=$2
  shift 2
  if ! [[ "$n" =~ ^[1-9][0-9]*$ ]]; then
    echo "$0: N '$n' is not a whole number of parts (1 or more)" >&2
    exit 2
  fi
  mkdir -p "$out"
  out=$(cd "$out" && pwd)
  parts=()
  for k in $(seq 1 "$n"); do parts+=("$out/part-$k"); done
  # On the command line, --cpus-per-task overrides the #SBATCH line above (sbatch's own
  # SBATCH_CPUS_PER_TASK is not read by every Slurm version, e.g. 22.05).
  cpu_option=()
  [ -z "$cpus" ] || cpu_option=(--cpus-per-task="$cpus")
  array=$(sbatch --parsable --array=1-"$n" "${cpu_option[@]}" --output="$out/slurm-%A_%a.out" \
    --export=ALL,GMG="$gmg" "$0" "$out" "$@")
  merge=$(sbatch --parsable --job-name=gmg-batch-merge --cpus-per-task=1 --dependency=afterany:"${array%%;*}" \
    --output="$out/slurm-%j-merge.out" --wrap "$(printf '%q ' "$gmg" batch --merge "${parts[@]}" -o "$out")")
  echo "slurm_batch: parts in job array ${array%%;*} (1-$n, ${cpus:-2} CPUs each), merge in job ${merge%%;*};" \
    "results in $out"
  exit 0
fi

if [ -z "${SLURM_ARRAY_TASK_ID:-}" ] || [ $# -lt 1 ]; then
  echo "usage: sbatch --array=1-N $0 OUTDIR [gmg batch options...]  (or: $0 submit [--cpus C] N OUTDIR ...)" >&2
  exit 2
fi
out=$1
shift
k=$((SLURM_ARRAY_TASK_ID - ${SLURM_ARRAY_TASK_MIN:-1} + 1))
n=${SLURM_ARRAY_TASK_COUNT:?not a job array task}
exec "$gmg" batch --shard "$k/$n" -o "$out/part-$k" --jobs "${SLURM_CPUS_PER_TASK:-0}" --progress lines "$@"
