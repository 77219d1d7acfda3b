"""Reading and writing files: racket descriptions (TOML), CSV tables and Universal Files."""

from racketdyn.io.frf_layout import read_frf_uff, read_frfs
from racketdyn.io.measured import MeasuredRebound, read_measured
from racketdyn.io.racket_file import (
    check_racket,
    default_racket,
    load_racket,
    racket_to_dict,
    write_racket_toml,
)
from racketdyn.io.tables import read_e_bg_table, read_load_deflection, read_points
from racketdyn.io.uff import (
    read_hammer_csv,
    read_hammer_uff,
    write_frf_uff,
    write_hammer_csv,
    write_hammer_uff,
    write_modes_uff,
)

__all__ = [
    "MeasuredRebound",
    "check_racket",
    "default_racket",
    "load_racket",
    "racket_to_dict",
    "read_e_bg_table",
    "read_frf_uff",
    "read_frfs",
    "read_hammer_csv",
    "read_hammer_uff",
    "read_load_deflection",
    "read_measured",
    "read_points",
    "write_frf_uff",
    "write_hammer_csv",
    "write_hammer_uff",
    "write_modes_uff",
    "write_racket_toml",
]
