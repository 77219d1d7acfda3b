"""Racket files of the new-user trials, shared by the tests that reproduce their findings."""

LAB_RACKET_102 = """schema_version = 1
name = "Trial9 285g 102sqin"

[racket]
mass_kg = 0.285
length_m = 0.685
balance_m = 0.335
swingweight_kgcm2 = 315.0
grip_m = 0.070

[head]
centre_x_m = 0.510
half_length_m = 0.170
area_cm2 = 658.06

[strings]
tension_n = 220.0
mains = 16
crosses = 19

[modal]
first_bending_hz = 165.0
"""
"""The ninth session's new-user trial racket: 285 g, 102 sq in, 165 Hz, 220 N."""

TRIAL_RACKET_100 = """schema_version = 1
name = "Trial 300g 100sqin"

[racket]
mass_kg = 0.300
length_m = 0.685
balance_m = 0.325
swingweight_kgcm2 = 320.0

[head]
centre_x_m = 0.505
half_length_m = 0.165
area_cm2 = 645.16

[strings]
tension_n = 235.0

[modal]
first_bending_hz = 145.0
"""
"""The eleventh session's new-user trial racket: 300 g, 100 sq in, 145 Hz, 235 N."""

TRIAL_RACKET_104 = """name = "Invented 276 g 104 sq in head-heavy"

[racket]
mass_kg = 0.276
length_m = 0.690
balance_m = 0.345
swingweight_kgcm2 = 318.0

[head]
centre_x_m = 0.510
half_length_m = 0.172
area_cm2 = 671.0

[modal]
first_bending_hz = 166.0
"""
"""The thirteenth session's new user's invented racket: 276 g, 104 sq in, 166 Hz, head-heavy."""
