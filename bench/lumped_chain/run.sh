#!/usr/bin/env bash
# Reproduces the lumped-mass chain comparison of docs/performance.md: builds bench-lumped-chain, runs the references, the sweep
# (one process at a time), the analysis and the plot. Resumable: a run whose file exists is skipped.
# Usage: bench/lumped_chain/run.sh [build-dir] [run-dir]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build-chain}
runs=${2:-$build/lumped_chain_runs}
stage=${STAGE:-all}   # all | ref | sweep | analyze | ratios (the speed ratios from results/lumped_chain_runs.csv)
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j1 --target bench-lumped-chain >/dev/null
B=$build/bench/bench-lumped-chain
if [[ $stage == ratios ]]; then
  "$B" ratios "$here/results/lumped_chain_runs.csv" | tee "$here/results/ratios.txt"
  exit 0
fi
mkdir -p "$runs"

run() {  # run <file> <args...>
  local f=$runs/$1; shift
  [[ -s $f ]] && return 0
  "$B" run "$@" --out "$f.tmp" 2>>"$runs/stderr.log" | tee -a "$runs/log.txt"
  mv "$f.tmp" "$f"
}

if [[ $stage == all || $stage == ref ]]; then
  # References (tight accuracy; wall times not used). ALE: modes refined; chain: N refined.
  run ref_ale_na12_nt6_a1e-11.csv --model ale --na 12 --nt 6 --integrator rk-merson --accuracy 1e-11 --repeats 1 --cap 600
  run ref_ale_na12_nt6_a1e-10.csv --model ale --na 12 --nt 6 --integrator rk-merson --accuracy 1e-10 --repeats 1 --cap 600
  run ref_ale_na16_nt8_a1e-11.csv --model ale --na 16 --nt 8 --integrator rk-merson --accuracy 1e-11 --repeats 1 --cap 600
  run ref_ale_na8_nt4_a1e-11.csv  --model ale --na 8 --nt 4 --integrator rk-merson --accuracy 1e-11 --repeats 1 --cap 600
  run ref_chain_N25_a1e-9.csv  --model chain --N 25  --integrator rk-merson --accuracy 1e-9 --repeats 1 --cap 900
  run ref_chain_N50_a1e-9.csv  --model chain --N 50  --integrator rk-merson --accuracy 1e-9 --repeats 1 --cap 900
  run ref_chain_N100_a1e-9.csv --model chain --N 100 --integrator rk-merson --accuracy 1e-9 --repeats 1 --cap 900
  # The ALE's exact velocity model (paper eq 12) instead of the default simplified one (eq 13).
  run ref_ale_complete_na12_nt6_a1e-10.csv --model ale --na 12 --nt 6 --velocity complete --integrator rk-merson --accuracy 1e-10 --repeats 1 --cap 600
  run ref_ale_complete_na16_nt8_a1e-10.csv --model ale --na 16 --nt 8 --velocity complete --integrator rk-merson --accuracy 1e-10 --repeats 1 --cap 600
  # A user's plain Force::TwoPointLinearSpring (T = EA (lambda - 1)) instead of the Green-strain law.
  run linear_chain_N25_a1e-9.csv --model chain-linear --N 25 --integrator rk-merson --accuracy 1e-9 --repeats 1 --cap 900
fi

R="--repeats 3 --repeat-below 20 --cap 120"
if [[ $stage == all || $stage == sweep ]]; then
  # ALE span: n_a x n_t x integrator x accuracy.
  for na in 0 1 2 3 5 8; do for nt in 1 2 4; do
    [[ $nt == 4 && $na != 0 && $na != 3 && $na != 8 ]] && continue
    for acc in 1e-4 1e-6 1e-8 1e-10; do
      run ale_na${na}_nt${nt}_rk-merson_${acc}.csv --model ale --na $na --nt $nt --integrator rk-merson --accuracy $acc $R
    done
  done; done
  for na in 0 1 3 5 8; do for acc in 1e-4 1e-6 1e-8; do
    run ale_na${na}_nt1_rk3_${acc}.csv --model ale --na $na --nt 1 --integrator rk3 --accuracy $acc $R
  done; done
  for na in 0 8; do for integ in rk-feldberg cpodes; do for acc in 1e-6 1e-10; do
    run ale_na${na}_nt1_${integ}_${acc}.csv --model ale --na $na --nt 1 --integrator $integ --accuracy $acc $R
  done; done; done
  # The exact velocity model (paper eq 12): with axial modes, the default simplified one (eq 13) has an
  # inertial model error of 0.13-0.2 N in the force on the payload (see docs/performance.md).
  for na in 1 3; do for nt in 1 2; do for acc in 1e-6 1e-8; do
    run ale_complete_na${na}_nt${nt}_rk-merson_${acc}.csv --model ale --na $na --nt $nt --velocity complete --integrator rk-merson --accuracy $acc $R
  done; done; done
  # Lumped chain: N x integrator x accuracy.
  for N in 5 10 20 50; do
    accs="1e-4 1e-6 1e-8 1e-10"; [[ $N == 50 ]] && accs="1e-4 1e-6 1e-8"
    for acc in $accs; do
      run chain_N${N}_rk-merson_${acc}.csv --model chain --N $N --integrator rk-merson --accuracy $acc $R
    done
    for acc in 1e-4 1e-6; do
      run chain_N${N}_rk3_${acc}.csv --model chain --N $N --integrator rk3 --accuracy $acc $R
    done
  done
  run chain_N10_rk-feldberg_1e-6.csv --model chain --N 10 --integrator rk-feldberg --accuracy 1e-6 $R
  run chain_N10_cpodes_1e-4.csv --model chain --N 10 --integrator cpodes --accuracy 1e-4 $R
  for N in 100 200; do
    run chain_N${N}_rk3_1e-4.csv --model chain --N $N --integrator rk3 --accuracy 1e-4 $R
  done
