"""The functions' keyword arguments come from the commands' parameter tables
(chaos/commands/parameter_tables.cpp, study/commands/sweep_parameters.cpp), the same tables the
`chaos` commands' and `study sweep`'s options come from: the
Python defaults are checked against the defaults the command line itself prints in its --help (CLI11
renders the bound field's value), so that Python and the command line cannot drift apart."""
import inspect
import re

import numpy as np
import pytest

import chaos
from chaos import _core, study

from conftest import run_cli, run_study

# Python function -> `chaos` command, for every function built from a parameter table.
COMMANDS = {"mutual": "mutual", "autocorrelation": "autocorrelation", "cao": "cao", "fnn": "fnn", "d2": "d2",
            "lyapunov": "lyapunov", "lyapunov_maps": "lyapunov-maps", "analyze": "analyze",
            "surrogates": "surrogates", "nonlinearity": "nonlinearity", "generate": "generate",
            "spectrum": "spectrum", "density": "density", "section": "section", "validate": "validate",
            "zoo": "zoo", "zoo_series": "zoo", "study_sweep": "study sweep"}


def function_of(name):
    return study.sweep if name == "study_sweep" else getattr(chaos, name)

# An option line of CLI11's help: "  -m,--min-dimension UINT=1   text": the names, then the type in
# capitals with the default after "=" (none for a flag), then the description.
OPTION = re.compile(r"^  (-[^ ]+)(?: ([A-Z][A-Za-z|]*(?:=[^ ]*)?)(?= |$))?")


def cli_options(command):
    """{long name: the default the help shows, or None} of `chaos COMMAND --help` (`study sweep --help`)."""
    options = {}
    study_command = command.startswith("study ")
    shown = run_study(command.split()[1], "--help") if study_command else run_cli(command, "--help")
    for line in shown.stdout.splitlines():
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
    signature = inspect.signature(function_of(function))
    shown = cli_options(COMMANDS[function])
    assert table, function
    for name, default, flags in table:
        parameter = signature.parameters[name]
        # Keyword-only, unless the function takes it by position (chaos.zoo's only, chaos.validate's
        # filter): then with the table's default all the same.
        assert parameter.kind in (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD), (function, name)
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
                              "level=0.8, change=0.1, sigmas=4.0, threads=1, progress=None, dt=None, column=1, skip=0, "
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


# Each command's result names every parameter of its table under the keyword argument's name (the
# report writes the table, then what the command chose for those left out: report_parameters.hpp).
RESULTS = {
    "mutual": lambda x, h: chaos.mutual(x),
    "autocorrelation": lambda x, h: chaos.autocorrelation(x),
    "cao": lambda x, h: chaos.cao(x, max_dimension=4),
    "fnn": lambda x, h: chaos.fnn(x, max_dimension=4),
    "d2": lambda x, h: chaos.d2(x, max_dimension=3, reference_points=300),
    "lyapunov": lambda x, h: chaos.lyapunov(h, dimension=2, delay=1, theiler=10, reference_points=200),
    "lyapunov_maps": lambda x, h: chaos.lyapunov_maps(h, dimension=2, delay=1),
    "analyze": lambda x, h: chaos.analyze(x, max_dimension=4, surrogates=3),
    "surrogates": lambda x, h: chaos.surrogates(x, count=1),
    "nonlinearity": lambda x, h: chaos.nonlinearity(x, count=3),
    "generate": lambda x, h: chaos.generate("henon", length=10),
    "spectrum": lambda x, h: chaos.spectrum("henon", iterations=2000),
    "density": lambda x, h: chaos.density(np.repeat([1.0, 2.0], 100), np.concatenate([x[:100], x[100:200]])),
    "section": lambda x, h: chaos.section(np.column_stack([x, np.roll(x, 7)]), hyperplane=1, level=float(np.mean(x))),
    "zoo_series": lambda x, h: chaos.zoo_series("henon", fast=True),
}


@pytest.mark.parametrize("function", sorted(RESULTS))
def test_results_name_every_parameter_of_the_table(function, lorenz, data_dir):
    henon = chaos.read(data_dir / "henon.txt")[0]
    names = [name for name, _, _ in _core.parameters(function)]
    result = RESULTS[function](lorenz[:3000], henon).to_dict()
    missing = [name for name in names if name not in result["parameters"]]
    assert not missing, (function, missing, list(result["parameters"]))
