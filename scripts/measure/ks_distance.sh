# Sourced by the measurement scripts. ks FILE_A FILE_B COLUMN: the two-sample Kolmogorov-Smirnov
# distance of one column of two stroboscopic tables (revolutions after 10), printed to 3 decimals.
# Uses $work (the caller's scratch folder). Ties advance one side at a time, so a file against
# itself reads 1/n, not 0.
ks() {
  awk -v c="$3" '!/^#/ && $1 > 10 {print $c}' "$1" | sort -g > "$work/a"
  awk -v c="$3" '!/^#/ && $1 > 10 {print $c}' "$2" | sort -g > "$work/b"
  awk 'NR == FNR {a[++na] = $1; next} {b[++nb] = $1}
       END {i = j = 1; d = 0
            while (i <= na && j <= nb) { if (a[i] <= b[j]) i++; else j++
              x = (i - 1) / na - (j - 1) / nb; if (x < 0) x = -x; if (x > d) d = x }
            printf "%.3f", d}' "$work/a" "$work/b"
}
