"""The package imported is the installed one, not the repository's C++ chaos/ folder."""
import os
from pathlib import Path

import chaos
from conftest import REPO


def test_imports_the_installed_package():
    assert Path(chaos.__file__).resolve().parent != (REPO / "chaos").resolve()
    assert hasattr(chaos, "d2") and hasattr(chaos._core, "d2")
    assert Path(os.getcwd()).resolve() != REPO  # CI runs pytest from outside the checkout


def test_help_carries_the_formula_and_citation():
    assert "Grassberger" in chaos.d2.__doc__ and "C(eps, m)" in chaos.d2.__doc__
    assert "Cao" in chaos.cao.__doc__ and "Physica D 110" in chaos.cao.__doc__
