#!/usr/bin/env python3
"""Medians and same-run ratios from a Google Benchmark JSON file written by interlin_bench.

Usage: python3 bench/bench_ratios.py RUN.json   (prints Markdown tables for docs/benchmarks.md)
Run interlin_bench with --benchmark_repetitions=N --benchmark_out=RUN.json
--benchmark_out_format=json; the medians (aggregate "median") of that one run are compared.
"""
import json
import sys


def medians(path):
    with open(path) as f:
        run = json.load(f)
    out, cv = {}, {}
    for b in run["benchmarks"]:
        name = b["run_name"].replace("/real_time", "")
        if b.get("aggregate_name") == "median":
            scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
            out[name] = b["real_time"] * scale  # milliseconds
        elif b.get("aggregate_name") == "cv":
            cv[name] = b["real_time"]
    return run["context"], out, cv


def row(cells):
    return "| " + " | ".join(cells) + " |"


def main():
    context, t, cv = medians(sys.argv[1])
    load = ", ".join(f"{x:.2f}" for x in context.get("load_avg", []))
    print(f"Run {context['date']}, load average at start {load}; medians of "
          f"repetitions, coefficient of variation (cv) over the repetitions.\n")

    def ms(name, digits):
        return f"{t[name]:.{digits}f} (cv {100 * cv.get(name, 0):.0f}%)"

    print("### Loft (7 sections)\n")
    print(row(["benchmark", "median [ms]", "ratio to interlin"]))
    print(row(["---"] * 3))
    base = t["BM_loft_interlin_7"]
    for name in ["BM_loft_interlin_7", "BM_loft_occt_thrusections_7",
                 "BM_loft_occt_sections_and_thrusections_7"]:
        if name in t:
            print(row([name, ms(name, 3), f"{t[name] / base:.1f}"]))

    print("\n### Mesh (~200k triangles)\n")
    print(row(["benchmark", "median [ms]", "ratio to fwrite floor"]))
    print(row(["---"] * 3))
    floor = t["BM_fwrite_floor_stl_bytes"]
    for name in ["BM_surface_mesh_200k", "BM_write_mesh/stl", "BM_write_mesh/ply",
                 "BM_write_mesh/obj", "BM_fwrite_floor_stl_bytes"]:
        print(row([name, ms(name, 2), f"{t[name] / floor:.2f}"]))

    print("\n### Basis and curve evaluation (10^6 evaluations)\n")
    print(row(["what", "degree", "explicit [ms]", "Cox-de Boor [ms]", "Cox-de Boor / explicit"]))
    print(row(["---"] * 5))
    pairs = [("basis, library API", "BM_basis_explicit/{p}", "BM_basis_cox_de_boor/{p}"),
             ("curve point, library API (evaluate on to_piecewise)",
              "BM_curve_point_piecewise/{p}", "BM_curve_point_cox_de_boor/{p}"),
             ("curve point, explicit basis sum vs Cox-de Boor sum",
              "BM_curve_point_explicit_basis_sum/{p}", "BM_curve_point_cox_de_boor/{p}"),
             ("basis, kernel, random u", "BM_basis_kernel_explicit/{p}/0",
              "BM_basis_kernel_cox_de_boor/{p}/0"),
             ("basis, kernel, sorted u", "BM_basis_kernel_explicit/{p}/1",
              "BM_basis_kernel_cox_de_boor/{p}/1"),
             ("curve point, kernel, random u", "BM_curve_point_kernel_piecewise/{p}/0",
              "BM_curve_point_kernel_cox_de_boor/{p}/0"),
             ("curve point, kernel, sorted u", "BM_curve_point_kernel_piecewise/{p}/1",
              "BM_curve_point_kernel_cox_de_boor/{p}/1")]
    for what, e, c in pairs:
        for p in (2, 3, 5):
            ne, nc = e.format(p=p), c.format(p=p)
            print(row([what, str(p), ms(ne, 1), ms(nc, 1), f"{t[nc] / t[ne]:.2f}"]))


if __name__ == "__main__":
    main()
