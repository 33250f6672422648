#!/usr/bin/env python3
"""Implicit normalisation quality: how close an implicit body F (F > 0 inside) is to the signed
distance d to its boundary, for every kind of implicit the library makes, on bodies whose exact
signed distance is known in closed form.

Measures (issue 10's normalisation criterion, applied to every implicit): points on the surface
offset by delta along the exact normal, outside (delta from 0.1 % to 5 % of the bounding-box
diagonal) and inside (the same, up to a quarter of the body's thickness); the ratio F / d at them
(1 for the distance itself, target [0.9, 1.1]); and max |F - d| over random points of a band
|d| <= 5 % of the diagonal and of the whole box.

Implicits (cases: body x implicit): the library's R-function primitive of the body (seed 000
normalised to first order, conjunctions by R0), the same through rf.normalize (seed 000 (2.26)),
and the partition-of-unity implicit fitted to a cloud sampled from the body (fit_cloud_implicit,
exact normals, no noise). Cases are spread over MPI ranks under mpirun; the tables are the same.

Usage: python3 studies/implicit_normalisation.py [OUT_DIR] [--quick] [-q]   (~1 min)
       mpirun -n 2 python3 studies/implicit_normalisation.py OUT_DIR
"""
import numpy as np

from study import Study, arguments, interlin, plt, run

rf = interlin.rf
OFFSETS = [0.001, 0.002, 0.005, 0.01, 0.02, 0.05]  # delta / bounding-box diagonal
BAND = 0.05  # the band |d| <= BAND * diagonal of the max |F - d| measure
RATIO_TARGET = (0.9, 1.1)  # issue 10's normalisation target for |F| / delta


class Body:
    """A solid with a closed-form signed distance (positive inside), area-uniform surface samples
    with outward normals, its R-function primitive and its thickness (for inside offsets)."""

    def __init__(self, name, half, thickness, expr, sdf, sample):
        self.name, self.thickness = name, thickness
        half = np.asarray(half, dtype=float)
        self.box = np.array([-half, half]) * 1.2  # 20 % margin: outside offsets up to 5 % fit
        self.diagonal = float(np.linalg.norm(2 * half))
        self.expr, self.sdf, self.sample = expr, sdf, sample


def box_sdf(q, half):
    """Signed distance (positive inside) of the box |q_i| <= half_i, any dimension."""
    e = np.abs(q) - half
    return -(np.linalg.norm(np.maximum(e, 0), axis=1) + np.minimum(e.max(axis=1), 0))


def sphere_samples(n, rng, R=1.0):
    N = rng.normal(size=(n, 3))
    N /= np.linalg.norm(N, axis=1)[:, None]
    return R * N, N


def torus_samples(n, rng, R=1.0, r=0.4):
    """Area-uniform on the torus: tube angle v accepted with probability (R + r cos v)/(R + r)."""
    u, v = [], []
    while len(u) < n:
        a, b, c = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 1, n)
        keep = c < (R + r * np.cos(b)) / (R + r)
        u, v = np.r_[u, a[keep]][:n], np.r_[v, b[keep]][:n]
    N = np.c_[np.cos(v) * np.cos(u), np.cos(v) * np.sin(u), np.sin(v)]
    return np.c_[R * np.cos(u), R * np.sin(u), np.zeros(n)] + r * N, N


def cylinder_samples(n, rng, R=1.0, h=0.6):
    """Side and caps by area."""
    side = rng.uniform(size=n) < 2 * h / (2 * h + R)
    t = rng.uniform(0, 2 * np.pi, n)
    rho = np.where(side, R, R * np.sqrt(rng.uniform(size=n)))
    z = np.where(side, rng.uniform(-h, h, n), h * np.sign(rng.uniform(-1, 1, n)))
    P = np.c_[rho * np.cos(t), rho * np.sin(t), z]
    N = np.where(side[:, None], np.c_[np.cos(t), np.sin(t), np.zeros(n)],
                 np.c_[np.zeros(n), np.zeros(n), np.sign(z)])
    return P, N


