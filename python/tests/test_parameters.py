"""The functions' keyword arguments come from the commands' parameter tables
(chaos/commands/parameter_tables.cpp), the same tables the `chaos` commands' options come from: the
Python defaults are checked against the defaults the command line itself prints in its --help (CLI11
renders the bound field's value), so that Python and the command line cannot drift apart."""
import inspect
import re

import numpy as np
import pytest

import chaos
from chaos import _core

from conftest import run_cli

# Python function -> `chaos` command, for every function built from a parameter table.
COMMANDS = {"mutual": "mutual", "autocorrelation": "autocorrelation", "cao": "cao", "fnn": "fnn", "d2": "d2",
            "lyapunov": "lyapunov", "lyapunov_maps": "lyapunov-maps", "analyze": "analyze",
            "surrogates": "surrogates", "nonlinearity": "nonlinearity", "generate": "generate",
            "spectrum": "spectrum", "density": "density", "section": "section"}

# An option line of CLI11's help: "  -m,--min-dimension UINT=1   text": the names, then the type in
# capitals with the default after "=" (none for a flag), then the description.
OPTION = re.compile(r"^  (-[^ ]+)(?: ([A-Z][A-Za-z|]*(?:=[^ ]*)?)(?= |$))?")


def cli_options(command):
    """{long name: the default the help shows, or None} of `chaos COMMAND --help`."""
    options = {}
    for line in run_cli(command, "--help").stdout.splitlines():
        m = OPTION.match(line)
        if not m:
            continue
        type_and_default = m.group(2) or ""
        default = type_and_default.split("=", 1)[1] if "=" in type_and_default else None
        for name in m.group(1).split(","):
            options[name.split("{")[0]] = default
    return options


def long_name(flags):
    """The first long name of a table entry's flags ("-m,--min-dimension" -> "--min-dimension")."""
    return next(f.lstrip("!") for f in flags.split(",") if f.lstrip("!").startswith("--"))


@pytest.mark.parametrize("function", sorted(COMMANDS))
def test_python_defaults_are_the_command_lines(function):
    table = _core.parameters(function)
    signature = inspect.signature(getattr(chaos, function))
    shown = cli_options(COMMANDS[function])
    assert table, function
    for name, default, flags in table:
        parameter = signature.parameters[name]
        assert parameter.kind is inspect.Parameter.KEYWORD_ONLY, (function, name)
        assert parameter.default == default, (function, name)
        option = long_name(flags)
        assert option in shown, (function, option)
        if isinstance(default, bool):
            # A switch: a field on by default is cleared by a "!--no-x" flag, one off by default is set by a plain flag.
            assert default == ("!" in flags), (function, name, flags)
        elif default is None:
            assert shown[option] is None, (function, option, shown[option])
        elif isinstance(default, str):
            assert shown[option] == default, (function, option)
        else:
            assert float(shown[option]) == pytest.approx(default, rel=1e-12), (function, option, shown[option])


def test_signature_shows_the_defaults():
    # The values written in the struct defaults of CaoParams/CaoOptions (commands.hpp, cao.hpp), as
    # help(chaos.cao) shows them; the series and the Python-only arguments keep their places.
    signature = inspect.signature(chaos.cao)
    assert str(signature) == ("(x, *, delay=None, min_dimension=1, max_dimension=10, theiler=None, norm='max', "
                              "level=0.8, change=0.1, sigmas=4.0, progress=None, dt=None, column=1, skip=0, "
                              "length=None)")
    assert list(inspect.signature(chaos.generate).parameters)[:2] == ["system", "length"]
    assert list(inspect.signature(chaos.analyze).parameters)[0] == "x"


def test_unknown_keyword_is_refused_as_python_refuses_it():
    x = np.sin(np.arange(500) * 0.3)
    with pytest.raises(TypeError, match=r"^cao\(\) got an unexpected keyword argument 'dimension'$"):
        chaos.cao(x, dimension=3)
    with pytest.raises(TypeError, match=r"^generate\(\) got an unexpected keyword argument 'samples'$"):
        chaos.generate("henon", samples=10)


def test_keyword_left_out_and_given_as_its_default_agree():
    # The default filled in by the signature is the command's own: passing it explicitly changes nothing.
    x = chaos.generate("henon", length=1500, components="x").components["x"]
    defaults = {name: default for name, default, _ in _core.parameters("cao") if default is not None}
    assert defaults
    assert chaos.cao(x, delay=1, theiler=0).to_dict() == chaos.cao(x, delay=1, theiler=0, **defaults).to_dict()


def test_unknown_command_has_no_table():
    with pytest.raises(ValueError, match="no parameter table"):
        _core.parameters("no_such_command")
