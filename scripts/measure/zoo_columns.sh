# shellcheck shell=bash
# zoo_columns "NAME<TAB>NAME...": the named columns of each automatic-choice row of docs/validation/zoo.md
# ("## Chaotic systems, automatic choices", both N), one line per row, cells joined by one blank with
# their own blanks taken out. Columns are found by the table's header names, so a column added to
# the report moves nothing in the scripts that read it. Sourced from the repository root.
zoo_columns() {
  awk -F'|' -v names="$1" '
    function trim(v) { gsub(/^ +| +$/, "", v); return v }
    /^## Chaotic systems, automatic choices/ { on = 1; next }
    /^## / { on = 0 }
    on && trim($2) == "system" {
      for (i = 2; i < NF; ++i) column[trim($i)] = i
      n = split(names, wanted, "\t")
      for (k = 1; k <= n; ++k)
        if (!(wanted[k] in column)) { print "zoo_columns: no column \"" wanted[k] "\" in docs/validation/zoo.md" > "/dev/stderr"; exit 3 }
      next }
    on && trim($3) ~ /^[0-9]+$/ {
      line = ""
      for (k = 1; k <= n; ++k) { v = $(column[wanted[k]]); gsub(/ /, "", v); line = line (k > 1 ? " " : "") v }
      print line }' docs/validation/zoo.md
}
