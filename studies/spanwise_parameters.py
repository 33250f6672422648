#!/usr/bin/env python3
"""Spanwise parameters of the loft on synthetic blades: which spacing of the section parameters
v_k (uniform, centripetal, chord length, the stations) and which span degree predict the blade
between the sections best, for families of blades, station spacings and station counts, and
what the default (span and span degree chosen by leave-one-out) picks.

A synthetic blade is a stack of seed 004 cascade profiles (interlin.stack_cascade_profiles,
13 parameters per radius from smooth span laws, stacked on the area centroid) at K stations on
r in [200, 300]. Its true shape between the stations is known: the profile of the same laws at
any radius. The loft of the K sections is measured against the true profiles at 3 radii inside
every gap (exact point-to-surface distances): interpolation error, not hold-out.

Families (cases): 2 span-law families x 4 station spacings (uniform, clustered at hub and tip,
growing towards the tip, jittered) x K in {5, 9, 17}; orders are fitted against the largest
gap; each case lofts one blade with every
parameterisation. The cases are spread over MPI ranks under mpirun; the table is the same.

Usage: python3 studies/spanwise_parameters.py [OUT_DIR] [--quick] [-q]
       mpirun -n 4 python3 studies/spanwise_parameters.py OUT_DIR
"""
import numpy as np

from study import Study, arguments, interlin, loglog, plt, run

R0, R1 = 200.0, 300.0
BASE = dict(relative_pitch=0.75, axial_width=40.0, stagger_deg=40, inlet_angle_deg=90,
            outlet_angle_deg=13, le_wedge_deg=30, te_wedge_deg=6, le_radius=2.4, te_radius=0.4,
            te_bend_deg=13, max_thickness_position=0.35, max_thickness=0.15, throat=0)


def law_mild(t):
    """Close to data/profiles/turbine_blade_span.json: chord, stagger, thickness and pitch
    changing smoothly from hub (t = 0) to tip (t = 1)."""
    return dict(axial_width=36 + 8 * t, stagger_deg=38 + 4 * t,
                max_thickness=0.17 - 0.02 * t - 0.04 * t * t,
                relative_pitch=0.6981 + 0.19 * t - 0.03 * t * t)


def law_twisted(t):
    """Strong twist with a bulge, tapering chord, outlet angle opening towards the tip."""
    return dict(axial_width=44 - 10 * t + 3 * t * t, stagger_deg=30 + 16 * t + 3 * np.sin(np.pi * t),
                outlet_angle_deg=13 + 5 * t, max_thickness=0.18 - 0.07 * t,
                relative_pitch=0.70 + 0.15 * t)


LAWS = {"mild": law_mild, "twisted": law_twisted}


def stations(spacing, K):
    """K increasing radii on [R0, R1]."""
    s = np.linspace(0, 1, K)
    if spacing == "clustered":  # denser at hub and tip (cosine)
        s = 0.5 - 0.5 * np.cos(np.pi * s)
    elif spacing == "growing":  # gaps growing towards the tip: s = t^1.5
        s = s ** 1.5
    elif spacing == "jittered":  # uniform +- 30 % of a gap, seeded by K
        s[1:-1] += np.random.default_rng(K).uniform(-0.3, 0.3, K - 2) / (K - 1)
    return R0 + (R1 - R0) * s


def sections_at(law, radii):
    params = []
    for r in radii:
        p = dict(BASE)
        p.update({k: float(v) for k, v in LAWS[law]((r - R0) / (R1 - R0)).items()})
        params.append((float(r), interlin.CascadeParameters(**p)))
    return interlin.stack_cascade_profiles(params)


def run_case(case, variants):
    """Errors of every parameterisation on one blade: [(max, rms), ...] in variant order."""
    law, spacing, K = case
    r = stations(spacing, K)
    truth_r = np.array([a + f * (b - a) for a, b in zip(r, r[1:]) for f in (0.25, 0.5, 0.75)])
    sections = sections_at(law, r)
    truth = np.concatenate(sections_at(law, truth_r))
    out, chosen = [], None
    for span, span_degree in variants:
        L = interlin.loft(sections, span=span, span_degree=span_degree)
        d = L.surface.distance(truth)
        out.append((float(d.max()), float(np.sqrt(np.mean(d ** 2)))))
        if span == "auto" and span_degree == "auto":
            chosen = (L.span.used.parameters, L.span.used.degree,
                      ["%s %d" % (c.parameters, c.degree) for c in L.span.candidates])
    return out, chosen


