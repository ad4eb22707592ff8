"""Every --json output carries schema_version and validates against its published schema
(symkin/cli/schemas/, symkin.cli.output_schema); failures against the error schema."""

from __future__ import annotations

import json

import jsonschema
import pytest

from symkin.cli import JSON_SCHEMA_VERSION, build_parser, main, output_schema
from symkin.papers.reproduce import SCHEMA_VERSION
from tests.support.hostile import COMMANDS

#: More ways to call the commands than tests/support/hostile.py's table: other options, other branches.
EXTRA = {
    "split-ok": ("split", "--total", "500", "--stages", "3", "--umin", "2", "--umax", "12", "--model", "1 + u/10",
                 "--json"),
    "helical-designs": ("helical", "AI", "--ratio", "25", "--tolerance", "0.05", "-k", "3", "--mn12", "2", "--mn34", "2",
                        "--top", "2", "--quiet", "--json"),
    "efficiency-locks": ("efficiency", "II", "--teeth", "200,99,100,201", "--driver", "1", "--driven", "H", "--fixed",
                         "4", "--json"),
    "efficiency-ravigneaux": ("efficiency", "--train", "ravigneaux", "--state", "first", "--json"),
    "speeds-expression": ("speeds", "AI", "--teeth", "20,30,20,70", "--omega", "1=2*pi", "--omega", "4=0", "--json"),
    "states-simpson": ("states", "--train", "simpson", "--json"),
    "states-one-way": ("states", "--train", "simpson-oneway", "--json"),
    "states-one-way-free": ("states", "--train", "hub-3speed", "--json"),
    "efficiency-operating-point": ("efficiency", "--train", "power-split", "--omega", "C=2000rpm", "--omega", "R=1500rpm",
                                   "--torque", "C=100", "--json"),
    "efficiency-one-way": ("efficiency", "--train", "simpson-oneway", "--state", "D1", "--json"),
    "synthesize-transmission": ("synthesize", "--train", "simpson", "--ratios", "first=29/12,second=17/12",
                                "--tolerance", "0.01", "--planets", "3", "--zmax", "80", "--json"),
    "reproduce-one": ("reproduce", "luo2018", "--no-pdf", "--quiet", "--json"),
    "synthesize-efficiency": ("synthesize", "--train", "ravigneaux", "--driver", "S1", "--driven", "R", "--fixed", "C",
                              "--ratio-range", "2.3,2.4", "--planets", "3", "--zmax", "60", "--shift", "0.5", "--top",
                              "2", "--efficiency", "--quiet", "--json"),
}
CALLS = {**{k: c.argv for k, c in COMMANDS.items() if c.argv[0] != "reproduce"}, **EXTRA}


def _version(command: str) -> str:
    """The layout version of a command's --json output: the report's own for reproduce."""
    return SCHEMA_VERSION if command == "reproduce" else JSON_SCHEMA_VERSION


def _validate(data: dict, schema: dict) -> None:
    jsonschema.Draft202012Validator(schema, format_checker=jsonschema.FormatChecker()).validate(data)


def test_every_command_has_a_published_schema_that_is_itself_valid():
    parser = build_parser()
    commands = parser._subparsers._group_actions[0].choices  # the registered commands
    for name in [*commands, "error"]:
        schema = output_schema(name)
        jsonschema.Draft202012Validator.check_schema(schema)
        assert schema["properties"]["schema_version"]["const"] == _version(name)
    with pytest.raises(ValueError, match="no output schema for 'nonsense'; known: animate"):
        output_schema("nonsense")


@pytest.mark.parametrize("key", list(CALLS))
def test_the_json_output_validates_against_its_schema(key, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    argv = [*CALLS[key], *([] if "--json" in CALLS[key] else ["--json"])]
    if argv[0] == "reproduce":
        argv += ["--out", str(tmp_path / "report")]
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse refused the line
        code = exc.code
    data = json.loads(capsys.readouterr().out)
    assert data["schema_version"] == _version(argv[0] if code in (0, 1) else "error")
    if key in EXTRA:
        assert code in (0, 1), data  # these calls are meant to succeed
    _validate(data, output_schema(argv[0] if code in (0, 1) else "error"))


def test_a_changed_layout_is_caught(capsys):
    assert main(["ratio", "AA", "--teeth", "100,100,101,99", "--driver", "H", "--driven", "1", "--fixed", "4",
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    schema = output_schema("ratio")
    _validate(data, schema)
    for broken in ({**data, "ratio": 50.5}, {k: v for k, v in data.items() if k != "coaxial"},
                   {**data, "teeth": ["100"]}, {k: v for k, v in data.items() if k != "schema_version"}):
        with pytest.raises(jsonschema.ValidationError):
            _validate(broken, schema)


@pytest.mark.parametrize("argv", [("ratio", "AA", "--teeth", "1,2", "--json"), ("ratio", "--no-such-option", "--json")])
def test_failures_validate_against_the_error_schema(argv, capsys):
    try:
        code = main(list(argv))
    except SystemExit as exc:
        code = exc.code
    assert code == 2
    data = json.loads(capsys.readouterr().out)
    _validate(data, output_schema("error"))
