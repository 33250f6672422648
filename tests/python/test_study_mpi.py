"""A study sweep under `mpirun -n 2` writes exactly the tables of the serial run."""
import glob
import os

from test_studies import run_study


def test_mpi_sweep_gives_the_serial_tables(tmp_path):
    run_study("spanwise_parameters", tmp_path / "serial")
    run_study("spanwise_parameters", tmp_path / "mpi", mpi_ranks=2)
    serial = sorted(os.path.basename(p) for p in glob.glob(str(tmp_path / "serial" / "*.csv")))
    assert serial == sorted(os.path.basename(p) for p in glob.glob(str(tmp_path / "mpi" / "*.csv")))
    for name in serial + ["report.md"]:
        assert (tmp_path / "serial" / name).read_bytes() == (tmp_path / "mpi" / name).read_bytes(), name