def cuboid_samples(n, rng, half=(1.0, 0.7, 0.5)):
    """Faces by area."""
    half = np.asarray(half)
    area = np.array([half[1] * half[2], half[0] * half[2], half[0] * half[1]])
    axis = rng.choice(3, n, p=area / area.sum())
    side = np.sign(rng.uniform(-1, 1, n))
    P = rng.uniform(-half, half, (n, 3))
    P[np.arange(n), axis] = side * half[axis]
    N = np.zeros((n, 3))
    N[np.arange(n), axis] = side
    return P, N


def bodies():
    x, y, z = rf.x, rf.y, rf.z
    cyl = lambda P: box_sdf(np.c_[np.hypot(P[:, 0], P[:, 1]), P[:, 2]], np.array([1.0, 0.6]))
    return {
        "sphere": Body("sphere", [1, 1, 1], 2.0, rf.sphere(x, y, z, 1.0),
                       lambda P: 1 - np.linalg.norm(P, axis=1), sphere_samples),
        "torus": Body("torus", [1.4, 1.4, 0.4], 0.8, rf.torus(x, y, z, 1.0, 0.4),
                      lambda P: 0.4 - np.hypot(np.hypot(P[:, 0], P[:, 1]) - 1, P[:, 2]),
                      torus_samples),
        "cylinder": Body("cylinder", [1, 1, 0.6], 1.2, rf.cylinder(x, y, z, 1.0, 0.6), cyl,
                         cylinder_samples),
        "cuboid": Body("cuboid", [1, 0.7, 0.5], 1.0, rf.cuboid(x, y, z, 1.0, 0.7, 0.5),
                       lambda P: box_sdf(P, np.array([1, 0.7, 0.5])), cuboid_samples),
    }


def implicit(body, kind, cloud_points):
    if kind == "R-function":
        return rf.compile(body.expr, body.box)
    if kind == "R-function, normalised":
        return rf.compile(rf.normalize(body.expr), body.box)
    P, N = body.sample(cloud_points, np.random.default_rng(7))
    return interlin.fit_cloud_implicit(interlin.PointCloud(P, N), threads=1).function


def measure(body, F, samples):
    """Per offset: (signed delta / diagonal, min, 1 %, 99 % quantiles and max of F/d, fraction in
    the target) and the
    max |F - d| in the band and over the box."""
    rng = np.random.default_rng(11)
    S, N = body.sample(samples, rng)
    rows = []
    for sign in (1, -1):  # outside, inside
        for o in OFFSETS:
            delta = o * body.diagonal
            if sign < 0 and delta > body.thickness / 4:
                continue
            P = S + sign * delta * N
            ratio = F(P) / body.sdf(P)
            ok = (ratio >= RATIO_TARGET[0]) & (ratio <= RATIO_TARGET[1])
            q1, q99 = np.quantile(ratio, [0.01, 0.99])
            rows.append((sign * o, float(ratio.min()), float(q1), float(q99), float(ratio.max()),
                         float(ok.mean())))
    Q = rng.uniform(body.box[0], body.box[1], (4 * samples, 3))
    d, f = body.sdf(Q), F(Q)
    band = np.abs(d) <= BAND * body.diagonal
    return rows, float(np.max(np.abs(f - d)[band])), float(np.max(np.abs(f - d)))


def run_case(case, samples, cloud_points):
    body = bodies()[case[0]]
    return measure(body, implicit(body, case[1], cloud_points), samples)


def main():
    args = arguments("implicit_normalisation", __doc__.splitlines()[0])
    study = Study("implicit_normalisation", "Implicit normalisation quality", args)
    names = ["sphere", "cuboid"] if args.quick else list(bodies())
    kinds = ["R-function", "R-function, normalised", "cloud implicit"]
    samples, cloud_points = (2000, 3000) if args.quick else (20000, 30000)
    cases = [(b, k) for b in names for k in kinds]
    results = study.map(lambda c: run_case(c, samples, cloud_points), cases, "body/implicit")
    if not study.writer:
        return
    write_report(study.report, names, kinds, cases, results, samples, cloud_points)
    study.progress("wrote " + study.report.write())