fi

if [[ $stage == all || $stage == analyze ]]; then
  out=$here/results
  mkdir -p "$out"
  # Reference (see docs/performance.md): position from the ALE with the exact velocity model, n_a = 16,
  # n_t = 8; axial force from the chain's Richardson extrapolation 2 P(N=100) - P(N=50) (its
  # error is O(1/N)). Checks: the same from N = 25, 50; position by order-2 extrapolation.
  "$B" richardson "$runs/ref_chain_N100_a1e-9.csv" "$runs/ref_chain_N50_a1e-9.csv" 2 1 "$runs/rich1_chain_N50_N100.csv"
  "$B" richardson "$runs/ref_chain_N50_a1e-9.csv" "$runs/ref_chain_N25_a1e-9.csv" 2 1 "$runs/rich1_chain_N25_N50.csv"
  "$B" richardson "$runs/ref_chain_N100_a1e-9.csv" "$runs/ref_chain_N50_a1e-9.csv" 2 2 "$runs/rich2_chain_N50_N100.csv"
  "$B" richardson "$runs/ref_chain_N50_a1e-9.csv" "$runs/ref_chain_N25_a1e-9.csv" 2 2 "$runs/rich2_chain_N25_N50.csv"
  "$B" compose-ref "$runs/ref_ale_complete_na16_nt8_a1e-10.csv" "$runs/rich1_chain_N50_N100.csv" "$runs/reference.csv"
  {
    echo "## reference agreement (max over 20 s of |dpos| and |dP|)"
    for pair in "ref_ale_na12_nt6_a1e-10 ref_ale_na12_nt6_a1e-11" "ref_ale_na12_nt6_a1e-11 ref_ale_na16_nt8_a1e-11" \
                "ref_ale_na8_nt4_a1e-11 ref_ale_na16_nt8_a1e-11" "ref_chain_N25_a1e-9 ref_ale_na16_nt8_a1e-11" \
                "ref_chain_N50_a1e-9 ref_ale_na16_nt8_a1e-11" "ref_chain_N100_a1e-9 ref_ale_na16_nt8_a1e-11" \
                "ref_chain_N25_a1e-9 ref_chain_N50_a1e-9" "ref_chain_N50_a1e-9 ref_chain_N100_a1e-9" \
                "ref_chain_N100_a1e-9 reference" "ref_chain_N50_a1e-9 reference" "ref_chain_N25_a1e-9 reference" \
                "ref_ale_na16_nt8_a1e-11 reference" "linear_chain_N25_a1e-9 ref_chain_N25_a1e-9" \
                "ref_ale_complete_na12_nt6_a1e-10 ref_ale_complete_na16_nt8_a1e-10" "ref_ale_complete_na16_nt8_a1e-10 reference" \
                "ref_ale_complete_na16_nt8_a1e-10 ref_ale_na16_nt8_a1e-11" "rich2_chain_N50_N100 reference" \
                "rich2_chain_N50_N100 rich2_chain_N25_N50" "rich1_chain_N50_N100 rich1_chain_N25_N50"; do
      set -- $pair
      [[ -s $runs/$1.csv && -s $runs/$2.csv ]] || continue
      printf '%-26s vs %-26s ' "$1" "$2"; "$B" compare "$runs/$1.csv" "$runs/$2.csv"
    done
    echo "## energy drift (max |E - E0| over the run) [J]"
    grep -h "^# " "$runs"/ref_*.csv | sed 's/.*model=\([^ ]*\) N=\([^ ]*\) na=\([^ ]*\) nt=\([^ ]*\) .*integrator=\([^ ]*\) accuracy=\([^ ]*\).*wall=\([^ ]*\) .*steps=\([^ ]*\) .*energy_drift=\(.*\)/\1 N=\2 na=\3 nt=\4 \5 \6 wall=\7 steps=\8 drift=\9/'
  } | tee "$out/reference_agreement.txt"
  files=$(ls "$runs"/ale_*.csv "$runs"/chain_*.csv 2>/dev/null)
  "$B" analyze --ref "$runs/reference.csv" --out-dir "$out" --files $files | tee "$out/ratios.txt"
  gnuplot -e "dir='$out'; png='$root/bench/lumped_chain_work_precision.png'" "$here/plot.gp"
fi
