"""Reprs in Python syntax that rebuild the object, run-time docstrings with
units on every class, method and property of the bindings, and real
signatures (no ``*args, **kwargs`` or ``...``) for help() and IDEs."""

from __future__ import annotations

import inspect
import re
from typing import Any

import pytest

import tcarod
from tcarod import Actuator, Body, Material, Routing, Section, Tca, _core
from tcarod.batch import fig6_square_robot

TCA = Tca(0.497, 0.110, 2e-3, 300.0)
NAMESPACE: dict[str, Any] = {
    n: getattr(tcarod, n) for n in ("Actuator", "Body", "Material", "Robot", "Routing", "Section", "Tca")
}

VALUES = [
    Material.silver_coated_nylon(),
    Material(youngs_modulus=1e9, shear_modulus=2e8, expansion=1e-4, t_ref=20.0, t_min=20.0, name="it's mine"),
    TCA,
    Tca(0.497, 0.110, 2e-3, 300.0, "contraction"),
    Section.circle(0.014),
    Section.rectangle(0.01, 0.02),
    Section.custom(1e-4, 1e-9, 2e-9, 3e-9),
    Routing.straight(0.005, 0.0),
    Routing.helix(0.003, 50.0, 0.25),
    Body(
        0.04,
        Section.rectangle(0.01, 0.01),
        37.8e3,
        density=1040.0,
        gravity=[0.0, 0.0, -9.81],
        omega_star=[0.0, 5.0, 0.0],
    ),
    Actuator.tca(TCA, Routing.straight(0.003, 0.0), pretension_n=0.01),
    Actuator.tca(TCA, Routing.straight(0.003, 0.0), 0.0, 0.04, 0.98),
    Actuator.tendon(Routing.straight(0.0, 0.003)),
    Actuator.linear_tendon(300.0, Routing.straight(0.0, 0.003), 0.01, 0.03),
    fig6_square_robot(),
]


@pytest.mark.parametrize("obj", VALUES, ids=lambda o: type(o).__name__)
def test_value_reprs_are_python_that_rebuilds_the_object(obj: Any) -> None:
    text = repr(obj)
    assert eval(text, NAMESPACE) == obj  # noqa: S307 - our own repr
    assert not re.search(r"[{}]|Some\(|None \{|\btrue\b|\bfalse\b", text), text  # no Rust Debug output


def test_result_reprs_are_python_syntax_without_rust_debug() -> None:
    robot = fig6_square_robot()
    sol = robot.solve([90.0, 90.0])
    inv = tcarod.tip_position(robot, [0.02, 0.0, 0.03], groups=[0, 0])  # far outside the workspace
    for obj in (sol, inv):
        text = repr(obj)
        assert "success=" in text and not re.search(r"\btrue\b|\bfalse\b|[{}]", text), text
    assert "success=False" in repr(inv) and "status=1" in repr(inv)
    assert repr(Body(0.04, Section.circle(0.01), 1e5)).startswith(
        "Body(length=0.04, section=Section.circle(diameter=0.01)"
    )
    assert repr(Routing.straight(0.005, 0.0)) == "Routing.straight(x=0.005, y=0.0)"


CLASSES = [
    _core.Tca,
    _core.Material,
    _core.Section,
    _core.Routing,
    _core.Body,
    _core.Actuator,
    _core.Robot,
    _core.Solution,
    _core.InverseResult,
    _core.BlockedResult,
]
UNIT = re.compile(r"\[[^\]]+\]|`")  # a unit in brackets, or the named value or type in backticks


def _members(cls: type) -> list[tuple[str, Any]]:
    return [(n, v) for n, v in vars(cls).items() if not n.startswith("_")]


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_every_class_method_and_property_has_a_run_time_docstring(cls: type) -> None:
    assert cls.__doc__ and len(cls.__doc__.strip()) > 20
    missing = [n for n, v in _members(cls) if not (getattr(v, "__doc__", None) or "").strip()]
    assert not missing, f"{cls.__name__}: no docstring on {missing}"


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_property_docstrings_give_units_or_meaning(cls: type) -> None:
    props = [(n, v) for n, v in _members(cls) if inspect.isdatadescriptor(v)]
    bad = [n for n, v in props if not UNIT.search(v.__doc__ or "")]
    assert not bad, f"{cls.__name__}: property docs without a unit or value description: {bad}"


def test_signatures_are_real() -> None:
    fns: list[Any] = [
        _core.Robot,
        _core.Body,
        _core.Tca,
        _core.Material,
        _core.Robot.solve,
        _core.Robot.sweep,
        _core.Actuator.tca,
        _core.Routing.helix,
        _core.tip_position,
        _core.solve_batch,
        _core.blocked_temperature,
        _core.blocked_force,
    ]
    for f in fns:
        sig = str(inspect.signature(f))
        assert "Ellipsis" not in sig and "..." not in sig, (f, sig)
    assert str(inspect.signature(_core.Robot)) == "(body, actuators=(), *, spacer_disks=False)"
    assert "steps=100" in str(inspect.signature(_core.Robot.solve))
    assert "pretension_n=None" in str(inspect.signature(_core.Actuator.tca))
