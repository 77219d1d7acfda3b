"""Reading and writing files: racket descriptions (TOML) and plain CSV tables."""

from racketdyn.io.racket_file import default_racket, load_racket, racket_to_dict
from racketdyn.io.tables import read_load_deflection, read_points

__all__ = ["default_racket", "load_racket", "racket_to_dict", "read_load_deflection", "read_points"]
