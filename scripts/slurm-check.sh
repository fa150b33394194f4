#!/bin/sh
# A shoal check over many day files on a Slurm cluster: one array task per day file (each a
# `shoal check --shard 0/1 DAY`), the grid sent to each task's node with sbcast, and a merge
# job that runs only when every task succeeded (afterok). docs/scale-out.md explains it.
#
#   scripts/slurm-check.sh DAYS.txt GRID.shoalgrid PARTS_DIR REPORT.geojson [CHECK OPTIONS...]
#
# DAYS.txt: one track file per line (absolute paths on the shared file system), in the order a
# single run would take them. GRID: made once with `shoal import` (read by every task from
# node-local /tmp, where sbcast puts it). PARTS_DIR and REPORT on the shared file system.
# CHECK OPTIONS: the ship and the rules (--ship F | --dims A,B,C,D, --step, --margin, ...);
# not --coast, -o or tracks. SHOAL: the shoal executable (default: shoal on PATH).
# SBATCH_OPTS: more sbatch options for both jobs (partition, time, ...).
# Prints the two job ids. One vessel in two day files is refused by the merge (one run would
# join its tracks): use --shard I/N over all the files then (docs/scale-out.md).
set -eu
if [ $# -lt 4 ]; then
    sed -n '2,15p' "$0" >&2
    exit 2
fi
days=$1 grid=$2 parts=$3 report=$4
shift 4
shoal=${SHOAL:-$(command -v shoal || true)}
[ -x "$shoal" ] || { echo "slurm-check: no shoal executable (set SHOAL)" >&2; exit 2; }
[ -r "$days" ] || { echo "slurm-check: cannot read $days" >&2; exit 2; }
[ -r "$grid" ] || { echo "slurm-check: cannot read $grid" >&2; exit 2; }
n=$(grep -c . "$days")
[ "$n" -gt 0 ] || { echo "slurm-check: $days lists no file" >&2; exit 2; }
mkdir -p "$parts"
days=$(readlink -f "$days") grid=$(readlink -f "$grid") parts=$(readlink -f "$parts")
local_grid=/tmp/shoal-$(basename "$grid")

# The options, quoted for the job scripts.
opts=
for o in "$@"; do opts="$opts '$(printf %s "$o" | sed "s/'/'\\\\''/g")'"; done

task=$parts/.check-task.sh
cat >"$task" <<SCRIPT
#!/bin/sh
# Array task \$SLURM_ARRAY_TASK_ID: day file number \$SLURM_ARRAY_TASK_ID + 1 of $days.
set -eu
day=\$(grep . '$days' | sed -n "\$((SLURM_ARRAY_TASK_ID + 1))p")
sbcast --force '$grid' '$local_grid'   # the grid on this node's disk
part=\$(printf '$parts/part-%06d.geojson' "\$SLURM_ARRAY_TASK_ID")
# Exit 1 is "a grounding was found", not a failure (afterok must still run the merge).
'$shoal' check --coast '$local_grid' $opts --no-progress --shard 0/1 -o "\$part" -- "\$day" || [ \$? -eq 1 ]
SCRIPT
chmod +x "$task"
array=$(sbatch --parsable ${SBATCH_OPTS:-} --job-name=shoal-check --array=0-$((n - 1)) --output="$parts/task-%a.log" "$task")

merge=$parts/.merge.sh
cat >"$merge" <<SCRIPT
#!/bin/sh
set -eu
'$shoal' merge '$parts'/part-*.geojson -o '$report' || [ \$? -eq 1 ]
SCRIPT
chmod +x "$merge"
merged=$(sbatch --parsable ${SBATCH_OPTS:-} --job-name=shoal-merge --dependency=afterok:"$array" --output="$parts/merge.log" "$merge")
echo "check array job $array ($n tasks), merge job $merged -> $report"
