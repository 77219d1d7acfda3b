"""Measurement: hammer-test records, FRF estimation, quality checks and contact times."""

from racketdyn.measurement.records import (
    FRF_TYPES,
    RESPONSE_TYPES,
    FrfReferences,
    FrfSet,
    HammerRecords,
)

__all__ = ["FRF_TYPES", "RESPONSE_TYPES", "FrfReferences", "FrfSet", "HammerRecords"]
