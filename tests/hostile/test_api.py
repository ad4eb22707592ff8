"""The Python API on wrong types and hostile values: each public entry point either gives a
result or raises a SymkinError (never TypeError, ZeroDivisionError, SympifyError, ...), and
no string reaches Python's evaluator."""

import math
import os
from fractions import Fraction

import pytest
import sympy as sp

import symkin
from symkin import SymkinError, schemes
from symkin import symbols as S
from symkin.drives import AngleLaw, ConstantSpeed, EllipticalGears
from symkin.mechanisms.cardan import CardanSlider
from symkin.mechanisms.helical import (
    helical_gear,
    lead,
    pitch_radius,
    working_pitch_radius,
)
from symkin.mechanisms.helical.balanced import HelicalRequest, existence_interval
from symkin.mechanisms.multistage.lostmotion import StageErrorModel, U
from symkin.mechanisms.multistage.split import SplitProblem
from symkin.mechanisms.multistage.stages import enumerate_stages
from symkin.model import Gear, Link, Mechanism
from symkin.parsing import parse_expression, parse_integer, parse_number
from symkin.values import as_expr, as_float, as_fraction, as_integer, as_rational, as_real, as_values

MARKER = "PWNED_API"
INJECTION = f"__import__('os').system('touch {MARKER}')"
#: Values put in place of each argument of every entry point below.
BAD = [None, True, "", INJECTION, "abc", [1, 2], {}, object(), float("nan"), float("inf"), -1, 0, 10**400,
       Fraction(1, 3), sp.nan, sp.zoo, sp.I, sp.Symbol("q"),
       # numbers that are not finite reals, written so that SymPy keeps them
       sp.tan(sp.pi / 2, evaluate=False), sp.atan2(0, 0, evaluate=False), sp.log(0, evaluate=False), sp.acos(2),
       # text, which the library never reads (symkin.parse does, bounded: tests/parsing/test_expressions.py)
       "tan(pi/2)", "((sqrt(2)**999)**999)**999", "sin(exp(exp(exp(3))))"]
# Sizes are not bounded in the library (the parser bounds what is typed): a Python caller's
# sp.exp(10**6) is computed with as SymPy computes, so such values are not in BAD.

AA = schemes.two_row("AA", teeth=(100, 100, 101, 99))
MOTION = schemes.single_row_AI(radii=(1, 1, 3)).motion({"4": 0, "H": 1})
PARTICLE = MOTION.particle("2", (1, 0))
MODEL = StageErrorModel(1 + U / 10)