def write_report(r, names, kinds, cases, results, samples, cloud_points):
    B = bodies()
    r.text("""Bodies with closed-form signed distances: unit sphere, torus (R = 1, r = 0.4),
cylinder (R = 1, |z| <= 0.6), cuboid 2 x 1.4 x 1. Offsets along the exact normal at %d
area-uniform surface points, delta in %s of the bounding-box diagonal, outside (+) and inside
(-, up to a quarter of the thickness); F / d with d the exact signed distance there (target
[%.1f, %.1f]). The cloud implicit is fitted to %d exact samples with exact normals. `band`:
max abs(F - d) over %d random points of the box with |d| <= %g diagonal; `box`: over all of them."""
           % (samples, ", ".join("%g %%" % (100 * o) for o in OFFSETS), RATIO_TARGET[0],
              RATIO_TARGET[1], cloud_points, 4 * samples, BAND))
    rows = [[b, k] + list(x) for (b, k), (res, _, _) in zip(cases, results) for x in res]
    r.table("offsets", ["body", "implicit", "delta / diagonal", "min F/d", "F/d 1 % quantile",
                        "F/d 99 % quantile", "max F/d", "fraction in [0.9, 1.1]"], rows,
            "F / d at offset surface points", markdown=False)
    summary = []
    for (b, k), (res, band, box) in zip(cases, results):
        summary.append([b, k, min(x[1] for x in res), min(x[2] for x in res),
                        max(x[3] for x in res), max(x[4] for x in res), min(x[5] for x in res),
                        band / B[b].diagonal, box / B[b].diagonal])
    if "sphere" in names:  # closed form: (1 - r^2) / 2 at r = 1 + delta gives F / d = 1 + delta / 2
        delta = OFFSETS[-1] * B["sphere"].diagonal
        got = max(x[4] for x in results[cases.index(("sphere", "R-function"))][0])
        r.text("Check against the closed form: the sphere primitive (1 - r^2) / 2 has F / d = 1 + "
               "delta / 2 outside, %.6f at the largest offset; measured max %.6f." %
               (1 + delta / 2, got))
    r.text("## Summary")
    r.table("summary", ["body", "implicit", "min F/d", "1 % quantile", "99 % quantile",
                        "max F/d", "worst fraction in [0.9, 1.1]",
                        "max abs(F - d) in band / diagonal", "max abs(F - d) in box / diagonal"],
            summary, "Over all offsets", digits=3)
    fig, axes = plt.subplots(2, len(names), figsize=(4 * len(names), 7), squeeze=False)
    for col, b in enumerate(names):
        for row, sign in enumerate((1, -1)):
            ax = axes[row][col]
            for k in kinds:
                res = [x for x in results[cases.index((b, k))][0] if np.sign(x[0]) == sign]
                o = [abs(x[0]) for x in res]
                ax.fill_between(o, [x[2] for x in res], [x[3] for x in res], alpha=0.3, label=k)
            ax.axhspan(*RATIO_TARGET, color="k", alpha=0.08)
            ax.set_xscale("log")
            ax.set_ylim(0, 2.5)
            ax.set_title("%s, %s" % (b, "outside" if sign > 0 else "inside"), fontsize=9)
            ax.set_xlabel("delta / diagonal")
            ax.grid(True, which="both", alpha=0.3)
        axes[0][col].legend(fontsize=7)
    for row in axes:
        row[0].set_ylabel("F / d, 1 % to 99 % quantile")
    fig.tight_layout()
    r.figure("ratios", fig, "F / d at offset surface points, 1 % to 99 % quantiles (grey: the "
             "target 0.9 to 1.1; min and max in the tables)")


if __name__ == "__main__":
    run("implicit_normalisation", main)
