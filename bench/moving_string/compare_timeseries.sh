#!/usr/bin/env bash
# Compares two timeseries.csv files (same header, same rows) column by column: for each column the
# largest |a - b| over the rows divided by the column's largest |b| (b: the reference). Prints every
# column's figure and exits 1 if one exceeds TOL, columns named in SKIP (comma list, e.g. the
# constraint residual, which is round-off itself) excepted.
# Usage: bench/moving_string/compare_timeseries.sh NEW.csv REFERENCE.csv [TOL] [SKIP]
#        (defaults: TOL 1e-8, SKIP constraint_error)
set -euo pipefail
new=$1
ref=$2
tol=${3:-1e-8}
skip=${4:-constraint_error}
[ "$(head -1 "$new")" = "$(head -1 "$ref")" ] || { echo "headers differ" >&2; exit 1; }
[ "$(wc -l <"$new")" = "$(wc -l <"$ref")" ] || { echo "row counts differ" >&2; exit 1; }
paste -d, "$new" "$ref" | awk -F, -v tol="$tol" -v skip="$skip" '
NR == 1 { n = NF / 2; for (j = 1; j <= n; ++j) name[j] = $j; next }
{ for (j = 1; j <= n; ++j) { a = $j; b = $(j + n); d = a - b; if (d < 0) d = -d; if (b < 0) b = -b;
      if (d > dmax[j]) dmax[j] = d; if (b > bmax[j]) bmax[j] = b } }
END { bad = 0; worst = 0; wj = 1; ns = split(skip, sk, ",")
      for (j = 1; j <= n; ++j) { r = bmax[j] > 0 ? dmax[j] / bmax[j] : dmax[j]; skipped = 0
          for (s = 1; s <= ns; ++s) if (name[j] == sk[s]) skipped = 1
          printf "  %-32s %.3e%s\n", name[j], r, skipped ? "  (not checked)" : (r > tol ? "  > TOL" : "")
          if (skipped) continue
          if (r > worst) { worst = r; wj = j }
          if (r > tol) bad = 1 }
      printf "%d columns, %d rows; worst checked column %s: %.3e relative to its max |value| (TOL %g)\n",
             n, NR - 1, name[wj], worst, tol
      exit bad }'
