#!/usr/bin/env python3
"""Same-run ratios of the implicit-extraction benchmarks (docs/benchmarks.md, "Implicit surface
extraction").

Usage: python3 bench/bench_implicit_ratios.py RUN.json
RUN.json: interlin_bench --benchmark_filter='BM_extract_|BM_valve_table'
          --benchmark_repetitions=N --benchmark_report_aggregates_only=true
          --benchmark_out=RUN.json --benchmark_out_format=json
Prints medians of wall-clock time (and of the main thread's CPU time for the 1-thread runs) and
the ratios VTK / interlin measured in that one run, then seed 002's valve table.
"""
import json
import sys


def main():
    with open(sys.argv[1]) as f:
        run = json.load(f)
    real, cpu, cv, counters = {}, {}, {}, {}
    for b in run["benchmarks"]:
        name = b["run_name"].replace("/real_time", "")
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        if b.get("aggregate_name") == "median":
            real[name] = b["real_time"] * scale
            cpu[name] = b["cpu_time"] * scale
            counters[name] = b
        elif b.get("aggregate_name") == "cv":
            cv[name] = b["real_time"]
    ctx = run["context"]
    load = ", ".join(f"{x:.2f}" for x in ctx.get("load_avg", []))
    print(f"Run {ctx['date']}, load average at start {load}, {ctx['num_cpus']} CPUs; medians of "
          f"the repetitions, cv in brackets.\n")

    def ms(name):
        return f"{real[name]:.1f} ({100 * cv.get(name, 0):.0f}%)"

    sets = [s for s in ["impeller", "torus", "gyroid"]
            if f"BM_extract_interlin/{s}_1thread" in real]
    if "BM_spin_threads/1" in real:
        print(f"Free parallelism (BM_spin_threads): 2 threads of fixed work take "
              f"{real['BM_spin_threads/2'] / real['BM_spin_threads/1']:.2f} x the time of one "
              f"(1.0: two free cores, 2.0: one).\n")
    if sets:
        extraction(sets, real, cpu, cv, counters, ms)
    valve_table(real, cv, counters)


def extraction(sets, real, cpu, cv, counters, ms):
    print("| grid | nodes | triangles | interlin 1 thread [ms] | interlin 2 threads [ms] | "
          "FlyingEdges3D 1 thread [ms] | FlyingEdges3D 2 threads [ms] | vtkMarchingCubes [ms] |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for s in sets:
        i1, i2 = f"BM_extract_interlin/{s}_1thread", f"BM_extract_interlin/{s}_2threads"
        f1, f2 = (f"BM_extract_vtk_flying_edges/{s}_1thread",
                  f"BM_extract_vtk_flying_edges/{s}_2threads")
        mc = f"BM_extract_vtk_marching_cubes/{s}"
        c = counters[i1]
        print(f"| {s} | {c['nodes'] / 1e6:.2f} M | {c['triangles'] / 1e6:.2f} M | {ms(i1)} | "
              f"{ms(i2)} | {ms(f1)} | {ms(f2)} | {ms(mc)} |")
    print("\nRatios (time of the baseline / time of interlin; above 1: interlin is faster):\n")
    print("| grid | FE 1t / interlin 1t (wall) | (main-thread CPU) | FE 1t / interlin 2t | "
          "FE 2t / interlin 2t | interlin 1t / 2t | vtkMarchingCubes / interlin 1t |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for s in sets:
        i1, i2 = f"BM_extract_interlin/{s}_1thread", f"BM_extract_interlin/{s}_2threads"
        f1, f2 = (f"BM_extract_vtk_flying_edges/{s}_1thread",
                  f"BM_extract_vtk_flying_edges/{s}_2threads")
        mc = f"BM_extract_vtk_marching_cubes/{s}"
        print(f"| {s} | **{real[f1] / real[i1]:.2f}** | {cpu[f1] / cpu[i1]:.2f} | "
              f"**{real[f1] / real[i2]:.2f}** | {real[f2] / real[i2]:.2f} | "
              f"{real[i1] / real[i2]:.2f} | {real[mc] / real[i1]:.1f} |")
    print("\nProcess CPU time per run, all threads [ms] (two workers that really run side by side "
          "take about half of it as wall time):\n")
    print("| grid | interlin 1t | interlin 2t | FE 1t | FE 2t |")
    print("| --- | --- | --- | --- | --- |")
    for s in sets:
        names = [f"BM_extract_interlin/{s}_1thread", f"BM_extract_interlin/{s}_2threads",
                 f"BM_extract_vtk_flying_edges/{s}_1thread",
                 f"BM_extract_vtk_flying_edges/{s}_2threads"]
        print(f"| {s} | " + " | ".join(
            f"{counters[n].get('process_cpu_ms', float('nan')):.1f} (wall {real[n]:.1f})"
            for n in names) + " |")


def valve_table(real, cv, counters):
    valve = {k: v for k, v in real.items() if k.startswith("BM_valve_table/")}
    if valve:
        print("\nValve (seed 002 Table 1 layout), whole pipeline, all cores, wall clock [s]:\n")
        pts = [125000, 2000000, 15500000]
        print("| sub-boxes | " + " | ".join(
            f"{counters[f'BM_valve_table/{p}/2/0']['nodes'] / 1e6:.3g} M points" for p in pts) +
            " |")
        print("| --- | --- | --- | --- |")
        for k in [2, 3, 4, 5]:
            cells = [f"{valve[f'BM_valve_table/{p}/{k}/0'] / 1e3:.3f} "
                     f"({100 * cv.get(f'BM_valve_table/{p}/{k}/0', 0):.0f}%)" for p in pts]
            print(f"| {k ** 3} | " + " | ".join(cells) + " |")
        print("\nProcess CPU time per run, all threads [s] (the work, whatever the load):\n")
        print("| sub-boxes | " + " | ".join(f"{p / 1e6:.3g} M" for p in pts) + " |")
        print("| --- | --- | --- | --- |")
        for k in [2, 3, 4, 5]:
            cells = [f"{counters[f'BM_valve_table/{p}/{k}/0'].get('process_cpu_ms', 0) / 1e3:.3f}"
                     for p in pts]
            print(f"| {k ** 3} | " + " | ".join(cells) + " |")
        name = "BM_valve_table/2000000/3/1"
        if name in valve:
            c = counters[name]
            print(f"\nWith the projection onto F = 0 (2 M points, 27 sub-boxes): "
                  f"{valve[name] / 1e3:.3f} s, of which projection {c['project_s']:.3f} s.")


if __name__ == "__main__":
    main()
