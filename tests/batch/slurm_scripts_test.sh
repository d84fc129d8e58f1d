#!/usr/bin/env bash
# The Slurm helpers without a cluster: scripts/slurm_batch.sh against a stand-in `sbatch` that
# records its arguments (the CPUs a part asks for, by --cpus and by SBATCH_CPUS_PER_TASK; what a
# task runs), and scripts/setup_local_slurm.sh refusing to overwrite a slurm.conf it did not write.
# Usage: slurm_scripts_test.sh SOURCE_DIR
set -euo pipefail
src=$1
work=$(mktemp -d /tmp/gmg_slurm_scripts.XXXXXX)
trap 'rm -rf "$work"' EXIT
status=0
fail() {
  echo "FAIL: $*"
  status=1
}

# A stand-in sbatch: one line of arguments per call in $work/sbatch.log, a job id on stdout.
mkdir -p "$work/bin"
cat > "$work/bin/sbatch" <<'FAKE'
#!/usr/bin/env bash
printf '%s\n' "$*" >> "$SBATCH_LOG"
echo $((4000 + $(wc -l < "$SBATCH_LOG")))
FAKE
chmod +x "$work/bin/sbatch"
export SBATCH_LOG=$work/sbatch.log

submit() {  # submit ARGS...: the array job's sbatch line
  : > "$SBATCH_LOG"
  PATH="$work/bin:$PATH" bash "$src/scripts/slurm_batch.sh" submit "$@" --graph g.gmg --tests t > "$work/submit.out"
  sed -n 1p "$SBATCH_LOG"
}

line=$(submit --cpus 8 3 "$work/out")
[[ "$line" == *"--array=1-3 --cpus-per-task=8 "* ]] || fail "submit --cpus 8 did not ask for 8 CPUs: $line"
line=$(SBATCH_CPUS_PER_TASK=6 submit 2 "$work/out")
[[ "$line" == *"--cpus-per-task=6 "* ]] || fail "SBATCH_CPUS_PER_TASK=6 did not reach sbatch: $line"
line=$(
  unset SBATCH_CPUS_PER_TASK
  submit 2 "$work/out"
)
[[ "$line" != *"--cpus-per-task"* ]] || fail "without --cpus the script's own default (#SBATCH) should apply: $line"
merge=$(sed -n 2p "$SBATCH_LOG")
[[ "$merge" == *"--dependency=afterany:"*"batch --merge"*"part-1"*"part-2"*"-o $work/out"* ]] ||
  fail "the merge job does not join the parts into OUTDIR: $merge"
if PATH="$work/bin:$PATH" bash "$src/scripts/slurm_batch.sh" submit --cpus many 2 "$work/out" 2> "$work/err"; then
  fail "--cpus many was accepted"
fi
grep -q "is not a whole number of CPUs" "$work/err" || fail "--cpus many: $(cat "$work/err")"

# A task of the array runs its part with its CPUs (a stand-in gmg prints its arguments).
printf '#!/usr/bin/env bash\necho "$@"\n' > "$work/bin/gmg"
chmod +x "$work/bin/gmg"
task=$(GMG="$work/bin/gmg" SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=3 SLURM_CPUS_PER_TASK=8 \
  bash "$src/scripts/slurm_batch.sh" "$work/out" --graph g.gmg)
[ "$task" = "batch --shard 2/3 -o $work/out/part-2 --jobs 8 --progress lines --graph g.gmg" ] ||
  fail "task 2 of 3 runs: $task"

# setup_local_slurm.sh leaves a slurm.conf it did not write alone, before doing anything else.
printf 'ClusterName=production\nSlurmctldHost=head\n' > "$work/slurm.conf"
cp "$work/slurm.conf" "$work/slurm.conf.orig"
if SLURM_CONF=$work/slurm.conf bash "$src/scripts/setup_local_slurm.sh" > "$work/out.txt" 2> "$work/err"; then
  fail "setup_local_slurm.sh went ahead over a foreign slurm.conf"
fi
grep -q "was not written by this script" "$work/err" || fail "setup_local_slurm.sh said: $(cat "$work/err")"
cmp -s "$work/slurm.conf" "$work/slurm.conf.orig" || fail "setup_local_slurm.sh changed the foreign slurm.conf"
[ ! -e "$work/slurm.conf.bak" ] || fail "setup_local_slurm.sh made a backup without --force"

[ $status -eq 0 ] && echo "PASS: slurm_batch.sh passes the CPUs and joins the parts; setup_local_slurm.sh keeps a foreign slurm.conf"
exit $status
