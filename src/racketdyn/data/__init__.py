"""Shipped data: the built-in racket description (see README.md in this folder)."""
