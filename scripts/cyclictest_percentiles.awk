# p50, p99, p99.9 and the maximum (µs) of a cyclictest-format histogram ("bin count" lines of
# 1 µs bins, "# Histogram Overflows", "# Max Latencies"): the upper edge of the bin where each
# share of the samples (overflows counted beyond every bin) is reached, else the maximum.
# Used by scripts/probe_period.sh and bench/core_vs_cyclictest.sh.
/^[0-9]/ { bin[n] = $1 + 0; count[n] = $2 + 0; total += $2; n++ }
/Max Latencies/ { max = $NF + 0 }
/Histogram Overflows/ { total += $NF + 0 }
END {
  split("0.5 0.99 0.999", shares, " ")
  for (k = 1; k <= 3; k++) {
    want = shares[k] * total; seen = 0; result[k] = max
    for (i = 0; i < n; i++) { seen += count[i]; if (seen >= want) { result[k] = bin[i] + 1; break } }
  }
  printf "%d %d %d %d\n", result[1], result[2], result[3], max
}
