#!/usr/bin/env bash
# A sweep as a Slurm job array: scripts/slurm_sweep.sh installs Slurm and munge if missing,
# starts a one-node cluster of its own (own key, config and ports), runs tests/data/sweep_small.yaml
# (8 short cases) as 3 array tasks, merges them and requires the merged results.csv to be
# byte-identical to the unsharded run's; every daemon it started must be gone afterwards. The
# work dir is removed on success and kept on failure.
# Labels `system` and `slurm`: CI runs it with the system tier (it installs the packages it misses,
# as root, and starts daemons of its own); alone: `ctest --test-dir build -L slurm` (about 20 s).
# Usage: slurm_sweep_test.sh <retrace binary> <source dir>
set -uo pipefail
retrace="$1"
src="$2"
tmp=$(mktemp -d /tmp/slurm_test.XXXXXX)
"$src/scripts/slurm_sweep.sh" "$retrace" "$src/tests/data/sweep_small.yaml" 3 "$tmp/work" ||
  { echo "FAIL: scripts/slurm_sweep.sh exited $? (logs in $tmp/work)"; exit 1; }
# The daemons, job steps and jobs it started all had the work dir in their command line or in
# their environment (SLURM_CONF); none may be left.
echo "$tmp/work" >"$tmp/pattern"
left=$(grep -lsFf "$tmp/pattern" /proc/[0-9]*/cmdline /proc/[0-9]*/environ | cut -d/ -f3 | sort -u)
[ -z "$left" ] || { echo "FAIL: processes left running: $(echo "$left" | tr '\n' ' ')"; exit 1; }
rm -rf "$tmp"
echo "PASS"