#: name -> (function, valid keyword arguments); each argument is replaced by each BAD value.
ENTRY_POINTS = {
    "schemes.scheme": (lambda name, teeth: schemes.scheme(name, teeth=teeth), dict(name="AA", teeth=(100, 100, 101, 99))),
    "schemes.common_ring_train": (lambda teeth, ring: schemes.common_ring_train(teeth=teeth, ring=ring),
                                  dict(teeth=[(20, 30), (40, 20)], ring=80)),
    "schemes.cardan": (lambda teeth, carrier_angle: schemes.cardan(teeth=teeth, carrier_angle=carrier_angle),
                       dict(teeth=(20, 40), carrier_angle=0)),
    "Gear": (lambda name, radius, teeth: Gear(name, radius, teeth=teeth), dict(name="1", radius=10, teeth=20)),
    "Gear.from_teeth": (lambda name, teeth, module: Gear.from_teeth(name, teeth, module=module), dict(name="1", teeth=20, module=1)),
    "Link.planet": (lambda name, carrier, arm, position_angle: Link.planet(name, Gear("2", 1), carrier=carrier, arm=arm,
                                                                           position_angle=position_angle),
                    dict(name="2", carrier="H", arm=2, position_angle=0)),
    "Mechanism": (lambda links, meshes: Mechanism(links=links, meshes=meshes),
                  dict(links=list(schemes.single_row_AI().links), meshes=[("1", "2"), ("2", "4")])),
    "Mechanism.ratio": (lambda driver, driven, fixed: AA.ratio(driver, driven, fixed=fixed), dict(driver="H", driven="1", fixed="4")),
    "Mechanism.speeds": (lambda known: AA.speeds(known), dict(known={"1": 100, "4": 0})),
    "Mechanism.speeds value": (lambda w: AA.speeds({"1": w, "4": 0}), dict(w=100)),
    "Mechanism.motion": (lambda inputs: AA.motion(inputs), dict(inputs={"1": 1, "4": 0})),
    "Motion.particle": (lambda link, point: MOTION.particle(link, point), dict(link="2", point=(1, 0))),
    "Particle.sample": (lambda t_end, samples: PARTICLE.sample(t_end, samples=samples), dict(t_end=1.0, samples=5)),
    "Motion.turn_time": (lambda turns, link: MOTION.turn_time(turns, link=link), dict(turns=1, link="H")),
    "compile": (lambda laws, args: symkin.compile(laws, args), dict(laws=AA.ratio("H", "1", fixed="4"), args=None)),
    "latex": (lambda obj: symkin.latex(obj), dict(obj=AA.ratio("H", "1", fixed="4"))),
    "ConstantSpeed": (lambda omega: ConstantSpeed(omega), dict(omega=1)),
    "EllipticalGears": (lambda omega, e, m: EllipticalGears(omega, e, m), dict(omega=1, e=sp.Rational(2, 5), m=1)),
    "AngleLaw": (lambda law: AngleLaw(law), dict(law=S.t + sp.sin(S.t))),
    "CardanSlider.build": (lambda length, drive, teeth, pin_radius, pin_angle, guide_angle:
                           CardanSlider.build(length, drive=drive, teeth=teeth, pin_radius=pin_radius, pin_angle=pin_angle,
                                              guide_angle=guide_angle),
                           dict(length=1, drive=1, teeth=(20, 40), pin_radius=1, pin_angle=0, guide_angle=0)),
    "enumerate_stages": (lambda ring, satellites, zmin, zmax, ha: enumerate_stages(ring, satellites, zmin=zmin, zmax=zmax, ha=ha),
                         dict(ring=60, satellites=3, zmin=12, zmax=60, ha=1)),
    "StageErrorModel": (lambda expr: StageErrorModel(expr), dict(expr=1 + U / 10)),
    "StageErrorModel.linear": (lambda a, b: StageErrorModel.linear(a, b), dict(a=1, b=sp.Rational(1, 10))),
    "SplitProblem.build": (lambda total, stages, lower, upper, model: SplitProblem.build(total, stages, lower=lower, upper=upper,
                                                                                         model=model),
                           dict(total=100, stages=2, lower=2, upper=12, model=MODEL)),
    "HelicalRequest": (lambda scheme, ratio, satellites, normal_modules: HelicalRequest(
        scheme=scheme, ratio=ratio, satellites=satellites, normal_modules=normal_modules),
        dict(scheme="AI", ratio=25, satellites=3, normal_modules=(2, 2))),
    "existence_interval": (lambda scheme, satellites, delta: existence_interval(scheme, satellites, delta),
                           dict(scheme="AI", satellites=3, delta=sp.Rational(1, 2))),
    "helical.pitch_radius": (lambda teeth, normal_module, beta: pitch_radius(teeth, normal_module, beta),
                             dict(teeth=sp.Integer(20), normal_module=2, beta=sp.Symbol("beta", positive=True))),
    "helical.working_pitch_radius": (lambda normal_module: working_pitch_radius(
        sp.Integer(20), normal_module, 0, sp.Symbol("a"), sp.Symbol("b")), dict(normal_module=2)),
    "helical.lead": (lambda normal_module: lead(sp.Integer(20), normal_module, sp.Symbol("beta")), dict(normal_module=2)),
    "helical_gear": (lambda name, teeth, normal_module, beta: helical_gear(name, teeth, normal_module, beta),
                     dict(name="2", teeth=30, normal_module=2, beta=sp.Symbol("beta", positive=True))),
    "parse_expression": (lambda text: parse_expression(text), dict(text="2*pi")),
    "parse_number": (lambda text: parse_number(text), dict(text="0.5")),
    "parse_integer": (lambda text: parse_integer(text), dict(text="12")),
    "as_expr": (lambda value: as_expr(value, what="x"), dict(value=2 * sp.pi)),
    "as_float": (lambda value: as_float(value, what="x"), dict(value=sp.pi / 2)),
    "as_real": (lambda value: as_real(value, what="x"), dict(value=sp.pi / 6)),
    "as_rational": (lambda value: as_rational(value, what="x"), dict(value=0.8)),
    "as_integer": (lambda value: as_integer(value, what="x"), dict(value=12)),
    "as_fraction": (lambda value: as_fraction(value, what="x"), dict(value=Fraction(1, 4))),
    "as_values": (lambda value: as_values({"r_1": value}), dict(value=Fraction(3, 2))),
}


