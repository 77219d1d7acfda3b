"""Shared fixtures: the built-in racket, the default ball and their modal model (built once)."""

from __future__ import annotations

import pytest

import racketdyn as rd


@pytest.fixture(scope="session")
def racket() -> rd.Racket:
    return rd.default_racket()


@pytest.fixture(scope="session")
def ball() -> rd.Ball:
    return rd.Ball()


@pytest.fixture(scope="session")
def model(racket: rd.Racket) -> rd.ModalModel:
    return rd.modal_model_for(racket)


@pytest.fixture(scope="session")
def law(racket: rd.Racket, ball: rd.Ball) -> rd.RestoringForce:
    return rd.compound_law(racket, ball)
