"""``figures.nc`` is written as xarray's ``to_netcdf(engine="scipy")`` writes it, byte for byte,
without xarray asking dask for its scheduler (issue 27's speed: that question imports
``dask.distributed``)."""

from __future__ import annotations

import functools
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from figure_catch import default_paper_figures
from racketdyn.workflows.figure_data import write_figure_data


def _datasets() -> list[xr.Dataset]:
    data = default_paper_figures()
    odd = xr.Dataset(  # what the other steps' data hold: strings, NaN, bools, attributes
        {
            "odd_name": ("odd_point", np.array(["free", "hand", "pinned"])),
            "odd_value_m": ("odd_point", np.array([1.5, np.nan, -2.0]), {"units": "m"}),
            "odd_flag": ("odd_point", np.array([True, False, True])),
        },
        attrs={"odd_description": "a dataset of every kind of variable"},
    )
    return [data.to_xarray(), odd]


def _printed(code: str, tmp_path: Path) -> list[str]:
    """What ``python -c code FILE`` prints (FILE a netCDF file in ``tmp_path``), word by word."""
    out = subprocess.run(
        [sys.executable, "-c", code, str(tmp_path / "f.nc")],
        capture_output=True,
        text=True,
        check=True,
    )
    return out.stdout.split()


def test_figures_nc_has_the_bytes_of_to_netcdf(tmp_path: Path) -> None:
    datasets = _datasets()
    ours = write_figure_data(tmp_path / "ours.nc", datasets)
    joined = xr.merge(datasets, combine_attrs="override")
    joined.attrs = {}
    for dataset in datasets:
        joined.attrs.update(dataset.attrs)
    joined.attrs["title"] = "racketdyn: the data each figure of the run draws"
    joined.to_netcdf(tmp_path / "xarray.nc", engine="scipy")
    assert ours.read_bytes() == (tmp_path / "xarray.nc").read_bytes()
    with xr.open_dataset(ours, engine="scipy") as back:
        assert back["odd_flag"].dtype == bool
        assert str(back["odd_name"].values[1]) == "hand"


@pytest.mark.slow
def test_writing_figures_nc_imports_no_dask_distributed(tmp_path: Path) -> None:
    code = (
        "import sys, numpy as np, xarray as xr; "
        "from racketdyn.workflows.figure_data import write_figure_data; "
        "write_figure_data(sys.argv[1], [xr.Dataset({'a': ('x', np.arange(3.0))})]); "
        "print('distributed' in sys.modules)"
    )
    assert _printed(code, tmp_path) == ["False"]


@pytest.mark.slow
def test_writing_figures_nc_imports_no_dask(tmp_path: Path) -> None:
    """xarray imports ``dask.array`` at its first Variable, and ``dask`` to encode text, only to
    ask whether an array is dask's (≈ 0.5 s of ``predict`` and ``identify``); a step's
    figures.nc is built and written without them, and xarray knows dask's arrays again after."""
    code = (
        "import sys, numpy as np, xarray as xr; "
        "from racketdyn.workflows.figure_data import write_figure_data; "
        "data = lambda: xr.Dataset({'a': ('x', np.arange(3.0))}); "
        "write_figure_data(sys.argv[1], [data]); "
        "print('dask.array' in sys.modules, 'dask' in sys.modules); "
        "import dask.array as da; "
        "from xarray.namedarray.pycompat import is_chunked_array; "
        "print(xr.DataArray(da.zeros(3), dims='x').chunks is not None, "
        "is_chunked_array(da.zeros(3)))"
    )
    assert _printed(code, tmp_path) == ["False", "False", "True", "True"]


def _same(dataset: xr.Dataset) -> xr.Dataset:
    return dataset


def test_figures_nc_of_datasets_made_while_writing_has_the_same_bytes(tmp_path: Path) -> None:
    datasets = _datasets()
    given = write_figure_data(tmp_path / "given.nc", datasets)
    made = write_figure_data(tmp_path / "made.nc", [functools.partial(_same, d) for d in datasets])
    assert made.read_bytes() == given.read_bytes()
