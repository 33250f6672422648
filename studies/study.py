"""What the study scripts share: finding the interlin module, command-line arguments, MPI
distribution of cases, fitted convergence orders, and the report every study writes into the
folder it is given: CSV files holding every number, PNG plots, and report.md embedding them.

A study is run as

    python3 studies/NAME.py [OUT_DIR] [--quick] [-q]             # serial
    mpirun -n 4 python3 studies/NAME.py [OUT_DIR] [--quick] [-q]  # cases spread over 4 ranks

through `run(NAME, main)`: bad input (a saved file that does not parse, an OUT_DIR that is a
file, an unreadable file, a failing tool) ends it with one line `NAME: message` naming the file,
exit status 1 and no report, as the CLI does.

OUT_DIR defaults to docs/studies/NAME (the reports docs/benchmarks.md links). --quick runs a
tiny version of the study (the smoke tests in CI use it). The serial and the MPI run write the
same files: every case is computed the same way wherever it runs, and rank 0 assembles the
results in case order.
"""
import argparse
import csv
import math
import os
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data")

# The module from PYTHONPATH, else from this checkout's build/python (README command 2).
try:
    import interlin
except ImportError:
    sys.path.insert(0, os.path.join(ROOT, "build", "python"))
    import interlin

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Environment variables set by MPI launchers (Open MPI, MPICH/Hydra, PMIx, Slurm's srun): only
# then is mpi4py imported, so that a serial run never initialises MPI.
_MPI_ENV = ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS")


def mpi_world():
    """(rank, size, comm): the MPI world when launched by mpirun/srun, else (0, 1, None)."""
    if not any(v in os.environ for v in _MPI_ENV):
        return 0, 1, None
    from mpi4py import MPI
    comm = MPI.COMM_WORLD
    return comm.Get_rank(), comm.Get_size(), comm


class StudyError(Exception):
    """Bad input to a study; `run` prints it as one line `NAME: message`."""


def run(name, main):
    """Calls main(). A StudyError, interlin.InputError or OSError (bad input, a file that cannot
    be read or written) ends the study with one line `NAME: message` on stderr and exit status 1,
    not a traceback; under MPI the other ranks are stopped too (they would wait in a gather)."""
    try:
        main()
    except (StudyError, interlin.InputError, OSError) as e:
        if isinstance(e, OSError) and e.filename is not None:
            message = "%s: %s" % (e.filename, e.strerror)
        else:
            message = str(e)
        print("%s: %s" % (name, message), file=sys.stderr, flush=True)
        _, size, comm = mpi_world()
        if size > 1:
            comm.Abort(1)
        sys.exit(1)


def folder(path):
    """Creates the folder `path` (and its parents) unless it exists; a file in its place is a
    StudyError, not os.makedirs' 'File exists'."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise StudyError("%s: not a folder" % path)
    os.makedirs(path, exist_ok=True)
    return path


def arguments(name, description, extra=None):
    """Parses OUT_DIR (default docs/studies/NAME), --quick and -q; `extra(parser)` adds more."""
    p = argparse.ArgumentParser(description=description)
    p.add_argument("out", nargs="?", default=os.path.join(ROOT, "docs", "studies", name),
                   help="output folder (default docs/studies/%s)" % name)
    p.add_argument("--quick", action="store_true", help="a tiny version (smoke test)")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    if extra:
        extra(p)
    return p.parse_args()


class Study:
    """One run of a study: progress lines, the cases spread over MPI ranks, the report."""

    def __init__(self, name, title, args):
        self.name, self.title, self.args = name, title, args
        self.rank, self.size, self.comm = mpi_world()
        self.report = Report(args.out, title, name, args) if self.rank == 0 else None

    def progress(self, what):
        if not self.args.quiet:
            print("[%s%s] %s" % (self.name, " rank %d" % self.rank if self.size > 1 else "",
                                 what), file=sys.stderr, flush=True)

    def map(self, run, cases, what="cases"):
        """[run(c) for c in cases], the cases dealt round-robin over the MPI ranks. Returns the
        results in case order on rank 0 and None on the other ranks."""
        mine = []
        for i in range(self.rank, len(cases), self.size):
            self.progress("%s %d/%d" % (what, i + 1, len(cases)))
            mine.append((i, run(cases[i])))
        if self.comm is None:
            return [r for _, r in mine]
        parts = self.comm.gather(mine, root=0)
        if self.rank != 0:
            return None
        results = [None] * len(cases)
        for part in parts:
            for i, r in part:
                results[i] = r
        return results

    @property
    def writer(self):
        """True on the rank that writes the report."""
        return self.rank == 0


def fit_order(h, e, floor=0.0):
    """Least-squares slope of log e against log h over the errors above `floor` (round-off)."""
    pts = [(math.log(a), math.log(b)) for a, b in zip(h, e) if b > floor]
    if len(pts) < 2:
        return float("nan")
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


def loglog(ax, h, e, label, floor=0.0, marker="o"):
    """One convergence curve with its fitted order in the legend; returns the order."""
    order = fit_order(h, e, floor)
    ax.loglog(h, e, marker=marker, label="%s (order %.2f)" % (label, order))
    return order


def label_axes(ax, xlabel, ylabel, title=None, legend_size=7):
    """Axis labels, an optional title, a light log grid and the legend of a convergence plot."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=legend_size)


def _atomic(path, write, mode="w"):
    d = os.path.dirname(path) or "."
    fd, tmp = tempfile.mkstemp(dir=d, suffix=os.path.splitext(path)[1])
    try:
        with os.fdopen(fd, mode) as f:
            write(f)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def fmt(x, digits=4):
    if isinstance(x, (float, np.floating)):
        return "%.*g" % (digits, x)
    return str(x)


class Report:
    """report.md with its CSV tables and PNG figures in one folder. Files are written whole or
    not at all (temporary name, then rename)."""

    def __init__(self, out, title, name, args):
        self.out = folder(out)
        command = "python3 studies/%s.py" % name
        if args.quick:
            command += " --quick"
        self.parts = ["# %s\n" % title,
                      "Generated by `%s OUT_DIR` (serial or under `mpirun`); every number below "
                      "is in the CSV files of this folder.\n" % command]

    def text(self, markdown):
        self.parts.append(markdown.strip("\n") + "\n")

    def table(self, name, header, rows, caption=None, digits=4, markdown=True):
        """Writes NAME.csv (full precision) and, unless markdown is False, a Markdown table."""
        def write(f):
            w = csv.writer(f, lineterminator="\n")
            w.writerow(header)
            for r in rows:
                w.writerow([repr(float(v)) if isinstance(v, (float, np.floating)) else v
                            for v in r])
        _atomic(os.path.join(self.out, name + ".csv"), write)
        if caption:
            self.parts.append("%s ([%s.csv](%s.csv))\n" % (caption, name, name))
        if markdown:
            lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
            lines += ["| " + " | ".join(fmt(v, digits) for v in r) + " |" for r in rows]
            self.parts.append("\n".join(lines) + "\n")

    def figure(self, name, fig, caption):
        """Saves the Matplotlib figure as NAME.png and embeds it."""
        path = os.path.join(self.out, name + ".png")
        _atomic(path, lambda f: fig.savefig(f, format="png", dpi=110,
                                            metadata={"Software": None}), mode="wb")
        plt.close(fig)
        self.parts.append("![%s](%s.png)\n\n*%s*\n" % (caption, name, caption))

    def write(self):
        text = "\n".join(self.parts)
        _atomic(os.path.join(self.out, "report.md"), lambda f: f.write(text))
        return os.path.join(self.out, "report.md")
