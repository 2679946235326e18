#!/usr/bin/env bash
# Issue 10 on a lent 16-core device, in one call of about 7 minutes (timings of the second
# loan, docs/clusters.md): (a) on 1 and 16 workers as threads and as processes, then (d)
# and (c) on 1 and 2 workers. Here first: bash ../shared/offline-wheels.sh; then call the
# device's `run` with carry [".whl"], command `bash benchmarks/device_scaling.sh`,
# timeout_s 560. Each step's output goes to $OUT as it is printed.
set -u
T0=$(date +%s)
left() { echo $(($1 - ($(date +%s) - T0))); } # seconds left until second $1 of the call
bash .whl/install.sh || exit 3
export PYTHONPATH=/tmp/site:$PWD PYTHONUNBUFFERED=1 MPLBACKEND=Agg
OUT=${OUT:-out/device}
mkdir -p "$OUT"
nproc >"$OUT/machine.txt"
python3 -c "import sys, numba; print(sys.version, numba.__version__)" >>"$OUT/machine.txt"
s=$(date +%s)
python3 -c "from frictiondisk.engine.worker import warm_up; warm_up()"
echo "cold compile: $(($(date +%s) - s)) s" | tee -a "$OUT/machine.txt"
scaling="python3 benchmarks/bench_scaling.py"
timeout "$(left 200)" $scaling --full --only a --workers 1,16 --repeats 1 2>&1 | tee "$OUT/a_threads.txt"
timeout "$(left 340)" $scaling --full --only a --workers 1,16 --repeats 1 --processes 2>&1 |
  tee "$OUT/a_processes.txt"
timeout "$(left 520)" $scaling --only dc --workers 1,2 --repeats 1 2>&1 | tee "$OUT/dc.txt"
echo "elapsed $(($(date +%s) - T0)) s"
