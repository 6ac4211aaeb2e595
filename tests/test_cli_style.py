"""One CLI style across the command groups: options declared with ``Annotated`` (no
``typer.Option`` defaults), and one ``--json`` flag, declared once (``_common.JsonFlag``)."""

from __future__ import annotations

import importlib
import inspect
import pkgutil
import typing

import pytest
from typer.models import ParameterInfo

import seahelm.cli
from seahelm.cli._common import JsonFlag

MODULES = [importlib.import_module(f"seahelm.cli.{m.name}")
           for m in pkgutil.iter_modules(seahelm.cli.__path__)]
COMMANDS = [(mod.__name__, name, obj) for mod in MODULES
            for name, obj in vars(mod).items()
            if inspect.isfunction(obj) and obj.__module__ == mod.__name__
            and any(True for _ in inspect.signature(obj).parameters)]


def _parameter_infos(func):
    hints = typing.get_type_hints(func, include_extras=True)
    for name, param in inspect.signature(func).parameters.items():
        meta = getattr(hints.get(name), "__metadata__", ())
        yield name, param, [m for m in meta if isinstance(m, ParameterInfo)]


@pytest.mark.parametrize(("module", "name", "func"), COMMANDS,
                         ids=[f"{m}.{n}" for m, n, _ in COMMANDS])
def test_options_are_annotated_not_defaults(module, name, func):
    for pname, param, _ in _parameter_infos(func):
        assert not isinstance(param.default, ParameterInfo), (
            f"{module}.{name}({pname}): typer.Option as a default; use Annotated")


@pytest.mark.parametrize(("module", "name", "func"), COMMANDS,
                         ids=[f"{m}.{n}" for m, n, _ in COMMANDS])
def test_json_flag_is_the_shared_one(module, name, func):
    shared = typing.get_args(JsonFlag)[1]
    for pname, _param, infos in _parameter_infos(func):
        if any(getattr(i, "param_decls", None) and "--json" in i.param_decls for i in infos):
            assert pname == "json_out" and infos == [shared], f"{module}.{name}({pname})"


def test_the_check_sees_commands():
    names = {(m.rsplit(".", 1)[1], n) for m, n, _ in COMMANDS}
    assert {("main", "demo"), ("compensate", "compensate"), ("averaging", "cpp")} <= names
