#!/usr/bin/env bash
# Runs one libFuzzer target under ctest with its chatter in a log file, so that a failure's report is short
# enough to reach CI's summary whole: the sanitizer's or libFuzzer's error lines, the log's last lines, and the
# crashing input in base64 (to reproduce: base64 -d > crash; ./fuzz_TARGET crash).
# usage: run_fuzzer.sh FUZZER WORK_CORPUS SEED_CORPUS SECONDS
set -u
fuzzer=$1 work=$2 seeds=$3 seconds=$4
log="$work.log" artifacts="$work-artifacts/"
rm -rf "$artifacts" && mkdir -p "$artifacts"
"$fuzzer" "$work" "$seeds" -max_total_time="$seconds" -max_len=4096 -print_final_stats=1 \
  -artifact_prefix="$artifacts" >"$log" 2>&1
rc=$?
if [ "$rc" -eq 0 ]; then
  grep -E '^(Done|stat::number_of_executed_units|stat::peak_rss_mb)' "$log"
  exit 0
fi
echo "$(basename "$fuzzer") failed (exit $rc); full log: $log"
grep -E 'ERROR|SUMMARY|deadly signal|out-of-memory|runtime error|Timeout|#[0-9]+ 0x' "$log" | head -60
echo "--- last lines of the log ---"
tail -n 25 "$log"
for f in "$artifacts"*; do
  [ -f "$f" ] && { echo "--- $(basename "$f"), base64 ---"; base64 -w 0 "$f" | head -c 8000; echo; }
done
exit "$rc"
