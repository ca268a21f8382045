"""The interactive examples of docs/guide/python.md (the `>>>` lines and the output shown under them)
run as doctests against the package, so the page cannot drift from what the package answers. The
expected values are the page's own; the series is the one the page names (`chaos generate lorenz -l
20000 --components x > lorenz.dat`), made by the command built from the same checkout."""
import doctest
import re

from conftest import REPO, run_cli

PAGE = REPO / "docs" / "guide" / "python.md"
FENCE = re.compile(r"^```python\n(.*?)^```", re.MULTILINE | re.DOTALL)


def interactive_blocks(text):
    return [block for block in FENCE.findall(text) if block.lstrip().startswith(">>>")]


def test_the_page_has_interactive_examples():
    # A property of the page: the test below would pass vacuously if the examples were rewritten
    # as plain code, so their presence is checked on its own.
    assert interactive_blocks(PAGE.read_text())


def test_the_interactive_examples_print_what_the_page_shows(tmp_path, monkeypatch):
    (tmp_path / "lorenz.dat").write_text(run_cli("generate", "lorenz", "-l", "20000", "--components", "x").stdout)
    monkeypatch.chdir(tmp_path)
    parser = doctest.DocTestParser()
    runner = doctest.DocTestRunner(optionflags=doctest.NORMALIZE_WHITESPACE)
    for number, block in enumerate(interactive_blocks(PAGE.read_text()), start=1):
        test = parser.get_doctest(block, {}, f"{PAGE.name} example {number}", str(PAGE), 0)
        runner.run(test)
    failed, attempted = runner.summarize(verbose=False)
    assert attempted > 0
    assert failed == 0, f"{failed} of {attempted} lines of {PAGE.name}'s examples print something else (see above)"