def write_default_section(r, cases, variants, name, results, chosen):
    """What the default (span and span degree "auto") chose on every blade, and its error
    against the best fixed variant of the same blade."""
    r.text("""## The default: span and span degree chosen by leave-one-out

`interlin.loft(sections)` and `interlin loft` default to `span="auto"`, `span_degree="auto"`
(`--span auto --span-degree auto`): the candidates are the span parameters station (when the
sections' stations are detected: parallel planes or coaxial surfaces of revolution), chord length
and uniform, each with span degree min(K - 1, 9), 5 and 3 (those below K, without repeats);
every candidate is lofted with each interior section withheld in turn and the lowest
leave-one-out score wins (ties go to the earlier candidate). Centripetal spacing is not a
candidate. On these blades (their stations are parallel planes) the candidates were, in order
of preference: %s.""" % "; ".join(
        "K = %d: %s" % (K, ", ".join(next(c[2] for (_, _, k), c in zip(cases, chosen) if k == K)))
        for K in sorted({k for _, _, k in cases})))
    auto = variants.index(("auto", "auto"))
    rows, ratios = [], []
    for (law, sp, K), res, (p, q, _) in zip(cases, results, chosen):
        fixed = [i for i in range(len(variants)) if i != auto]
        best = min(fixed, key=lambda i: res[i][0])
        ratios.append(res[auto][0] / res[best][0])
        rows.append([law, sp, K, "%s, span degree %d" % (p, q), res[auto][0], name[best],
                     res[best][0], ratios[-1]])
    r.table("default_choice", ["law", "spacing", "K", "chosen by auto", "its max error",
                               "best fixed variant", "its max error", "ratio"], rows,
            "What the default chose on every blade", digits=3)
    r.text("The default's max error over the best fixed variant's (those of the tables below): "
           "at most %.2f, median %.2f over the %d blades (below 1 where the default's degree, "
           "e.g. K - 1, is not among the fixed variants)." % (max(ratios),
                                                             float(np.median(ratios)),
                                                             len(ratios)))


def main():
    args = arguments("spanwise_parameters", __doc__.splitlines()[0])
    study = Study("spanwise_parameters", "Spanwise parameters on synthetic blades", args)
    if args.quick:
        laws, spacings, counts = ["mild"], ["clustered"], [5, 9]
        variants = [("auto", "auto"), ("centripetal", 3), ("chord", 3)]
    else:
        laws, spacings, counts = list(LAWS), ["uniform", "clustered", "growing", "jittered"], [5, 9, 17]
        variants = [("auto", "auto")] + [(p, q) for q in (3, 5)
                                         for p in ("uniform", "centripetal", "chord", "station")]
    cases = [(law, sp, K) for law in laws for sp in spacings for K in counts]
    runs = study.map(lambda c: run_case(c, variants), cases, "blade")
    if not study.writer:
        return
    results = [errors for errors, _ in runs]
    chosen = [c for _, c in runs]
    r = study.report
    r.text("""Blades: profiles of 152 points (seed 004, G3 joints) at K stations on r in [200, 300]
(units of the profile lengths: axial width about 40), laws `mild` (as
data/profiles/turbine_blade_span.json) and `twisted` (stagger +16 deg plus a 3 deg bulge, chord
-23 %%, outlet angle +5 deg). Error: distance of the true profiles at 3 radii inside every gap to
the loft of the K stations (%d x 3 x 152 points per blade).""" % (max(counts) - 1))
    name = ["%s, span degree %s" % v for v in variants]
    write_default_section(r, cases, variants, name, results, chosen)
    rows = [[law, sp, K, n, mx, rms] for (law, sp, K), res in zip(cases, results)
            for n, (mx, rms) in zip(name, res)]
    r.table("errors", ["law", "spacing", "K", "parameterisation", "max", "rms"], rows,
            "Every blade and parameterisation", markdown=False)
    summary, wins = [], {n: 0 for n in name}
    for law in laws:
        fig, axes = plt.subplots(1, len(spacings), figsize=(4.2 * len(spacings), 4.2),
                                 sharey=True, squeeze=False)
        for ax, sp in zip(axes[0], spacings):
            h = [np.max(np.diff(stations(sp, K))) / (R1 - R0) for K in counts]
            for i, n in enumerate(name):
                e = [results[cases.index((law, sp, K))][i][0] for K in counts]
                order = loglog(ax, h, e, n)
                summary.append([law, sp, n] + e + [order])
            for K in counts:
                best = min(range(len(variants)), key=lambda i: results[cases.index((law, sp, K))][i][0])
                wins[name[best]] += 1
            ax.set_title("%s blade, %s stations" % (law, sp), fontsize=9)
            ax.set_xlabel("largest station gap / span")
            ax.grid(True, which="both", alpha=0.3)
            ax.legend(fontsize=6)
        axes[0][0].set_ylabel("max distance to the true blade")
        r.figure("convergence_%s" % law, fig,
                 "Max interpolation error against the largest station gap (log-log), fitted "
                 "orders in the legends: %s blade" % law)
    r.text("## Max error per blade and parameterisation")
    r.table("summary", ["law", "spacing", "parameterisation"] + ["K = %d" % K for K in counts]
            + ["fitted order"], summary, digits=3)
    r.table("wins", ["parameterisation",
                     "blades where it is best (max error; a tie counts for the upper row)"],
            [[n, wins[n]] for n in name])
    study.progress("wrote " + r.write())


if __name__ == "__main__":
    run("spanwise_parameters", main)
