#!/usr/bin/env bash
# A sweep as a Slurm job array: scripts/slurm_sweep.sh installs Slurm and munge if missing,
# starts a one-node cluster of its own (own key, config and ports), runs tests/data/sweep_small.yaml
# (8 short cases) as 3 array tasks, merges them and requires the merged results.csv to be
# byte-identical to the unsharded run's; every daemon it started must be gone afterwards. The
# work dir is removed on success and kept on failure.
# Labels `system` and `slurm`: CI runs it with the system tier (it installs the packages it misses,
# as root, and starts daemons of its own); alone: `ctest --test-dir build -L slurm` (about 20 s).
# Usage: slurm_sweep_test.sh <retrace binary> <source dir>
cli_tmp_template=/tmp/slurm_test.XXXXXX
cli_keep_tmp_on_failure=1  # the work dir, with the cluster's logs, is kept on failure
. "$(dirname "$0")/lib.sh" || exit 1
"$src/scripts/slurm_sweep.sh" "$retrace" "$src/tests/data/sweep_small.yaml" 3 "$tmp/work" ||
  die "scripts/slurm_sweep.sh exited $? (logs in $tmp/work)"
# The daemons, job steps and jobs it started all had the work dir in their command line or in
# their environment (SLURM_CONF); none may be left.
echo "$tmp/work" >"$tmp/pattern"
left=$(grep -lsFf "$tmp/pattern" /proc/[0-9]*/cmdline /proc/[0-9]*/environ | cut -d/ -f3 | sort -u)
[ -z "$left" ] || die "processes left running: $(echo "$left" | tr '\n' ' ')"
echo "PASS"
