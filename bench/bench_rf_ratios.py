#!/usr/bin/env python3
"""Same-run ratios of the R-function evaluation benchmarks (docs/benchmarks.md).

Usage: python3 bench/bench_rf_ratios.py RUN.json
RUN.json: interlin_bench --benchmark_filter=BM_rf_ --benchmark_repetitions=N
          --benchmark_report_aggregates_only=true --benchmark_out=RUN.json
          --benchmark_out_format=json
Prints medians of wall-clock time (real) and of the main thread's CPU time, points per second,
and the ratios: 2 threads vs 1 on the 256^3 grid and on an arithmetic loop (the parallelism the
shared machine offered during the run), batch vs one call per point, gradient vs value.
"""
import json
import sys


def main():
    with open(sys.argv[1]) as f:
        run = json.load(f)
    med, cv = {}, {}
    for b in run["benchmarks"]:
        name = b["run_name"].replace("/real_time", "")
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        if b.get("aggregate_name") == "median":
            med[name] = (b["real_time"] * scale, b["cpu_time"] * scale,
                         b.get("items_per_second", 0))
        elif b.get("aggregate_name") == "cv":
            cv[name] = b["real_time"]
    ctx = run["context"]
    load = ", ".join(f"{x:.2f}" for x in ctx.get("load_avg", []))
    print(f"Run {ctx['date']}, load average at start {load}, {ctx['num_cpus']} CPUs.\n")
    print("| benchmark | real median [ms] (cv) | CPU median [ms] | points/s (real) |")
    print("| --- | --- | --- | --- |")
    for n, (r, c, ips) in med.items():
        rate = f"{ips / 1e6:.2f} M" if ips else ""
        print(f"| {n} | {r:.2f} ({100 * cv.get(n, 0):.0f}%) | {c:.2f} | {rate} |")
    g1, g2 = med["BM_rf_impeller_grid256/1"], med["BM_rf_impeller_grid256/2"]
    s1, s2 = med["BM_parallel_baseline/1"], med["BM_parallel_baseline/2"]
    b, p, g = (med["BM_rf_impeller_layer_" + k] for k in ("batch", "per_point", "gradient"))
    print()
    print("| ratio | real time | CPU time |")
    print("| --- | --- | --- |")
    # with 2 threads the main thread's CPU time covers half the grid: 2 x its CPU time is the
    # total work, so CPU 1-thread / (2 x main-thread CPU) is the work ratio (1 = no overhead)
    print(f"| 256^3 grid, 1 thread / 2 threads (speed-up) | **{g1[0] / g2[0]:.2f}** | "
          f"work ratio {g1[1] / (2 * g2[1]):.2f} |")
    print(f"| arithmetic loop, 1 thread / 2 threads (what the machine allowed) | "
          f"{s1[0] / s2[0]:.2f} | |")
    print(f"| grid speed-up / loop speed-up (parallel efficiency) | "
          f"**{(g1[0] / g2[0]) / (s1[0] / s2[0]):.2f}** | |")
    print(f"| layer, one call per point / one batch | **{p[0] / b[0]:.2f}** | {p[1] / b[1]:.2f} |")
    print(f"| layer, value + gradient / value | {g[0] / b[0]:.2f} | {g[1] / b[1]:.2f} |")


if __name__ == "__main__":
    main()