def shown(value) -> str:
    """repr of a value for a failure message, shortened (an int of 5000 digits has no repr)."""
    try:
        text = repr(value)
    except ValueError:
        text = f"<int of {len(str(value.bit_length()))} digit bit length>"
    return text[:40]


def test_every_entry_point_works_with_its_valid_arguments():
    for _name, (func, valid) in ENTRY_POINTS.items():
        func(**valid)


@pytest.mark.parametrize("name", list(ENTRY_POINTS))
def test_bad_arguments_give_a_result_or_a_symkin_error(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    problems, tried = [], 0
    func, valid = ENTRY_POINTS[name]
    for key in valid:
        for value in BAD:
            tried += 1
            try:
                func(**{**valid, key: value})
            except SymkinError as err:
                message = str(err)
                if "\n" in message or not message.strip() or len(message) > 2000:
                    problems.append(f"{key}={shown(value)}: message {message[:200]!r}")
            except Exception as err:
                try:
                    text = str(err)[:150]
                except Exception:
                    text = "(its message cannot be printed)"
                problems.append(f"{key}={shown(value)}: {type(err).__name__}: {text}")
    assert not (tmp_path / MARKER).exists(), "an injected string was evaluated"
    assert tried == len(valid) * len(BAD)
    assert not problems, "\n".join(problems)


def test_errors_form_one_hierarchy_users_can_catch():
    for cls in (symkin.ModelError, symkin.InputError, symkin.UnderdeterminedError, symkin.OverdeterminedError,
                symkin.SingularConfigurationError, symkin.UnsupportedError, symkin.ToolError):
        assert issubclass(cls, SymkinError)
    assert issubclass(symkin.InputError, ValueError) and issubclass(symkin.UnsupportedError, NotImplementedError)
    with pytest.raises(symkin.DeterminacyError) as info:
        AA.speeds({"1": 1})
    assert info.value.dof == 2 and len(info.value.admissible) == 2


@pytest.mark.parametrize("text", [INJECTION, "().__class__.__base__.__subclasses__()", "lambda: 0",
                                  "open('x').read()", "globals()", "t.__class__", "[1][0]", "{'a': 1}", "x if t else t",
                                  "sin.__globals__", "(t for t in ())", "t @ t", "t < 1", "f'{t}'"])
def test_user_expressions_refuse_everything_outside_the_allow_list(text, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    with pytest.raises(symkin.InputError, match="not allowed|not a valid expression|is not a number"):
        parse_expression(text, names=("t",))
    with pytest.raises(symkin.TextInputError, match="symkin.parse"):  # the library takes no text at all
        AngleLaw(text)
    assert not os.listdir(tmp_path)


def test_allowed_expressions_mean_what_they_say():
    t = S.t
    assert parse_expression("2*pi*sin(t)^2 + E**t - sqrt(4)", names=("t",)) == 2 * sp.pi * sp.sin(t) ** 2 + sp.exp(t) - 2
    assert parse_expression("0.1") == sp.Rational(1, 10)  # exact, not the float 0.1000000000000000055...
    assert parse_expression("0.30000000000000000001") == sp.Rational(30000000000000000001, 10**20)
    assert math.isclose(float(parse_expression("atan2(1, 1)")), math.pi / 4)
