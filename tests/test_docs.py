"""Every public object is documented, and every parameter of a public function is described."""

from __future__ import annotations

import inspect

import pytest

import racketdyn as rd
import racketdyn.impact as impact
import racketdyn.io as rio
import racketdyn.modal as modal

PUBLIC = sorted(
    {
        (m.__name__, name)
        for m in (rd, impact, rio, modal)
        for name in m.__all__
        if name != "__version__"
    }
)


@pytest.mark.parametrize(("module", "name"), PUBLIC)
def test_public_object_is_documented(module: str, name: str) -> None:
    obj = getattr(__import__(module, fromlist=[name]), name)
    doc = inspect.getdoc(obj)
    assert doc, f"{module}.{name} has no docstring"
    if inspect.isfunction(obj):
        for parameter in inspect.signature(obj).parameters:
            assert parameter in doc, f"{module}.{name}: parameter {parameter!r} is not described"
